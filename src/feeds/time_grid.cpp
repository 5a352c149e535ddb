// Sequence numbers from sample times at the nominal rate (time_grid.hpp).
#include "rocking_monitor/feeds/time_grid.hpp"

#include <cmath>
#include <stdexcept>

namespace rocking_monitor::feeds {

TimeGrid::TimeGrid(double rate_hz) : rate_(rate_hz) {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) throw std::invalid_argument("time grid: the rate must be > 0 Hz");
}

std::optional<std::uint64_t> TimeGrid::sequence(double time_s) {
  if (!started_) {
    started_ = true;
    t_first_ = time_s;
  }
  const double x = (time_s - t_first_) * rate_;
  const double k = std::round(x);
  if (std::abs(x - k) > 0.25) return std::nullopt;
  // An origin offset lets a sample from just before the first one (reordered) keep its place.
  const double seq = k + static_cast<double>(kOrigin);
  if (seq < 0.0 || seq > 9.0e15) return std::nullopt;
  return static_cast<std::uint64_t>(seq);
}

}  // namespace rocking_monitor::feeds
