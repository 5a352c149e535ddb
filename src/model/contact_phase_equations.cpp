// ContactModel's phase equations: the corner geometry, the equations of motion of each contact
// phase (SLIDE, ROCK, SLIDE-ROCK, FLIGHT), ROCK's friction check, and the event functions that
// end a phase (REST's exit conditions solved exactly, the others located by event_values).
#include "rocking_monitor/model/contact_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact_model_internal.hpp"
#include "rocking_monitor/physics/criteria.hpp"

namespace rocking_monitor::core {

// Vector from the centre of mass to corner c (+1: corner 1, -1: corner 2), rotated by theta.
void ContactModel::corner(int c, const State& s, double& rx, double& ry) const {
  const double dx = c > 0 ? -body_.nu1() * body_.width() : body_.nu2() * body_.width();
  const double dy = -body_.cg_height();
  const double ct = std::cos(s[2]), st = std::sin(s[2]);
  rx = ct * dx - st * dy;
  ry = st * dx + ct * dy;
}

// Slide-rock about corner `side` with the pivot slipping in direction sigma (friction
// -sigma mu_k N). Newton-Euler with the constraint y_pivot = 0 (see docs/contact_model.md):
//   theta'' = -K (G - R cos(phi) w^2) / (i_g^2 + K s R sin(phi)),  K = R (s sin(phi) + mu_k sigma cos(phi))
//   N = G + s R sin(phi) theta'' - R cos(phi) w^2,   x'' = -a_xg - sigma mu_k N,   y'' = N - G.
double ContactModel::slide_rock_theta_ddot(int side, int sigma, double G, const State& s,
                                           double& normal) const {
  const Pivot& pv = body_.pivot(side);
  const double phi = pv.alpha - side * s[2];
  const double sp = std::sin(phi), cp = std::cos(phi), w2 = s[3] * s[3], R = pv.radius;
  const double K = R * (side * sp + mu_k_ * sigma * cp);
  const double acc = -K * (G - R * cp * w2) / (ig2_ + K * side * R * sp);
  normal = G + side * R * sp * acc - R * cp * w2;
  return acc;
}

void ContactModel::derivative(const GroundInput& in, double tau, const State& s, State& d,
                              Support* support) const {
  const double ax = in.ax(tau), G = in.ay(tau) + kGravity;
  d = {s[1], 0.0, s[3], 0.0, s[5], 0.0};
  switch (mode_) {
    case ContactMode::Slide:
      d[1] = -ax - sigma_ * mu_k_ * std::max(G, 0.0);
      break;
    case ContactMode::Rock: {
      const Pivot& pv = body_.pivot(side_);
      const RockingOde ode{&pv, side_, ModelKind::Nonlinear, in};
      const double acc = ode.angular_acceleration(tau, s[2]);
      const double phi = pv.alpha - side_ * s[2];
      const double c = std::cos(phi), sn = std::sin(phi), w2 = s[3] * s[3];
      d[3] = acc;
      d[1] = -pv.radius * (c * acc + side_ * sn * w2);
      d[5] = -pv.radius * c * w2 + side_ * pv.radius * sn * acc;
      // rocking_reaction(): the same expressions, in the same order
      if (support != nullptr) *support = {in.ax(tau) + d[1], kGravity + in.ay(tau) + d[5]};
      break;
    }
    case ContactMode::SlideRock: {
      double normal;
      d[3] = slide_rock_theta_ddot(side_, sigma_, G, s, normal);
      d[1] = -ax - sigma_ * mu_k_ * normal;
      d[5] = normal - G;
      if (support != nullptr) support->ry = normal;
      break;
    }
    case ContactMode::Flight:
      d[1] = -ax;
      d[5] = -G;
      break;
    default:
      d = {0, 0, 0, 0, 0, 0};
  }
}

ContactReaction ContactModel::rock_reaction() const {
  const Pivot& pv = body_.pivot(side_);
  GroundInput in;
  in.ax0 = ax_prev_;
  in.ay0 = ay_prev_;
  const RockingOde ode{&pv, side_, ModelKind::Nonlinear, in};
  return rocking_reaction(pv, side_, x_[2], x_[3], ode.angular_acceleration(0.0, x_[2]), ax_prev_, ay_prev_);
}

bool ContactModel::rock_friction_ok(const GroundInput& in, double tau, int side, double& rx) const {
  const Pivot& pv = body_.pivot(side);
  const RockingOde ode{&pv, side, ModelKind::Nonlinear, in};
  const double acc = ode.angular_acceleration(tau, x_[2]);
  const ContactReaction r = rocking_reaction(pv, side, x_[2], x_[3], acc, in.ax(tau), in.ay(tau));
  rx = r.rx;
  return std::isinf(mu_s_) || std::abs(r.rx) <= mu_s_ * std::max(r.ry, 0.0);
}

// Event functions: event ev happens when f[ev] becomes > 0. Only the events in `want` (bit ev) are
// evaluated, the others set to -1. support: what derivative() gave at (tau, s): the lift-off and slip
// events of ROCK and SLIDE-ROCK read the reaction the equations of motion already computed.
void ContactModel::event_values(unsigned want, const GroundInput& in, double tau, const State& s,
                                double (&f)[kCount], const Support& support) const {
  for (double& v : f) v = -1.0;
  auto wanted = [want](int ev) { return (want >> ev) & 1u; };
  const double G = in.ay(tau) + kGravity;
  switch (mode_) {
    case ContactMode::Slide:
      if (wanted(kFlight)) f[kFlight] = -G;
      if (wanted(kSlipOrStick)) f[kSlipOrStick] = -sigma_ * s[1];  // relative velocity reached zero
      return;
    case ContactMode::Rock:
    case ContactMode::SlideRock:
      if (wanted(kImpact)) f[kImpact] = -side_ * s[2];
      if (wanted(kOverturn)) f[kOverturn] = side_ * s[2] - body_.overturn_angle();
      if (mode_ == ContactMode::Rock) {
        if (wanted(kFlight)) f[kFlight] = -support.ry;
        if (wanted(kSlipOrStick) && !std::isinf(mu_s_))
          f[kSlipOrStick] = std::abs(support.rx) - mu_s_ * support.ry;
      } else {
        if (wanted(kFlight)) f[kFlight] = -support.ry;  // the normal force
        if (wanted(kSlipOrStick)) {  // pivot slip velocity reached zero
          double rx, ry;
          corner(side_, s, rx, ry);
          f[kSlipOrStick] = -sigma_ * (s[1] - s[3] * ry);
        }
      }
      return;
    case ContactMode::Flight: {
      if (wanted(kOverturn)) f[kOverturn] = std::abs(s[2]) - body_.overturn_angle();
      if (!wanted(kLanding)) return;
      double rx1, ry1, rx2, ry2;
      corner(1, s, rx1, ry1);
      corner(-1, s, rx2, ry2);
      f[kLanding] = -(s[4] + std::min(ry1, ry2));
      return;
    }
    default: return;
  }
}

// REST: every exit condition is linear in the ground acceleration, hence linear in time within a
// sample; crossings are solved exactly. fired: which conditions cross at the returned time.
double ContactModel::find_rest_exit(const GroundInput& in, double tau, double tau_end,
                                    unsigned& fired, int& up_side) const {
  const double inf = std::numeric_limits<double>::infinity();
  auto crossing = [&](auto f) {
    const double f0 = f(tau), f1 = f(tau_end);
    if (f0 > 0.0) return tau;
    if (f1 > 0.0) return std::clamp(tau + (tau_end - tau) * (-f0) / (f1 - f0), tau, tau_end);
    return inf;
  };
  const double t_flight = crossing([&](double t) { return -(in.ay(t) + kGravity); });
  double t_slide = inf;
  if (!std::isinf(mu_s_)) {
    t_slide = std::min(
        crossing([&](double t) { return in.ax(t) - mu_s_ * (in.ay(t) + kGravity); }),
        crossing([&](double t) { return -in.ax(t) - mu_s_ * (in.ay(t) + kGravity); }));
  }
  double t_up = inf;
  up_side = 0;
  for (int s : {1, -1}) {
    const Pivot& pv = body_.pivot(s);
    const double when = crossing([&](double t) {
      return uplift_function(pv, s, ModelKind::Nonlinear, in.ax(t), in.ay(t));
    });
    if (std::isinf(when)) continue;
    const RockingOde ode{&pv, s, ModelKind::Nonlinear, in};  // same guard as RockingModel
    if (!(s * ode.angular_acceleration(when, 0.0) > 0.0) &&
        !(s * ode.angular_acceleration(tau_end, 0.0) > 0.0))
      continue;
    if (when < t_up || (when == t_up && s == tipping_side(in.ax(when)))) {
      t_up = when;
      up_side = s;
    }
  }
  const double when = std::min({t_flight, t_slide, t_up});
  fired = 0;
  if (std::isinf(when)) return when;
  const double eps = 1e-12 * (tau_end - tau);
  if (t_flight <= when + eps) fired |= kFiredFlight;
  if (t_slide <= when + eps) fired |= kFiredSlide;
  if (t_up <= when + eps) fired |= kFiredUplift;
  return when;
}

}  // namespace rocking_monitor::core
