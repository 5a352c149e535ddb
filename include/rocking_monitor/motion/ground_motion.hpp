#pragma once

#include <string>
#include <vector>

#include "rocking_monitor/motion/component.hpp"

namespace rocking_monitor::core {

/// Horizontal (in the body's rocking direction) and optional vertical ground acceleration on a
/// common time grid, SI units. This is what a simulation consumes.
struct GroundMotion {
  double t0 = 0.0;                 ///< time of the first sample, s
  double dt = 0.0;                 ///< sample interval, s
  std::vector<double> horizontal;  ///< a_xg, m/s^2
  std::vector<double> vertical;    ///< a_yg, m/s^2 (positive up); empty = none
  std::string description;         ///< where it came from (file names)

  std::size_t size() const { return horizontal.size(); }
  double ay(std::size_t i) const { return vertical.empty() ? 0.0 : vertical[i]; }
};

/// Combines components into a GroundMotion, multiplying both by `scale`. A vertical must have
/// the horizontal's dt (relative 1e-6); when it is shorter it is zero-padded and `notice` says so.
/// Throws std::invalid_argument naming the file on a mismatch or an empty/invalid series.
GroundMotion make_ground_motion(const Component& horizontal, const Component* vertical,
                                double scale, std::string* notice = nullptr);

}  // namespace rocking_monitor::core
