#pragma once

#include <vector>

#include "rocking_monitor/motion/ground_motion.hpp"
#include "rocking_monitor/model/rocking_model.hpp"

namespace rocking_monitor::core {

/// One row of a time history (taken at every input sample).
struct HistorySample {
  double t = 0.0;            ///< s
  double ax = 0.0, ay = 0.0; ///< ground acceleration, m/s^2
  Mode mode = Mode::Rest;
  int side = 0;              ///< active pivot
  double theta = 0.0;        ///< rad
  double omega = 0.0;        ///< rad/s
  double rotation_ratio = 0.0;  ///< |theta| / alpha of the active pivot
  double margin = 1.0;          ///< overturn energy margin (see OverturnMargin)
};

/// Onset of a violated pure-rocking condition (the model keeps running; see README).
struct Violation {
  Criterion criterion;
  double time = 0.0;  ///< s
};

struct SimulationResult {
  RockingOutcome outcome;
  Mode final_mode = Mode::Rest;
  std::vector<Violation> violations;
  std::vector<HistorySample> history;  ///< empty unless requested
  double cpu_time_s = 0.0;
};

/// Runs a whole record through a RockingModel (batch API over the streaming one): the body starts
/// at rest with the first sample, then steps sample by sample.
SimulationResult simulate(const Body& body, const SolverSettings& settings,
                          const GroundMotion& motion, bool keep_history = false);

}  // namespace rocking_monitor::core
