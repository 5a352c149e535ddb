// The 3-D model's landings: which base points touch the floor (the closing contact set), the impact
// law over them (physics/impact_3d.hpp: plastic, sticking, solved over the whole set), and the mode
// the body continues in. One routine for every landing: the base coming back flat from an edge or
// a vertex, a neighbour vertex touching down while the base is tilted.
#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "rocking_3d_internal.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/physics/impact_3d.hpp"

namespace rocking_monitor::core {

void Rocking3DModel::record_impact(double tau, double energy_before) {
  if (report_.impacts == 0) report_.first_impact_time = t_ + tau;
  ++report_.impacts;
  ++outcome_.impacts;
  const double after = kinetic_energy();
  if (energy_before > 0.0)
    outcome3_.max_impact_energy_ratio = std::max(outcome3_.max_impact_energy_ratio, after / energy_before);
}

void Rocking3DModel::capture_rest(const Eigen::Matrix3d& rotation, int vertex, const Eigen::Vector3d& point) {
  // The footprint from the pose: the base lies flat, the vertex keeps its place on the floor.
  yaw_ = std::atan2(rotation(1, 0), rotation(0, 0));
  const Eigen::Vector3d placed = yaw_matrix() * body_.vertex(vertex).position;
  shift_ = Eigen::Vector2d(point.x() - placed.x(), point.y() - placed.y());
  go_to_rest();
  report_.rest_capture = true;
  ++outcome_.rest_captures;
}

// The energy below which a landing puts the body at rest: that of rest_capture_ratio * p * alpha about
// the vertex (for a planar motion exactly the planar engine's rule on omega), J/kg.
double Rocking3DModel::capture_energy(const BaseVertex& v) const {
  const double r = settings_.rest_capture_ratio;
  return 0.5 * r * r * kGravity * v.radius * v.alpha * v.alpha;
}

// `touching`: the vertex whose touchdown was located (VERTEX), or -1 (EDGE back to flat).
void Rocking3DModel::land(int touching, double tau) {
  const double before = kinetic_energy();
  const bool from_edge = mode_ == Mode3D::Edge;
  // The pose, the motion before and a point that does not move (on the edge's axis or the pivot).
  Eigen::Matrix3d r;
  Eigen::Vector3d t, omega, fixed;
  if (from_edge) {
    // Back to flat: the pose is the footprint exactly (theta = 0 is the event), every base vertex
    // on the floor.
    r = yaw_matrix();
    t = Eigen::Vector3d(shift_.x(), shift_.y(), 0.0);
    omega = r * (omega_ * body_.edge(contact_).axis);
    fixed = r * body_.vertex(body_.edge(contact_).a).position + t;
    ++outcome3_.flat_impacts;
  } else {
    r = vertex_rotation(y_);
    t = pivot_world_ - r * body_.vertex(contact_).position;
    omega = y_.tail<3>();
    fixed = pivot_world_;
    ++outcome3_.vertex_impacts;
  }
  // The closing contact set: every base point on the floor at this instant, to floor_tol_ (far
  // below any physical scale, above the dense output's error in the pose at the event).
  const int n = body_.vertex_count();
  // One per thread, not per item: 3.6 KB that only a landing uses (no allocation per sample).
  static thread_local LandingContacts set;
  static_assert(LandingContacts::kMax == kMaxBaseVertices, "a contact for every base vertex");
  set.count = 0;
  set.base_vertex_count = n;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d p = r * body_.vertex(i).position + t;
    if (!from_edge && i != touching && i != contact_ && std::abs(p.z()) > floor_tol_) continue;
    p.z() = 0.0;
    set.point[set.count] = p;
    set.vertex[set.count] = i;
    ++set.count;
  }
  const bool flat = set.count >= 3;
  LandingBody lb;
  lb.central_inertia = r * body_.central_inertia_per_mass() * r.transpose();
  lb.centre = r * body_.centre_of_mass() + t;
  lb.omega = omega;
  lb.velocity = omega.cross(lb.centre - fixed);
  const Landing law = plastic_landing(lb, set);
  outcome3_.max_landing_violation = std::max(outcome3_.max_landing_violation, law.violation);
  if (law.normal_impulse > 0.0) {
    const double demand = law.tangential_impulse / law.normal_impulse;
    outcome3_.max_friction_demand = std::max(outcome3_.max_friction_demand, demand);
    // (mu_s = +inf when the item does not give it: never counted)
    if (demand > body_.parameters().mu_s) ++outcome3_.slipping_landings;
  }
  const double kappa = body_.restitution_factor();
  Eigen::Vector3d w = kappa * law.omega;
  Landing chosen = law;
  if (law.mode == LandingMode::Vertex && set.count == 2 &&
      ((set.vertex[0] + 1) % n == set.vertex[1] || (set.vertex[1] + 1) % n == set.vertex[0])) {
    // The Zeno rule of a see-saw on a tilted edge: pivoting on its two ends in turn, the body loses
    // a fixed fraction of the wobble across the edge at each landing, infinitely often in finite
    // time, converging to rocking about the edge. Once the wobble's energy is below the rest
    // capture's energy (rest_capture_ratio * p * alpha, as for rest), it rocks about the edge.
    const int a = (set.vertex[0] + 1) % n == set.vertex[1] ? 0 : 1;
    const Eigen::Vector3d& pa = set.point[a];
    const Eigen::Vector3d w_edge = rotation_about_line(lb, pa, (set.point[1 - a] - pa).normalized());
    const Eigen::Matrix3d j = inertia_about(lb.central_inertia, lb.centre, pa);
    if (kappa * kappa * (law.energy_after - rotation_energy(j, w_edge)) <
        capture_energy(body_.vertex(set.vertex[chosen.first]))) {
      chosen.mode = LandingMode::Edge;
      chosen.first = a;
      chosen.second = 1 - a;
      w = kappa * w_edge;
      ++outcome3_.edge_captures;
    }
  }

  // The planar engine's rest capture (its Zeno rule) needs an almost flat base.
  const bool near_flat =
      flat || std::acos(std::clamp(r(2, 2), -1.0, 1.0)) < settings_.rest_capture_ratio * body_.min_alpha();
  if (chosen.mode == LandingMode::Rest || kappa <= 0.0) {
    capture_rest(r, set.vertex[0], set.point[0]);
  } else if (chosen.mode == LandingMode::Edge) {
    const int edge = set.vertex[chosen.first];  // edge k joins vertex k and k + 1
    const BaseEdge& e = body_.edge(edge);
    const double w_axis = w.dot(r * e.axis);
    // almost no energy left: w below rest_capture_ratio * p * alpha of the edge
    if (!(w_axis > 0.0) || (w_axis < settings_.rest_capture_ratio * e.pivot.p * e.pivot.alpha && near_flat)) {
      capture_rest(r, set.vertex[chosen.first], set.point[chosen.first]);
    } else if (from_edge) {
      mode_ = Mode3D::Edge;
      contact_ = edge;
      theta_ = 0.0;
      omega_ = w_axis;
      dopri5_.invalidate();
    } else {
      enter_edge_from_pose(edge, r, set.point[chosen.first], set.vertex[chosen.first], w_axis);
    }
  } else {
    const int vertex = set.vertex[chosen.first];
    const BaseVertex& v = body_.vertex(vertex);
    if (rotation_energy(r * v.inertia * r.transpose(), w) < capture_energy(v) && near_flat) {
      capture_rest(r, vertex, set.point[chosen.first]);
    } else {
      enter_vertex(vertex, set.point[chosen.first], r, w);
    }
  }
  record_impact(tau, before);
}

}  // namespace rocking_monitor::core
