#pragma once

// An item's two principal rocking planes (planar decomposition): it rocks in its x-z plane with its
// width and in its y-z plane with its depth, each plane a planar body of the paper under its own
// horizontal component and the shared vertical. The planes are not coupled (README, "Two rocking
// planes"): a documented approximation.

#include <cstdint>
#include <limits>
#include <string>

#include "rocking_monitor/physics/body.hpp"

namespace rocking_monitor::core {

enum class Plane : std::uint8_t { X = 0, Y = 1 };
inline constexpr int kPlaneCount = 2;
/// "x" or "y".
const char* to_string(Plane plane);

/// What the y-z plane adds to the x-z plane's BodyParameters. SI units.
struct DepthParameters {
  /// D, base depth along the item's y, m. NaN = not given: the item rocks in its x plane only.
  double depth = std::numeric_limits<double>::quiet_NaN();
  /// CoM at eccentricity_y * D from the -y corner, in (0, 1).
  double eccentricity_y = 0.5;
  /// Central radius of gyration for rocking in the y-z plane (about the x axis), m. NaN = derived
  /// by y_plane_body().
  double radius_of_gyration_y = std::numeric_limits<double>::quiet_NaN();

  bool given() const { return depth == depth; }  // not NaN
};

/// Empty if valid (or depth not given), else "<field> = <value> (<requirement>)" with the field
/// named as in the catalogue: depth, eccentricity_y, radius_of_gyration_y.
std::string validate(const DepthParameters& y);

/// The planar body of the y-z plane: width = depth, nu1 = eccentricity_y, same height, friction,
/// restitution and overturn angle. Its radius of gyration is radius_of_gyration_y when given; else,
/// when the x plane's is given, i_y^2 = i_x^2 + (D^2 - B^2) / 12 (mass spread uniformly in plan: exact
/// for any body whose plan is a uniform rectangle, whatever its mass distribution over the height);
/// else NaN (homogeneous D x 2h). Throws BodyError naming the field when that is not positive.
BodyParameters y_plane_body(const BodyParameters& x, const DepthParameters& y);

}  // namespace rocking_monitor::core
