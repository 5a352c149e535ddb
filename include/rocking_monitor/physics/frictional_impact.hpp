#pragma once

// The 3-D impact law with Coulomb friction at every closing contact (issue 51, part 3): Moreau's
// plastic impact of a rigid body on the floor, each contact with its own friction cone, as the 3-D
// literature states it (Moreau 1988; Glocker 2001; Acary & Brogliato 2008, ch. 13): with the
// impulses r_k and the contact velocities after u_k = W r + u_before (W: the body's Delassus
// operator over the contact set),
//   u_n >= 0, r_n >= 0, u_n r_n = 0                          (plastic: no rebound, no pull)
//   |r_t| <= mu_s r_n where u_t = 0; r_t = -mu_k r_n u_t/|u_t| with u_n = 0 where it slips.
// With mu_s = mu_k this is the second-order cone complementarity problem that Siconos numerics
// solves as "fc3d" (its reference solves are in test_frictional_impact.cpp).
//
// Solved by non-smooth Gauss-Seidel over the contacts (Jean & Moreau; Siconos' NSGS) with each
// contact's 3 x 3 problem solved exactly (separate, stick, or slip in the direction that makes the
// slip velocity and the friction impulse opposite: a one-dimensional root in the slip angle). The
// body's velocities after are unique even where the impulses are not (a face's redundant contacts).
//
// The sticking law (impact_3d.hpp) is this law's limit mu -> infinity where an admissible sticking
// set exists; where none exists (about 5 % of random landings) this law has the answer.

#include <Eigen/Core>

#include "rocking_monitor/physics/impact_3d.hpp"

namespace rocking_monitor::core {

/// Friction of the impact: static for the stick test, kinetic while slipping (dimensionless).
struct ImpactFriction {
  double mu_s = 0.5;
  double mu_k = 0.5;
};

/// The frictional impact's solution (per unit mass, world frame, velocities relative to the floor).
struct FrictionalLanding {
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();     ///< angular velocity after, rad/s
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  ///< centre of mass velocity after, m/s
  Eigen::Vector3d impulse = Eigen::Vector3d::Zero();   ///< total impulse per unit mass, m/s
  double energy_before = 0.0;                          ///< J/kg
  double energy_after = 0.0;                           ///< J/kg
  int stay = 0;       ///< contacts on the floor after (normal velocity 0)
  int slipping = 0;   ///< of those, the ones that slip after (tangential velocity > tolerance)
  /// Largest violation of the contact law at the end (a contact velocity into the floor, a slip
  /// not opposed by its impulse, an impulse outside its cone), m/s; 0 to rounding when converged.
  double residual = 0.0;
  int sweeps = 0;           ///< Gauss-Seidel sweeps used
  bool converged = false;
};

/// The velocity of the body's point p after a motion (omega, v of the centre c), m/s.
inline Eigen::Vector3d point_velocity(const Eigen::Vector3d& omega, const Eigen::Vector3d& v,
                                      const Eigen::Vector3d& c, const Eigen::Vector3d& p) {
  return v + omega.cross(p - c);
}

/// Solves the frictional plastic impact over the contact set (points on z = 0). `count` >= 1,
/// mu_s >= mu_k >= 0. No allocation. `first` (optional, `first_count` indices into the set): the
/// contacts to try alone first, e.g. those the sticking law loads; their answer is taken when it keeps
/// the law at every contact of the set (the others leave the floor or stay on it), else the whole set
/// is solved.
FrictionalLanding frictional_landing(const LandingBody& body, const LandingContacts& contacts,
                                     const ImpactFriction& friction, const int* first = nullptr, int first_count = 0);

/// A screening in O(1), for a landing whose sticking answer pivots on `pivot` (one contact or the
/// two ends of an edge) and leaves the rest of the set: whether the frictionless impact on the pivot
/// leaves the rest of the set too (upward at 1e-6 of the velocity scale). With the sticking answer,
/// the two ends of the friction range then keep the pivot, and the frictional answer is taken to
/// keep it as well: a slipping pivot, not a flat landing (not a proof: the monotone case).
bool keeps_pivot(const LandingBody& body, const LandingContacts& contacts, const int* pivot, int pivot_count);

}  // namespace rocking_monitor::core
