#pragma once

// The study's tables: cases.csv (one row per case), bodies.csv and records.csv, written through the
// csv layer (rocking_monitor/csv/csv_writer.hpp).

#include <iosfwd>
#include <string>
#include <vector>

#include "rocking_monitor/study/study_bodies.hpp"
#include "rocking_monitor/study/study_records.hpp"
#include "rocking_monitor/study/study_runner.hpp"

namespace rocking_monitor::core::study {

/// Column names of cases.csv, in order (documented in docs/study.md).
const std::vector<std::string>& case_csv_columns();
void write_case_csv_header(std::ostream& out);
/// One line per case (no header), fields as named by case_csv_columns().
void write_case_csv_rows(std::ostream& out, const std::vector<CaseResult>& results,
                         const std::vector<StudyBody>& bodies, const std::vector<StudyRecord>& records);

/// bodies.csv: one row per body with its derived geometry and screening thresholds.
void write_bodies_csv(std::ostream& out, const std::vector<StudyBody>& bodies);
/// records.csv: one row per record component (index, event, station, component, file, vertical,
/// dt, samples, PGA, PGV, vertical PGA).
void write_records_csv(std::ostream& out, const std::vector<StudyRecord>& records);

}  // namespace rocking_monitor::core::study
