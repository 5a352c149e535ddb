#pragma once

// The 3-D impact law (issue 27): the 3-D form of the paper's eq. 34. At an impact the new contact
// takes the whole impulse and sticks (no slip, no rebound); the old contact is free to leave.
// The impulse has no moment about the new contact, so the angular momentum about it is conserved:
//   pivoting on a vertex Q:      J_Q omega+ = H_Q-                  (3 equations)
//   rocking about an edge (Q, e): J_e omega+ = e . H_Q-, omega+ || e (the axial component only)
// with H_Q- = J_c omega- + (c - Q) x v_c-, everything per unit mass. omega+ is the projection of
// omega- onto the motions the new contact allows in the kinetic-energy metric (Carnot's theorem),
// so the kinetic energy never grows. For a planar rectangle this is exactly eq. 34.

#include <Eigen/Core>

namespace rocking_monitor::core {

/// Angular momentum per unit mass about the point q of a body turning with omega about the fixed
/// point pivot: J_c omega + (c - q) x (omega x (c - pivot)). J_c: central inertia / mass in the
/// same (world) frame, m^2; c: centre of mass, m.
Eigen::Vector3d angular_momentum_about(const Eigen::Matrix3d& central_inertia, const Eigen::Vector3d& omega,
                                       const Eigen::Vector3d& centre, const Eigen::Vector3d& pivot,
                                       const Eigen::Vector3d& q);

/// Kinetic energy per unit mass of a rotation omega about a fixed point with inertia J (per unit
/// mass, about that point), J/kg.
inline double rotation_energy(const Eigen::Matrix3d& inertia, const Eigen::Vector3d& omega) {
  return 0.5 * omega.dot(inertia * omega);
}

}  // namespace rocking_monitor::core
