// SEED orientation codes -> slots, and the rotation of the horizontals into ENU (see the header).
#include "rocking_monitor/feeds/seed_channels.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rocking_monitor::feeds {

std::optional<ChannelRole> channel_role(const std::string& channel) {
  if (channel.size() != 3) return std::nullopt;
  switch (channel[2]) {
    case 'Z': return ChannelRole{Slot::Z, false};
    case 'N': return ChannelRole{Slot::H1, false};
    case 'E': return ChannelRole{Slot::H2, false};
    case '1': return ChannelRole{Slot::H1, true};
    case '2': return ChannelRole{Slot::H2, true};
    default: return std::nullopt;
  }
}

StationFrame::StationFrame(double gain, double azimuth_deg) : gain_(gain), azimuth_deg_(azimuth_deg) {
  if (!std::isfinite(gain) || !(gain > 0.0))
    throw std::invalid_argument("gain " + std::to_string(gain) + " must be finite and > 0 (counts per m/s^2)");
  if (!std::isfinite(azimuth_deg)) throw std::invalid_argument("azimuth must be finite (degrees clockwise from north)");
  const double a = std::remainder(azimuth_deg, 360.0);
  north_ = a == 0.0;
  const double rad = a * M_PI / 180.0;
  sin_ = std::sin(rad);
  cos_ = std::cos(rad);
}

std::array<double, 3> StationFrame::to_enu(double h1, double h2, double z) const {
  if (north_) return {h2 / gain_, h1 / gain_, z / gain_};
  // h1 along (sin a, cos a) in (E, N); h2, 90 deg clockwise of it, along (cos a, -sin a).
  return {(h1 * sin_ + h2 * cos_) / gain_, (h1 * cos_ - h2 * sin_) / gain_, z / gain_};
}

std::array<double, 3> StationFrame::to_counts(double east, double north, double up) const {
  if (north_) return {north * gain_, east * gain_, up * gain_};
  return {(east * sin_ + north * cos_) * gain_, (east * cos_ - north * sin_) * gain_, up * gain_};
}

}  // namespace rocking_monitor::feeds
