#pragma once

// Ground motion expressed on the axes of an accelerometer bolted to the ground, as a real sensor
// reports it (REP 145): the specific force, i.e. the ground acceleration minus the gravity vector.
// ROS-free, so the mapping that record_to_bag and ground_motion_player publish is unit-tested here.
//
// Sensor frame (REP 103: x forward, y left, z up):
//   x = the first horizontal of the station (StationRecord::horizontals[0]) or, with an azimuth,
//       the ground acceleration along that azimuth (degrees clockwise from north);
//   y = 90 deg counter-clockwise of x seen from above (for x = east, y = north: ENU): the second
//       horizontal as recorded when the pair is orthogonal, else resolved from both (see rotate());
//   z = up.
// An accelerometer at rest on level ground reads +g on z: specific_force.z = a_up + g.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rocking_monitor/motion/component.hpp"
#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/motion/station.hpp"

namespace rocking_monitor::core {

/// What to do when the components of a station have different numbers of samples (PEER pairs often
/// differ by a few samples at the end, e.g. El Centro #10: 7411 and 7403).
enum class LengthMismatch {
  Error,     ///< refuse (StationError naming both files)
  Truncate,  ///< cut every component to the shortest; the dropped samples are counted in the notes
  Pad,       ///< extend the shorter ones with zeros (ground at rest) to the longest; counted in the notes
};

/// Parses "error" | "truncate" | "pad"; throws std::invalid_argument naming the value otherwise.
LengthMismatch parse_length_mismatch(const std::string& text);
const char* to_string(LengthMismatch policy);

struct SensorFrameOptions {
  /// Azimuth of the sensor x axis, degrees clockwise from north. nullopt: x = horizontals[0] as
  /// recorded (no rotation). Needs two orthogonal horizontals with known azimuths.
  std::optional<double> azimuth_deg;
  LengthMismatch length_mismatch = LengthMismatch::Pad;
  /// Multiplies the ground acceleration (all three axes; gravity is added after scaling).
  double scale = 1.0;
};

/// One sample as an accelerometer reports it.
struct AccelerometerSample {
  std::int64_t time_ns = 0;            ///< record time of the sample, ns: round((t0 + i dt) * 1e9)
  std::array<double, 3> ground{};      ///< ground acceleration on x, y, z (gravity excluded), m/s^2
  std::array<double, 3> specific_force{};  ///< ground - gravity vector: (x, y, z + g), m/s^2 (REP 145)
};

/// Ground motion on the sensor axes, uniformly sampled.
struct SensorFrameMotion {
  double dt = 0.0;  ///< s
  double t0 = 0.0;  ///< record time of the first sample, s
  std::array<std::vector<double>, 3> ground;  ///< x, y, z ground acceleration, m/s^2 (gravity excluded)
  std::array<bool, 3> recorded{};  ///< false: no such channel in the source, the axis is all zeros
  std::array<std::string, 3> source;  ///< what each axis is, e.g. "RSN1063_NORTHR_RRS228.AT2 [228]", "rotated to 045 from ...", "none (zeros)"
  std::optional<double> x_azimuth_deg;  ///< azimuth of x when known (y is x - 90, z up)
  std::string station;  ///< StationInfo::id or the file name
  std::vector<std::string> notes;  ///< StationRecord notes + padding / truncation counts

  std::size_t size() const { return ground[0].size(); }
  double duration() const { return size() == 0 ? 0.0 : dt * static_cast<double>(size() - 1); }
  /// Record time of sample i in integer nanoseconds (exact for stamps: no float error accumulates).
  std::int64_t time_ns(std::size_t i) const;
  AccelerometerSample sample(std::size_t i) const;
};

/// Record time t0 + i dt rounded to the nearest nanosecond.
std::int64_t sample_time_ns(double t0, double dt, std::size_t i);

/// Maps a loaded station to the sensor frame (see the file comment). Missing channels are zeros and
/// flagged in `recorded` and `source` (one horizontal: y = 0; no vertical: z = 0, i.e. the sensor reads
/// exactly +g). Throws StationError for unequal dt or t0 between components (naming both files), for
/// a length mismatch under LengthMismatch::Error, for an azimuth with fewer than two horizontals, and
/// for non-orthogonal or unlabelled horizontals when an azimuth is requested; std::invalid_argument for
/// a non-finite scale or azimuth.
SensorFrameMotion to_sensor_frame(const StationRecord& station, const SensorFrameOptions& options = {});

}  // namespace rocking_monitor::core
