// rocking_experiments: predicts the real shaking-table experiments of a data set (issue 20):
// every tests/TestNNN.csv(.gz) for every specimen of a catalogue (rocking_geometry's output),
// predicted overturn vs outcomes.csv; a CSV table and accuracy, precision, recall, F1. Items with
// distributions (a calibrated input_gain, issue 41) run as the node's ensemble; --margins writes each
// test's margin (the smallest scale of its table motion that overturns the model) instead.
// Thin command-line layer: parse the flags, then run one job. All physics lives in the core
// (study/shaking_table_experiments). The parts, one job each: experiments_options.* (the flags),
// experiment_run.* (outcomes, specimens, tests: what both jobs share), experiment_specimens.*,
// experiment_histories.*, experiment_predictions.cpp and experiment_scores.* (predicting and scoring),
// experiment_margins.cpp (--margins).
#include <iostream>

#include <CLI/CLI.hpp>

#include "command_line.hpp"
#include "experiment_run.hpp"
#include "experiments_options.hpp"

namespace ex = rocking_monitor::tools::experiments;

int main(int argc, char** argv) {
  CLI::App app{"Predicts real shaking-table tests: each specimen of the catalogue through each "
               "tests/TestNNN.csv.gz of DIR, compared with DIR/outcomes.csv (docs/validation.md)"};
  ex::Options options;
  ex::add_options(app, options);
  if (auto status = rocking_monitor::tools::parse_command_line(app, argc, argv, "rocking_experiments"))
    return *status;
  try {
    const ex::Run run = ex::prepare_run(options);
    return options.margins.empty() ? ex::run_predictions(run) : ex::run_margins(run);
  } catch (const std::exception& e) {
    std::cerr << "rocking_experiments: error: " << e.what() << "\n";
    return 2;
  }
}
