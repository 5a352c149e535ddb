#include "rocking_monitor/model/rocking_3d_model.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "rocking_monitor/integrate/event_location.hpp"
#include "rocking_monitor/physics/criteria.hpp"
#include "rocking_monitor/physics/impact_3d.hpp"

namespace rocking_monitor::core {

const char* to_string(Mode3D mode) {
  switch (mode) {
    case Mode3D::Rest: return "REST";
    case Mode3D::Edge: return "EDGE";
    case Mode3D::Vertex: return "VERTEX";
    case Mode3D::Overturned: return "OVERTURNED";
  }
  return "UNKNOWN";
}

namespace {

const SolverSettings& checked(const SolverSettings& s) {
  if (const std::string e = validate(s); !e.empty()) throw std::invalid_argument(e);
  if (s.method != Method::Dopri5 || s.model != ModelKind::Nonlinear)
    throw std::invalid_argument("Rocking3DModel: only the nonlinear model with dopri5 is available in 3-D");
  return s;
}

Eigen::Matrix3d rot_z(double yaw) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

Eigen::Vector3d gravity_and_inertia(const Eigen::Vector3d& a) {
  // Per unit mass in the ground's frame: gravity and the ground's inertial force.
  return Eigen::Vector3d(-a.x(), -a.y(), -(kGravity + a.z()));
}

}  // namespace

Rocking3DModel::Rocking3DModel(const BaseBody& body, const SolverSettings& settings)
    : Rocking3DModel(body, settings, true) {}

Rocking3DModel::Rocking3DModel(const BaseBody& body, const SolverSettings& settings, bool with_probe)
    : body_(body), settings_(checked(settings)) {
  if (with_probe) probe_.reset(new Rocking3DModel(body, settings, false));
  reset(0.0);
}

bool Rocking3DModel::falls_if_shaking_stops(double t_now) {
  Rocking3DModel& p = *probe_;
  // the state of the motion (save/restore: plain values, no allocation), the input gone from now on
  Saved state;
  save(state);
  p.restore(state);
  p.t_ = t_now;
  p.a_prev_.setZero();
  p.dopri5_.invalidate();  // the derivative cached for the shaken motion no longer holds
  p.vector_.invalidate();
  for (double s = 0.0; s < kProbeHorizon; s += kProbeStep) {
    p.step(Eigen::Vector3d::Zero(), kProbeStep);
    if (p.mode_ == Mode3D::Overturned) return true;
    if (p.mode_ == Mode3D::Rest) return false;
  }
  return false;
}

void Rocking3DModel::reset(double t, const Eigen::Vector3d& a) {
  mode_ = Mode3D::Rest;
  contact_ = -1;
  theta_ = omega_ = 0.0;
  y_.setZero();
  y_(0) = 1.0;
  pivot_world_.setZero();
  yaw_ = 0.0;
  shift_.setZero();
  t_ = t;
  a_prev_ = a;
  report_ = StepReport{};
  outcome_ = RockingOutcome{};
  outcome3_ = Rocking3DOutcome{};
  last_probe_t_ = -1e300;
  dopri5_.reset(0.05 / body_.max_p());
  vector_.reset(0.05 / body_.max_p());
}

void Rocking3DModel::save(Saved& out) const {
  out.mode = mode_;
  out.contact = contact_;
  out.theta = theta_;
  out.omega = omega_;
  out.y = y_;
  out.pivot_world = pivot_world_;
  out.yaw = yaw_;
  out.shift = shift_;
  out.t = t_;
  out.a_prev = a_prev_;
  std::copy(std::begin(armed_), std::end(armed_), std::begin(out.armed));
  out.report = report_;
  out.outcome = outcome_;
  out.outcome_3d = outcome3_;
  dopri5_.save(out.dopri5);
  vector_.save(out.vector);
  out.last_probe_t = last_probe_t_;
}

void Rocking3DModel::restore(const Saved& in) {
  mode_ = in.mode;
  contact_ = in.contact;
  theta_ = in.theta;
  omega_ = in.omega;
  y_ = in.y;
  pivot_world_ = in.pivot_world;
  yaw_ = in.yaw;
  shift_ = in.shift;
  t_ = in.t;
  a_prev_ = in.a_prev;
  std::copy(std::begin(in.armed), std::end(in.armed), std::begin(armed_));
  report_ = in.report;
  outcome_ = in.outcome;
  outcome3_ = in.outcome_3d;
  dopri5_.restore(in.dopri5);
  vector_.restore(in.vector);
  last_probe_t_ = in.last_probe_t;
}

Eigen::Matrix3d Rocking3DModel::yaw_matrix() const { return rot_z(yaw_); }

Eigen::Vector3d Rocking3DModel::to_footprint(const Eigen::Vector3d& world) const {
  return yaw_ == 0.0 ? world : Eigen::Vector3d(rot_z(-yaw_) * world);
}

Eigen::Matrix3d Rocking3DModel::vertex_rotation(const Vec7& y) const {
  return Eigen::Quaterniond(y(0), y(1), y(2), y(3)).normalized().toRotationMatrix();
}

Eigen::Matrix3d Rocking3DModel::rotation() const {
  switch (mode_) {
    case Mode3D::Edge: {
      const BaseEdge& e = body_.edge(contact_);
      return yaw_matrix() * Eigen::AngleAxisd(theta_, e.axis).toRotationMatrix();
    }
    case Mode3D::Vertex: return vertex_rotation(y_);
    default: return yaw_matrix();
  }
}

Eigen::Vector3d Rocking3DModel::translation() const {
  const Eigen::Vector3d shift3(shift_.x(), shift_.y(), 0.0);
  switch (mode_) {
    case Mode3D::Edge: {
      const Eigen::Vector3d& a = body_.vertex(body_.edge(contact_).a).position;
      // footprint(a + R_e (x - a)): x -> Rz R_e x + Rz (a - R_e a) + shift
      const Eigen::Matrix3d re = Eigen::AngleAxisd(theta_, body_.edge(contact_).axis).toRotationMatrix();
      return yaw_matrix() * (a - re * a) + shift3;
    }
    case Mode3D::Vertex: return pivot_world_ - vertex_rotation(y_) * body_.vertex(contact_).position;
    default: return shift3;
  }
}

Eigen::Vector3d Rocking3DModel::angular_velocity() const {
  if (mode_ == Mode3D::Edge) return yaw_matrix() * (omega_ * body_.edge(contact_).axis);
  if (mode_ == Mode3D::Vertex) return y_.tail<3>();
  return Eigen::Vector3d::Zero();
}

double Rocking3DModel::tilt() const {
  if (mode_ == Mode3D::Edge) return theta_;
  if (mode_ == Mode3D::Vertex) return std::acos(std::clamp(vertex_rotation(y_)(2, 2), -1.0, 1.0));
  if (mode_ == Mode3D::Overturned) return body_.overturn_angle();
  return 0.0;
}

double Rocking3DModel::rotation_ratio() const {
  if (mode_ == Mode3D::Edge) return theta_ / body_.edge(contact_).pivot.alpha;
  if (mode_ == Mode3D::Overturned) return outcome_.max_rotation_ratio;  // as it went over (> 1)
  if (mode_ != Mode3D::Vertex) return 0.0;
  const BaseVertex& v = body_.vertex(contact_);
  const Eigen::Matrix3d r = vertex_rotation(y_);
  const Eigen::Vector3d lever = r * v.to_centre;
  // Which side of the vertical through the vertex the centre of mass is on: the side of the base
  // (inside, ratio < 1) or beyond it (ratio > 1).
  const Eigen::Vector3d inside = r * (body_.centroid() - v.position);
  const double phi = std::atan2(std::hypot(lever.x(), lever.y()), lever.z());
  const bool beyond = lever.x() * inside.x() + lever.y() * inside.y() < 0.0;
  return beyond ? 1.0 + phi / v.alpha : 1.0 - phi / v.alpha;
}

OverturnMargin Rocking3DModel::margin() const {
  switch (mode_) {
    case Mode3D::Rest: return {1.0, false};
    case Mode3D::Overturned: return {-1.0, true};
    case Mode3D::Edge:
      return overturn_margin(body_.edge(contact_).pivot, 1, ModelKind::Nonlinear, theta_, omega_);
    case Mode3D::Vertex: break;
  }
  const BaseVertex& v = body_.vertex(contact_);
  const double height = (vertex_rotation(y_) * v.to_centre).z();
  const double energy = kinetic_energy() + kGravity * height;
  const double tip = kGravity * v.radius, rest = kGravity * v.to_centre.z();
  const double m = (tip - energy) / (tip - rest);
  return {m, m < 0.0};
}

double Rocking3DModel::kinetic_energy() const {
  if (mode_ == Mode3D::Edge) return 0.5 * body_.edge(contact_).pivot.inertia * omega_ * omega_;
  if (mode_ != Mode3D::Vertex) return 0.0;
  const Eigen::Matrix3d r = vertex_rotation(y_);
  const Eigen::Vector3d w = y_.tail<3>();
  return rotation_energy(r * body_.vertex(contact_).inertia * r.transpose(), w);
}

void Rocking3DModel::note_ratio() {
  const double ratio = rotation_ratio();
  if (ratio > outcome_.max_rotation_ratio) {
    outcome_.max_rotation_ratio = ratio;
    outcome_.max_rotation_side = contact_ + 1;
  }
  outcome3_.max_tilt = std::max(outcome3_.max_tilt, tilt());
  if (ratio > 1.0 && !outcome_.beyond_tipping) {
    outcome_.beyond_tipping = true;
    outcome_.beyond_tipping_time = t_;
    report_.beyond_tipping_entered = true;
  }
}

void Rocking3DModel::go_to_rest() {
  mode_ = Mode3D::Rest;
  contact_ = -1;
  theta_ = omega_ = 0.0;
  dopri5_.invalidate();
  vector_.invalidate();
}

void Rocking3DModel::set_edge_state(int edge, double theta, double omega) {
  if (edge < 0 || edge >= body_.vertex_count() || !std::isfinite(theta) || !std::isfinite(omega) ||
      theta < 0.0)
    throw std::invalid_argument("set_edge_state: edge index, theta >= 0 and omega finite");
  mode_ = Mode3D::Edge;
  contact_ = edge;
  theta_ = theta;
  omega_ = omega;
  dopri5_.invalidate();
}

void Rocking3DModel::set_vertex_state(int vertex, const Eigen::Quaterniond& rotation,
                                      const Eigen::Vector3d& omega) {
  if (vertex < 0 || vertex >= body_.vertex_count() || !omega.allFinite())
    throw std::invalid_argument("set_vertex_state: vertex index and omega finite");
  const Eigen::Matrix3d r = rotation.normalized().toRotationMatrix();
  enter_vertex(vertex, yaw_matrix() * body_.vertex(vertex).position +
                           Eigen::Vector3d(shift_.x(), shift_.y(), 0.0),
               r, omega);
}

Eigen::Vector3d Rocking3DModel::edge_normal(int edge) const {
  return yaw_ == 0.0 ? body_.edge(edge).normal : Eigen::Vector3d(yaw_matrix() * body_.edge(edge).normal);
}

void Rocking3DModel::apply_rest_samples(double t, const Eigen::Vector3d& a, double dt, long n) {
  // What n calls of step() do at REST without a lift (or OVERTURNED and committed): a fresh report,
  // the clock, the last input, the sample count.
  report_ = StepReport{};
  sample_dt_ = dt;
  lifts_ = 0;
  t_ = t;
  a_prev_ = a;
  outcome_.samples += n;
}

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
  return uplift_function(body_.edge(edge).pivot, 1, ModelKind::Nonlinear, g.ax(tau), g.ay(tau));
}

// Reactions (per unit mass, vertical) at the two ends of the rocking edge, in the footprint frame:
// from the moment equation about one end, the other end's force (see the note in the header).
void Rocking3DModel::endpoint_reactions(int edge, double theta, double omega, double theta_ddot,
                                        const Eigen::Vector3d& a_fp, double& fa, double& fb) const {
  const BaseEdge& e = body_.edge(edge);
  const Eigen::Matrix3d re = Eigen::AngleAxisd(theta, e.axis).toRotationMatrix();
  const Eigen::Vector3d g = gravity_and_inertia(a_fp);
  const Eigen::Vector3d w = omega * e.axis, alpha = theta_ddot * e.axis;
  auto moment = [&](int end) {
    const BaseVertex& v = body_.vertex(end);
    const Eigen::Matrix3d j = re * v.inertia * re.transpose();
    const Eigen::Vector3d r = re * v.to_centre;
    return Eigen::Vector3d(j * alpha + w.cross(j * w) - r.cross(g));
  };
  // L e x F_b = M_a  =>  F_b,perp = (M_a / L) x e ;  -L e x F_a = M_b  =>  F_a,perp = -(M_b / L) x e
  fb = moment(e.a).cross(e.axis).z() / e.length;
  fa = -moment(e.b).cross(e.axis).z() / e.length;
}

// Pivoting on end `stays` of the rocking edge alone (the vertex mode's equations at this state), the
// vertical acceleration of the other end, m/s^2 (> 0: it rises).
double Rocking3DModel::end_rise(int edge, double theta, double omega, const Eigen::Vector3d& a_fp, int stays) const {
  const BaseEdge& e = body_.edge(edge);
  const int other = stays == e.a ? e.b : e.a;
  const BaseVertex& v = body_.vertex(stays);
  const Eigen::Matrix3d re = Eigen::AngleAxisd(theta, e.axis).toRotationMatrix();
  const Eigen::Matrix3d j = re * v.inertia * re.transpose();
  const Eigen::Vector3d w = omega * e.axis;
  const Eigen::Vector3d w_dot =
      re * v.inertia_inverse * re.transpose() * ((re * v.to_centre).cross(gravity_and_inertia(a_fp)) - w.cross(j * w));
  // The edge's ends lie on the axis: no centripetal term.
  return w_dot.cross(body_.vertex(other).position - v.position).z();
}

Rocking3DModel::Event Rocking3DModel::advance_edge(const GroundInput3& in, double& tau, double tau_end,
                                                   int& lift_vertex) {
  const BaseEdge& edge = body_.edge(contact_);
  const Pivot& pv = edge.pivot;
  const RockingOde ode{&pv, 1, ModelKind::Nonlinear, edge_input(in, contact_)};
  const double t_tol = 1e-12 * std::max(sample_dt_, 1e-6);
  while (tau < tau_end) {
    const double t_start = tau, th_start = theta_, om_start = omega_;
    report_.integrator_steps += dopri5_.step(ode, tau, theta_, omega_, tau_end, settings_.tol,
                                             settings_.tol * pv.alpha, settings_.tol * pv.p * pv.alpha);
    const StepEvents ev = scan_step(
        [this](double t, double& th, double& om) { dopri5_.eval(t, th, om); }, 1, pv.alpha,
        body_.overturn_angle(), dopri5_.t0(), dopri5_.t1(), theta_, omega_, dopri5_.theta1(),
        dopri5_.omega1(), t_tol);
    if (ev.has_peak) {
      report_.peak_ratio = std::max(report_.peak_ratio, ev.peak_abs_theta / pv.alpha);
      if (ev.peak_abs_theta / pv.alpha > outcome_.max_rotation_ratio) {
        outcome_.max_rotation_ratio = ev.peak_abs_theta / pv.alpha;
        outcome_.max_rotation_side = contact_ + 1;
      }
      outcome3_.max_tilt = std::max(outcome3_.max_tilt, ev.peak_abs_theta);
    }
    if (ev.tipping_crossed && !outcome_.beyond_tipping) {
      outcome_.beyond_tipping = true;
      outcome_.beyond_tipping_time = t_ + ev.t_tipping;
      report_.beyond_tipping_entered = true;
    }
    // One end of the edge lifting (the corner wobble begins): checked at the step's end, located
    // on the dense output, before the step's own events when it comes first.
    double t_end_step = dopri5_.t1();
    Event terminal = Event::None;
    if (ev.terminal == StepEvents::Terminal::Impact) { terminal = Event::Impact; t_end_step = ev.t_event; }
    if (ev.terminal == StepEvents::Terminal::Overturn) { terminal = Event::Overturn; t_end_step = ev.t_event; }
    if (ev.terminal == StepEvents::Terminal::Degenerate) { tau = dopri5_.t1(); return Event::Degenerate; }
    {
      double th, om;
      dopri5_.eval(t_end_step, th, om);
      // < 0 when one end lets go: its reaction would have to pull (f < 0) AND, pivoting on the other
      // end alone, it rises (the vertex mode's own acceleration of it, > 0). With sticking contacts
      // the two tests can disagree (the end's friction force is released too); then the edge holds,
      // which keeps the modes from chattering.
      auto lift_margin = [&](double t, double theta, double omega, int& stays) {
        const Eigen::Vector3d a_fp = to_footprint(in.at(t));
        double fa, fb;
        endpoint_reactions(contact_, theta, omega, ode.angular_acceleration(t, theta), a_fp, fa, fb);
        stays = fb < fa ? edge.a : edge.b;
        if (!(fa + fb > 0.0)) return 1.0;
        const double f = std::min(fa, fb);
        if (f >= 0.0) return f;
        return std::max(f, -end_rise(contact_, theta, omega, a_fp, stays));
      };
      int stays = -1;
      // Bounded: after kMaxLiftsPerSample lifts in one sample the edge holds for the rest of it (a
      // body whose end neither holds nor lifts consistently, where the real one slips: flagged by
      // the count in the outcome, never a loop without time advancing).
      const double m1 = lifts_ < kMaxLiftsPerSample ? lift_margin(t_end_step, th, om, stays) : 1.0;
      if (m1 < 0.0) {
        ++lifts_;
        auto f = [&](double t) {
          double a, b;
          dopri5_.eval(t, a, b);
          int s;
          return lift_margin(t, a, b, s);
        };
        const double f0 = f(dopri5_.t0());
        const double t_lift = f0 > 0.0 ? bracketed_root(f, dopri5_.t0(), t_end_step, f0, m1, t_tol)
                                       : dopri5_.t0();
        if (t_lift > t_start) {
          dopri5_.single_step(ode, t_start, th_start, om_start, t_lift - t_start, theta_, omega_);
        } else {
          theta_ = th_start;
          omega_ = om_start;
        }
        dopri5_.invalidate();
        tau = t_lift;
        lift_margin(t_lift, theta_, omega_, stays);
        lift_vertex = stays;  // the end that keeps touching: the new vertex pivot
        return Event::Lift;
      }
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

// ---------------------------------------------------------------- VERTEX

void Rocking3DModel::vertex_rhs(const GroundInput3& in, double t, const Vec7& y, Vec7& dy) const {
  const BaseVertex& v = body_.vertex(contact_);
  const Eigen::Quaterniond q = Eigen::Quaterniond(y(0), y(1), y(2), y(3)).normalized();
  const Eigen::Matrix3d r = q.toRotationMatrix();
  const Eigen::Vector3d w = y.tail<3>();
  const Eigen::Matrix3d j = r * v.inertia * r.transpose();
  const Eigen::Matrix3d j_inv = r * v.inertia_inverse * r.transpose();
  const Eigen::Vector3d torque = (r * v.to_centre).cross(gravity_and_inertia(in.at(t)));
  // Euler's equations about the fixed vertex, in the ground frame: J w' = M - w x J w.
  dy.tail<3>() = j_inv * (torque - w.cross(j * w));
  // q' = 1/2 (0, w) q (w in the world frame).
  const Eigen::Quaterniond wq(0.0, w.x(), w.y(), w.z());
  const Eigen::Quaterniond qd = wq * Eigen::Quaterniond(y(0), y(1), y(2), y(3));
  dy(0) = 0.5 * qd.w();
  dy(1) = 0.5 * qd.x();
  dy(2) = 0.5 * qd.y();
  dy(3) = 0.5 * qd.z();
}

int Rocking3DModel::edge_between(int v, int u) const {
  if (u == body_.next(v)) return v;
  if (v == body_.next(u)) return u;
  return -1;
}

void Rocking3DModel::enter_vertex(int vertex, const Eigen::Vector3d& pivot_world,
                                  const Eigen::Matrix3d& rotation, const Eigen::Vector3d& omega_world) {
  mode_ = Mode3D::Vertex;
  contact_ = vertex;
  pivot_world_ = Eigen::Vector3d(pivot_world.x(), pivot_world.y(), 0.0);
  const Eigen::Quaterniond q(rotation);
  y_ << q.w(), q.x(), q.y(), q.z(), omega_world;
  vector_.invalidate();
  // A vertex on the floor now may only trigger an impact after it has been off the floor (it is
  // an end of the edge just left, or a neighbour of a flat base).
  const double eps = 1e-12 * body_.vertex(vertex).radius;
  for (int i = 0; i < body_.vertex_count(); ++i) {
    const double z = (rotation * (body_.vertex(i).position - body_.vertex(vertex).position)).z();
    armed_[i] = i != vertex && z > eps;
  }
}

void Rocking3DModel::enter_vertex_from_edge(int vertex) {
  const BaseEdge& e = body_.edge(contact_);
  const Eigen::Matrix3d r = yaw_matrix() * Eigen::AngleAxisd(theta_, e.axis).toRotationMatrix();
  const Eigen::Vector3d w = yaw_matrix() * (omega_ * e.axis);
  const Eigen::Vector3d p =
      yaw_matrix() * body_.vertex(vertex).position + Eigen::Vector3d(shift_.x(), shift_.y(), 0.0);
  ++outcome3_.edge_to_vertex;
  enter_vertex(vertex, p, r, w);
}

// The body rests on edge `edge` (both ends on the floor) with pose `rotation` and angular velocity
// omega_axis about the edge: the footprint (yaw, shift) and theta follow from the pose.
void Rocking3DModel::enter_edge_from_pose(int edge, const Eigen::Matrix3d& rotation,
                                          const Eigen::Vector3d& pivot_world, int pivot_vertex,
                                          double omega_axis) {
  const BaseEdge& e = body_.edge(edge);
  Eigen::Vector3d axis_w = rotation * e.axis;
  axis_w.z() = 0.0;  // both ends on the floor (to the event tolerance)
  axis_w.normalize();
  const Eigen::Vector3d normal_w = axis_w.cross(Eigen::Vector3d::UnitZ());
  const Eigen::Vector3d base_normal = rotation.col(2);
  const double theta = std::max(0.0, std::atan2(base_normal.dot(normal_w), base_normal.z()));
  const Eigen::Matrix3d flat = Eigen::AngleAxisd(-theta, axis_w).toRotationMatrix() * rotation;
  yaw_ = std::atan2(flat(1, 0), flat(0, 0));
  // The pivot vertex keeps its place on the floor.
  const Eigen::Vector3d placed = yaw_matrix() * body_.vertex(pivot_vertex).position;
  shift_ = Eigen::Vector2d(pivot_world.x() - placed.x(), pivot_world.y() - placed.y());
  mode_ = Mode3D::Edge;
  contact_ = edge;
  theta_ = theta;
  omega_ = omega_axis;
  dopri5_.invalidate();
}

Rocking3DModel::Event Rocking3DModel::advance_vertex(const GroundInput3& in, double& tau, double tau_end,
                                                     int& touching) {
  const double t_tol = 1e-12 * std::max(sample_dt_, 1e-6);
  const double alpha = body_.min_alpha(), p = body_.max_p();
  Vec7 atol;
  atol << Eigen::Vector4d::Constant(settings_.tol * alpha), Eigen::Vector3d::Constant(settings_.tol * p * alpha);
  auto f = [&](double t, const Vec7& y, Vec7& dy) { vertex_rhs(in, t, y, dy); };
  const int n = body_.vertex_count();
  const BaseVertex& pivot = body_.vertex(contact_);
  const double eps = 1e-12 * pivot.radius;
  const double sink = 1e-9 * pivot.radius;  // an unarmed vertex this far below the floor touches down
  const double cos_over = std::cos(body_.overturn_angle());
  auto height = [&](const Vec7& y, int i) {
    return (vertex_rotation(y) * (body_.vertex(i).position - pivot.position)).z();
  };
  while (tau < tau_end) {
    report_.integrator_steps += vector_.step(f, tau, y_, tau_end, settings_.tol, atol);
    const double t0 = vector_.t0(), t1 = vector_.t1();
    // The first touchdown of an armed vertex or the overturn inside the step, on the dense
    // output, probed at quarter steps so that a grazing dip inside the step is not missed.
    double t_event = std::numeric_limits<double>::infinity();
    Event event = Event::None;
    touching = -1;
    constexpr int kProbes = 4;
    for (int i = 0; i < n; ++i) {
      if (i == contact_) continue;
      double ta = t0, za = height(y_, i);
      for (int k = 1; k <= kProbes; ++k) {
        const double tb = k == kProbes ? t1 : t0 + (t1 - t0) * k / kProbes;
        const double zb = height(k == kProbes ? vector_.y1() : Vec7(vector_.eval(tb)), i);
        const bool armed = armed_[i] || za > eps;
        // An unarmed vertex that sinks clearly below the floor is a touchdown too (the pivot
        // turned the wrong way for the vertex it left): resolved as an impact.
        if ((armed && zb <= 0.0 && za > 0.0) || zb < -sink) {
          const double te = za > 0.0 ? bracketed_root(
                                           [&](double t) { return height(Vec7(vector_.eval(t)), i); },
                                           ta, tb, za, zb, t_tol)
                                     : ta;
          if (te < t_event) {
            t_event = te;
            event = Event::Impact;
            touching = i;
          }
          break;
        }
        ta = tb;
        za = zb;
      }
    }
    {
      const double c1 = vertex_rotation(vector_.y1())(2, 2) - cos_over;
      if (c1 <= 0.0) {
        const double c0 = vertex_rotation(y_)(2, 2) - cos_over;
        const double te = c0 > 0.0 ? bracketed_root(
                                         [&](double t) { return vertex_rotation(Vec7(vector_.eval(t)))(2, 2) - cos_over; },
                                         t0, t1, c0, c1, t_tol)
                                   : t0;
        if (te < t_event) {
          t_event = te;
          event = Event::Overturn;
        }
      }
    }
    if (event == Event::None) {
      y_ = vector_.y1();
      y_.head<4>().normalize();
      tau = t1;
      for (int i = 0; i < n; ++i)
        if (!armed_[i] && i != contact_ && height(y_, i) > eps) armed_[i] = true;
      note_ratio();
      continue;
    }
    y_ = vector_.eval(t_event);
    y_.head<4>().normalize();
    vector_.invalidate();
    tau = t_event;
    note_ratio();
    return event;
  }
  return Event::None;
}

// ---------------------------------------------------------------- impacts

void Rocking3DModel::record_impact(double tau, double energy_before) {
  if (report_.impacts == 0) report_.first_impact_time = t_ + tau;
  ++report_.impacts;
  ++outcome_.impacts;
  const double after = kinetic_energy();
  if (energy_before > 0.0)
    outcome3_.max_impact_energy_ratio = std::max(outcome3_.max_impact_energy_ratio, after / energy_before);
}

// The base lands flat (EDGE, theta back to 0). Housner's rule in 3-D: the part of the base that
// strikes hardest (the vertex or edge farthest from the old edge) takes the impulse; the body
// then turns about it with its angular momentum about it conserved, or comes to rest.
void Rocking3DModel::flat_impact(double tau) {
  ++outcome3_.flat_impacts;
  const double before = kinetic_energy();
  const BaseEdge& old = body_.edge(contact_);
  const Eigen::Vector3d w = omega_ * old.axis;  // footprint frame (flat pose: rotation = yaw)
  const Eigen::Vector3d& c = body_.centre_of_mass();
  const Eigen::Vector3d& p_old = body_.vertex(old.a).position;
  const Eigen::Matrix3d& jc = body_.central_inertia_per_mass();
  const int n = body_.vertex_count();
  double far = -1.0;
  for (int i = 0; i < n; ++i) far = std::max(far, -(body_.vertex(i).position - p_old).dot(old.normal));
  int first = -1, second = -1;
  for (int i = 0; i < n; ++i) {
    const double d = -(body_.vertex(i).position - p_old).dot(old.normal);
    if (d >= far * (1.0 - 1e-9)) (first < 0 ? first : second) = i;
  }
  const double kappa = body_.restitution_factor();
  auto rock_about_edge = [&](int k) {
    const BaseEdge& e = body_.edge(k);
    const Eigen::Vector3d h = angular_momentum_about(jc, w, c, p_old, body_.vertex(e.a).position);
    const double w_new = kappa * e.axis.dot(h) / e.pivot.inertia;
    if (!(w_new > 0.0) || w_new < settings_.rest_capture_ratio * e.pivot.p * e.pivot.alpha) {
      go_to_rest();
      report_.rest_capture = true;
      ++outcome_.rest_captures;
      return;
    }
    mode_ = Mode3D::Edge;
    contact_ = k;
    theta_ = 0.0;
    omega_ = w_new;
    dopri5_.invalidate();
  };
  int edge = second >= 0 ? edge_between(first, second) : -1;
  if (edge < 0) {
    const BaseVertex& v = body_.vertex(first);
    const Eigen::Vector3d h = angular_momentum_about(jc, w, c, p_old, v.position);
    const Eigen::Vector3d w_v = kappa * (v.inertia_inverse * h);
    // A neighbour pushed into the floor joins the contact: the body rocks about that edge.
    double worst = 0.0;
    for (int m : {body_.previous(first), body_.next(first)}) {
      const double vz = w_v.cross(body_.vertex(m).position - v.position).z();
      if (vz < worst) {
        worst = vz;
        edge = edge_between(first, m);
      }
    }
    if (edge < 0) {
      const double tip = kGravity * (v.radius - v.to_centre.z());
      if (rotation_energy(v.inertia, w_v) <
          settings_.rest_capture_ratio * settings_.rest_capture_ratio * tip) {
        go_to_rest();
        report_.rest_capture = true;
        ++outcome_.rest_captures;
      } else {
        enter_vertex(first, yaw_matrix() * v.position + Eigen::Vector3d(shift_.x(), shift_.y(), 0.0),
                     yaw_matrix(), yaw_matrix() * w_v);
      }
      record_impact(tau, before);
      return;
    }
  }
  rock_about_edge(edge);
  record_impact(tau, before);
}

// Pivoting on a vertex, vertex `touching` (a neighbour) reaches the floor: the base now lies on
// the edge between them, tilted. The new vertex takes the impulse; if the old pivot then lifts,
// the body pivots on the new vertex, else it rocks about the edge.
void Rocking3DModel::vertex_impact(int touching, double tau) {
  ++outcome3_.vertex_impacts;
  const double before = kinetic_energy();
  const int old = contact_;
  const Eigen::Matrix3d r = vertex_rotation(y_);
  const Eigen::Vector3d w = y_.tail<3>();
  const Eigen::Vector3d c = pivot_world_ + r * body_.vertex(old).to_centre;
  Eigen::Vector3d q = pivot_world_ + r * (body_.vertex(touching).position - body_.vertex(old).position);
  q.z() = 0.0;
  const Eigen::Matrix3d jc = r * body_.central_inertia_per_mass() * r.transpose();
  const Eigen::Vector3d h = angular_momentum_about(jc, w, c, pivot_world_, q);
  const double kappa = body_.restitution_factor();
  const BaseVertex& nv = body_.vertex(touching);
  const Eigen::Vector3d w_v = kappa * (r * nv.inertia_inverse * r.transpose() * h);
  const int edge = edge_between(old, touching);
  // Rest capture (the Zeno rule of the planar engine, by energy): the base lands almost flat with
  // almost no energy left, e.g. a body see-sawing on two corners as it comes to rest.
  const double tilt_now = std::acos(std::clamp(r(2, 2), -1.0, 1.0));
  const double tip = kGravity * (nv.radius - nv.to_centre.z());
  if (tilt_now < settings_.rest_capture_ratio * body_.min_alpha() &&
      rotation_energy(r * nv.inertia * r.transpose(), w_v) <
          settings_.rest_capture_ratio * settings_.rest_capture_ratio * tip) {
    yaw_ = std::atan2(r(1, 0), r(0, 0));
    const Eigen::Vector3d placed = yaw_matrix() * nv.position;
    shift_ = Eigen::Vector2d(q.x() - placed.x(), q.y() - placed.y());
    go_to_rest();
    report_.rest_capture = true;
    ++outcome_.rest_captures;
    record_impact(tau, before);
    return;
  }
  const bool old_lifts = w_v.cross(pivot_world_ - q).z() >= 0.0;
  if (old_lifts || edge < 0) {
    enter_vertex(touching, q, r, w_v);
  } else {
    const BaseEdge& e = body_.edge(edge);
    const Eigen::Vector3d axis_w = r * e.axis;
    const double w_e = kappa * axis_w.dot(h) / e.pivot.inertia;
    enter_edge_from_pose(edge, r, q, touching, w_e);
  }
  record_impact(tau, before);
}

// ---------------------------------------------------------------- REST -> motion

double Rocking3DModel::find_uplift(const GroundInput3& in, double tau, double tau_end) const {
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < body_.vertex_count(); ++k) {
    const double u0 = uplift_at(in, k, tau), u1 = uplift_at(in, k, tau_end);
    double when;
    if (u0 > 0.0) when = tau;
    else if (u1 > 0.0) when = std::clamp(tau + (tau_end - tau) * (-u0) / (u1 - u0), tau, tau_end);
    else continue;
    const RockingOde ode{&body_.edge(k).pivot, 1, ModelKind::Nonlinear, edge_input(in, k)};
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
  for (int k = 0; k < body_.vertex_count(); ++k) {
    const RockingOde ode{&body_.edge(k).pivot, 1, ModelKind::Nonlinear, edge_input(in, k)};
    const double acc = ode.angular_acceleration(tau, 0.0);
    if (acc > best_acc || best < 0) {
      best_acc = acc;
      best = k;
    }
  }
  report_.uplift = true;
  if (std::isnan(outcome_.uplift_time)) outcome_.uplift_time = t_ + tau;
  const BaseEdge& e = body_.edge(best);
  double fa, fb;
  endpoint_reactions(best, 0.0, 0.0, best_acc, a_fp, fa, fb);
  int vertex = -1;
  if (fa + fb > 0.0 && std::min(fa, fb) < 0.0) vertex = fb < fa ? e.a : e.b;
  if (vertex < 0) {
    mode_ = Mode3D::Edge;
    contact_ = best;
    theta_ = omega_ = 0.0;
    dopri5_.invalidate();
    return;
  }
  // Pivoting on the vertex from rest: check that neither neighbour is pushed into the floor.
  const BaseVertex& v = body_.vertex(vertex);
  const Eigen::Vector3d w_dot = v.inertia_inverse * v.to_centre.cross(g);
  for (int m : {body_.previous(vertex), body_.next(vertex)}) {
    if (w_dot.cross(body_.vertex(m).position - v.position).z() < 0.0) {
      mode_ = Mode3D::Edge;  // the reactions' sign was rounding: keep the edge
      contact_ = best;
      theta_ = omega_ = 0.0;
      dopri5_.invalidate();
      return;
    }
  }
  enter_vertex(vertex, yaw_matrix() * v.position + Eigen::Vector3d(shift_.x(), shift_.y(), 0.0),
               yaw_matrix(), Eigen::Vector3d::Zero());
}

// ---------------------------------------------------------------- the sample

const StepReport& Rocking3DModel::step(const Eigen::Vector3d& a, double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt) || !a.allFinite())
    throw std::invalid_argument("Rocking3DModel::step: dt must be finite and > 0 and the acceleration finite");
  report_ = StepReport{};
  sample_dt_ = dt;
  lifts_ = 0;
  GroundInput3 in;
  in.a0 = a_prev_;
  in.slope = (a - a_prev_) / dt;
  double tau = 0.0;
  int events = 0;
  while (tau < dt && mode_ != Mode3D::Overturned) {
    if (mode_ == Mode3D::Rest) {
      const double when = find_uplift(in, tau, dt);
      if (!std::isfinite(when)) break;
      tau = when;
      start_motion(in, tau);
      ++events;
    }
    Event e = Event::None;
    int other = -1;
    if (mode_ == Mode3D::Edge) e = advance_edge(in, tau, dt, other);
    else if (mode_ == Mode3D::Vertex) e = advance_vertex(in, tau, dt, other);
    if (e == Event::None) break;
    if (e == Event::Overturn) {
      note_ratio();
      mode_ = Mode3D::Overturned;
      outcome_.overturned = true;
      outcome_.overturn_time = t_ + tau;
      report_.overturned = true;
      break;
    }
    if (e == Event::Degenerate) {
      go_to_rest();
      report_.rest_capture = true;
      ++outcome_.rest_captures;
    } else if (e == Event::Lift) {
      enter_vertex_from_edge(other);
    } else if (mode_ == Mode3D::Edge) {
      flat_impact(tau);
    } else {
      vertex_impact(other, tau);
    }
    if (++events >= settings_.max_events_per_sample) {
      // Bounded work per sample: the body is put down flat for the rest of the sample.
      go_to_rest();
      report_.forced_rest = true;
      ++outcome_.forced_rest_captures;
      break;
    }
  }
  if (mode_ == Mode3D::Edge && !outcome_.committed) {
    const OverturnMargin m = overturn_margin(body_.edge(contact_).pivot, 1, ModelKind::Nonlinear, theta_, omega_);
    if (m.committed) {
      outcome_.committed = true;
      outcome_.committed_time = t_ + dt;
      report_.committed_entered = true;
    }
  } else if (mode_ == Mode3D::Vertex && !outcome_.committed && probe_ && t_ + dt - last_probe_t_ >= kProbeInterval &&
             margin().committed) {
    last_probe_t_ = t_ + dt;
    if (falls_if_shaking_stops(t_ + dt)) {
      outcome_.committed = true;
      outcome_.committed_time = t_ + dt;
      report_.committed_entered = true;
    }
  } else if (mode_ == Mode3D::Overturned && !outcome_.committed) {
    outcome_.committed = true;
    outcome_.committed_time = outcome_.overturn_time;
    report_.committed_entered = true;
  }
  t_ += dt;
  a_prev_ = a;
  ++outcome_.samples;
  outcome_.integrator_steps += report_.integrator_steps;
  return report_;
}

}  // namespace rocking_monitor::core
