#include "rocking_monitor/physics/principal_planes.hpp"

#include <cmath>
#include <algorithm>
#include <cstdio>

namespace rocking_monitor::core {
namespace {

std::string bad(const char* field, double value, const char* requirement) {
  char number[32];
  std::snprintf(number, sizeof number, "%.12g", value);
  return std::string(field) + " = " + number + " (" + requirement + ")";
}

}  // namespace

const char* to_string(Plane plane) { return plane == Plane::X ? "x" : "y"; }

std::string validate(const DepthParameters& y) {
  if (!y.given()) return {};
  if (!std::isfinite(y.depth) || y.depth <= 0.0) return bad("depth", y.depth, "must be a finite length > 0 m");
  if (!std::isfinite(y.eccentricity_y) || y.eccentricity_y <= 0.0 || y.eccentricity_y >= 1.0)
    return bad("eccentricity_y", y.eccentricity_y, "must lie strictly between 0 and 1");
  if (!std::isnan(y.radius_of_gyration_y) && (!std::isfinite(y.radius_of_gyration_y) || y.radius_of_gyration_y <= 0.0))
    return bad("radius_of_gyration_y", y.radius_of_gyration_y, "must be a finite length > 0 m");
  return {};
}

BodyParameters y_plane_body(const BodyParameters& x, const DepthParameters& y) {
  if (const std::string e = validate(y); !e.empty()) throw BodyError("invalid body: " + e);
  if (!y.given()) throw BodyError("invalid body: depth not given (the item rocks in its x plane only)");
  BodyParameters b = x;
  b.width = y.depth;
  b.nu1 = y.eccentricity_y;
  if (!std::isnan(y.radius_of_gyration_y)) {
    b.radius_of_gyration = y.radius_of_gyration_y;
  } else if (!std::isnan(x.radius_of_gyration)) {
    const double i2 = x.radius_of_gyration * x.radius_of_gyration + (y.depth * y.depth - x.width * x.width) / 12.0;
    if (!(i2 > 0.0))
      throw BodyError("invalid body: " + bad("radius_of_gyration_y", std::sqrt(std::max(i2, 0.0)),
                                             "derived from radius_of_gyration and the depth; give it explicitly"));
    b.radius_of_gyration = std::sqrt(i2);
  }
  return b;
}

}  // namespace rocking_monitor::core
