#include "rocking_monitor/monitoring/simulation.hpp"

#include <ctime>

namespace rocking_monitor::core {
namespace {

HistorySample snapshot(const RockingModel& m) {
  HistorySample h;
  h.t = m.time();
  h.ax = m.last_ax();
  h.ay = m.last_ay();
  h.mode = m.mode();
  h.side = m.side();
  h.theta = m.theta();
  h.omega = m.omega();
  h.rotation_ratio = m.rotation_ratio();
  h.margin = m.margin().margin;
  return h;
}

}  // namespace

SimulationResult simulate(const Body& body, const SolverSettings& settings,
                          const GroundMotion& motion, bool keep_history) {
  const std::clock_t start = std::clock();
  SimulationResult result;
  RockingModel model(body, settings);
  const std::size_t n = motion.size();
  if (keep_history) result.history.reserve(n);
  if (n == 0) return result;
  model.reset(motion.t0, motion.horizontal[0], motion.ay(0));
  if (keep_history) result.history.push_back(snapshot(model));
  for (std::size_t i = 1; i < n; ++i) {
    const StepReport& r = model.step(motion.horizontal[i], motion.ay(i), motion.dt);
    if (r.violation_onsets != 0) {
      for (int c = 0; c < kCriterionCount; ++c) {
        if (r.violation_onsets & (1u << c))
          result.violations.push_back({static_cast<Criterion>(c), model.time()});
      }
    }
    if (keep_history) result.history.push_back(snapshot(model));
  }
  result.outcome = model.outcome();
  result.final_mode = model.mode();
  result.cpu_time_s = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  return result;
}

}  // namespace rocking_monitor::core
