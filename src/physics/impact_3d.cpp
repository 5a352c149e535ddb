#include "rocking_monitor/physics/impact_3d.hpp"

#include <Eigen/Geometry>

namespace rocking_monitor::core {

Eigen::Vector3d angular_momentum_about(const Eigen::Matrix3d& central_inertia, const Eigen::Vector3d& omega,
                                       const Eigen::Vector3d& centre, const Eigen::Vector3d& pivot,
                                       const Eigen::Vector3d& q) {
  const Eigen::Vector3d v_c = omega.cross(centre - pivot);
  return central_inertia * omega + (centre - q).cross(v_c);
}

}  // namespace rocking_monitor::core
