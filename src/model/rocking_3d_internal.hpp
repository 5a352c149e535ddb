#pragma once

// Helpers shared by the 3-D model's files (rocking_3d_*.cpp); not part of the public interface.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rocking_monitor/constants.hpp"

namespace rocking_monitor::core::rocking_3d {

inline Eigen::Matrix3d rot_z(double yaw) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

/// Per unit mass in the ground's frame: gravity and the ground's inertial force.
inline Eigen::Vector3d gravity_and_inertia(const Eigen::Vector3d& a) {
  return Eigen::Vector3d(-a.x(), -a.y(), -(kGravity + a.z()));
}

}  // namespace rocking_monitor::core::rocking_3d
