#pragma once

// The 3-D impact law (issues 27, 40): the 3-D form of the paper's eq. 34 over the whole set of base
// points that touch the floor at a landing.
//
// At a landing every base point on the floor may take an impulse (the closing contact set, found by
// the model). The law is Moreau's plastic impact (no rebound) with sticking contacts, the paper's
// assumptions in 3-D: a contact either takes a compressive impulse and sticks (it does not move
// after the impact) or takes none and does not move into the floor. What sticks fixes the motion
// after: one point (the body pivots on it: J_Q omega+ = H_Q-, the angular momentum about it is
// conserved), two ends of a base edge (rocking about the edge: J_e omega+ = e . H_Q-, omega+ || e),
// or three or more points of the flat base (rest). Each candidate's velocity is the projection of
// the velocity before onto the motions it allows in the kinetic-energy metric (Carnot's theorem), so
// kinetic energy never grows. The law's solution is the candidate that is admissible: every other
// contact point leaves the floor or stays on it, and every sticking contact's normal impulse is
// compressive (for rest: the centre of the normal impulse inside the contact polygon). This is the
// linear complementarity problem of the impact over the contact set, solved by enumerating its
// active sets, which for a polygonal base on a plane are exactly the vertices, edges and the face:
// O(n^2) for n contacts, no allocation. Eq. 34 and the planar engine's impacts are special cases
// (tests: test_impact_law.cpp, test_rocking_3d*.cpp).

#include <cstdint>

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

/// Inertia per unit mass about the point q (parallel axes), m^2.
Eigen::Matrix3d inertia_about(const Eigen::Matrix3d& central_inertia, const Eigen::Vector3d& centre,
                              const Eigen::Vector3d& q);

/// The body just before a landing (world frame; per unit mass).
struct LandingBody {
  Eigen::Matrix3d central_inertia;  ///< J_c / m in the world frame, m^2
  Eigen::Vector3d centre;           ///< centre of mass, m
  Eigen::Vector3d omega;            ///< angular velocity before, rad/s
  Eigen::Vector3d velocity;         ///< velocity of the centre of mass before, m/s
};

/// The closing contact set: base points on the floor (z = 0) at the landing instant, in the base's
/// counter-clockwise order; `vertex` is the base vertex index (edges join vertex k and k + 1 mod n).
struct LandingContacts {
  static constexpr int kMax = 128;  // = kMaxBaseVertices (physics/base_body.hpp)
  Eigen::Vector3d point[kMax];
  int vertex[kMax] = {};
  int count = 0;
  int base_vertex_count = 0;  ///< n of the base polygon (for adjacency)
};

enum class LandingMode : std::uint8_t { Vertex, Edge, Rest };

/// The law's solution.
struct Landing {
  LandingMode mode = LandingMode::Rest;
  int first = -1;                 ///< Vertex: the pivot's index in LandingContacts; Edge: the edge's start (ccw)
  int second = -1;                ///< Edge: the edge's end
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();     ///< after, rad/s (world)
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  ///< of the centre of mass after, m/s
  double energy_before = 0.0;     ///< J/kg
  double energy_after = 0.0;      ///< J/kg
  double normal_impulse = 0.0;    ///< total normal impulse per unit mass, m/s (>= 0)
  double tangential_impulse = 0.0;  ///< magnitude of the total horizontal impulse per unit mass, m/s
  /// 0 when the candidate satisfies the complementarity conditions (to rounding); otherwise the
  /// smallest violation of any candidate, m/s (a velocity into the floor or a pulling impulse).
  double violation = 0.0;
  int admissible = 0;             ///< how many candidates were admissible (1 in a well-posed landing)
};

/// The angular velocity after an impact that leaves the body turning about the line through p along
/// the unit vector e: the angular momentum about the line is conserved, w+ = e (e . H_p) / (e . J_p e).
Eigen::Vector3d rotation_about_line(const LandingBody& body, const Eigen::Vector3d& p, const Eigen::Vector3d& e);

/// Solves the plastic sticking impact over the contact set (see the header comment). `count` >= 1.
Landing plastic_landing(const LandingBody& body, const LandingContacts& contacts);

}  // namespace rocking_monitor::core
