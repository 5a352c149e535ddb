#include "rocking_monitor/model/adaptive_model.hpp"

#include "rocking_monitor/prefetch.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "rocking_monitor/physics/criteria.hpp"

namespace rocking_monitor::core {

const char* to_string(Fidelity f) {
  switch (f) {
    case Fidelity::Rocking: return "rocking";
    case Fidelity::Contact: return "contact";
    case Fidelity::Adaptive: return "adaptive";
  }
  return "unknown";
}

bool parse_fidelity(const char* text, Fidelity& f) {
  for (Fidelity c : {Fidelity::Rocking, Fidelity::Contact, Fidelity::Adaptive}) {
    if (std::strcmp(text, to_string(c)) == 0) {
      f = c;
      return true;
    }
  }
  return false;
}

const char* to_string(ActiveModel m) {
  return m == ActiveModel::Rocking ? "rocking_model" : "contact_model";
}

const char* to_string(SwitchReason r) {
  switch (r) {
    case SwitchReason::None: return "none";
    case SwitchReason::FrictionRulesOutSliding: return "friction rules out sliding (mu_s = inf)";
    case SwitchReason::SceneRulesOutContact:
      return "friction rules out sliding, slip at impact and flight in the scene envelope";
    case SwitchReason::PureRockingValid: return "pure rocking valid";
    case SwitchReason::FixedFidelity: return "fixed fidelity";
    case SwitchReason::SlideFromRest: return "slide from rest";
    case SwitchReason::SlideAtUplift: return "slide at uplift";
    case SwitchReason::SlideWhileRocking: return "slide while rocking";
    case SwitchReason::FreeFlight: return "free flight";
    case SwitchReason::SlipAtImpact: return "slip at impact";
    case SwitchReason::FrictionNearLimit: return "friction near its limit while rocking";
    case SwitchReason::NearLiftOff: return "rocking reaction near lift-off";
    case SwitchReason::RestHeld: return "contact model at rest for the hold time";
    case SwitchReason::RockHeld: return "pure rocking (sticking pivot) for the hold time";
    case SwitchReason::SharedFrictionCone: return "the planar pair's shared friction cone exceeded";
  }
  return "unknown";
}

namespace {

void latch_min(double& slot, double value) {
  if (std::isnan(slot) && !std::isnan(value)) slot = value;
}

// The up switch keeps the RockingModel's start-of-sample state by value (a few scalars); a full
// copy of the model would be allocation-free too (all members are plain values):
static_assert(std::is_trivially_copyable_v<RockingModel>, "RockingModel copy must not allocate");
static_assert(std::is_trivially_copyable_v<ContactModel>, "ContactModel copy must not allocate");

const AdaptiveSettings& checked(const AdaptiveSettings& s) {
  if (const std::string e = validate(s.rocking); !e.empty()) throw std::invalid_argument(e);
  if (!(s.hold_time_s >= 0.0) || !std::isfinite(s.hold_time_s))
    throw std::invalid_argument("AdaptiveSettings::hold_time_s must be finite and >= 0");
  if (!(s.lift_off_margin >= 0.0 && s.lift_off_margin < 1.0))
    throw std::invalid_argument("AdaptiveSettings::lift_off_margin must be in [0, 1)");
  if (!(s.friction_safety > 0.0 && s.friction_safety <= 1.0))
    throw std::invalid_argument("AdaptiveSettings::friction_safety must be in (0, 1]");
  if (!(s.linearized_max_alpha >= 0.0) || !(s.linearized_max_ratio > 0.0 && s.linearized_max_ratio < 1.0))
    throw std::invalid_argument(
        "AdaptiveSettings: linearized_max_alpha must be >= 0 rad and linearized_max_ratio in (0, 1)");
  if (s.max_switch_records < 0)
    throw std::invalid_argument("AdaptiveSettings::max_switch_records must be >= 0");
  if (!(s.scene.horizontal >= 0.0) || !(s.scene.vertical >= 0.0))
    throw std::invalid_argument(
        "AdaptiveSettings::scene: horizontal and vertical limits must be >= 0 m/s^2 (inf = unknown)");
  return s;
}

SolverSettings linearized_settings(SolverSettings s) {
  s.method = Method::Analytic;
  s.model = ModelKind::Linearized;
  return s;
}

}  // namespace

AdaptiveModel::AdaptiveModel(const BodyParameters& body, const AdaptiveSettings& settings)
    : AdaptiveModel(Body(body), settings) {}

AdaptiveModel::AdaptiveModel(const Body& body, const AdaptiveSettings& settings)
    : body_(body),
      settings_(checked(settings)),
      rock_(body, settings.rocking),
      contact_(body, settings.contact),
      lin_(body, linearized_settings(settings.rocking)) {
  lin_eligible_ = settings_.fidelity == Fidelity::Adaptive && settings_.linearized_max_alpha > 0.0 &&
                  std::max(body_.pivot(1).alpha, body_.pivot(-1).alpha) <= settings_.linearized_max_alpha;
  bound_ = core::sliding_bound(body_, settings_.scene);
  scene_rules_out_contact_ = !std::isinf(body_.mu_s()) && body_.mu_s() >= bound_.required_mu();
  switches_.reserve(static_cast<std::size_t>(settings_.max_switch_records));
  reset(0.0);
}

double AdaptiveModel::impact_friction_demand(int new_side) const {
  return core::impact_friction_demand(body_, new_side);
}

void AdaptiveModel::save(Saved& out) const {
  rock_.save(out.rock);
  out.has_lin = lin_eligible_;  // else never stepped
  if (lin_eligible_) lin_.save(out.lin);
  contact_.save(out.contact);
  out.lin_active = lin_active_;
  out.active = active_;
  out.initial_reason = initial_reason_;
  out.scene_guarantee = scene_guarantee_;
  out.t = t_;
  out.ax_prev = ax_prev_;
  out.ay_prev = ay_prev_;
  out.hold = hold_;
  out.rock_slip = rock_slip_;
  out.switches.assign(switches_.begin(), switches_.end());
  out.report = report_;
  out.outcome = outcome_;
}

void AdaptiveModel::restore(const Saved& in) {
  if (in.switches.size() > static_cast<std::size_t>(settings_.max_switch_records))
    throw std::invalid_argument("AdaptiveModel::restore: " + std::to_string(in.switches.size()) +
                                " switch records, this model keeps " + std::to_string(settings_.max_switch_records));
  if (in.has_lin != lin_eligible_)
    throw std::invalid_argument(std::string("AdaptiveModel::restore: the linearized tier's state ") +
                                (in.has_lin ? "given for a model not eligible for it" : "missing"));
  rock_.restore(in.rock);
  if (lin_eligible_) lin_.restore(in.lin);
  contact_.restore(in.contact);
  lin_active_ = in.lin_active;
  active_ = in.active;
  initial_reason_ = in.initial_reason;
  scene_guarantee_ = in.scene_guarantee;
  t_ = in.t;
  ax_prev_ = in.ax_prev;
  ay_prev_ = in.ay_prev;
  hold_ = in.hold;
  rock_slip_ = in.rock_slip;
  switches_.assign(in.switches.begin(), in.switches.end());  // within the reserved capacity
  report_ = in.report;
  outcome_ = in.outcome;
}

void AdaptiveModel::reset(double t, double ax, double ay) {
  rock_.reset(t, ax, ay);
  contact_.reset(t, ax, ay);
  lin_active_ = false;
  t_ = t;
  ax_prev_ = ax;
  ay_prev_ = ay;
  hold_ = 0.0;
  rock_slip_ = 0.0;
  switches_.clear();
  report_ = AdaptiveReport{};
  outcome_ = AdaptiveOutcome{};
  // Static pre-check: mu_s = inf (sliding never evaluated; flight still possible), or finite
  // mu_s above what the scene envelope can demand (sliding_bound(), docs/fidelity.md).
  outcome_.sliding_ruled_out = std::isinf(body_.mu_s()) || scene_rules_out_contact_;
  scene_guarantee_ = scene_rules_out_contact_;
  switch (settings_.fidelity) {
    case Fidelity::Rocking:
      active_ = ActiveModel::Rocking;
      initial_reason_ = SwitchReason::FixedFidelity;
      break;
    case Fidelity::Contact:
      active_ = ActiveModel::Contact;
      initial_reason_ = SwitchReason::FixedFidelity;
      break;
    case Fidelity::Adaptive:
      active_ = ActiveModel::Rocking;
      initial_reason_ = scene_rules_out_contact_       ? SwitchReason::SceneRulesOutContact
                        : outcome_.sliding_ruled_out ? SwitchReason::FrictionRulesOutSliding
                                                     : SwitchReason::PureRockingValid;
      break;
  }
  report_.model = active_;
}

ContactMode AdaptiveModel::mode() const {
  if (active_ == ActiveModel::Contact) return contact_.mode();
  switch (rocking_model().mode()) {
    case Mode::Rest: return ContactMode::Rest;
    case Mode::Rocking: return ContactMode::Rock;
    case Mode::Overturned: return ContactMode::Overturned;
  }
  return ContactMode::Rest;
}

const char* AdaptiveModel::mode_name() const {
  return active_ == ActiveModel::Contact ? to_string(contact_.mode()) : to_string(rocking_model().mode());
}

int AdaptiveModel::side() const {
  return active_ == ActiveModel::Contact ? contact_.side() : rocking_model().side();
}
double AdaptiveModel::theta() const {
  return active_ == ActiveModel::Contact ? contact_.theta() : rocking_model().theta();
}
double AdaptiveModel::omega() const {
  return active_ == ActiveModel::Contact ? contact_.omega() : rocking_model().omega();
}
double AdaptiveModel::slip() const {
  return active_ == ActiveModel::Contact ? contact_.slip() : rock_slip_;
}

double AdaptiveModel::slip_velocity() const {
  if (active_ != ActiveModel::Contact) return 0.0;
  const ContactMode m = contact_.mode();
  return m == ContactMode::Slide || m == ContactMode::SlideRock ? contact_.slip_velocity() : 0.0;
}

double AdaptiveModel::friction_demand(double ax, double ay) const {
  auto ratio = [](double rx, double ry) {
    return ry > 0.0 ? std::abs(rx) / ry : std::numeric_limits<double>::infinity();
  };
  if (mode() == ContactMode::Overturned) return 0.0;  // the item is down: nothing left to hold
  // Rocking on a sticking pivot: its reaction, the same on either tier (the pair's shares must not
  // depend on which model runs the plane).
  if (active_ == ActiveModel::Rocking && rocking_model().mode() == Mode::Rocking) {
    const ContactReaction r = rocking_model().reaction();
    return ratio(r.rx, r.ry);
  }
  if (active_ == ActiveModel::Contact && contact_.mode() == ContactMode::Rock) {
    const ContactReaction r = contact_.rock_reaction();
    return ratio(r.rx, r.ry);
  }
  // At rest: the ground's demand on a base that follows it, per unit mass.
  return ratio(ax, ay + kGravity);
}

void AdaptiveModel::set_friction_share(double share) {
  contact_.set_friction_share(share);  // checks the range
  share_ = contact_.friction_share();
}

void AdaptiveModel::record(double time, ActiveModel to, SwitchReason reason, double onset) {
  ++outcome_.model_switches;
  report_.switched = true;
  report_.reason = reason;
  if (switches_.size() < switches_.capacity()) switches_.push_back({time, to, reason, onset});
}

void AdaptiveModel::count_rocking_work(const StepReport& r) {
  ++outcome_.samples_rocking_model;
  outcome_.rocking_steps += r.integrator_steps;
  ++report_.rocking_samples;
  report_.rocking_steps += r.integrator_steps;
  report_.integrator_steps += r.integrator_steps;
}

// The physics of a RockingModel sample whose result stands (no up switch in it).
void AdaptiveModel::accumulate_rocking(const RockingModel& m, const StepReport& r) {
  const RockingOutcome& o = m.outcome();
  ++outcome_.samples;
  outcome_.impacts += r.impacts;
  if (r.uplift) latch_min(outcome_.uplift_time, o.uplift_time);
  if (r.beyond_tipping_entered && !outcome_.beyond_tipping) {
    outcome_.beyond_tipping = true;
    outcome_.beyond_tipping_time = o.beyond_tipping_time;
  }
  if (r.committed_entered && !outcome_.committed) {
    outcome_.committed = true;
    outcome_.committed_time = o.committed_time;
  }
  if (r.overturned && !outcome_.overturned) {
    outcome_.overturned = true;
    outcome_.overturn_time = o.overturn_time;
  }
  outcome_.max_rotation_ratio = std::max(outcome_.max_rotation_ratio, o.max_rotation_ratio);
}

// ContactModel has no tipping / committed alarms of its own: they are derived here with the same
// definitions as RockingModel (docs/fidelity.md). The tipping crossing inside a sample without
// transitions is located on the cubic Hermite interpolant of (theta, omega) at the sample ends.
void AdaptiveModel::accumulate_contact(const ContactReport& r, double t0, double dt, double th0,
                                       double om0, int side0, ContactMode mode0) {
  const ContactOutcome& o = contact_.outcome();
  ++outcome_.samples;
  outcome_.impacts += r.impacts;
  outcome_.slip_episodes += r.slip_episodes;
  outcome_.flight_episodes += r.flight_episodes;
  latch_min(outcome_.uplift_time, o.first_uplift_time);
  latch_min(outcome_.first_slip_time, o.first_slip_time);
  latch_min(outcome_.first_flight_time, o.first_flight_time);
  outcome_.max_abs_slip = std::max(outcome_.max_abs_slip, std::abs(slip()));
  const double t1 = t0 + dt;
  if (!outcome_.beyond_tipping && o.max_rotation_ratio > 1.0) {
    double when = t1;
    const double th1 = contact_.theta(), om1 = contact_.omega();
    if (r.transitions == 0 && pivoting(mode0) && pivoting(r.mode) && side0 == r.side && side0 != 0) {
      const double a = body_.pivot(side0).alpha;
      auto f = [&](double s) {  // Hermite on [0, 1]
        const double s2 = s * s, s3 = s2 * s;
        const double th = (2 * s3 - 3 * s2 + 1) * th0 + (s3 - 2 * s2 + s) * dt * om0 +
                          (-2 * s3 + 3 * s2) * th1 + (s3 - s2) * dt * om1;
        return side0 * th - a;
      };
      if (f(0.0) <= 0.0 && f(1.0) > 0.0) {
        double lo = 0.0, hi = 1.0;
        for (int i = 0; i < 60; ++i) {
          const double mid = 0.5 * (lo + hi);
          (f(mid) > 0.0 ? hi : lo) = mid;
        }
        when = t0 + hi * dt;
      }
    }
    outcome_.beyond_tipping = true;
    outcome_.beyond_tipping_time = when;
  }
  outcome_.max_rotation_ratio = std::max(outcome_.max_rotation_ratio, o.max_rotation_ratio);
  if (r.overturned && !outcome_.overturned) {
    outcome_.overturned = true;
    outcome_.overturn_time = o.overturn_time;
  }
  if (!outcome_.committed) {
    if (pivoting(r.mode) && r.side != 0 &&
        overturn_margin(body_.pivot(r.side), r.side, ModelKind::Nonlinear, contact_.theta(),
                        contact_.omega()).committed) {
      outcome_.committed = true;
      outcome_.committed_time = t1;
    } else if (outcome_.overturned) {
      outcome_.committed = true;
      outcome_.committed_time = outcome_.overturn_time;
    }
  }
}

void AdaptiveModel::contact_step(double ax, double ay, double dt) {
  const double t0 = contact_.time(), th0 = contact_.theta(), om0 = contact_.omega();
  const int side0 = contact_.side();
  const ContactMode mode0 = contact_.mode();
  const ContactReport& r = contact_.step(ax, ay, dt);
  ++outcome_.samples_contact_model;
  outcome_.contact_steps += r.integrator_steps;
  ++report_.contact_samples;
  report_.contact_steps += r.integrator_steps;
  report_.integrator_steps += r.integrator_steps;
  accumulate_contact(r, t0, dt, th0, om0, side0, mode0);
}

SwitchReason AdaptiveModel::check_rocking(const RockingModel& rock, const StepReport& r) const {
  if (rock.mode() == Mode::Overturned && !r.overturned) return SwitchReason::None;
  // No friction given: the body is the paper's pure-rocking body, unchanged (a free-flight onset
  // stays a flagged violation, as under Fidelity::Rocking).
  if (std::isinf(body_.mu_s())) return SwitchReason::None;
  const std::uint8_t v = static_cast<std::uint8_t>(r.violation_onsets | rock.violations());
  auto has = [v](Criterion c) { return (v >> static_cast<int>(c)) & 1u; };
  if (has(Criterion::FreeFlight)) return SwitchReason::FreeFlight;
  if (has(Criterion::SlideFromRest)) return SwitchReason::SlideFromRest;
  if (has(Criterion::SlideAtUplift)) return SwitchReason::SlideAtUplift;
  if (has(Criterion::SlideWhileRocking)) return SwitchReason::SlideWhileRocking;
  if (share_ < 1.0 && shared_cone_exceeded(rock)) return SwitchReason::SharedFrictionCone;
  // Under the scene guarantee the exact criteria above cannot fire (sliding_bound()); they are
  // still checked so that a broken assumption is never missed, but the early margins are not.
  if (scene_guarantee_ && share_ == 1.0) return SwitchReason::None;  // (it assumes the whole budget)
  const double mu = share_ == 1.0 ? body_.mu_s() : body_.mu_s() * share_;
  if (!std::isinf(mu)) {
    if (r.impacts > 0 && mu < bound_.impact)  // the larger corner's sticking-impact demand
      return SwitchReason::SlipAtImpact;
    if (rock.mode() == Mode::Rocking) {
      const ContactReaction cr = rock.reaction();
      if (std::abs(cr.rx) > settings_.friction_safety * mu * std::max(cr.ry, 0.0))
        return SwitchReason::FrictionNearLimit;
    }
  }
  if (rock.mode() == Mode::Rocking && settings_.lift_off_margin > 0.0) {
    if (rock.reaction().ry < settings_.lift_off_margin * kGravity) return SwitchReason::NearLiftOff;
  }
  return SwitchReason::None;
}

// The rocking tier's own criteria use the whole mu_s; with a share of it (the planar pair's other
// plane slides, or demands friction too) the sample end is checked against mu_s x share. Found, the
// sample is recomputed by the contact model, which locates the onset inside it.
bool AdaptiveModel::shared_cone_exceeded(const RockingModel& rock) const {
  const double mu = body_.mu_s() * share_;
  if (rock.mode() == Mode::Rocking) {
    const ContactReaction r = rock.reaction();
    return std::abs(r.rx) > mu * std::max(r.ry, 0.0);
  }
  if (rock.mode() == Mode::Rest) return std::abs(rock.last_ax()) > mu * std::max(rock.last_ay() + kGravity, 0.0);
  return false;
}

// A linearized-tier sample stands only if it stayed in small rotation and nothing happened that
// the nonlinear model must decide (rest, tipping, overturn, a validity criterion or margin).
bool AdaptiveModel::linearized_sample_stands(const StepReport& r) const {
  if (lin_.mode() != Mode::Rocking || r.beyond_tipping_entered || r.overturned) return false;
  const double limit = settings_.linearized_max_ratio;
  if (lin_.rotation_ratio() > limit || r.peak_ratio > limit) return false;
  return check_rocking(lin_, r) == SwitchReason::None;
}

// One sample on the linearized tier. True when its result stands; otherwise the rocking model is
// put back in the start state and the caller recomputes the sample with the nonlinear model.
bool AdaptiveModel::linearized_step(double ax, double ay, double dt, const RockStart& start) {
  const StepReport& rl = lin_.step(ax, ay, dt);
  outcome_.rocking_steps += rl.integrator_steps;  // its work counts either way
  report_.rocking_steps += rl.integrator_steps;
  report_.integrator_steps += rl.integrator_steps;
  ++outcome_.samples_linearized_model;
  report_.linearized_samples = 1;
  if (linearized_sample_stands(rl)) {
    ++outcome_.samples_rocking_model;
    ++report_.rocking_samples;
    accumulate_rocking(lin_, rl);
    return true;
  }
  ++outcome_.linearized_fallbacks;
  lin_active_ = false;
  rock_.reset(t_, ax_prev_, ay_prev_);
  rock_.set_state(start.theta, start.omega);
  return false;
}

// After a nonlinear sample that stands: go to the linearized tier when the item is eligible and
// well inside the small-rotation region (half the limit: hysteresis against toggling).
void AdaptiveModel::maybe_enter_linearized(double ax, double ay) {
  if (!lin_eligible_ || lin_active_ || active_ != ActiveModel::Rocking) return;
  if (rock_.mode() != Mode::Rocking || rock_.theta() == 0.0 || rock_.violations() != 0) return;
  if (rock_.rotation_ratio() > 0.5 * settings_.linearized_max_ratio) return;
  lin_.reset(t_, ax, ay);
  lin_.set_state(rock_.theta(), rock_.omega());
  lin_active_ = true;
}

// Exact state transfer: the sample in which `reason` fired is recomputed with ContactModel placed
// in the RockingModel state at the start of that sample (REST, or ROCK with the pivot sticking;
// pure rocking was valid there, else the previous sample would have switched). The rocking run's
// result for this sample is discarded (only its work counts); everything latched before stands.
void AdaptiveModel::switch_up(SwitchReason reason, const RockStart& start, double ax, double ay,
                              double dt) {
  if (start.mode == Mode::Rocking) {
    // side * theta >= 0 while rocking; a rounding-level excursion past theta = 0 is clamped.
    const double theta = start.side * start.theta < 0.0 ? 0.0 : start.theta;
    contact_.set_state(t_, ax_prev_, ay_prev_, start.side, theta, start.omega, rock_slip_);
  }
  else
    contact_.set_state(t_, ax_prev_, ay_prev_, 0, 0.0, 0.0, rock_slip_);
  active_ = ActiveModel::Contact;  // slip() reads the contact model from here on
  record(t_, ActiveModel::Contact, reason, t_ + dt);
  contact_step(ax, ay, dt);
  ++outcome_.recomputed_samples;
  report_.recomputed_samples = 1;
  hold_ = 0.0;
}

void AdaptiveModel::switch_down(SwitchReason reason, double ax, double ay) {
  rock_slip_ = slip();  // constant while the pivot sticks
  rock_.reset(t_, ax, ay);
  if (contact_.mode() == ContactMode::Rock) rock_.set_state(contact_.theta(), contact_.omega());
  active_ = ActiveModel::Rocking;
  hold_ = 0.0;
  record(t_, ActiveModel::Rocking, reason, t_);
}

void AdaptiveModel::apply_rest_samples(double t, double ax, double ay, double dt, long n) {
  // What n calls of step() do on these paths: RockingModel rest (or overturned) samples without
  // integrator steps, count_rocking_work() and accumulate_rocking() with an empty report; or
  // ContactModel overturned samples, contact_step() and accumulate_contact() changing nothing but
  // counters, the hold timer reset; then the clock and inputs.
  report_ = AdaptiveReport{};
  if (active_ == ActiveModel::Contact) {
    contact_.apply_overturned_samples(t, ax, ay, dt, n);
    report_.contact_samples = 1;
    outcome_.samples_contact_model += n;
    if (settings_.fidelity == Fidelity::Adaptive) hold_ = 0.0;
  } else {
    rock_.apply_rest_samples(t, ax, ay, n);
    report_.rocking_samples = 1;
    outcome_.samples_rocking_model += n;
  }
  report_.model = active_;
  outcome_.samples += n;
  t_ = t;
  ax_prev_ = ax;
  ay_prev_ = ay;
}

void AdaptiveModel::apply_rocking_samples(double t, double ax, double ay, double dt, long n, double theta,
                                          double omega, double h_next, double k1_theta, double k1_omega,
                                          long integrator_steps, int last_integrator_steps, double max_ratio) {
  // What n calls of step() do then: rock_.step() without an event (apply_rocking_samples), then
  // count_rocking_work(), check_rocking() finding nothing and accumulate_rocking() with an empty report.
  rock_.apply_rocking_samples(t, ax, ay, dt, n, theta, omega, h_next, k1_theta, k1_omega, integrator_steps,
                              last_integrator_steps, max_ratio);
  report_ = AdaptiveReport{};
  report_.rocking_samples = 1;
  report_.rocking_steps = last_integrator_steps;
  report_.integrator_steps = last_integrator_steps;
  report_.model = active_;
  outcome_.samples_rocking_model += n;
  outcome_.rocking_steps += integrator_steps;
  outcome_.samples += n;
  outcome_.max_rotation_ratio = std::max(outcome_.max_rotation_ratio, rock_.outcome().max_rotation_ratio);
  t_ = t;
  ax_prev_ = ax;
  ay_prev_ = ay;
}

void AdaptiveModel::prefetch(std::uint8_t hint) const {
  prefetch_lines(&body_, &settings_ + 1);  // body (friction) and settings
  if (hint == 2) prefetch_lines(&contact_, sizeof(contact_));
  else if (hint == 1) prefetch_lines(&lin_, sizeof(lin_));
  else prefetch_lines(&rock_, sizeof(rock_));
  prefetch_lines(&lin_eligible_, &scene_guarantee_ + 1);  // the flags
  prefetch_lines(&t_, &outcome_ + 1);                      // clock, inputs, report and totals
}

const AdaptiveReport& AdaptiveModel::step(double ax, double ay, double dt) {
  require_valid_sample(ax, ay, dt, "AdaptiveModel::step");
  report_ = AdaptiveReport{};
  if (settings_.fidelity == Fidelity::Rocking) {
    const StepReport& r = rock_.step(ax, ay, dt);
    count_rocking_work(r);
    accumulate_rocking(rock_, r);
  } else if (settings_.fidelity == Fidelity::Contact || active_ == ActiveModel::Contact) {
    contact_step(ax, ay, dt);
  } else {
    if (!settings_.scene.contains(ax, ay)) {
      if (std::isnan(outcome_.scene_exceeded_time)) outcome_.scene_exceeded_time = t_ + dt;
      ++outcome_.samples_outside_scene;
      scene_guarantee_ = false;
    }
    // The rocking model in use is at (t_, ax_prev_, ay_prev_) here: same clock and input.
    const RockingModel& cur = rocking_model();
    const RockStart start{cur.mode(), cur.side(), cur.theta(), cur.omega()};
    if (!(lin_active_ && linearized_step(ax, ay, dt, start))) {
      const StepReport& r = rock_.step(ax, ay, dt);
      count_rocking_work(r);
      // The guarantee holds below the tipping angle only (sliding_bound()).
      if (scene_guarantee_ && (outcome_.beyond_tipping || r.beyond_tipping_entered)) scene_guarantee_ = false;
      const SwitchReason why = check_rocking(rock_, r);
      if (why == SwitchReason::None) accumulate_rocking(rock_, r);
      else switch_up(why, start, ax, ay, dt);
    }
  }
  t_ += dt;
  ax_prev_ = ax;
  ay_prev_ = ay;
  if (settings_.fidelity == Fidelity::Adaptive && active_ == ActiveModel::Contact &&
      !report_.switched) {
    // Back only from REST or ROCK, whatever the hold time (a zero hold must not hand back a body in
    // SLIDE-ROCK or FLIGHT: it would restart upright at rest).
    const ContactMode m = contact_.mode();
    // Nor while the pair shares the friction budget: the rocking tier assumes all of it.
    if ((m != ContactMode::Rest && m != ContactMode::Rock) || share_ < 1.0) {
      hold_ = 0.0;
    } else if ((hold_ += dt) >= settings_.hold_time_s) {
      switch_down(m == ContactMode::Rest ? SwitchReason::RestHeld : SwitchReason::RockHeld, ax, ay);
    }
  }
  if (settings_.fidelity == Fidelity::Adaptive && !report_.switched) maybe_enter_linearized(ax, ay);
  report_.model = active_;
  return report_;
}

}  // namespace rocking_monitor::core
