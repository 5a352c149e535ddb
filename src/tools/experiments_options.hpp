#pragma once
// rocking_experiments' command line: every flag's value in one struct, and the table that declares
// them (src/tools/experiments_options.cpp). src/tools/rocking_experiments.cpp parses, the jobs run.

#include <CLI/CLI.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "rocking_monitor/study/table_test_margin.hpp"

namespace rocking_monitor::tools::experiments {

/// Every flag's value as parsed; the defaults are those --help states.
struct Options {
  std::string dir, catalogue, out;
  double restitution = std::nan("");  ///< NaN: eq. 34
  double mu_s = std::nan("");         ///< NaN: the catalogue's
  int direction = 1, max_tests = 0;
  double tail_s = 5.0;
  std::string model_name = "auto";
  double restitution_factor = std::nan("");  ///< NaN: the catalogue's, else 1
  double azimuth_deg = 0.0;
  std::string histories, history_tests = "misses";
  int history_every = 1;
  int samples = 32;
  long seed = 1;
  std::string margins;
  core::MarginSearch search;
  std::vector<double> margin_range{core::MarginSearch{}.lo, core::MarginSearch{}.hi};
  bool quiet = false;  ///< no progress on a terminal (there is none off one)
};

/// Declares every flag on `app`, bound to `o`, in --help's order.
void add_options(CLI::App& app, Options& o);

}  // namespace rocking_monitor::tools::experiments
