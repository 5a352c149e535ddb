#include "rocking_monitor/model/rocking_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rocking_monitor/integrate/event_location.hpp"

namespace rocking_monitor::core {

const char* to_string(Mode mode) {
  switch (mode) {
    case Mode::Rest: return "REST";
    case Mode::Rocking: return "ROCKING";
    case Mode::Overturned: return "OVERTURNED";
  }
  return "UNKNOWN";
}

namespace {

Body checked_body(const BodyParameters& p) { return Body(p); }

const SolverSettings& checked(const SolverSettings& s) {
  if (const std::string e = validate(s); !e.empty()) throw std::invalid_argument(e);
  return s;
}

constexpr std::uint8_t bit(Criterion c) { return static_cast<std::uint8_t>(1u << static_cast<int>(c)); }

}  // namespace

RockingModel::RockingModel(const BodyParameters& body, const SolverSettings& settings)
    : RockingModel(checked_body(body), settings) {}

RockingModel::RockingModel(const Body& body, const SolverSettings& settings)
    : body_(body), settings_(checked(settings)) {
  reset(0.0);
}

void RockingModel::reset(double t, double ax, double ay) {
  mode_ = Mode::Rest;
  side_ = 0;
  theta_ = omega_ = 0.0;
  t_ = t;
  ax_prev_ = ax;
  ay_prev_ = ay;
  violations_ = 0;
  report_ = StepReport{};
  outcome_ = RockingOutcome{};
  const double p_max = std::max(body_.pivot(1).p, body_.pivot(-1).p);
  dopri5_.reset(0.05 / p_max);
}

void RockingModel::set_state(double theta, double omega) {
  if (!std::isfinite(theta) || !std::isfinite(omega))
    throw std::invalid_argument("set_state: theta and omega must be finite");
  if (theta == 0.0 && omega == 0.0) {
    go_to_rest();
    return;
  }
  mode_ = Mode::Rocking;
  side_ = theta != 0.0 ? (theta > 0.0 ? 1 : -1) : (omega > 0.0 ? 1 : -1);
  theta_ = theta;
  omega_ = omega;
  dopri5_.invalidate();
  const double ratio = rotation_ratio();
  if (ratio > outcome_.max_rotation_ratio) {
    outcome_.max_rotation_ratio = ratio;
    outcome_.max_rotation_side = side_;
  }
}

void RockingModel::save(Saved& out) const {
  out.mode = mode_;
  out.side = side_;
  out.theta = theta_;
  out.omega = omega_;
  out.t = t_;
  out.ax_prev = ax_prev_;
  out.ay_prev = ay_prev_;
  out.violations = violations_;
  out.report = report_;
  out.outcome = outcome_;
  dopri5_.save(out.dopri5);
}

void RockingModel::restore(const Saved& in) {
  mode_ = in.mode;
  side_ = in.side;
  theta_ = in.theta;
  omega_ = in.omega;
  t_ = in.t;
  ax_prev_ = in.ax_prev;
  ay_prev_ = in.ay_prev;
  violations_ = in.violations;
  report_ = in.report;
  outcome_ = in.outcome;
  dopri5_.restore(in.dopri5);
}

double RockingModel::rotation_ratio() const {
  return side_ == 0 ? 0.0 : std::abs(theta_) / body_.pivot(side_).alpha;
}

OverturnMargin RockingModel::margin() const {
  if (mode_ == Mode::Rest) return {1.0, false};
  if (mode_ == Mode::Overturned) return {-1.0, true};
  return overturn_margin(body_.pivot(side_), side_, settings_.model, theta_, omega_);
}

void RockingModel::go_to_rest() {
  mode_ = Mode::Rest;
  side_ = 0;
  theta_ = omega_ = 0.0;
  dopri5_.invalidate();
}

// Earliest time in [tau, tau_end] at which a corner lifts. The uplift function is linear in the
// ground acceleration, hence linear in time within a sample: the crossing is solved exactly.
double RockingModel::find_uplift(const GroundInput& in, double tau, double tau_end, int& side) const {
  double best = std::numeric_limits<double>::infinity();
  side = 0;
  for (int s : {1, -1}) {
    const Pivot& pv = body_.pivot(s);
    const double u0 = uplift_function(pv, s, settings_.model, in.ax(tau), in.ay(tau));
    const double u1 = uplift_function(pv, s, settings_.model, in.ax(tau_end), in.ay(tau_end));
    double when;
    if (u0 > 0.0) when = tau;
    else if (u1 > 0.0) when = std::clamp(tau + (tau_end - tau) * (-u0) / (u1 - u0), tau, tau_end);
    else continue;
    // With the input held within rounding of the threshold, the uplift function can be > 0 while
    // the equation of motion gives theta'' <= 0 at theta = 0: lifting would be undone at once
    // (a degenerate step, back to REST) in every sample. Lift only if theta'' agrees somewhere
    // in the rest of the sample.
    const RockingOde ode{&pv, s, settings_.model, in};
    if (!(s * ode.angular_acceleration(when, 0.0) > 0.0) &&
        !(s * ode.angular_acceleration(tau_end, 0.0) > 0.0))
      continue;
    if (when < best || (when == best && s == tipping_side(in.ax(when)))) {
      best = when;
      side = s;
    }
  }
  return best;
}

void RockingModel::start_rocking(const GroundInput& in, double tau, int side) {
  mode_ = Mode::Rocking;
  side_ = side;
  theta_ = 0.0;
  omega_ = 0.0;
  dopri5_.invalidate();
  report_.uplift = true;
  if (std::isnan(outcome_.uplift_time)) outcome_.uplift_time = t_ + tau;
  // Eqs. 24-26: does the pivot hold when rocking starts?
  if (!std::isinf(body_.mu_s())) {
    const double normal = in.ay(tau) + kGravity;
    const double abs_a = normal > 0.0 ? std::abs(in.ax(tau)) / normal : std::numeric_limits<double>::infinity();
    if (body_.mu_s() < rock_without_slip_friction(body_, body_.pivot(side), abs_a))
      report_.violation_onsets |= bit(Criterion::SlideAtUplift);
  }
}

// Eq. 34 at the new pivot, then the rest-capture rule. Returns true if the body came to rest.
bool RockingModel::apply_impact(const GroundInput& /*in*/, double tau) {
  if (report_.impacts == 0) report_.first_impact_time = t_ + tau;
  ++report_.impacts;
  ++outcome_.impacts;
  const int new_side = -side_;
  const Pivot& pv = body_.pivot(new_side);
  const double omega_after = pv.restitution * omega_;
  if (pv.restitution <= 0.0 ||
      std::abs(omega_after) < settings_.rest_capture_ratio * pv.p * pv.alpha) {
    go_to_rest();
    report_.rest_capture = true;
    ++outcome_.rest_captures;
    return true;
  }
  side_ = new_side;
  theta_ = 0.0;
  omega_ = omega_after;
  dopri5_.invalidate();
  return false;
}

template <class Stepper>
RockingModel::Event RockingModel::handle_step(const Stepper& st, const Pivot& pv, double& tau) {
  const double t_tol = 1e-12 * std::max(sample_dt_, 1e-6);
  const StepEvents ev = scan_step(
      [&st](double t, double& th, double& om) { st.eval(t, th, om); }, side_, pv.alpha,
      body_.overturn_angle(), st.t0(), st.t1(), theta_, omega_, st.theta1(), st.omega1(), t_tol);
  if (ev.has_peak) {
    const double ratio = ev.peak_abs_theta / pv.alpha;
    report_.peak_ratio = std::max(report_.peak_ratio, ratio);
    if (ratio > outcome_.max_rotation_ratio) {
      outcome_.max_rotation_ratio = ratio;
      outcome_.max_rotation_side = side_;
    }
  }
  if (ev.tipping_crossed && !outcome_.beyond_tipping) {
    outcome_.beyond_tipping = true;
    outcome_.beyond_tipping_time = t_ + ev.t_tipping;
    report_.beyond_tipping_entered = true;
  }
  switch (ev.terminal) {
    case StepEvents::Terminal::None:
      theta_ = st.theta1();
      omega_ = st.omega1();
      tau = st.t1();
      return Event::None;
    case StepEvents::Terminal::Impact: tau = ev.t_event; return Event::Impact;
    case StepEvents::Terminal::Overturn: tau = ev.t_event; return Event::Overturn;
    case StepEvents::Terminal::Degenerate: tau = st.t1(); return Event::Degenerate;
  }
  return Event::None;
}

// Integrates rocking about side_ from tau towards tau_end; stops at the first impact or overturn
// with the state placed at the event time (re-stepped from the step start for the RK methods).
RockingModel::Event RockingModel::advance_rocking(const GroundInput& in, double& tau, double tau_end) {
  const Pivot& pv = body_.pivot(side_);
  const RockingOde ode{&pv, side_, settings_.model, in};
  while (tau < tau_end) {
    const double t_start = tau, th_start = theta_, om_start = omega_;
    Event e;
    switch (settings_.method) {
      case Method::Dopri5: {
        report_.integrator_steps += dopri5_.step(ode, tau, theta_, omega_, tau_end, settings_.tol,
                                                 settings_.tol * pv.alpha,
                                                 settings_.tol * pv.p * pv.alpha);
        e = handle_step(dopri5_, pv, tau);
        if (e == Event::Impact || e == Event::Overturn) {
          dopri5_.single_step(ode, t_start, th_start, om_start, tau - t_start, theta_, omega_);
          dopri5_.invalidate();
        }
        break;
      }
      case Method::Rk4: {
        const double h_nominal = sample_dt_ / settings_.substeps;
        double h = std::min(h_nominal, tau_end - tau);
        if (tau_end - tau - h < 1e-9 * h_nominal) h = tau_end - tau;
        rk4_.step(ode, tau, theta_, omega_, h);
        if (h == tau_end - tau) {  // land exactly on the sample time
          // (rk4_.t1() is tau + h, equal to tau_end up to rounding)
        }
        ++report_.integrator_steps;
        e = handle_step(rk4_, pv, tau);
        if (e == Event::None && std::abs(tau - tau_end) < 1e-12 * h_nominal) tau = tau_end;
        if (e == Event::Impact || e == Event::Overturn)
          Rk4Stepper::single_step(ode, t_start, th_start, om_start, tau - t_start, theta_, omega_);
        break;
      }
      case Method::Analytic:
      default: {
        analytic_.step(ode, tau, theta_, omega_, tau_end);
        ++report_.integrator_steps;
        e = handle_step(analytic_, pv, tau);
        if (e == Event::Impact || e == Event::Overturn) analytic_.eval(tau, theta_, omega_);
        break;
      }
    }
    if (e == Event::None) {
      const double ratio = std::abs(theta_) / pv.alpha;
      if (ratio > outcome_.max_rotation_ratio) {
        outcome_.max_rotation_ratio = ratio;
        outcome_.max_rotation_side = side_;
      }
      continue;
    }
    return e;
  }
  return Event::None;
}

ContactReaction RockingModel::reaction_at(double ax, double ay) const {
  const Pivot& pv = body_.pivot(side_);
  GroundInput in;
  in.ax0 = ax;
  in.ay0 = ay;
  const RockingOde ode{&pv, side_, settings_.model, in};
  return rocking_reaction(pv, side_, theta_, omega_, ode.angular_acceleration(0.0, theta_), ax, ay);
}

void RockingModel::update_criteria(const GroundInput& in, double tau) {
  const double ax = in.ax(tau), ay = in.ay(tau);
  std::uint8_t now = 0;
  if (mode_ == Mode::Rest) {
    if (free_flight(ay)) now |= bit(Criterion::FreeFlight);
    if (slides_from_rest(body_, ax, ay)) now |= bit(Criterion::SlideFromRest);
  } else if (mode_ == Mode::Rocking) {
    const ContactReaction r = reaction_at(ax, ay);
    if (r.ry < 0.0) now |= bit(Criterion::FreeFlight);
    if (slides_while_rocking(r, body_.mu_s())) now |= bit(Criterion::SlideWhileRocking);
  }
  report_.violation_onsets |= static_cast<std::uint8_t>(now & ~violations_);
  violations_ = now;
}

const StepReport& RockingModel::step(double ax, double ay, double dt) {
  require_valid_sample(ax, ay, dt, "RockingModel::step");
  report_ = StepReport{};
  sample_dt_ = dt;
  const GroundInput in = GroundInput::first_order_hold(ax_prev_, ay_prev_, ax, ay, dt);

  double tau = 0.0;
  int events = 0;
  while (tau < dt && mode_ != Mode::Overturned) {
    if (mode_ == Mode::Rest) {
      int side = 0;
      const double when = find_uplift(in, tau, dt, side);
      if (side == 0) break;
      start_rocking(in, when, side);
      tau = when;
      ++events;
    }
    const Event e = advance_rocking(in, tau, dt);
    if (e == Event::None) break;
    if (e == Event::Overturn) {
      mode_ = Mode::Overturned;
      theta_ = side_ * body_.overturn_angle();
      omega_ = 0.0;
      outcome_.max_rotation_ratio = std::max(outcome_.max_rotation_ratio, rotation_ratio());
      if (outcome_.max_rotation_ratio == rotation_ratio()) outcome_.max_rotation_side = side_;
      outcome_.overturned = true;
      outcome_.overturn_time = t_ + tau;
      report_.overturned = true;
      break;
    }
    if (e == Event::Degenerate) {
      go_to_rest();
      report_.rest_capture = true;
      ++outcome_.rest_captures;
    } else {
      apply_impact(in, tau);
    }
    if (++events >= settings_.max_events_per_sample) {
      go_to_rest();
      report_.forced_rest = true;
      ++outcome_.forced_rest_captures;
      break;
    }
  }

  finish_sample(in, ax, ay, dt);
  return report_;
}

void RockingModel::finish_sample(const GroundInput& in, double ax, double ay, double dt,
                                 bool end_clear) {
  if (end_clear) {
    violations_ = 0;  // what update_criteria() would find; no onset
  } else {
    update_criteria(in, dt);
  }
  if (mode_ == Mode::Rocking && !end_clear) {
    const OverturnMargin m = margin();
    if (m.committed && !outcome_.committed) {
      outcome_.committed = true;
      outcome_.committed_time = t_ + dt;
      report_.committed_entered = true;
    }
  } else if (mode_ == Mode::Overturned && !outcome_.committed) {
    // Reaching the side implies it was committed, even if no sample caught it in between.
    outcome_.committed = true;
    outcome_.committed_time = outcome_.overturn_time;
    report_.committed_entered = true;
  }
  t_ += dt;
  ax_prev_ = ax;
  ay_prev_ = ay;
  ++outcome_.samples;
  outcome_.integrator_steps += report_.integrator_steps;
}

const StepReport& RockingModel::advance_at_rest(double ax, double ay, double dt) {
  report_ = StepReport{};
  sample_dt_ = dt;
  const GroundInput in = GroundInput::first_order_hold(ax_prev_, ay_prev_, ax, ay, dt);
  finish_sample(in, ax, ay, dt);
  return report_;
}

void RockingModel::apply_rest_samples(double t, double ax, double ay, long n) {
  report_ = StepReport{};
  violations_ = 0;
  t_ = t;
  ax_prev_ = ax;
  ay_prev_ = ay;
  outcome_.samples += n;
}

const StepReport& RockingModel::commit_rocking_sample(double ax, double ay, double dt,
                                                      double theta, double omega, double h_next,
                                                      double k1_theta, double k1_omega,
                                                      int integrator_steps, double max_ratio,
                                                      bool end_clear) {
  report_ = StepReport{};
  sample_dt_ = dt;
  const GroundInput in = GroundInput::first_order_hold(ax_prev_, ay_prev_, ax, ay, dt);
  theta_ = theta;
  omega_ = omega;
  dopri5_.restore(h_next, k1_theta, k1_omega);
  report_.integrator_steps = integrator_steps;
  if (max_ratio > outcome_.max_rotation_ratio) {
    outcome_.max_rotation_ratio = max_ratio;
    outcome_.max_rotation_side = side_;
  }
  finish_sample(in, ax, ay, dt, end_clear);
  return report_;
}

void RockingModel::apply_rocking_samples(double t, double ax, double ay, double dt, long n, double theta,
                                         double omega, double h_next, double k1_theta, double k1_omega,
                                         long integrator_steps, int last_integrator_steps,
                                         double max_ratio) {
  report_ = StepReport{};
  report_.integrator_steps = last_integrator_steps;
  sample_dt_ = dt;
  theta_ = theta;
  omega_ = omega;
  dopri5_.restore(h_next, k1_theta, k1_omega);
  if (max_ratio > outcome_.max_rotation_ratio) {
    outcome_.max_rotation_ratio = max_ratio;
    outcome_.max_rotation_side = side_;
  }
  violations_ = 0;  // finish_sample with end_clear
  t_ = t;
  ax_prev_ = ax;
  ay_prev_ = ay;
  outcome_.samples += n;
  outcome_.integrator_steps += integrator_steps;
}

}  // namespace rocking_monitor::core
