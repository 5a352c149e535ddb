#pragma once
// rocking_experiments' shared setup for its two jobs (predicting the tests, their margins): the
// outcomes, the specimens, the test files, the history choice and the one way a member is run.

#include <string>
#include <vector>

#include "experiment_histories.hpp"
#include "experiment_specimens.hpp"
#include "experiments_options.hpp"

namespace rocking_monitor::tools::experiments {

struct Run {
  Options options;
  rm::MeasuredOutcomes outcomes;
  std::vector<Specimen> specimens;
  std::vector<std::string> files;  ///< DIR/tests/TestNNN.csv(.gz), sorted, at most --max-tests
  HistoryChoice history;
  bool solid = false;              ///< the 3-D model (--model)
  rm::MarginSearch search;         ///< --margin-range/-grid/-bisections
  rm::ExperimentSettings settings;
};

/// Reads the outcomes and the catalogue, builds the specimens (printing their pivots), lists the
/// tests and checks the flags together, in the order the tool has always reported errors.
Run prepare_run(const Options& o);

/// One member through one test: the 3-D model with the member's table azimuth and input gain, or
/// the planar model with the run's settings. history: filled when not null.
rm::TestPrediction predict(const Run& run, const Member& m, const std::string& id, const rm::TableTest& test,
                           std::vector<rm::TableHistorySample>* history);

/// The jobs: each returns main's exit status.
int run_margins(const Run& run);
int run_predictions(const Run& run);

}  // namespace rocking_monitor::tools::experiments
