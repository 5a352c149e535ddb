// The 3-D model sliding flat on a face (issue 51): slip onset from rest, sliding and turning under one
// isotropic Coulomb law over the face's contact polygon, stick, and the lift that ends a slide.
#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "rocking_3d_internal.hpp"
#include "rocking_monitor/integrate/event_location.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/physics/criteria.hpp"

namespace rocking_monitor::core {

using rocking_3d::rot2;

namespace {

Eigen::Vector2d perp2(const Eigen::Vector2d& a) { return Eigen::Vector2d(-a.y(), a.x()); }  // z x a

// How far the demand of the static law lies outside the friction cone: |a_h| - mu (g + a_z), m/s^2
// (> 0: the floor cannot hold the body). Convex in the input, so along a sample's linear input it
// turns positive at most once.
double cone_excess(const Eigen::Vector3d& a, double mu) {
  return std::hypot(a.x(), a.y()) - mu * (kGravity + a.z());
}

constexpr int kMaxSlideRestarts = 8;  // per sample: slips that reverse through zero speed
constexpr double kSlipFloorPerTol = 100.0;  // m/s per unit tol: the slip velocity error resolved (advance_slide)

}  // namespace

Eigen::Vector2d Rocking3DModel::slip() const {
  const Eigen::Vector3d c = body_.centre_of_mass();
  return (rotation() * c + translation() - c).head<2>();
}

void Rocking3DModel::set_slide_state(const Eigen::Vector2d& u, double spin) {
  if (!u.allFinite() || !std::isfinite(spin) || face_ != 0 || (mode_ != Mode3D::Rest && mode_ != Mode3D::Slide))
    throw std::invalid_argument("set_slide_state: flat on the base, finite velocity and spin");
  mode_ = Mode3D::Slide;
  contact_ = -1;
  slide_ << u.x(), u.y(), spin, shift_.x(), shift_.y(), yaw_;
  slide_stepper_.invalidate();
}

// REST -> SLIDE: the first instant the static law's demand leaves the cone |a_h| <= mu_s (g + a_z).
double Rocking3DModel::find_slip(const GroundInput3& in, double tau, double tau_end) const {
  const double mu = body_.parameters().mu_s;
  const double inf = std::numeric_limits<double>::infinity();
  if (!std::isfinite(mu) || slide_lifts_ > 0) return inf;
  const bool lips = !body_.parameters().support_lips.empty();
  auto f = [&](double t) { return lips ? static_excess(in.at(t), mu) : cone_excess(in.at(t), mu); };
  const double f0 = f(tau);
  if (f0 > 0.0) return tau;
  const double f1 = f(tau_end);
  if (!(f1 > 0.0)) return inf;  // convex, <= 0 at both ends: inside all through the sample
  return bracketed_root(f, tau, tau_end, f0, f1, 1e-15 * std::max(tau_end, 1e-9), 200);
}

// cone_excess with the lips the base lies against taking their part of the demand (lip_demand).
double Rocking3DModel::static_excess(const Eigen::Vector3d& a, double mu) const {
  if (body_.parameters().support_lips.empty()) return cone_excess(a, mu);
  const Eigen::Vector2d d = lip_demand(a);
  return std::hypot(d.x(), d.y()) - mu * (kGravity + a.z());  // (as cone_excess: the same where no lip takes part)
}

void Rocking3DModel::start_slide(double tau) {
  mode_ = Mode3D::Slide;
  contact_ = -1;
  lip_held_ = -1;
  slide_ << 0.0, 0.0, 0.0, shift_.x(), shift_.y(), yaw_;
  slide_stepper_.reset(sample_dt_);  // (a step size left from an event's bracket would start it crawling)
  ++outcome3_.slides;
  if (std::isnan(outcome3_.first_slip_time)) outcome3_.first_slip_time = t_ + tau;
}

// Friction per unit mass on the body (world frame, m/s^2) and its torque about the vertical through
// the centre of mass (per unit mass, m^2/s^2), for the state y at local time t.
namespace {

// At zero slip the body starts to slip where the ground pulls away from it; friction follows the
// ground, at most mu_k N (it is more only when mu_k > mu_s and the body then moves with it).
Eigen::Vector2d ground_following_friction(const Eigen::Vector2d& ah, double cap) {
  const double n = ah.norm();
  return n > 0.0 ? Eigen::Vector2d(ah * std::min(1.0, cap / n)) : Eigen::Vector2d::Zero();
}

}  // namespace

Eigen::Vector2d Rocking3DModel::slide_friction(const GroundInput3& in, double t, const Vec6& y,
                                               double& torque) const {
  torque = 0.0;
  const Eigen::Vector3d a = in.at(t);
  const double normal = std::max(kGravity + a.z(), 0.0);  // N / m; 0: the floor drops away (flight)
  if (normal == 0.0) return Eigen::Vector2d::Zero();
  const double mu = mu_k(), cap = mu * normal;
  Eigen::Vector2d u = y.head<2>();
  double spin = y(2);
  // Past the stop inside a step (the slip turned against its direction at the step's start, or is
  // still zero), the law keeps that direction: the right-hand side stays smooth up to the stop, so
  // the stepper's dense output locates it exactly (polynomial motion under linear input is exact).
  const double rho = spin != 0.0 || slide_ref_.z() != 0.0 ? std::sqrt(fb().central_inertia_per_mass()(2, 2)) : 1.0;
  if (slide_ref_.squaredNorm() > 0.0 && slide_ref_.dot(Eigen::Vector3d(u.x(), u.y(), rho * spin)) <= 0.0) {
    u = slide_ref_.head<2>();
    spin = slide_ref_.z() / rho;
  }
  if (spin == 0.0) {
    const double speed = u.norm();
    if (speed > 0.0) return -cap * u / speed;  // at the centre of pressure: no torque (see the docs)
    return ground_following_friction(held_demand(a), cap);
  }
  // Turning: the centre of pressure d (from the centre of mass, footprint frame) solves the moment
  // equations about the centre of mass (friction acts at the floor, h below it; the turning body's
  // gyroscopic moment), which depend on d through the pressure: Newton's method on the 2-D residual,
  // its Jacobian by differences, to 1e-10 of the base (a fixed-point iteration does not contract for
  // every body). The first guess is continuous in (u, spin), the pure slide's mu h u / |u| scaled by
  // how much of the motion is slip: a guess that jumped with the slip's direction would make the law
  // jump with it wherever the iteration stops short.
  const Eigen::Matrix2d r = rot2(y(5));
  const Eigen::Vector2d u_fp = r.transpose() * u;
  const Eigen::Vector3d& c = fb().centre_of_mass();
  const Eigen::Vector2d cxy = c.head<2>();
  const double h = c.z();
  const Eigen::Matrix3d& j = fb().central_inertia_per_mass();
  const BaseFriction& fr = friction_[static_cast<std::size_t>(face_)];
  Eigen::Vector2d f = Eigen::Vector2d::Zero();
  auto residual = [&](const Eigen::Vector2d& d) {
    const FrictionLoad l = fr.load(u_fp, spin, cxy, cxy + d);
    f = cap * l.force;
    torque = cap * l.torque;
    const Eigen::Vector3d m = torque / j(2, 2) * j.col(2) + spin * spin * Eigen::Vector3d::UnitZ().cross(j.col(2));
    return Eigen::Vector2d(Eigen::Vector2d(-(m.y() + h * f.x()), m.x() - h * f.y()) / normal - d);
  };
  const double scale = std::sqrt(fr.area()), eps = 1e-7 * scale;
  Eigen::Vector2d d = mu * h * u_fp / std::hypot(u_fp.norm(), rho * spin);
  for (int iteration = 0; iteration < 8; ++iteration) {
    const Eigen::Vector2d r0 = residual(d);
    if (r0.norm() < 1e-10 * scale) break;
    Eigen::Matrix2d jac;
    jac.col(0) = (residual(d + Eigen::Vector2d(eps, 0.0)) - r0) / eps;
    jac.col(1) = (residual(d + Eigen::Vector2d(0.0, eps)) - r0) / eps;
    d -= jac.partialPivLu().solve(r0);
  }
  residual(d);  // f and torque at the solution
  return r * f;
}

void Rocking3DModel::slide_rhs(const GroundInput3& in, double t, const Vec6& y, Vec6& dy) const {
  double torque;
  const Eigen::Vector2d f = slide_friction(in, t, y, torque);
  const Eigen::Vector3d a = in.at(t);
  const double spin = y(2);
  dy.head<2>() = f - a.head<2>();  // relative to the floor: the body's acceleration minus the ground's
  dy(2) = torque / fb().central_inertia_per_mass()(2, 2);
  // The centre of mass is at R c + shift: shift' = u - spin z x (R c).
  if (spin == 0.0) dy.segment<2>(3) = y.head<2>();
  else dy.segment<2>(3) = y.head<2>() - spin * perp2(rot2(y(5)) * fb().centre_of_mass().head<2>());
  dy(5) = spin;
  if (lip_held_ >= 0) {  // the lip takes the motion into it and the turning (lip_push >= 0 while held)
    const Eigen::Vector2d n = lip_normal(lip_held_);
    dy.head<2>() -= dy.head<2>().dot(n) * n;
    dy(2) = 0.0;
  }
}

// The friction the uplift test sees. The stepper resolves the slip velocity to the floor of
// slide_atol, so the slip's direction is known to floor / |u| rad: below 100 floors (0.01 rad) it is
// not resolved, and there the stiff law (the slip's sideways part decays at the rate mu_k N / |u|)
// has the friction follow the ground, as at zero slip. The explicit stepper's wobble of a slip of
// 1e-7 m/s must not decide whether an edge lifts: issue 51's Moreau-Jean reference found a box with
// mu_k above an edge's tan(alpha) lifting at an oblique slip's onset, where the real box slides on.
Eigen::Vector2d Rocking3DModel::lift_friction(const GroundInput3& in, double t, const Vec6& y) const {
  double torque;
  constexpr double kResolvedFloors = 100.0;
  const bool resolved = y(2) != 0.0 || y.head<2>().norm() > kResolvedFloors * kSlipFloorPerTol * settings_.tol;
  if (lip_held_ < 0 && resolved) return slide_friction(in, t, y, torque);
  const Eigen::Vector3d a = in.at(t);
  const Eigen::Vector2d f = resolved ? slide_friction(in, t, y, torque)
                                     : ground_following_friction(held_demand(a), mu_k() * std::max(kGravity + a.z(), 0.0));
  if (lip_held_ < 0) return f;
  // Held by a lip: its push acts at the floor as the friction does (the body's own acceleration
  // into the lip is the ground's).
  const Eigen::Vector2d n = lip_normal(lip_held_);
  return f - std::max((f - a.head<2>()).dot(n), 0.0) * n;
}

// > 0 when an edge lifts: the uplift test with the body's own acceleration (the friction) in place
// of the ground's (the planar eq. 19 about each edge of the face).
double Rocking3DModel::slide_lift(const GroundInput3& in, double t, const Vec6& y) const {
  // (on a support: about the whole base's lines, the contact's cut moving with the slide)
  if (!body_.parameters().support.empty()) return support_lift(in, t, y, false, 0.0);
  // A pure slide (no spin, slip not held past a stop) pulls with mu_k N against the slip: no edge
  // lifts while mu_k stays below every edge's tan(alpha), the planar slide-first rule (saves the
  // edge loop at every probe).
  if (y(2) == 0.0 && y.head<2>().squaredNorm() > 0.0 && mu_k() < slide_first_[static_cast<std::size_t>(face_)] * (1.0 - 1e-9) &&
      kGravity + in.at(t).z() > 0.0)
    return -1.0;
  const Eigen::Vector2d f = lift_friction(in, t, y);
  const Eigen::Matrix2d r = rot2(y(5));
  const double az = in.at(t).z();
  double best = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < fb().vertex_count(); ++k) {
    const BaseEdge& e = fb().edge(k);
    const Eigen::Vector2d n = r * e.normal.head<2>();
    best = std::max(best, uplift_function(e.pivot, 1, ModelKind::Nonlinear, -f.dot(n), az));
  }
  return best;
}

void Rocking3DModel::note_slide() {
  yaw_ = slide_(5);
  shift_ = slide_.segment<2>(3);
  outcome3_.max_slip = std::max(outcome3_.max_slip, slip().norm());
  outcome3_.max_slip_speed = std::max(outcome3_.max_slip_speed, slide_.head<2>().norm());
  outcome3_.max_twist = std::max(outcome3_.max_twist, std::abs(yaw_));
  if (!body_.parameters().support_lips.empty()) note_lip_overhang();
}

// The slide ends on an edge: the body pivots on it, the pivot sticking (issue 40's plastic impact
// onto the edge: angular momentum about the edge kept, the rest of the slip stopped).
void Rocking3DModel::slide_to_edge(const GroundInput3& in, double tau) {
  note_slide();
  fit_contact(shift_, yaw_);  // (on a support, the contact cut where it lifts: it pivots on one of the cut's edges)
  int best = 0;
  double best_u = -std::numeric_limits<double>::infinity();
  const Eigen::Vector2d f = lift_friction(in, tau, slide_);
  const Eigen::Matrix2d r = rot2(slide_(5));
  for (int k = 0; k < fb().vertex_count(); ++k) {
    const BaseEdge& e = fb().edge(k);
    const double u = uplift_function(e.pivot, 1, ModelKind::Nonlinear, -f.dot(r * e.normal.head<2>()), in.at(tau).z());
    if (u > best_u) { best_u = u; best = k; }
  }
  const BaseEdge& e = fb().edge(best);
  const Eigen::Vector2d u_fp = r.transpose() * slide_.head<2>();
  const Eigen::Vector3d lever = fb().centre_of_mass() - fb().vertex(e.a).position;
  const Eigen::Vector3d h = fb().central_inertia_per_mass() * Eigen::Vector3d(0.0, 0.0, slide_(2)) +
                            lever.cross(Eigen::Vector3d(u_fp.x(), u_fp.y(), 0.0));
  mode_ = Mode3D::Edge;
  contact_ = best;
  theta_ = 0.0;
  lip_held_ = -1;
  omega_ = std::max(0.0, e.axis.dot(h) / e.pivot.inertia);
  dopri5_.invalidate();
  ++outcome3_.slide_to_rock;
  ++slide_lifts_;
  report_.uplift = true;
  if (std::isnan(outcome_.uplift_time)) outcome_.uplift_time = t_ + tau;
}

// Absolute error scales of the slide's state (u, spin, shift, yaw).
Rocking3DModel::Vec6 Rocking3DModel::slide_atol() const {
  const double size = std::max(fb().edge(0).length, fb().centre_of_mass().z());
  const double rho = std::sqrt(fb().central_inertia_per_mass()(2, 2));
  const double v_scale = kGravity / body_.max_p();
  Vec6 atol;
  atol << v_scale, v_scale, v_scale / rho, size, size, 1.0;
  atol *= settings_.tol;
  // Near zero slip the slip's direction turns on the time scale |u| / |a|: resolving a slip of
  // micrometres per second to the tolerance would crawl (steps of microseconds) for displacements of
  // nanometres. A floor of 100 tol m/s on the slip's error (1 um/s at the default 1e-8) keeps the
  // step at the shaking's scale; the slip still converges as tol falls (docs/rocking_3d.md).
  const double floor = kSlipFloorPerTol * settings_.tol;
  atol.head<2>() = atol.head<2>().cwiseMax(floor);
  atol(2) = std::max(atol(2), floor / rho);
  return atol;
}

// The stick event's reference: the generalised slip velocity (u, rho spin) at the step's start; from
// zero slip the body starts to move against the ground's acceleration (at the onset its relative
// acceleration is still zero when mu_k = mu_s: the direction is the ground's).
void Rocking3DModel::aim_slide_ref(const GroundInput3& in, double tau, double rho) {
  slide_ref_ = Eigen::Vector3d(slide_(0), slide_(1), rho * slide_(2));
  if (slide_ref_.squaredNorm() > 0.0) return;
  const Eigen::Vector3d a = in.at(tau);
  const Eigen::Vector2d d = held_demand(a);
  slide_ref_ = Eigen::Vector3d(-d.x(), -d.y(), 0.0);
  slide_stepper_.invalidate();
}

// The slide's state at an event inside the last step (the stepper restarts from it).
void Rocking3DModel::slide_to_event(double tau, double t_start) {
  slide_ = slide_stepper_.eval(tau);
  slide_stepper_.invalidate();
  outcome3_.slip_time += tau - t_start;
}

// The centre of mass passed the support's edge at tau, inside the last step: it fell off.
void Rocking3DModel::fall_off_support(double tau, double t_start) {
  slide_to_event(tau, t_start);
  note_slide();
  outcome3_.fell_off_support = true;
  outcome3_.fell_off_time = t_ + tau;
}

// Braking would tip the item over the support's edge from t_over (support_lift): recorded when that
// comes before what ends the stepped interval at t_end.
void Rocking3DModel::note_over_support_edge(double t_over, double t_end) {
  if (!(t_over <= t_end)) return;
  ++outcome3_.slides_over_support_edge;
  note_transition(Mode3D::Slide, Transition3D::SlidesOverSupportEdge, t_over);
}

Rocking3DModel::Event Rocking3DModel::advance_slide(const GroundInput3& in, double& tau, double tau_end) {
  auto f = [&](double t, const Vec6& y, Vec6& dy) { slide_rhs(in, t, y, dy); };
  const double rho = std::sqrt(fb().central_inertia_per_mass()(2, 2));
  const Vec6 atol = slide_atol();
  int restarts = 0;
  while (tau < tau_end) {
    if (slide_lift(in, tau, slide_) > 0.0) return Event::Lift;
    if (lip_held_ >= 0 && lip_push(in, tau, slide_) < 0.0) {  // (the demand already turned away)
      lip_held_ = -1;
      note_transition(Mode3D::Slide, Transition3D::LeavesLip, tau);
    }
    aim_slide_ref(in, tau, rho);
    if (!body_.parameters().support_lips.empty()) note_lip_floors();
    const double t_start = tau;
    report_.integrator_steps += slide_stepper_.step(f, tau, slide_, tau_end, settings_.tol, atol);
    Event e = Event::None;
    if (slide_step_events(in, tau, t_start, rho, restarts, e)) return e;
  }
  return Event::None;
}

// The events of the slide step just taken from t_start, located on its dense output: true when the
// slide ends there (`e`, tau its instant), false to step on from tau (the step's end, or a stop the
// slip reverses through, or the lip letting go).
bool Rocking3DModel::slide_step_events(const GroundInput3& in, double& tau, double t_start, double rho, int& restarts,
                                       Event& e) {
  const bool supported = !body_.parameters().support.empty(), lips = !body_.parameters().support_lips.empty();
  const double t_tol = 1e-13 * std::max(sample_dt_, 1e-6);
  const Eigen::Vector3d ref = slide_ref_;
  const double t0 = slide_stepper_.t0(), t1 = slide_stepper_.t1();
  // Event functions: the stop (along <= 0), an edge lifting (> 0), the support's edge (margin <= 0),
  // a lip met (a base corner a tolerance beyond its line: <= 0), the holding lip letting go (< 0).
  auto along = [&](const Vec6& y) { return ref.dot(Eigen::Vector3d(y(0), y(1), rho * y(2))); };
  auto lift = [&](const Vec6& y, double t) { return slide_lift(in, t, y); };
  auto margin = [&](const Vec6& y) { return supported ? support_margin_of(y) : 1.0; };
  auto over = [&](const Vec6& y, double t, double m) {  // > 0: braking would tip it over the support's edge
    return supported ? support_lift(in, t, y, true, m) : -1.0;
  };
  auto gap = [&](const Vec6& y) { int lip; return lips ? lip_gap(y, lip) + floor_tol_ : 1.0; };
  auto push = [&](const Vec6& y, double t) { return lip_held_ >= 0 ? lip_push(in, t, y) : 1.0; };
  constexpr int kProbes = 4;
  double t_prev = t0, s_prev = 1.0, l_prev = lift(slide_, t0), m_prev = margin(slide_), o_prev = over(slide_, t0, m_prev);
  const bool watch = lips || lip_held_ >= 0;  // (without lips nothing more is evaluated)
  double g_prev = watch ? gap(slide_) : 1.0, p_prev = watch ? push(slide_, t0) : 1.0;
  for (int k = 1; k <= kProbes; ++k) {
    const double tk = k == kProbes ? t1 : t0 + (t1 - t0) * k / kProbes;
    const Vec6 yk = k == kProbes ? Vec6(slide_stepper_.y1()) : Vec6(slide_stepper_.eval(tk));
    const double s = along(yk), l = lift(yk, tk), mk = margin(yk), ok = over(yk, tk, mk);
    const double gk = watch ? gap(yk) : 1.0, pk = watch ? push(yk, tk) : 1.0;
    auto root = [&](auto g, double ga, double gb) {
      return bracketed_root([&](double t) { return g(Vec6(slide_stepper_.eval(t)), t); }, t_prev, tk, ga, gb, t_tol);
    };
    const double inf = std::numeric_limits<double>::infinity();
    const double t_over = ok > 0.0 && !(o_prev > 0.0) ? root([&](const Vec6& y, double t) { return over(y, t, margin(y)); }, o_prev, ok) : inf;
    auto over_before = [&](double t_end) { note_over_support_edge(t_over, t_end); };
    auto along_t = [&](const Vec6& y, double) { return along(y); };
    if (mk <= 0.0 && m_prev > 0.0) {
      // Falling off the support comes first when it is in this interval (a stop or lift after it
      // would be located on a body no longer on the support).
      const double tf = root([&](const Vec6& y, double) { return margin(y); }, m_prev, mk);
      const double ts = s <= 0.0 ? root(along_t, s_prev, s) : tk;
      if (!(ts < tf)) {
        over_before(tf);
        fall_off_support(tau = tf, t_start);
        e = Event::Overturn;
        return true;
      }
    }
    const bool stops = s <= 0.0 && restarts < kMaxSlideRestarts, lifts = l > 0.0 && !(l_prev > 0.0);
    const bool meets = gk <= 0.0 && g_prev > 0.0, leaves = pk < 0.0 && !(p_prev < 0.0);
    if (stops || lifts || meets || leaves) {
      const double ts = stops ? root(along_t, s_prev, s) : inf;
      const double tl = lifts ? root(lift, l_prev, l) : inf;
      const double tm = meets ? root([&](const Vec6& y, double) { return gap(y); }, g_prev, gk) : inf;
      const double tr = leaves ? root(push, p_prev, pk) : inf;
      tau = std::min({ts, tl, tm, tr});
      over_before(tau);
      slide_to_event(tau, t_start);
      return slide_event(in, tau, ts, tl, tm, tr, restarts, e);
    }
    over_before(tk);
    t_prev = tk;
    s_prev = s;
    l_prev = l;
    m_prev = mk;
    o_prev = ok;
    g_prev = gk;
    p_prev = pk;
  }
  slide_ = slide_stepper_.y1();
  outcome3_.slip_time += t1 - t_start;
  tau = t1;
  note_slide();
  return false;
}

// The first of the slide's events at tau (its instants ts: the stop, tl: an edge lifting, tm: a lip
// met, tr: the lip letting go; a stop first on a tie): as slide_step_events returns.
bool Rocking3DModel::slide_event(const GroundInput3& in, double tau, double ts, double tl, double tm, double tr,
                                 int& restarts, Event& e) {
  if (tau == tl && ts > tl) {
    e = Event::Lift;
    return true;
  }
  if (tau == tm && ts > tm && tl > tm) {
    lip_gap(slide_, lip_met_);
    e = Event::Lip;
    return true;
  }
  if (tau == tr && ts > tr) {
    lip_held_ = -1;  // the demand turned away from the lip: free again
    note_transition(Mode3D::Slide, Transition3D::LeavesLip, tau);
    slide_stepper_.reset(sample_dt_);
    return false;
  }
  slide_(0) = slide_(1) = slide_(2) = 0.0;
  note_slide();
  // Zero slip: the static law decides; where it cannot hold the body slips on (reversing).
  if (!(static_excess(in.at(tau), body_.parameters().mu_s) > 0.0)) {
    e = Event::Stick;
    return true;
  }
  ++restarts;
  slide_stepper_.reset(sample_dt_);
  return false;
}

}  // namespace rocking_monitor::core
