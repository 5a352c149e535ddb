#pragma once

// Helpers shared by the study's source files (private: not under include/, not part of the API).

#include <cstdio>
#include <string>
#include <vector>

#include "rocking_monitor/csv/csv_reader.hpp"
#include "rocking_monitor/study/study_error.hpp"

namespace rocking_monitor::core::study::detail {

/// One number through a printf format (the study's tables and messages use "%g", "%.9g", ...).
inline std::string format_number(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

/// A CSV file of the study (csv layer); its errors become StudyErrors with the same file:line text.
inline std::vector<csv::Row> read_csv(const std::string& path) {
  try {
    return csv::read_file(path);
  } catch (const csv::CsvError& e) {
    throw StudyError(e.what());
  }
}

}  // namespace rocking_monitor::core::study::detail
