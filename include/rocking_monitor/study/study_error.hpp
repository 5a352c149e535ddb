#pragma once

// The error of the study (rocking_monitor/study/study.hpp): every layer of it throws this one.

#include <stdexcept>

namespace rocking_monitor::core::study {

/// Thrown for a bad study input (records directory, manifest, shard, case file); what() is one line
/// naming the file (and line or item) and the problem.
class StudyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rocking_monitor::core::study
