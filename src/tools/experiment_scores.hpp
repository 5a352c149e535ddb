#pragma once
// rocking_experiments' scores of the predictions against the measured outcomes: the confusion
// counts per specimen and overall, and the Brier score and 5-bin reliability diagram of P(overturn).

#include <map>
#include <string>

#include "rocking_monitor/study/shaking_table_experiments.hpp"

namespace rocking_monitor::tools::experiments {

/// Brier score and a 5-bin reliability diagram of P(overturn).
struct Reliability {
  double brier = 0.0;
  long n = 0;
  long bin_n[5] = {};
  double bin_p[5] = {};
  long bin_y[5] = {};
  void add(double p, int y);
};

struct Scores {
  std::map<std::string, core::Confusion> per;  ///< by specimen
  core::Confusion all;
  std::map<std::string, Reliability> reliability;  ///< by specimen, and "all"
  long without_outcome = 0;
  /// One specimen's prediction on one test (P(overturn) over its members); measured -1: no outcome.
  void add(const std::string& specimen, double probability, bool predicted, int measured);
};

/// The confusion lines (per specimen, then all); with reliability, its lines too (ensembles only).
void print_scores(const Scores& scores, bool reliability);

}  // namespace rocking_monitor::tools::experiments
