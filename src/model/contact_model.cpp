// ContactModel's state machine: construction, reset and set_state, the public accessors, and
// step() -> advance() / handle_event(), which integrate the current phase until one of its events
// fires and dispatch it. The phases' equations are in contact_phase_equations.cpp, the changes
// of phase in contact_transitions.cpp.
#include "rocking_monitor/model/contact_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rocking_monitor/integrate/event_location.hpp"

namespace rocking_monitor::core {

const char* to_string(ContactMode mode) {
  switch (mode) {
    case ContactMode::Rest: return "REST";
    case ContactMode::Slide: return "SLIDE";
    case ContactMode::Rock: return "ROCK";
    case ContactMode::SlideRock: return "SLIDE_ROCK";
    case ContactMode::Flight: return "FLIGHT";
    case ContactMode::Overturned: return "OVERTURNED";
  }
  return "UNKNOWN";
}

ContactModel::ContactModel(const BodyParameters& body, const ContactSettings& settings)
    : ContactModel(Body(body), settings) {}

ContactModel::ContactModel(const Body& body, const ContactSettings& settings)
    : body_(body), settings_(settings) {
  if (settings_.substeps < 1 || settings_.substeps > 100000)
    throw std::invalid_argument("ContactSettings::substeps must be in [1, 100000]");
  if (settings_.max_events_per_sample < 1)
    throw std::invalid_argument("ContactSettings::max_events_per_sample must be >= 1");
  if (!(settings_.rest_capture_ratio >= 0.0))
    throw std::invalid_argument("ContactSettings::rest_capture_ratio must be >= 0");
  mu_s_ = body_.mu_s();
  mu_k_ = std::isnan(body_.parameters().mu_k) ? mu_s_ : body_.parameters().mu_k;
  if (mu_k_ > mu_s_) throw std::invalid_argument("ContactModel: mu_k must not exceed mu_s");
  mu_s_body_ = mu_s_;
  mu_k_body_ = mu_k_;
  ig2_ = body_.radius_of_gyration() * body_.radius_of_gyration();
  reset(0.0);
}

void ContactModel::set_friction_share(double share) {
  if (!(share >= 0.0 && share <= 1.0))
    throw std::invalid_argument("ContactModel::set_friction_share: " + std::to_string(share) + " is not in [0, 1]");
  if (std::isinf(mu_s_body_)) return;  // no friction given: nothing to share
  share_ = share;
  // (share 1 gives the body's own coefficients bit for bit: one component alone is today's answer)
  mu_s_ = share == 1.0 ? mu_s_body_ : mu_s_body_ * share;
  mu_k_ = share == 1.0 ? mu_k_body_ : mu_k_body_ * share;
}

void ContactModel::save(Saved& out) const {
  out.mode = mode_;
  out.side = side_;
  out.sigma = sigma_;
  out.pivot_x = pivot_x_;
  out.x = x_;
  out.t = t_;
  out.ax_prev = ax_prev_;
  out.ay_prev = ay_prev_;
  out.dt = dt_;
  out.report = report_;
  out.outcome = outcome_;
}

void ContactModel::restore(const Saved& in) {
  mode_ = in.mode;
  side_ = in.side;
  sigma_ = in.sigma;
  pivot_x_ = in.pivot_x;
  x_ = in.x;
  t_ = in.t;
  ax_prev_ = in.ax_prev;
  ay_prev_ = in.ay_prev;
  dt_ = in.dt;
  report_ = in.report;
  outcome_ = in.outcome;
}

void ContactModel::reset(double t, double ax, double ay) {
  mode_ = ContactMode::Rest;
  side_ = 0;
  sigma_ = 0;
  x_ = {body_.nu1() * body_.width(), 0.0, 0.0, 0.0, body_.cg_height(), 0.0};
  pivot_x_ = 0.0;
  t_ = t;
  ax_prev_ = ax;
  ay_prev_ = ay;
  report_ = ContactReport{};
  outcome_ = ContactOutcome{};
}

void ContactModel::set_state(double t, double ax, double ay, int side, double theta, double omega,
                             double slip, const ContactOutcome& outcome) {
  set_state(t, ax, ay, side, theta, omega, slip);
  outcome_ = outcome;
}

void ContactModel::set_state(double t, double ax, double ay, int side, double theta, double omega,
                             double slip) {
  if (!std::isfinite(t) || !std::isfinite(ax) || !std::isfinite(ay) || !std::isfinite(theta) ||
      !std::isfinite(omega) || !std::isfinite(slip))
    throw std::invalid_argument("ContactModel::set_state: arguments must be finite");
  if (side != 0 && side != 1 && side != -1)
    throw std::invalid_argument("ContactModel::set_state: side must be 0 (REST), +1 or -1 (ROCK)");
  if (side == 0 && (theta != 0.0 || omega != 0.0))
    throw std::invalid_argument("ContactModel::set_state: REST needs theta = omega = 0");
  if (side != 0 && (side * theta < 0.0 || std::abs(theta) >= body_.overturn_angle()))
    throw std::invalid_argument(
        "ContactModel::set_state: ROCK needs side * theta >= 0 and |theta| < overturn angle");
  t_ = t;
  ax_prev_ = ax;
  ay_prev_ = ay;
  sigma_ = 0;
  if (side == 0) {
    mode_ = ContactMode::Rest;
    side_ = 0;
    pivot_x_ = 0.0;
    x_ = {slip + body_.nu1() * body_.width(), 0.0, 0.0, 0.0, body_.cg_height(), 0.0};
  } else {
    mode_ = ContactMode::Rock;
    side_ = side;
    pivot_x_ = slip + (side > 0 ? 0.0 : body_.width());  // corner 1 at u, corner 2 at u + B
    x_[2] = theta;
    x_[3] = omega;
    project_rock();
  }
  report_ = ContactReport{};
  report_.mode = mode_;
  report_.side = side_;
  report_.slip = this->slip();
  report_.slip_velocity = slip_velocity();
  report_.theta = x_[2];
}

double ContactModel::slip() const {
  const int c = x_[2] < 0.0 ? -1 : 1;
  double rx, ry;
  corner(c, x_, rx, ry);
  return x_[0] + rx - (c > 0 ? 0.0 : body_.width());
}

double ContactModel::slip_velocity() const {
  const int c = x_[2] < 0.0 ? -1 : 1;
  double rx, ry;
  corner(c, x_, rx, ry);
  return x_[1] - x_[3] * ry;
}

double ContactModel::energy() const {
  return 0.5 * (x_[1] * x_[1] + x_[5] * x_[5] + ig2_ * x_[3] * x_[3]) + kGravity * x_[4];
}

void ContactModel::rk4_from(const GroundInput& in, double tau, const State& s0, const State& k1, double h,
                            State& out) const {
  State k2, k3, k4, y;
  for (int i = 0; i < 6; ++i) y[i] = s0[i] + 0.5 * h * k1[i];
  derivative(in, tau + 0.5 * h, y, k2);
  for (int i = 0; i < 6; ++i) y[i] = s0[i] + 0.5 * h * k2[i];
  derivative(in, tau + 0.5 * h, y, k3);
  for (int i = 0; i < 6; ++i) y[i] = s0[i] + h * k3[i];
  derivative(in, tau + h, y, k4);
  for (int i = 0; i < 6; ++i) out[i] = s0[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
}

int ContactModel::advance(const GroundInput& in, double& tau, double tau_end) {
  const double h_nom = dt_ / settings_.substeps;
  const double t_tol = 1e-12 * dt_;
  // The derivative at a step's end is the next step's first stage (same time, same state), and it
  // gives the event functions the reaction they need: one evaluation serves both.
  State k1;
  Support support0;  // at (tau, x_), with k1
  derivative(in, tau, x_, k1, &support0);
  while (tau < tau_end) {
    double h = std::min(h_nom, tau_end - tau);
    if (tau_end - tau - h < 1e-9 * h_nom) h = tau_end - tau;
    State x1, d1;
    rk4_from(in, tau, x_, k1, h, x1);
    ++report_.integrator_steps;
    int best = kNone;
    double t_best = tau + h;
    Support support;
    derivative(in, tau + h, x1, d1, &support);
    double f1[kCount], f0[kCount];
    event_values(~0u, in, tau + h, x1, f1, support);
    unsigned crossed = 0;
    for (int ev = 0; ev < kCount; ++ev)
      if (f1[ev] > 0.0) crossed |= 1u << ev;
    if (crossed) event_values(crossed, in, tau, x_, f0, support0);
    for (int ev = 0; ev < kCount; ++ev) {
      if (!((crossed >> ev) & 1u)) continue;
      double te = tau;
      if (!(f0[ev] > 0.0)) {
        const State x0 = x_;
        const double t0 = tau;
        te = bracketed_root(
            [&](double t) {
              State y, d;
              Support sup;
              rk4_from(in, t0, x0, k1, t - t0, y);  // k1: the derivative at (t0, x0), as rk4() would compute it
              derivative(in, t, y, d, &sup);
              double f[kCount];
              event_values(1u << ev, in, t, y, f, sup);
              return f[ev];
            },
            t0, t0 + h, f0[ev], f1[ev], t_tol);
      }
      if (best == kNone || te < t_best) {
        best = ev;
        t_best = te;
      }
    }
    if (best == kNone) {
      x_ = x1;
      tau = (h == tau_end - tau) ? tau_end : tau + h;
      k1 = d1;  // at tau + h: when tau became tau_end instead, the loop ends here
      support0 = support;
      const int s = x_[2] < 0.0 ? -1 : 1;
      outcome_.max_rotation_ratio =
          std::max(outcome_.max_rotation_ratio, std::abs(x_[2]) / body_.pivot(s).alpha);
      continue;
    }
    if (t_best > tau) {
      State xe;
      rk4_from(in, tau, x_, k1, t_best - tau, xe);
      x_ = xe;
    }
    tau = t_best;
    return best;
  }
  return kNone;
}

void ContactModel::handle_event(int ev, const GroundInput& in, double tau) {
  if (ev == kOverturn) {
    const int s = x_[2] < 0.0 ? -1 : 1;
    mode_ = ContactMode::Overturned;
    side_ = s;
    x_[2] = s * body_.overturn_angle();
    x_[1] = x_[3] = x_[5] = 0.0;
    report_.overturned = true;
    outcome_.overturned = true;
    outcome_.overturn_time = t_ + tau;
    return;
  }
  switch (mode_) {
    case ContactMode::Slide:
      if (ev == kFlight) {
        set_mode(ContactMode::Flight, 0, 0, tau);
      } else {  // stick: relative velocity reached zero
        x_[1] = 0.0;
        enter_flat(in, tau);
      }
      return;
    case ContactMode::Rock:
      if (ev == kImpact) {
        x_[2] = 0.0;
        project_rock();
        impact(-side_, in, tau, false);
      } else if (ev == kFlight) {
        set_mode(ContactMode::Flight, 0, 0, tau);
      } else {  // |R_x| reached mu_s R_y: the pivot starts to slip
        set_mode(ContactMode::SlideRock, side_, consistent_sigma(side_, in, tau), tau);
      }
      return;
    case ContactMode::SlideRock:
      if (ev == kImpact) {
        x_[2] = 0.0;
        double rx, ry;
        corner(side_, x_, rx, ry);
        x_[4] = -ry;
        impact(-side_, in, tau, false);
      } else if (ev == kFlight) {
        set_mode(ContactMode::Flight, 0, 0, tau);
      } else {  // pivot slip velocity reached zero
        double rx, ry;
        corner(side_, x_, rx, ry);
        x_[1] = x_[3] * ry;
        enter_pivot(side_, in, tau);
      }
      return;
    case ContactMode::Flight: {
      int c = x_[2] > 0.0 ? 1 : (x_[2] < 0.0 ? -1 : (x_[3] > 0.0 ? 1 : -1));
      double rx, ry;
      corner(c, x_, rx, ry);
      x_[4] = -ry;  // exactly on the floor
      impact(c, in, tau, true);
      return;
    }
    default: return;
  }
}

const ContactReport& ContactModel::step(double ax, double ay, double dt) {
  require_valid_sample(ax, ay, dt, "ContactModel::step");
  report_ = ContactReport{};
  dt_ = dt;
  const GroundInput in = GroundInput::first_order_hold(ax_prev_, ay_prev_, ax, ay, dt);

  double tau = 0.0;
  int events = 0;
  while (tau < dt && mode_ != ContactMode::Overturned) {
    if (mode_ == ContactMode::Rest) {
      unsigned fired = 0;
      int up_side = 0;
      const double when = find_rest_exit(in, tau, dt, fired, up_side);
      if (std::isinf(when)) break;
      tau = when;
      leave_rest(in, tau, fired, up_side);
    } else {
      const int ev = advance(in, tau, dt);
      if (ev == kNone) break;
      handle_event(ev, in, tau);
    }
    ++report_.transitions;
    if (++events >= settings_.max_events_per_sample && tau < dt) {
      const double u = slip();
      x_ = {u + body_.nu1() * body_.width(), 0.0, 0.0, 0.0, body_.cg_height(), 0.0};
      mode_ = ContactMode::Rest;
      side_ = sigma_ = 0;
      report_.forced_rest = true;
      ++outcome_.forced_rests;
      break;
    }
  }
  t_ += dt;
  ax_prev_ = ax;
  ay_prev_ = ay;
  ++outcome_.samples;
  report_.mode = mode_;
  report_.side = side_;
  report_.slip = slip();
  report_.slip_velocity = slip_velocity();
  report_.theta = x_[2];
  outcome_.max_abs_slip = std::max(outcome_.max_abs_slip, std::abs(report_.slip));
  return report_;
}

void ContactModel::apply_overturned_samples(double t, double ax, double ay, double dt, long n) {
  report_ = ContactReport{};
  dt_ = dt;
  t_ = t;
  ax_prev_ = ax;
  ay_prev_ = ay;
  outcome_.samples += n;
  report_.mode = mode_;
  report_.side = side_;
  report_.slip = slip();
  report_.slip_velocity = slip_velocity();
  report_.theta = x_[2];
}

}  // namespace rocking_monitor::core
