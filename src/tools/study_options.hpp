#pragma once
// rocking_study's command line: every flag's value in one struct, and the table that declares them
// (src/tools/study_options.cpp). src/tools/rocking_study.cpp parses, the jobs run.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "rocking_monitor/integrate/solver_settings.hpp"
#include "rocking_monitor/study/study.hpp"

#ifndef ROCKING_RECORDS_DIR
#define ROCKING_RECORDS_DIR "../shared/records"
#endif

namespace rocking_monitor::tools::study {

namespace rm = rocking_monitor::core;
namespace st = rocking_monitor::core::study;

/// Every flag's value as parsed; the defaults are those --help states.
struct Options {
  std::string records_dir = ROCKING_RECORDS_DIR, bodies_file, out_dir = "study_out", shard_text = "1/1";
  std::string method_text = "dopri5", model_text = "nonlinear", eccentricities_text = "0.5,0.4,0.3,0.2";
  std::vector<std::string> only, exclude, merge_files, azimuth_texts{"0,90"};
  std::string solid_model = "auto";
  st::StudyGrid grid;
  rm::SolverSettings settings;
  int threads = 0;
  bool no_vertical = false, one_polarity = false, quiet = false, dry_run = false;
  // --fragility
  bool fragility = false;
  std::string im_text = "pgv", pgv_range_text = "0.02,2";
  int levels = 12, bootstrap = 200, members = 32;
  std::uint64_t member_seed = 1;
  // the engine
  bool scalar = false, fast_trig = false, exact_trig = false;
};

/// Declares every flag on `app`, bound to `o`, in --help's order.
void add_options(CLI::App& app, Options& o);

/// "a,b,c" as numbers; throws st::StudyError naming `what` (the flag) and the bad item.
std::vector<double> parse_number_list(const std::string& text, const char* what);

}  // namespace rocking_monitor::tools::study
