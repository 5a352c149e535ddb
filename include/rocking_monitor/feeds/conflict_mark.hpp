#pragma once

// How a conflicting sample travels on sensor_msgs/Imu (issue 52 item 3, docs/inputs.md): two
// datagrams gave one sequence number different values, the bridge kept the first and published it
// with the linear acceleration's variance infinite, i.e. "these values carry no information". The
// values stay (a logger records what was kept); a consumer that steps a model on them must not.
// One rule for the bridge that writes the mark and the monitor that reads it. ROS-free: `Covariance`
// is any indexable row-major 3x3 (sensor_msgs' boost::array<double, 9>, std::array).

#include <cmath>
#include <limits>

namespace rocking_monitor::feeds {

/// The variance a conflicting sample carries on each axis, (m/s^2)^2.
inline constexpr double kConflictVariance = std::numeric_limits<double>::infinity();

/// Marks the sample as conflicting: the diagonal +inf. The off-diagonal is left as it is (0 from a
/// bridge): inf times 0 would make NaN of a consumer's weighting.
template <class Covariance>
void mark_conflicting(Covariance& cov, bool conflicting, double normal_variance) {
  const double v = conflicting ? kConflictVariance : normal_variance;
  for (int k = 0; k < 3; ++k) cov[4 * k] = v;
}

/// True when any axis carries +inf variance: that axis says nothing, and a model stepped on all
/// three would step on it. NaN or -1 (REP 145's "unknown") are not the mark.
template <class Covariance>
bool conflict_marked(const Covariance& cov) {
  for (int k = 0; k < 3; ++k)
    if (std::isinf(cov[4 * k]) && cov[4 * k] > 0.0) return true;
  return false;
}

}  // namespace rocking_monitor::feeds
