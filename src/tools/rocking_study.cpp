// rocking_study: the paper's study (Boroschek & Romo) over every record of a directory.
// Thin command-line layer over rocking_monitor/study/study.hpp (grid, records, cases, summary) and
// study_io.hpp (YAML bodies, JSON summary): parse the flags, then run one job. See docs/study.md.
// The parts, one job each: study_options.* (the flags), study_inputs.cpp (solver, bodies, records),
// study_cases_job.cpp (the study), study_fragility_job.cpp (--fragility), study_merge_job.cpp
// (--merge), study_output_files.*; progress_meter.* (shared with the other long tools).
#include <iostream>

#include <CLI/CLI.hpp>

#include "command_line.hpp"
#include "study_jobs.hpp"
#include "study_options.hpp"

namespace sj = rocking_monitor::tools::study;

int main(int argc, char** argv) {
  CLI::App app{
      "rocking_study: the overturning study of Boroschek & Romo over every horizontal record component "
      "of a directory (both polarities, with and without the station's vertical), for the paper's "
      "body grid or your own bodies; bodies with a depth (two-plane items) run on both horizontals of each "
      "station rotated to --azimuth. Writes cases.csv, bodies.csv, records.csv, summary.json (and with "
      "--bodies item_cases.csv) to "
      "--out and prints the summary. See docs/study.md."};
  sj::Options options;
  sj::add_options(app, options);
  if (const auto status = rocking_monitor::tools::parse_command_line(app, argc, argv, "rocking_study")) return *status;

  try {
    if (!options.merge_files.empty()) return sj::run_merge_job(options);
    sj::Inputs inputs = sj::load_inputs(options);
    if (options.fragility) return sj::run_fragility_job(options, std::move(inputs));
    return sj::run_cases_job(options, inputs);
  } catch (const std::exception& e) {
    std::cerr << "rocking_study: error: " << e.what() << "\n";
    return 2;
  }
}
