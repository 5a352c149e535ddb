// Slide-rock on a vertex (issue 51 part 2): the body pivots on a hull vertex that slips on the floor.
// Per unit mass, with c the vertex-to-centre vector, w the angular velocity, u the vertex's velocity on
// the floor and lambda the normal force: Newton  a_c = g + lambda d,  d = (-mu_k u/|u|, 1);  Euler about
// the centre  J_c w' + w x J_c w = -c x lambda d;  the vertex stays on the floor  a_c = (u', 0) + w' x c
// + w x (w x c). Linear in lambda: one equation for it, then w' and u'. (A non-negative coefficient of
// lambda is Painleve's paradox: no consistent normal force; reported as a lift.) The slip ends where its
// velocity reverses (then the static law decides: stick, or slip on the other way) or the normal force
// vanishes (flight, not modelled: followed as sticking, counted).
#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "rocking_3d_internal.hpp"
#include "rocking_monitor/integrate/event_location.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"

namespace rocking_monitor::core {

using rocking_3d::gravity_and_inertia;

namespace {
// Below this speed (m/s) the slip's direction is the one it started or restarted with.
constexpr double kSlipSpeedFloor = 1e-12;
}  // namespace

// Returns lambda (m/s^2); w_dot (rad/s^2) and u_dot (m/s^2) in the world frame; friction against `dir`.
double Rocking3DModel::slip_accelerations(const GroundInput3& in, double t, const Vec11& y, const Eigen::Vector2d& dir,
                                          Eigen::Vector3d& w_dot, Eigen::Vector2d& u_dot) const {
  const Eigen::Matrix3d r = vertex_rotation(Vec7(y.head<7>()));
  const Eigen::Vector3d c = r * hv(contact_).to_centre;
  const Eigen::Vector3d w = y.segment<3>(4);
  const Eigen::Vector3d d(-mu_k() * dir.x(), -mu_k() * dir.y(), 1.0);
  // (the inertia turned by r applied as r J r^T x: matrix-vector products only, the per-stage cost)
  const Eigen::Matrix3d& jb = body_.central_inertia_per_mass();
  const Eigen::Vector3d jw = r * (jb * (r.transpose() * w));
  const Eigen::Vector3d a = r * (central_inverse_ * (r.transpose() * (-c).cross(d)));  // w' per unit lambda
  const Eigen::Vector3d b = -(r * (central_inverse_ * (r.transpose() * w.cross(jw))));  // w' without it
  const Eigen::Vector3d centripetal = w.cross(w.cross(c));
  const Eigen::Vector3d g = gravity_and_inertia(in.at(t));
  const double coefficient = a.cross(c).z() - 1.0;
  const double lambda = coefficient < 0.0 ? (g.z() - b.cross(c).z() - centripetal.z()) / coefficient : -1.0;
  w_dot = lambda * a + b;
  u_dot = (g + lambda * d - w_dot.cross(c) - centripetal).head<2>();
  return lambda;
}

double Rocking3DModel::slip_dynamics(const GroundInput3& in, double t, const Vec11& y, Eigen::Vector3d& w_dot,
                                     Eigen::Vector2d& u_dot) const {
  // Past the stop inside a step (the slip turned against its direction at the step's start) the law
  // keeps that direction: the right-hand side stays smooth through the stop, whose root the dense
  // output then locates (as the flat slide does, rocking_3d_slide.cpp).
  const Eigen::Vector2d u = y.segment<2>(9);
  const double speed = u.norm();
  const Eigen::Vector2d dir = speed > kSlipSpeedFloor && u.dot(slip_ref_) > 0.0 ? Eigen::Vector2d(u / speed)
                                                                               : Eigen::Vector2d(slip_ref_.normalized());
  const double l = slip_accelerations(in, t, y, dir, w_dot, u_dot);
  return l;
}

// From a standstill the slip starts along a direction it accelerates along (u' = s dir, s > 0): a root
// in the direction's angle of dir x u'(dir), scanned and bisected; of several, the one nearest `guess`
// (against the friction the held pivot needed). None found: the guess.
Eigen::Vector2d Rocking3DModel::starting_slip_direction(const GroundInput3& in, double t, const Eigen::Vector2d& guess) const {
  constexpr int kScan = 24;
  Vec11 y;
  y << y_, pivot_world_.x(), pivot_world_.y(), 0.0, 0.0;
  auto at_dir = [&](const Eigen::Vector2d& dir, double& along) {
    Eigen::Vector3d w_dot;
    Eigen::Vector2d u_dot;
    slip_accelerations(in, t, y, dir, w_dot, u_dot);
    along = dir.dot(u_dot);
    return dir.x() * u_dot.y() - dir.y() * u_dot.x();
  };
  auto at = [&](double phi, double& along) { return at_dir(Eigen::Vector2d(std::cos(phi), std::sin(phi)), along); };
  // (the scan turns its direction by a fixed rotation: no sine or cosine per probe)
  const Eigen::Rotation2Dd turn(2 * kPi / kScan);
  const double phi0 = std::atan2(guess.y(), guess.x());
  double along = 0.0, best_gap = std::numeric_limits<double>::infinity();
  Eigen::Vector2d best = guess;
  Eigen::Vector2d probe = guess.normalized();
  double fa = at_dir(probe, along);
  for (int k = 1; k <= kScan; ++k) {
    const double pa = phi0 + 2 * kPi * (k - 1) / kScan, pb = phi0 + 2 * kPi * k / kScan;
    probe = turn * probe;
    const double fb = at_dir(probe, along);
    if ((fa <= 0.0) != (fb <= 0.0)) {
      const double phi = bracketed_root([&](double q) { double s; return at(q, s); }, pa, pb, fa, fb, 1e-12);
      const double gap = std::min(phi - phi0, 2 * kPi - (phi - phi0));
      at(phi, along);
      if (along > 0.0 && gap < best_gap) {
        best_gap = gap;
        best = Eigen::Vector2d(std::cos(phi), std::sin(phi));
      }
    }
    fa = fb;
  }
  return best;
}

void Rocking3DModel::slip_rhs(const GroundInput3& in, double t, const Vec11& y, Vec11& dy) const {
  Eigen::Vector3d w_dot;
  Eigen::Vector2d u_dot;
  slip_dynamics(in, t, y, w_dot, u_dot);
  dy.head<4>() = rocking_3d::quaternion_rate(Eigen::Vector3d(y.segment<3>(4)), y);
  dy.segment<3>(4) = w_dot;
  dy.segment<2>(7) = y.segment<2>(9);
  dy.segment<2>(9) = u_dot;
}

// At the onset (watch_pivot located it; y_ is the state there): the slip starts from rest against the
// friction the sticking pivot needed.
void Rocking3DModel::begin_slip(const GroundInput3& in, double tau) {
  const Eigen::Vector3d f = vertex_reaction(in, tau, y_);
  const Eigen::Vector2d fh = f.head<2>();
  slip_dir_ = starting_slip_direction(in, tau, fh.norm() > 0.0 ? Eigen::Vector2d(-fh / fh.norm()) : Eigen::Vector2d::UnitX());
  ys_ << y_, pivot_world_.x(), pivot_world_.y(), 0.0, 0.0;
  if (slip_presses_neighbour(in, tau) || point_lip_gap(pivot_world_.head<2>(), slip_dir_) <= 10.0 * floor_tol_) {
    // (or the slip would carry the pivot over a lip it lies against: the lip holds it)
    // The slip would drive a base point lying on the floor into it (the body turning onto an edge:
    // slide-rock on an edge, not modelled): held, for the rest of the sample, counted.
    ++outcome3_.pivot_slips_not_followed;
    slip_switches_ = kMaxSlipSwitches;
    pivot_outside_cone_ = true;
    return;
  }
  pivot_slipping_ = true;
  slip_stepper_.invalidate();
}

// Whether a hull vertex on the floor beside the pivot would move down, the pivot starting to slip.
bool Rocking3DModel::slip_presses_neighbour(const GroundInput3& in, double tau) const {
  Eigen::Vector3d w_dot;
  Eigen::Vector2d u_dot;
  slip_accelerations(in, tau, ys_, slip_dir_, w_dot, u_dot);
  const Eigen::Matrix3d r = vertex_rotation(y_);
  const Eigen::Vector3d w = y_.tail<3>();
  const double eps = 3.0 * floor_tol_;
  for (int i : hull().neighbours[static_cast<std::size_t>(contact_)]) {
    const Eigen::Vector3d d = r * (hv(i).position - hv(contact_).position);
    if (d.z() > eps) continue;
    const double v = w.cross(d).z(), a = (w_dot.cross(d) + w.cross(w.cross(d))).z();
    if (v < 0.0 || (v == 0.0 && a < 0.0) || (std::abs(v) < 1e-12 && a < 0.0)) return true;
  }
  return false;
}

// The stop event's reference at a step's start: the slip's velocity, or from a standstill its direction.
void Rocking3DModel::aim_slip_ref() {
  const Eigen::Vector2d u = ys_.segment<2>(9);
  slip_ref_ = u.norm() > kSlipSpeedFloor ? u : slip_dir_;
}

// y_, pivot_world_ from the slipping state: every measure of the vertex mode reads them.
void Rocking3DModel::sync_slip() {
  y_ = ys_.head<7>();
  pivot_world_ = Eigen::Vector3d(ys_(7), ys_(8), 0.0);
}

// The first instant in [t0, t1] (dense output valid) where the slip reverses (its velocity turns
// against that at t0) or the normal force vanishes (lifts); NaN if neither.
double Rocking3DModel::slip_end(const GroundInput3& in, double t0, double t1, double t_tol, bool& lifts) const {
  auto lambda_at = [&](double t) {
    Eigen::Vector3d w_dot;
    Eigen::Vector2d u_dot;
    Vec11 y = slip_stepper_.eval(t);
    y.head<4>().normalize();
    return slip_dynamics(in, t, y, w_dot, u_dot);
  };
  auto along = [&](double t) { return Eigen::Vector2d(slip_stepper_.eval(t).segment<2>(9)).dot(slip_ref_); };
  double best = std::numeric_limits<double>::infinity();
  const double l1 = lambda_at(t1);
  if (!(l1 > 0.0)) {
    const double l0 = lambda_at(t0);
    best = l0 > 0.0 ? bracketed_root(lambda_at, t0, t1, l0, l1, t_tol) : t0;
    lifts = true;
  }
  auto earlier = [&](double t) {
    if (t < best) {
      best = t;
      lifts = false;
    }
  };
  {
    // (from a standstill the slip grows along slip_dir_: along(t0) = 0, then > 0)
    const double a1 = along(t1), a0 = along(t0);
    if (!(a1 > 0.0)) earlier(a0 > 0.0 ? bracketed_root(along, t0, t1, a0, a1, t_tol) : t0);
  }
  {
    // A slip that dies away without reversing (its direction turning as it fades: the 2-D law's
    // approach to sticking, stiff near zero speed): stopped once its speed falls below stop_speed_.
    auto fade = [&](double t) { return Eigen::Vector2d(slip_stepper_.eval(t).segment<2>(9)).norm() - stop_speed_; };
    const double s0 = fade(t0), s1 = fade(t1);
    if (s0 > 0.0 && !(s1 > 0.0)) earlier(bracketed_root(fade, t0, t1, s0, s1, t_tol));
  }
  if (!body_.parameters().support_lips.empty()) {
    // The slipping pivot reaching a lip stops there (end_slip: it sticks, or is held, counted).
    auto gap = [&](double t) {
      const Vec11 y = slip_stepper_.eval(t);
      return point_lip_gap(y.segment<2>(7), slip_ref_) + floor_tol_;
    };
    const double g0 = gap(t0), g1 = gap(t1);
    if (g0 > 0.0 && !(g1 > 0.0)) earlier(bracketed_root(gap, t0, t1, g0, g1, t_tol));
  }
  if (!std::isfinite(best)) {
    // Slower than stop_speed_ at the step's end and not speeding up (a slip that never grew, or faded
    // there): it has stopped; end_slip() decides what follows.
    Vec11 y = slip_stepper_.eval(t1);
    y.head<4>().normalize();
    Vec11 dy;
    slip_rhs(in, t1, y, dy);
    const Eigen::Vector2d u = y.segment<2>(9);
    if (u.norm() <= stop_speed_ && !(u.dot(dy.segment<2>(9)) > 0.0)) {
      best = t1;
      lifts = false;
    }
  }
  return std::isfinite(best) ? best : std::numeric_limits<double>::quiet_NaN();
}

// The slip stopped (its velocity is put to zero there) or the pivot lifts: stick where the static law
// holds, else slip on the other way; a lift goes on as sticking (flight is not modelled).
void Rocking3DModel::end_slip(const GroundInput3& in, double tau, bool lifts) {
  pivot_slipping_ = false;
  if (lifts) {
    ++outcome3_.pivot_lifts;
    pivot_outside_cone_ = true;
    note_transition(Mode3D::Vertex, Transition3D::PivotLifts, tau);
    vector_.invalidate();
    return;
  }
  if (cone_margin(vertex_reaction(in, tau, y_)) >= 0.0 || slip_switches_ >= kMaxSlipSwitches) {
    hold_slip(in, tau);
    return;
  }
  ++slip_switches_;
  begin_slip(in, tau);
}

// The pivot held from here: it sticks (the static law holds), or the sample's bound on slips or steps
// was reached (counted; the onset is not counted again until the reaction comes back inside the cone).
void Rocking3DModel::hold_slip(const GroundInput3& in, double tau) {
  pivot_slipping_ = false;
  const bool outside = cone_margin(vertex_reaction(in, tau, y_)) < 0.0;
  if (outside) ++outcome3_.pivot_slips_not_followed;
  else ++outcome3_.pivot_sticks;
  note_transition(Mode3D::Vertex, Transition3D::PivotSticks, tau);
  pivot_outside_cone_ = outside;
  vector_.invalidate();
}

}  // namespace rocking_monitor::core
