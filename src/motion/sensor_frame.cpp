// Station -> accelerometer axes (x along an azimuth, y 90 deg to its left, z up) with gravity on z.

#include "rocking_monitor/motion/sensor_frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace rocking_monitor::core {

namespace {

std::string name(const Component& c) {
  return std::filesystem::path(c.file).filename().string() + " [" + c.label + "]";
}

std::string seconds(double s) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.6g s", s);
  return buf;
}

}  // namespace

LengthMismatch parse_length_mismatch(const std::string& text) {
  if (text == "error") return LengthMismatch::Error;
  if (text == "truncate") return LengthMismatch::Truncate;
  if (text == "pad") return LengthMismatch::Pad;
  throw std::invalid_argument("length mismatch policy '" + text + "' is not one of error, truncate, pad");
}

const char* to_string(LengthMismatch policy) {
  switch (policy) {
    case LengthMismatch::Error:
      return "error";
    case LengthMismatch::Truncate:
      return "truncate";
    case LengthMismatch::Pad:
      return "pad";
  }
  return "unknown";
}

std::int64_t sample_time_ns(double t0, double dt, std::size_t i) {
  return static_cast<std::int64_t>(std::llround((t0 + dt * static_cast<double>(i)) * 1e9));
}

std::int64_t SensorFrameMotion::time_ns(std::size_t i) const { return sample_time_ns(t0, dt, i); }

AccelerometerSample SensorFrameMotion::sample(std::size_t i) const {
  AccelerometerSample s;
  s.time_ns = time_ns(i);
  for (std::size_t k = 0; k < 3; ++k) {
    s.ground[k] = ground[k][i];
    s.specific_force[k] = ground[k][i];
  }
  // The sensor measures specific force f = a - g_vec; with z up g_vec = (0, 0, -g).
  s.specific_force[2] += kGravity;
  return s;
}

namespace {

// Every component has samples, one sample interval and one start time.
void check_common_timing(const std::vector<Component>& comps) {
  const Component& ref = comps.front();
  for (const Component& c : comps) {
    if (!(c.dt > 0.0) || c.accel.empty()) throw StationError(name(c) + ": no samples");
    if (std::fabs(c.dt - ref.dt) > 1e-9 * ref.dt) {
      char buf[96];
      std::snprintf(buf, sizeof buf, ": different sample intervals (%.9g s and %.9g s)", ref.dt, c.dt);
      throw StationError(name(ref) + " and " + name(c) + buf);
    }
    if (std::fabs(c.t0 - ref.t0) > 1e-6 * ref.dt) {
      throw StationError(name(ref) + " and " + name(c) + ": different start times (" + seconds(ref.t0) + " and " + seconds(c.t0) + ")");
    }
  }
}

// Equal lengths: PEER pairs often differ by a few samples at the end. Truncated or padded as the
// policy says (a note each), or an error.
void equal_lengths(std::vector<Component>& comps, LengthMismatch policy, std::vector<std::string>& notes) {
  std::size_t n_min = comps.front().accel.size();
  std::size_t n_max = n_min;
  for (const Component& c : comps) {
    n_min = std::min(n_min, c.accel.size());
    n_max = std::max(n_max, c.accel.size());
  }
  if (n_min == n_max) return;
  const auto shortest = std::min_element(comps.begin(), comps.end(), [](const Component& a, const Component& b) { return a.accel.size() < b.accel.size(); });
  const auto longest = std::max_element(comps.begin(), comps.end(), [](const Component& a, const Component& b) { return a.accel.size() < b.accel.size(); });
  switch (policy) {
    case LengthMismatch::Error:
      throw StationError(name(*shortest) + " and " + name(*longest) + ": different lengths (" + std::to_string(n_min) + " and " +
                         std::to_string(n_max) + " samples); choose truncate or pad");
    case LengthMismatch::Truncate:
      for (Component& c : comps) {
        const std::size_t drop = c.accel.size() - n_min;
        if (drop == 0) continue;
        notes.push_back("truncated " + name(c) + " from " + std::to_string(c.accel.size()) + " to " + std::to_string(n_min) +
                        " samples (dropped the last " + std::to_string(drop) + ", " + seconds(static_cast<double>(drop) * c.dt) + ")");
        c.accel.resize(n_min);
      }
      break;
    case LengthMismatch::Pad:
      for (Component& c : comps) {
        const std::size_t add = n_max - c.accel.size();
        if (add == 0) continue;
        notes.push_back("padded " + name(c) + " with " + std::to_string(add) + " zero samples (" +
                        seconds(static_cast<double>(add) * c.dt) + ", ground at rest) to " + std::to_string(n_max) + " samples");
        c.accel.resize(n_max, 0.0);
      }
      break;
  }
}

// x along azimuth `az` and y to its left: the two horizontals rotated, or the one that already
// points there.
void horizontals_along(const std::string& station, const std::vector<Component>& comps, std::size_t nh, double az,
                       SensorFrameMotion& out) {
  if (nh == 2) {
    RotatedPair r = rotate(comps[0], comps[1], az);
    out.ground[0] = std::move(r.along.accel);
    out.ground[1] = std::move(r.left.accel);
    out.recorded[0] = out.recorded[1] = true;
    out.source[0] = "rotated to " + r.along.label + " from " + name(comps[0]) + " and " + name(comps[1]);
    out.source[1] = "rotated to " + r.left.label + " from " + name(comps[0]) + " and " + name(comps[1]);
    out.x_azimuth_deg = label_azimuth_deg(r.along.label);
    if (!out.x_azimuth_deg) out.x_azimuth_deg = az;
  } else if (nh == 1 && label_azimuth_deg(comps[0].label) &&
             std::fabs(std::remainder(*label_azimuth_deg(comps[0].label) - az, 360.0)) < 1e-9) {
    // the single horizontal already points along the requested azimuth: nothing to rotate
    out.ground[0] = comps[0].accel;
    out.recorded[0] = true;
    out.source[0] = name(comps[0]);
    out.x_azimuth_deg = label_azimuth_deg(comps[0].label);
  } else {
    throw StationError(station + ": an azimuth needs two horizontal components, the station has " + std::to_string(nh) +
                       (nh == 1 ? " (" + name(comps[0]) + ")" : std::string()));
  }
}

// x and y as recorded (y resolved to be orthogonal to x when the channels are not).
void horizontals_as_recorded(const std::vector<Component>& comps, std::size_t nh, SensorFrameMotion& out) {
  for (std::size_t k = 0; k < nh; ++k) {
    out.ground[k] = comps[k].accel;
    out.recorded[k] = true;
    out.source[k] = name(comps[k]);
  }
  if (nh >= 1) out.x_azimuth_deg = label_azimuth_deg(comps[0].label);
  const auto a0 = nh == 2 ? label_azimuth_deg(comps[0].label) : std::nullopt;
  const auto a1 = nh == 2 ? label_azimuth_deg(comps[1].label) : std::nullopt;
  if (a0 && a1 && std::fabs(std::fabs(std::remainder(*a0 - *a1, 360.0)) - 90.0) > 1e-6) {
    // Not orthogonal (Lucerne 345/260): x stays the first channel, y is resolved from both so that
    // the frame is orthonormal.
    RotatedPair r = rotate(comps[0], comps[1], *a0);
    out.ground[1] = std::move(r.left.accel);
    out.source[1] = "resolved along " + r.left.label + " from " + name(comps[0]) + " and " + name(comps[1]) +
                    " (not orthogonal)";
  }
}

}  // namespace

SensorFrameMotion to_sensor_frame(const StationRecord& station, const SensorFrameOptions& options) {
  if (!std::isfinite(options.scale)) throw std::invalid_argument("scale is not finite");
  if (options.azimuth_deg && !std::isfinite(*options.azimuth_deg)) throw std::invalid_argument("azimuth is not finite");

  std::vector<Component> comps = station.horizontals;  // copies: lengths may be adjusted below
  const std::size_t nh = comps.size();
  if (station.vertical) comps.push_back(*station.vertical);
  if (comps.empty()) throw StationError(station.info.id + ": the station has no components");

  SensorFrameMotion out;
  out.station = station.info.id;
  out.notes = station.notes;
  check_common_timing(comps);
  equal_lengths(comps, options.length_mismatch, out.notes);
  const Component& ref = comps.front();
  const std::size_t n = ref.accel.size();
  out.dt = ref.dt;
  out.t0 = ref.t0;
  for (auto& axis : out.ground) axis.assign(n, 0.0);
  for (std::size_t k = 0; k < 3; ++k) out.source[k] = "none (zeros)";
  if (options.azimuth_deg)
    horizontals_along(station.info.id, comps, nh, *options.azimuth_deg, out);
  else
    horizontals_as_recorded(comps, nh, out);
  if (station.vertical) {
    out.ground[2] = comps[nh].accel;
    out.recorded[2] = true;
    out.source[2] = name(comps[nh]);
  }
  if (options.scale != 1.0) {
    for (auto& axis : out.ground) {
      for (double& v : axis) v *= options.scale;
    }
  }
  return out;
}

}  // namespace rocking_monitor::core
