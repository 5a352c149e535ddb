#pragma once
// rocking_study's jobs, one per file: the study over the grid or a body file (study_cases_job.cpp),
// --fragility (study_fragility_job.cpp) and --merge (study_merge_job.cpp); what the first two read
// first (study_inputs.cpp). Each job returns main's exit status and throws on bad input.

#include <vector>

#include "rocking_monitor/study/study.hpp"
#include "rocking_monitor/study/study_io.hpp"
#include "study_options.hpp"

namespace rocking_monitor::tools::study {

/// What the study and --fragility run on.
struct Inputs {
  rm::SolverSettings settings;          ///< the flags' solver, method and model settled and checked
  int shard_k = 1, shard_n = 1;         ///< --shard k/n
  std::vector<double> azimuths;         ///< --azimuth, degrees
  std::vector<st::StudyBody> bodies;    ///< the grid, or the body file's single-plane bodies
  std::vector<st::StudyItem> items;     ///< the body file's two-plane items
  st::StudyRecords records;
  double load_s = 0.0;                  ///< s spent loading the records
};

/// Checks the solver flags and --shard, reads the bodies (or builds the grid) and loads the records,
/// printing their notes on stderr, in the order the tool has always reported errors.
Inputs load_inputs(const Options& o);

int run_cases_job(const Options& o, const Inputs& in);
int run_fragility_job(const Options& o, Inputs in);
int run_merge_job(const Options& o);

}  // namespace rocking_monitor::tools::study
