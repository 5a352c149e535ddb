// Rotating a pair of horizontals to any azimuth (non-orthogonal pairs solved exactly; rotations by
// multiples of 90 deg copy or negate samples without rounding).
#include "rocking_monitor/motion/station.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "rocking_monitor/constants.hpp"

#include "station_internal.hpp"

namespace rocking_monitor::core {

namespace fs = std::filesystem;
using namespace station_io;

// ------------------------------------------------------------------ rotation

RotatedPair rotate(const Component& a, const Component& b, double azimuth_deg) {
  auto name = [](const Component& c) { return base_name(c.file) + " [" + c.label + "]"; };
  const std::string both = name(a) + " and " + name(b);
  if (!std::isfinite(azimuth_deg)) throw StationError("rotate " + both + ": azimuth is not finite");
  if (a.vertical || b.vertical) throw StationError("rotate " + both + ": only horizontal components can be rotated");
  if (a.dt != b.dt) {
    char buf[128];
    std::snprintf(buf, sizeof buf, ": different sample intervals (%.9g s and %.9g s)", a.dt, b.dt);
    throw StationError("rotate " + both + buf);
  }
  if (a.accel.size() != b.accel.size()) {
    throw StationError("rotate " + both + ": different lengths (" + std::to_string(a.accel.size()) + " and " +
                       std::to_string(b.accel.size()) + " samples)");
  }
  if (std::fabs(a.t0 - b.t0) > 1e-9 * std::max(1.0, std::fabs(a.t0))) {
    throw StationError("rotate " + both + ": different start times");
  }
  const auto az_a = label_azimuth_deg(a.label);
  const auto az_b = label_azimuth_deg(b.label);
  if (!az_a || !az_b) {
    throw StationError("rotate " + both + ": the label " + squote(!az_a ? a.label : b.label) + " carries no azimuth");
  }
  const double separation = azimuth_difference(*az_a, *az_b);
  if (separation < kMinSeparationDeg || separation > 180.0 - kMinSeparationDeg) {
    throw StationError("rotate " + both + ": components are nearly parallel (" + deg_text(separation) +
                       " deg apart), the horizontal motion cannot be resolved");
  }
  // Weights of a and b in the ground acceleration along an azimuth `t` (degrees).
  double ca = 0.0, cb = 0.0, la = 0.0, lb = 0.0;
  if (std::fabs(separation - 90.0) <= 1e-6) {
    // Orthogonal: along(t) = a cos(t - az_a) + b cos(t - az_b), exact at multiples of 90 deg.
    ca = cos_deg(azimuth_deg - *az_a);
    cb = cos_deg(azimuth_deg - *az_b);
    la = cos_deg(azimuth_deg - 90.0 - *az_a);
    lb = cos_deg(azimuth_deg - 90.0 - *az_b);
  } else {
    // Not orthogonal (e.g. Lucerne 260/345, 85 deg apart): a = g.u_a, b = g.u_b with u(az) =
    // (sin az, cos az) in (east, north); solve for g, then project: along(t) = g.u(t), i.e.
    // along(t) = [a sin(az_b - t) - b sin(az_a - t)] / sin(az_b - az_a).
    const double det = std::sin((*az_b - *az_a) * kPi / 180.0);
    auto sin_deg = [](double d) { return std::sin(d * kPi / 180.0); };
    ca = sin_deg(*az_b - azimuth_deg) / det;
    cb = -sin_deg(*az_a - azimuth_deg) / det;
    la = sin_deg(*az_b - (azimuth_deg - 90.0)) / det;
    lb = -sin_deg(*az_a - (azimuth_deg - 90.0)) / det;
  }
  RotatedPair out;
  out.along = a;
  out.left = a;
  out.along.label = format_azimuth_label(azimuth_deg);
  out.left.label = format_azimuth_label(azimuth_deg - 90.0);
  const std::size_t n = a.accel.size();
  for (std::size_t i = 0; i < n; ++i) {
    out.along.accel[i] = a.accel[i] * ca + b.accel[i] * cb;
    out.left.accel[i] = a.accel[i] * la + b.accel[i] * lb;
  }
  return out;
}

}  // namespace rocking_monitor::core
