// The 3-D model on a base edge: planar rocking about the edge, one end lifting (EDGE -> VERTEX), and
// the uplift from rest.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "rocking_3d_internal.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/integrate/event_location.hpp"
#include "rocking_monitor/physics/criteria.hpp"

namespace rocking_monitor::core {

using rocking_3d::gravity_and_inertia;
using rocking_3d::rot_z;

// ---------------------------------------------------------------- EDGE

GroundInput Rocking3DModel::edge_input(const GroundInput3& in, int edge) const {
  // The horizontal acceleration that tips the body outward over this edge is minus the ground's
  // acceleration along the edge's outward normal (the planar convention: a_xg > 0 tips about the
  // -x corner); the normal is turned by the footprint's yaw into the world frame.
  const Eigen::Vector3d n = edge_normal(edge);
  GroundInput g;
  g.ax0 = -(in.a0.x() * n.x() + in.a0.y() * n.y());
  g.ax_slope = -(in.slope.x() * n.x() + in.slope.y() * n.y());
  g.ay0 = in.a0.z();
  g.ay_slope = in.slope.z();
  return g;
}

double Rocking3DModel::uplift_at(const GroundInput3& in, int edge, double tau) const {
  const GroundInput g = edge_input(in, edge);
  return uplift_function(fb().edge(edge).pivot, 1, ModelKind::Nonlinear, g.ax(tau), g.ay(tau));
}

// Reactions (per unit mass, vertical) at the two ends of the rocking edge, in the footprint frame:
// from the moment equation about one end, the other end's force (see the note in the header).
void Rocking3DModel::endpoint_reactions(int edge, double theta, double omega, double theta_ddot,
                                        const Eigen::Vector3d& a_fp, double& f_a, double& f_b) const {
  const BaseEdge& e = fb().edge(edge);
  const Eigen::Matrix3d re = Eigen::AngleAxisd(theta, e.axis).toRotationMatrix();
  const Eigen::Vector3d g = gravity_and_inertia(a_fp);
  const Eigen::Vector3d w = omega * e.axis, alpha = theta_ddot * e.axis;
  auto moment = [&](int end) {
    const BaseVertex& v = fb().vertex(end);
    const Eigen::Matrix3d j = re * v.inertia * re.transpose();
    const Eigen::Vector3d r = re * v.to_centre;
    return Eigen::Vector3d(j * alpha + w.cross(j * w) - r.cross(g));
  };
  // L e x F_b = M_a  =>  F_b,perp = (M_a / L) x e ;  -L e x F_a = M_b  =>  F_a,perp = -(M_b / L) x e
  f_b = moment(e.a).cross(e.axis).z() / e.length;
  f_a = -moment(e.b).cross(e.axis).z() / e.length;
}

// Pivoting on end `stays` of the rocking edge alone (the vertex mode's equations at this state), the
// vertical acceleration of the other end, m/s^2 (> 0: it rises).
double Rocking3DModel::end_rise(int edge, double theta, double omega, const Eigen::Vector3d& a_fp, int stays) const {
  const BaseEdge& e = fb().edge(edge);
  const int other = stays == e.a ? e.b : e.a;
  const BaseVertex& v = fb().vertex(stays);
  const Eigen::Matrix3d re = Eigen::AngleAxisd(theta, e.axis).toRotationMatrix();
  const Eigen::Matrix3d j = re * v.inertia * re.transpose();
  const Eigen::Vector3d w = omega * e.axis;
  const Eigen::Vector3d w_dot =
      re * v.inertia_inverse * re.transpose() * ((re * v.to_centre).cross(gravity_and_inertia(a_fp)) - w.cross(j * w));
  // The edge's ends lie on the axis: no centripetal term.
  return w_dot.cross(fb().vertex(other).position - v.position).z();
}

// The step's peak and the tipping angle crossed (located by scan_step on the dense output).
void Rocking3DModel::note_edge_peaks(const StepEvents& ev, double alpha) {
  if (ev.has_peak) {
    report_.peak_ratio = std::max(report_.peak_ratio, ev.peak_abs_theta / alpha);
    if (ev.peak_abs_theta / alpha > outcome_.max_rotation_ratio) {
      outcome_.max_rotation_ratio = ev.peak_abs_theta / alpha;
      outcome_.max_rotation_side = contact_ + 1;
    }
    outcome3_.max_tilt = std::max(outcome3_.max_tilt, ev.peak_abs_theta);
  }
  if (ev.tipping_crossed && !outcome_.beyond_tipping) {
    outcome_.beyond_tipping = true;
    outcome_.beyond_tipping_time = t_ + ev.t_tipping;
    report_.beyond_tipping_entered = true;
  }
}

// < 0 when one end lets go: its reaction would have to pull (f < 0) AND, pivoting on the other end
// alone, it rises (the vertex mode's own acceleration of it, > 0). With sticking contacts the two
// tests can disagree (the end's friction force is released too); then the edge holds, which keeps
// the modes from chattering. `stays`: the end that keeps touching.
double Rocking3DModel::edge_lift_margin(const GroundInput3& in, const RockingOde& ode, double t, double theta,
                                        double omega, int& stays) const {
  const BaseEdge& edge = fb().edge(contact_);
  const Eigen::Vector3d a_fp = to_footprint(in.at(t));
  double f_a, f_b;
  endpoint_reactions(contact_, theta, omega, ode.angular_acceleration(t, theta), a_fp, f_a, f_b);
  stays = f_b < f_a ? edge.a : edge.b;
  if (!(f_a + f_b > 0.0)) return 1.0;
  const double f = std::min(f_a, f_b);
  if (f >= 0.0) return f;
  return std::max(f, -end_rise(contact_, theta, omega, a_fp, stays));
}

// One end of the edge lifting (the corner wobble begins) in the step that ends at t_end_step (the
// step's end or its first event): checked there, located on the dense output; the edge's state is
// put at the lift, `lift_vertex` the end that keeps touching. Bounded: after kMaxLiftsPerSample
// lifts in one sample the edge holds for the rest of it (a body whose end neither holds nor lifts
// consistently, where the real one slips: flagged by the count, never a loop without time advancing).
bool Rocking3DModel::edge_lifts(const GroundInput3& in, const RockingOde& ode, double t_start, double th_start,
                                double om_start, double t_end_step, double t_tol, double& tau, int& lift_vertex) {
  if (lifts_ >= kMaxLiftsPerSample) return false;
  double th, om;
  dopri5_.eval(t_end_step, th, om);
  int stays = -1;
  const double m1 = edge_lift_margin(in, ode, t_end_step, th, om, stays);
  if (!(m1 < 0.0)) return false;
  ++lifts_;
  auto f = [&](double t) {
    double a, b;
    dopri5_.eval(t, a, b);
    int s;
    return edge_lift_margin(in, ode, t, a, b, s);
  };
  const double f0 = f(dopri5_.t0());
  const double t_lift = f0 > 0.0 ? bracketed_root(f, dopri5_.t0(), t_end_step, f0, m1, t_tol) : dopri5_.t0();
  if (t_lift > t_start) {
    dopri5_.single_step(ode, t_start, th_start, om_start, t_lift - t_start, theta_, omega_);
  } else {
    theta_ = th_start;
    omega_ = om_start;
  }
  dopri5_.invalidate();
  tau = t_lift;
  edge_lift_margin(in, ode, t_lift, theta_, omega_, stays);
  lift_vertex = stays;  // the end that keeps touching: the new vertex pivot
  return true;
}

Rocking3DModel::Event Rocking3DModel::advance_edge(const GroundInput3& in, double& tau, double tau_end,
                                                   int& lift_vertex) {
  const Pivot& pv = fb().edge(contact_).pivot;
  // The rotation that ends the edge's motion on the far side: the face across lying flat (a hull)
  // or the side (the overturn angle, about a base edge).
  const double fold = fc().fold[static_cast<std::size_t>(contact_)];
  const bool folds = face_ != 0 || fold < body_.overturn_angle();
  const double limit = folds ? fold : body_.overturn_angle();
  const RockingOde ode{&pv, 1, ModelKind::Nonlinear, edge_input(in, contact_)};
  const double t_tol = 1e-12 * std::max(sample_dt_, 1e-6);
  while (tau < tau_end) {
    const double t_start = tau, th_start = theta_, om_start = omega_;
    report_.integrator_steps += dopri5_.step(ode, tau, theta_, omega_, tau_end, settings_.tol,
                                             settings_.tol * pv.alpha, settings_.tol * pv.p * pv.alpha);
    const StepEvents ev = scan_step(
        [this](double t, double& th, double& om) { dopri5_.eval(t, th, om); }, 1, pv.alpha,
        limit, dopri5_.t0(), dopri5_.t1(), theta_, omega_, dopri5_.theta1(),
        dopri5_.omega1(), t_tol);
    note_edge_peaks(ev, pv.alpha);
    // The step's own events; an end lifting before the first of them comes first.
    double t_end_step = dopri5_.t1();
    Event terminal = Event::None;
    if (ev.terminal == StepEvents::Terminal::Impact) { terminal = Event::Impact; t_end_step = ev.t_event; }
    if (ev.terminal == StepEvents::Terminal::Overturn) {
      terminal = folds ? Event::Impact : Event::Overturn;
      if (folds) lift_vertex = -2;  // the face across lands
      t_end_step = ev.t_event;
    }
    if (ev.terminal == StepEvents::Terminal::Degenerate) { tau = dopri5_.t1(); return Event::Degenerate; }
    if (edge_lifts(in, ode, t_start, th_start, om_start, t_end_step, t_tol, tau, lift_vertex)) return Event::Lift;
    // The pivot's normal reaction vanishing in the step (before its own event): the body flies.
    double lift_at;
    watch_pivot(in, dopri5_.t0(), t_end_step, t_tol, lift_at);
    const double t_fly = lift_in_step(in, dopri5_.t0(), t_end_step, t_tol, lift_at);
    if (std::isfinite(t_fly) && (terminal == Event::None || t_fly < t_end_step)) {
      tau = t_fly;
      if (tau > t_start) dopri5_.single_step(ode, t_start, th_start, om_start, tau - t_start, theta_, omega_);
      else theta_ = th_start, omega_ = om_start;
      dopri5_.invalidate();
      return Event::Flight;
    }
    if (terminal == Event::None) {
      theta_ = dopri5_.theta1();
      omega_ = dopri5_.omega1();
      tau = dopri5_.t1();
      if (theta_ / pv.alpha > outcome_.max_rotation_ratio) {
        outcome_.max_rotation_ratio = theta_ / pv.alpha;
        outcome_.max_rotation_side = contact_ + 1;
      }
      outcome3_.max_tilt = std::max(outcome3_.max_tilt, theta_);
      continue;
    }
    tau = t_end_step;
    dopri5_.single_step(ode, t_start, th_start, om_start, tau - t_start, theta_, omega_);
    dopri5_.invalidate();
    return terminal;
  }
  return Event::None;
}

// ---------------------------------------------------------------- REST -> motion

double Rocking3DModel::find_uplift(const GroundInput3& in, double tau, double tau_end) const {
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < fb().vertex_count(); ++k) {
    const double u0 = uplift_at(in, k, tau), u1 = uplift_at(in, k, tau_end);
    double when;
    if (u0 > 0.0) when = tau;
    else if (u1 > 0.0) when = std::clamp(tau + (tau_end - tau) * (-u0) / (u1 - u0), tau, tau_end);
    else continue;
    const RockingOde ode{&fb().edge(k).pivot, 1, ModelKind::Nonlinear, edge_input(in, k)};
    if (!(ode.angular_acceleration(when, 0.0) > 0.0) && !(ode.angular_acceleration(tau_end, 0.0) > 0.0))
      continue;
    best = std::min(best, when);
  }
  return best;
}

// At the uplift instant: the edge with the largest angular acceleration lifts, unless one of its
// ends would be pulled off the floor, or its neighbour lifts too and the shared vertex alone
// carries the body (then it pivots on that vertex).
void Rocking3DModel::start_motion(const GroundInput3& in, double tau) {
  const Eigen::Vector3d a_fp = to_footprint(in.at(tau));
  const Eigen::Vector3d g = gravity_and_inertia(a_fp);
  int best = -1;
  double best_acc = 0.0;
  for (int k = 0; k < fb().vertex_count(); ++k) {
    const RockingOde ode{&fb().edge(k).pivot, 1, ModelKind::Nonlinear, edge_input(in, k)};
    const double acc = ode.angular_acceleration(tau, 0.0);
    if (acc > best_acc || best < 0) {
      best_acc = acc;
      best = k;
    }
  }
  report_.uplift = true;
  if (std::isnan(outcome_.uplift_time)) outcome_.uplift_time = t_ + tau;
  const BaseEdge& e = fb().edge(best);
  if (!(e.pivot.alpha > 0.0)) {
    // Off a face the centre of mass overhangs (held there by the shaking until now): the body
    // turns back over that edge, rocking about it from the face across at its fold.
    const Eigen::Matrix3d r = rotation();
    const Eigen::Vector3d pivot = r * hv(fc().hull_vertex[static_cast<std::size_t>(e.a)]).position + translation();
    int face = -1, edge = -1;
    if (!hull().face_with_edge(fc().hull_vertex[static_cast<std::size_t>(e.a)], fc().hull_vertex[static_cast<std::size_t>(e.b)], r, face, edge)) {
      // (no face at this edge holds the centre of mass inside it: only at rounding of a flat fold)
      enter_vertex(fc().hull_vertex[static_cast<std::size_t>(e.a)], pivot, r, Eigen::Vector3d::Zero());
      return;
    }
    const HullFace& h = hull().faces[static_cast<std::size_t>(face)];
    const BaseEdge& he = h.body->edge(edge);
    const int pv = h.hull_vertex[static_cast<std::size_t>(he.a)] == fc().hull_vertex[static_cast<std::size_t>(e.a)] ? he.a : he.b;
    enter_edge_from_pose(face, edge, r, pivot, pv, 0.0);
    return;
  }
  double f_a, f_b;
  endpoint_reactions(best, 0.0, 0.0, best_acc, a_fp, f_a, f_b);
  int vertex = -1;
  if (f_a + f_b > 0.0 && std::min(f_a, f_b) < 0.0) vertex = f_b < f_a ? e.a : e.b;
  if (vertex < 0) {
    mode_ = Mode3D::Edge;
    contact_ = best;
    theta_ = omega_ = 0.0;
    dopri5_.invalidate();
    return;
  }
  // Pivoting on the vertex from rest: check that neither neighbour is pushed into the floor.
  const BaseVertex& v = fb().vertex(vertex);
  const Eigen::Vector3d w_dot = v.inertia_inverse * v.to_centre.cross(g);
  for (int m : {fb().previous(vertex), fb().next(vertex)}) {
    if (w_dot.cross(fb().vertex(m).position - v.position).z() < 0.0) {
      mode_ = Mode3D::Edge;  // the reactions' sign was rounding: keep the edge
      contact_ = best;
      theta_ = omega_ = 0.0;
      dopri5_.invalidate();
      return;
    }
  }
  const Eigen::Matrix3d r = face_ == 0 ? yaw_matrix() : Eigen::Matrix3d(yaw_matrix() * fc().rotation);
  enter_vertex(fc().hull_vertex[static_cast<std::size_t>(vertex)],
               yaw_matrix() * v.position + Eigen::Vector3d(shift_.x(), shift_.y(), 0.0), r, Eigen::Vector3d::Zero());
}

}  // namespace rocking_monitor::core
