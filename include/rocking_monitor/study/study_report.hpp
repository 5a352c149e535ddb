#pragma once

// The summary as text (what rocking_study prints); summary.json is study_io.hpp's.

#include <string>

#include "rocking_monitor/study/study_summary.hpp"

namespace rocking_monitor::core::study {

/// Human-readable table (what rocking_study prints).
std::string format_summary(const StudySummary& summary);

}  // namespace rocking_monitor::core::study
