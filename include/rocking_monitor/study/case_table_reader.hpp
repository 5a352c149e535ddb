#pragma once

// Reading cases.csv back (rocking_study --merge), through the csv layer
// (rocking_monitor/csv/csv_reader.hpp).

#include <string>
#include <vector>

#include "rocking_monitor/study/study_error.hpp"
#include "rocking_monitor/study/study_summary.hpp"

namespace rocking_monitor::core::study {

/// Reads the rows of one or more cases.csv files (header required; columns found by name), for
/// merging shards. Throws StudyError "<file>:<line>: ..." (malformed CSV included, csv layer).
struct CaseFile {
  std::vector<CaseRow> rows;
  std::vector<std::string> lines;  ///< the data rows as written (csv::Row::text), same order as rows
  std::string header;              ///< the header row as written
};
CaseFile read_case_csv(const std::string& path);

}  // namespace rocking_monitor::core::study
