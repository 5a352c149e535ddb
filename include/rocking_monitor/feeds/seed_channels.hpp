#pragma once

// SEED channel codes of strong-motion instruments -> the station frame.
//
// The orientation code (the channel's third letter) says which axis a channel measures:
//   Z up; N north and E east; 1 and 2 two orthogonal horizontals, 2 being 90 deg clockwise of 1
//   (seen from above, as E is of N), 1 at the station's azimuth (degrees clockwise from north,
//   from the station's metadata). Band and instrument codes: HN, HL, EN, ... (any pair).
// The station frame is ENU (REP 103): x east, y north, z up. Counts become m/s^2 by dividing by
// the gain (counts per m/s^2, the sensitivity of the station's StationXML or dataless SEED).

#include <array>
#include <optional>
#include <string>

namespace rocking_monitor::feeds {

/// Slot of a channel in a station's triple: the first horizontal (N or 1), the second (E or 2),
/// the vertical (Z).
enum class Slot { H1 = 0, H2 = 1, Z = 2 };

/// Which slot a channel code fills and whether it is of the N/E or the 1/2 kind; nothing for other
/// orientation codes (e.g. U, V, W, 3) and for codes that are not three characters.
struct ChannelRole {
  Slot slot = Slot::Z;
  bool numbered = false;  ///< 1 / 2 (needs an azimuth) rather than N / E
};
std::optional<ChannelRole> channel_role(const std::string& channel);

/// Counts in the three slots -> (east, north, up) in m/s^2. `azimuth_deg` is that of H1: 0 for
/// N/E channels (exactly: no rounding from sines), the station's azimuth for 1/2 channels.
class StationFrame {
 public:
  /// Throws std::invalid_argument for a gain that is not finite and > 0, or a non-finite azimuth.
  StationFrame(double gain_counts_per_mps2, double azimuth_deg);
  std::array<double, 3> to_enu(double h1, double h2, double z) const;
  /// The inverse: (east, north, up) m/s^2 -> counts in the slots (not rounded).
  std::array<double, 3> to_counts(double east, double north, double up) const;
  double gain() const { return gain_; }
  double azimuth_deg() const { return azimuth_deg_; }

 private:
  double gain_;
  double azimuth_deg_;
  double sin_ = 0.0, cos_ = 1.0;
  bool north_ = true;  ///< azimuth 0: H1 is north, H2 east, no trigonometry
};

}  // namespace rocking_monitor::feeds
