#pragma once

namespace rocking_monitor::core {

/// Standard gravity, m/s^2. The one place g lives; records in g are converted with it.
inline constexpr double kGravity = 9.80665;

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace rocking_monitor::core
