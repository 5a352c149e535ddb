#include "rocking_monitor/physics/impact_3d.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <Eigen/Geometry>

namespace rocking_monitor::core {

Eigen::Vector3d angular_momentum_about(const Eigen::Matrix3d& central_inertia, const Eigen::Vector3d& omega,
                                       const Eigen::Vector3d& centre, const Eigen::Vector3d& pivot,
                                       const Eigen::Vector3d& q) {
  const Eigen::Vector3d v_c = omega.cross(centre - pivot);
  return central_inertia * omega + (centre - q).cross(v_c);
}

Eigen::Matrix3d inertia_about(const Eigen::Matrix3d& central_inertia, const Eigen::Vector3d& centre,
                              const Eigen::Vector3d& q) {
  const Eigen::Vector3d d = centre - q;
  return central_inertia + d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose();
}

Eigen::Vector3d rotation_about_line(const LandingBody& b, const Eigen::Vector3d& p, const Eigen::Vector3d& e) {
  const Eigen::Vector3d h = b.central_inertia * b.omega + (b.centre - p).cross(b.velocity);
  return (e.dot(h) / e.dot(inertia_about(b.central_inertia, b.centre, p) * e)) * e;
}

namespace {

// One candidate active set's motion after the impact and how far it violates complementarity.
struct Candidate {
  Eigen::Vector3d omega, velocity;
  double violation;  // the larger of the two below, m/s
  double into_floor = 0.0;  // fastest contact point moving into the floor, m/s
};

double energy(const LandingBody& b, const Eigen::Vector3d& omega, const Eigen::Vector3d& v) {
  return 0.5 * omega.dot(b.central_inertia * omega) + 0.5 * v.squaredNorm();
}

// The lowest vertical velocity after of any contact but the sticking ones (negative: into the floor).
double worst_other(const LandingContacts& c, const Eigen::Vector3d& omega, const Eigen::Vector3d& q, int skip_a,
                   int skip_b) {
  double worst = std::numeric_limits<double>::infinity();
  for (int k = 0; k < c.count; ++k) {
    if (k == skip_a || k == skip_b) continue;
    worst = std::min(worst, omega.cross(c.point[k] - q).z());
  }
  return worst;
}

// Pivoting on contact i: the angular momentum about it is conserved.
Candidate pivot_on(const LandingBody& b, const LandingContacts& c, int i) {
  const Eigen::Vector3d& q = c.point[i];
  const Eigen::Vector3d h = b.central_inertia * b.omega + (b.centre - q).cross(b.velocity);
  Candidate out;
  out.omega = inertia_about(b.central_inertia, b.centre, q).inverse() * h;
  out.velocity = out.omega.cross(b.centre - q);
  const double impulse_z = out.velocity.z() - b.velocity.z();
  out.into_floor = std::max(0.0, -worst_other(c, out.omega, q, i, i));
  out.violation = std::max(-impulse_z, out.into_floor);
  return out;
}

// Rocking about the base edge i -> j: the angular momentum about the edge is conserved; the normal
// impulses at its two ends follow from the moments about the other end.
Candidate rock_about(const LandingBody& b, const LandingContacts& c, int i, int j) {
  const Eigen::Vector3d& pi = c.point[i];
  const Eigen::Vector3d& pj = c.point[j];
  const Eigen::Vector3d d = pj - pi;
  const double length = d.norm();
  const Eigen::Vector3d e = d / length;
  Candidate out;
  out.omega = rotation_about_line(b, pi, e);
  out.velocity = out.omega.cross(b.centre - pi);
  const Eigen::Vector3d dw = out.omega - b.omega, dv = out.velocity - b.velocity;
  const Eigen::Vector3d side = e.cross(Eigen::Vector3d::UnitZ());
  const double pj_z = (b.central_inertia * dw + (b.centre - pi).cross(dv)).dot(side) / length;
  const double pi_z = -(b.central_inertia * dw + (b.centre - pj).cross(dv)).dot(side) / length;
  out.into_floor = std::max(0.0, -worst_other(c, out.omega, pi, i, j));
  out.violation = std::max({-pi_z, -pj_z, out.into_floor});
  return out;
}

// Coming to rest on the flat base: the centre of the normal impulse must lie in the contact polygon.
Candidate come_to_rest(const LandingBody& b, const LandingContacts& c, double size, double v_tol) {
  Candidate out;
  out.omega.setZero();
  out.velocity.setZero();
  const double impulse_z = -b.velocity.z();
  const Eigen::Vector3d& q = c.point[0];
  const Eigen::Vector3d dh = -(b.central_inertia * b.omega + (b.centre - q).cross(b.velocity));
  if (!(impulse_z > v_tol)) {
    // Nothing pushes the base down: rest only holds when there is (almost) nothing to stop.
    out.violation = std::max(0.0, -impulse_z) + std::hypot(dh.x(), dh.y()) / size;
    return out;
  }
  const Eigen::Vector2d x(q.x() - dh.y() / impulse_z, q.y() + dh.x() / impulse_z);
  double outside = 0.0;
  for (int k = 0; k < c.count; ++k) {
    const Eigen::Vector3d& a = c.point[k];
    const Eigen::Vector3d& n = c.point[(k + 1) % c.count];
    const Eigen::Vector2d edge(n.x() - a.x(), n.y() - a.y());
    const double cross = edge.x() * (x.y() - a.y()) - edge.y() * (x.x() - a.x());
    outside = std::max(outside, -cross / edge.norm());
  }
  out.violation = impulse_z * outside / size;
  return out;
}

}  // namespace

Landing plastic_landing(const LandingBody& b, const LandingContacts& c) {
  double size = 0.0;
  for (int k = 0; k < c.count; ++k) size = std::max(size, (c.point[k] - b.centre).norm());
  const double scale = b.velocity.norm() + b.omega.norm() * size;
  const double v_tol = 1e-9 * scale + 1e-300;

  Landing best;
  best.energy_before = energy(b, b.omega, b.velocity);
  double best_violation = std::numeric_limits<double>::infinity();
  double best_energy = -1.0;
  bool best_kinematic = false;
  auto consider = [&](const Candidate& k, LandingMode mode, int first, int second) {
    const double e = energy(b, k.omega, k.velocity);
    const bool ok = k.violation <= v_tol;
    if (ok) ++best.admissible;
    const bool best_ok = best_violation <= v_tol;
    // Admissible candidates first; among them (ties of rounding) the one that dissipates least.
    // Without one (the landing would need slip), the least violation among the candidates that
    // move no contact into the floor (so that the landing is not found again at once).
    const bool kinematic = k.into_floor <= v_tol;
    const bool better = ok ? (!best_ok || e > best_energy)
                           : !best_ok && (kinematic != best_kinematic ? kinematic : k.violation < best_violation);
    if (!better) return;
    best_kinematic = kinematic;
    best_violation = k.violation;
    best_energy = e;
    best.mode = mode;
    best.first = first;
    best.second = second;
    best.omega = k.omega;
    best.velocity = k.velocity;
  };
  for (int i = 0; i < c.count; ++i) consider(pivot_on(b, c, i), LandingMode::Vertex, i, -1);
  if (c.count >= 2 && c.base_vertex_count > 0) {
    for (int i = 0; i < c.count; ++i) {
      const int j = (i + 1) % c.count;
      if (j == i || (c.vertex[i] + 1) % c.base_vertex_count != c.vertex[j]) continue;
      consider(rock_about(b, c, i, j), LandingMode::Edge, i, j);
    }
  }
  if (c.count >= 3) consider(come_to_rest(b, c, size, v_tol), LandingMode::Rest, -1, -1);

  best.energy_after = energy(b, best.omega, best.velocity);
  best.violation = best_violation <= v_tol ? 0.0 : best_violation;
  const Eigen::Vector3d impulse = best.velocity - b.velocity;
  best.normal_impulse = std::max(0.0, impulse.z());
  best.tangential_impulse = std::hypot(impulse.x(), impulse.y());
  return best;
}

}  // namespace rocking_monitor::core
