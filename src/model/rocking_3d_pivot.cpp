// The 3-D model's pivot while rocking (EDGE, VERTEX): the floor's reaction on the body from the
// equations of motion, against Coulomb's cone. Rocking on a sticking pivot is exact only while
// |F_h| <= mu_s F_z; where the reaction leaves the cone the real body slide-rocks (or, F_z <= 0, flies):
// not modelled in 3-D yet, so the onset is located, named and counted (the planar ContactModel's
// SLIDE-ROCK and FLIGHT onsets, which the tests compare with).
#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "rocking_3d_internal.hpp"
#include "rocking_monitor/integrate/event_location.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"

namespace rocking_monitor::core {

using rocking_3d::gravity_and_inertia;

// Per unit mass, in the footprint frame: m a_rel = F + m (gravity and the ground's inertial force),
// with a_rel the centre of mass's acceleration turning about the fixed edge.
Eigen::Vector3d Rocking3DModel::edge_reaction(const GroundInput3& in, double t, double theta, double omega) const {
  const BaseEdge& e = fb().edge(contact_);
  const RockingOde ode{&e.pivot, 1, ModelKind::Nonlinear, edge_input(in, contact_)};
  const Eigen::Vector3d r = Eigen::AngleAxisd(theta, e.axis) * fb().vertex(e.a).to_centre;
  const Eigen::Vector3d w = omega * e.axis;
  const Eigen::Vector3d a_rel = (ode.angular_acceleration(t, theta) * e.axis).cross(r) + w.cross(w.cross(r));
  return a_rel - gravity_and_inertia(to_footprint(in.at(t)));
}

// Per unit mass, in the world frame: as above, the angular acceleration from Euler's equations.
Eigen::Vector3d Rocking3DModel::vertex_reaction(const GroundInput3& in, double t, const Vec7& y) const {
  Vec7 dy;
  vertex_rhs(in, t, y, dy);
  return vertex_reaction(in, t, y, dy);
}

// The same with the state's derivative known (dy: at a step's end the stepper's last stage).
Eigen::Vector3d Rocking3DModel::vertex_reaction(const GroundInput3& in, double t, const Vec7& y, const Vec7& dy) const {
  const Eigen::Vector3d c = vertex_rotation(y) * hv(contact_).to_centre;
  const Eigen::Vector3d w = y.tail<3>();
  return Eigen::Vector3d(dy.tail<3>().cross(c) + w.cross(w.cross(c)) - gravity_and_inertia(in.at(t)));
}

// At local time t inside the current step, on the stepper's dense output.
Eigen::Vector3d Rocking3DModel::pivot_reaction(const GroundInput3& in, double t) const {
  if (mode_ == Mode3D::Vertex) {
    if (t == vector_.t1()) return vertex_reaction(in, t, vector_.y1(), vector_.derivative1());
    Vec7 y = vector_.eval(t);
    y.head<4>().normalize();
    return vertex_reaction(in, t, y);
  }
  double th, om;
  dopri5_.eval(t, th, om);
  return edge_reaction(in, t, th, om);
}

// >= 0 inside the cone and pressing (m/s^2); continuous, so that its root is the onset. Without a
// friction coefficient (mu_s infinite) only a pull counts.
double Rocking3DModel::cone_margin(const Eigen::Vector3d& f) const {
  const double mu = body_.parameters().mu_s;
  return std::isfinite(mu) ? mu * f.z() - std::hypot(f.x(), f.y()) : f.z();
}

// Over the step [t0, t1] just taken (its dense output valid): the largest demand at its end, and the
// first instant the reaction leaves the cone, located and recorded once until it comes back inside.
// Returns that instant where the motion after it is modelled (a vertex's slip: slide-rock), else NaN.
// lift_at: where the reaction leaves the cone through its apex (the normal force vanishing with the
// friction it needs: the body flies, follows_flight()), else NaN. A normal force that vanishes only
// after the cone was left (the pivot outside it, followed as sticking on an edge or at the bound on
// slips) is not a flight: the sticking motion is no longer the body's there.
double Rocking3DModel::watch_pivot(const GroundInput3& in, double t0, double t1, double t_tol, double& lift_at) {
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  lift_at = kNone;
  const Eigen::Vector3d f1 = pivot_reaction(in, t1);
  if (f1.z() > 0.0)
    outcome3_.max_pivot_friction_demand = std::max(outcome3_.max_pivot_friction_demand, std::hypot(f1.x(), f1.y()) / f1.z());
  const double m1 = cone_margin(f1);
  if (m1 >= 0.0) {
    pivot_outside_cone_ = pivot_pulled_ = false;
    return kNone;
  }
  if (pivot_outside_cone_) {
    const bool pulled = !(f1.z() > 0.0);
    // The floor dropping faster than gravity lets go of any pivot, outside the cone too: the body flies
    // from where both hold (the normal force negative and g + a_z <= 0).
    if (pulled && follows_flight()) {
      const double t_floor = flight_onset(in, t0, t1);
      if (std::isfinite(t_floor)) {
        lift_at = t_floor;
        return kNone;
      }
    }
    if (pulled && !pivot_pulled_) ++outcome3_.pulled_pivots;
    pivot_pulled_ = pulled;
    // Outside already (counted on the edge this vertex ended, or held by the bound): a vertex pressing
    // on the floor slips from here.
    if (mode_ != Mode3D::Vertex || !(f1.z() > 0.0) || slip_switches_ >= kMaxSlipSwitches) return kNone;
    ++slip_switches_;
    return t0;
  }
  pivot_outside_cone_ = true;
  auto margin_at = [&](double t) { return cone_margin(pivot_reaction(in, t)); };
  const double m0 = margin_at(t0);
  const double t = m0 > 0.0 ? bracketed_root(margin_at, t0, t1, m0, m1, t_tol) : t0;
  // At the root mu_s F_z = |F_h|: a pull when F_z is (to rounding) zero there, a slip otherwise.
  const bool lifts = !(pivot_reaction(in, t).z() > 1e-9 * kGravity);
  if (lifts && follows_flight()) {  // (the body flies from there: lift_in_step locates it)
    lift_at = t;
    return kNone;
  }
  if (lifts) ++outcome3_.pivot_lifts;
  else ++outcome3_.pivot_slips;
  if (std::isnan(outcome3_.first_pivot_slip_time)) outcome3_.first_pivot_slip_time = t_ + t;
  note_transition(mode_, lifts ? Transition3D::PivotLifts : Transition3D::PivotSlips, t);
  if (lifts || mode_ != Mode3D::Vertex) return kNone;
  if (slip_switches_ >= kMaxSlipSwitches) {
    ++outcome3_.pivot_slips_not_followed;
    return kNone;
  }
  ++slip_switches_;
  return t;
}

// VERTEX, over the step [t0, t1] just taken: the first instant the pivot's contact changes, NaN if none:
// a slip beginning (sticking) or ending (slipping; `lifts` where its normal force vanished), or the
// body leaving the floor (`flies`: the reaction left the cone through its apex, or the slipping
// pivot's normal force vanished, where flight is followed).
double Rocking3DModel::pivot_change_in_step(const GroundInput3& in, double t0, double t1, double t_tol, bool& lifts,
                                            bool& flies) {
  lifts = flies = false;
  if (pivot_slipping_) {
    const double t = slip_end(in, t0, t1, t_tol, lifts);
    if (lifts && follows_flight()) {
      // (not where the slipping corner's normal force is indeterminate, Painleve's paradox: free, the
      // corner would move into the floor; end_slip counts that as before)
      Vec11 y = slip_stepper_.eval(t);
      y.head<4>().normalize();
      const Eigen::Matrix3d r = vertex_rotation(Vec7(y.head<7>()));
      flies = free_rise(in, t, r, y.segment<3>(4), -(r * hv(contact_).to_centre)) >= -1e-9 * kGravity;
    }
    return t;
  }
  double lift_at;
  const double t_switch = watch_pivot(in, t0, t1, t_tol, lift_at);
  const double t_fly = lift_in_step(in, t0, t1, t_tol, lift_at);
  flies = std::isfinite(t_fly);
  return flies ? t_fly : t_switch;
}

}  // namespace rocking_monitor::core
