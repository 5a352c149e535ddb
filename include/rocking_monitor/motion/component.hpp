#pragma once

#include <string>
#include <vector>

namespace rocking_monitor::core {

/// One uniformly sampled ground-acceleration time series in SI units.
/// Every reader converts to this; nothing downstream knows about g or cm/s^2.
struct Component {
  std::string file;           ///< path it was read from
  std::string event;          ///< event name from the header (may be empty)
  std::string station;        ///< station name (may be empty)
  std::string label;          ///< component label as written in the source ("090", "N", "UP", "N-S", ...)
  std::string channel;        ///< SEED channel code of a miniSEED component ("HNE"); empty for other formats
  bool vertical = false;      ///< true for an up/down component (stored positive up)
  double dt = 0.0;            ///< sample interval, s
  double t0 = 0.0;            ///< time of the first sample, s
  std::vector<double> accel;  ///< ground acceleration, m/s^2

  double duration() const { return accel.empty() ? 0.0 : dt * static_cast<double>(accel.size() - 1); }
};

}  // namespace rocking_monitor::core
