#include "rocking_monitor/motion/peak_ground_motion.hpp"

#include <cmath>

namespace rocking_monitor::core {

PeakValue absolute_peak(const std::vector<double>& x, double dt, double t0) {
  PeakValue peak;
  peak.time = t0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double magnitude = std::abs(x[i]);
    if (magnitude > peak.value) {
      peak.value = magnitude;
      peak.index = i;
    }
  }
  peak.time = t0 + dt * static_cast<double>(peak.index);
  return peak;
}

PeakGroundMotion peak_ground_motion(const Component& component, const BaselineOptions& options) {
  const GroundMotionHistories h = integrate_ground_motion(component, options);
  PeakGroundMotion peaks;
  peaks.pga = absolute_peak(component.accel, component.dt, component.t0);
  peaks.pgv = absolute_peak(h.vel, h.dt, h.t0);
  peaks.pgd = absolute_peak(h.disp, h.dt, h.t0);
  return peaks;
}

PeakGroundMotion peak_ground_motion(const GroundMotionHistories& histories) {
  PeakGroundMotion peaks;
  peaks.pga = absolute_peak(histories.accel, histories.dt, histories.t0);
  peaks.pgv = absolute_peak(histories.vel, histories.dt, histories.t0);
  peaks.pgd = absolute_peak(histories.disp, histories.dt, histories.t0);
  return peaks;
}

}  // namespace rocking_monitor::core
