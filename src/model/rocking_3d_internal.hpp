#pragma once

// Helpers shared by the 3-D model's files (rocking_3d_*.cpp); not part of the public interface.

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rocking_monitor/constants.hpp"

namespace rocking_monitor::core::rocking_3d {

inline Eigen::Matrix3d rot_z(double yaw) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

/// The footprint's turn by yaw about the vertical, in the floor's plane.
inline Eigen::Matrix2d rot2(double yaw) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  return r;
}

/// Per unit mass in the ground's frame: gravity and the ground's inertial force.
inline Eigen::Vector3d gravity_and_inertia(const Eigen::Vector3d& a) {
  return Eigen::Vector3d(-a.x(), -a.y(), -(kGravity + a.z()));
}

/// The rotation of the quaternion (w, x, y, z) in y's first four entries, normalised.
template <class V>
inline Eigen::Matrix3d quaternion_rotation(const V& y) {
  return Eigen::Quaterniond(y(0), y(1), y(2), y(3)).normalized().toRotationMatrix();
}

/// q' = (0, w) q / 2 for the quaternion in y's first four entries and w in the world frame.
template <class V>
inline Eigen::Vector4d quaternion_rate(const Eigen::Vector3d& w, const V& y) {
  const Eigen::Quaterniond qd = Eigen::Quaterniond(0.0, w.x(), w.y(), w.z()) * Eigen::Quaterniond(y(0), y(1), y(2), y(3));
  return Eigen::Vector4d(0.5 * qd.w(), 0.5 * qd.x(), 0.5 * qd.y(), 0.5 * qd.z());
}

}  // namespace rocking_monitor::core::rocking_3d
