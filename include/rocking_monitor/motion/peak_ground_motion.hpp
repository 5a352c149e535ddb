#pragma once

// Peak ground acceleration, velocity and displacement of a record, with the time each occurs.
//
// Why: PGA/PGV/PGD are the simplest intensity measures; PGV in particular governs whether a
// free-standing block starts rocking and how large the rocking gets, so the monitor reports all three.
// Units: m/s^2, m/s, m; times in s on the record's clock (Component::t0 + index * dt).

#include <cstddef>
#include <vector>

#include "rocking_monitor/motion/component.hpp"
#include "rocking_monitor/motion/ground_motion_integration.hpp"

namespace rocking_monitor::core {

/// An absolute maximum and where it occurs (the first sample if several are equal).
struct PeakValue {
  double value = 0.0;     ///< max |x| (>= 0), units of x
  double time = 0.0;      ///< t0 + index * dt, s
  std::size_t index = 0;  ///< sample index
};

struct PeakGroundMotion {
  PeakValue pga;  ///< m/s^2, from the acceleration exactly as recorded (see peak_ground_motion)
  PeakValue pgv;  ///< m/s, from the baseline-corrected, integrated velocity
  PeakValue pgd;  ///< m, from the baseline-corrected, integrated displacement
};

/// max |x[i]| and its time. An empty series gives value 0 at t0.
PeakValue absolute_peak(const std::vector<double>& x, double dt, double t0 = 0.0);

/// PGA, PGV and PGD of a record. PGA is taken from the acceleration as given (a sample-wise maximum
/// should not depend on a baseline fit, and a live monitor can only report the raw samples); PGV and
/// PGD come from integrate_ground_motion(component, options), i.e. after baseline correction.
/// Peaks are sample maxima: no interpolation between samples.
PeakGroundMotion peak_ground_motion(const Component& component, const BaselineOptions& options = {});

/// Same from already integrated histories (PGA then from histories.accel, i.e. the corrected one).
PeakGroundMotion peak_ground_motion(const GroundMotionHistories& histories);

}  // namespace rocking_monitor::core
