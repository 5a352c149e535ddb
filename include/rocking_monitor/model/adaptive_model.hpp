#pragma once
// Fidelity selection per item (issue 7, part 2): run the cheap pure-rocking RockingModel while pure
// rocking is valid and the full ContactModel only when sliding or free flight can happen.
// See docs/fidelity.md.

#include <cstdint>
#include <limits>
#include <vector>

#include "rocking_monitor/model/contact_model.hpp"
#include "rocking_monitor/model/rocking_model.hpp"
#include "rocking_monitor/physics/sliding_bound.hpp"

namespace rocking_monitor::core {

/// Which model(s) an item runs.
enum class Fidelity : std::uint8_t {
  Rocking,   ///< RockingModel only (today's behaviour; violations are only flagged)
  Contact,   ///< ContactModel only (the richest model)
  Adaptive,  ///< RockingModel while pure rocking is valid, ContactModel when it is not
};
const char* to_string(Fidelity fidelity);
/// "rocking" | "contact" | "adaptive"; false for an unknown name.
bool parse_fidelity(const char* text, Fidelity& fidelity);

enum class ActiveModel : std::uint8_t { Rocking, Contact };
const char* to_string(ActiveModel model);

/// Why the active model is what it is (initial choice and every switch).
enum class SwitchReason : std::uint8_t {
  None,
  FrictionRulesOutSliding,  ///< initial: mu_s = inf, the sliding model is never needed
  SceneRulesOutContact,     ///< initial: mu_s >= the scene's SlidingBound::required_mu() and no
                            ///< flight possible: no slide, slip at impact or flight below alpha
  PureRockingValid,         ///< initial: start on RockingModel, ContactModel on demand
  FixedFidelity,            ///< initial: --fidelity rocking or contact
  SlideFromRest,            ///< up: eq. 22 violated at rest
  SlideAtUplift,            ///< up: mu_s below eq. 25 when rocking starts
  SlideWhileRocking,        ///< up: |R_x| > mu_s R_y while rocking
  FreeFlight,               ///< up: a_yg + g < 0 at rest or R_y < 0 while rocking
  SlipAtImpact,             ///< up: an impact whose tangential impulse exceeds mu_s P_y
  FrictionNearLimit,        ///< up: |R_x| > friction_safety mu_s R_y at a sample end (early, safe)
  NearLiftOff,              ///< up: R_y < lift_off_margin g at a sample end while rocking (early, safe)
  RestHeld,                 ///< down: ContactModel at REST for hold_time
  RockHeld,                 ///< down: ContactModel in pure ROCK (sticking pivot) for hold_time
  SharedFrictionCone,       ///< up: the planar pair's shared budget (mu_s x share) exceeded at a
                            ///< sample end (monitoring/friction_share.hpp)
};
const char* to_string(SwitchReason reason);

struct SwitchRecord {
  double time = 0.0;  ///< s: up switch: start of the sample recomputed by ContactModel (the
                      ///< state transfer); down switch: sample end
  ActiveModel to = ActiveModel::Rocking;
  SwitchReason reason = SwitchReason::None;
  double onset_time = 0.0;  ///< s: end of the sample in which the reason was detected
};

struct AdaptiveSettings {
  Fidelity fidelity = Fidelity::Adaptive;
  SolverSettings rocking{};   ///< RockingModel settings (default dopri5, tol 1e-8)
  ContactSettings contact{};  ///< ContactModel settings
  /// Down switch: ContactModel at REST, or in ROCK (pivot sticking, zero slip velocity), for at
  /// least this long (s, measured at sample ends) goes back to RockingModel.
  double hold_time_s = 0.1;
  /// Up switch also when |R_x| > friction_safety * mu_s * R_y at a sample end while rocking (the
  /// rocking model checks the exact condition only at sample ends; this catches excursions that
  /// approach the limit inside a sample). 1 = exact criterion only.
  double friction_safety = 0.9;
  /// Up switch also when the rocking normal reaction R_y < lift_off_margin * g at a sample end
  /// (catches lift-off inside a sample early). 0 = exact criterion (R_y < 0) only.
  double lift_off_margin = 0.1;
  /// Switch records kept (the count goes on beyond it). Reserved at construction.
  int max_switch_records = 256;
  /// Scene envelope for the static pre-check (sliding_bound()). Inside it an item with
  /// mu_s >= required_mu() provably never leaves pure rocking while |theta| < alpha, and the
  /// early margins above are not applied to it. An input sample outside the envelope, or a
  /// rotation beyond alpha, ends the guarantee: the margins apply again from that sample on.
  SceneEnvelope scene{};
  /// Linearized tier (issue 7: "a slender item in small rotation may use the linearized model
  /// only where the error bound allows it"). An item whose tipping angles are both <= this (rad)
  /// rocks on the closed-form linearized model (method analytic) while |theta| / alpha stays below
  /// linearized_max_ratio; any sample that would leave that region (or reach rest, an overturn or
  /// a validity criterion) is recomputed by the nonlinear model from its start state, so every
  /// alarm is decided by the nonlinear (or contact) model. 0 = off (default). docs/performance.md
  /// gives the linearized model's error: overturning amplitude 0.3 % at alpha = 5 deg, 1.2 % at 10.
  double linearized_max_alpha = 0.0;
  double linearized_max_ratio = 0.5;
};

/// One sample.
struct AdaptiveReport {
  ActiveModel model = ActiveModel::Rocking;  ///< model whose result stands at the sample end
  bool switched = false;                     ///< a switch happened in this sample
  SwitchReason reason = SwitchReason::None;  ///< its reason
  /// 1 when this sample was first stepped by RockingModel and then recomputed by ContactModel
  /// from the RockingModel state at the sample start (up switch), else 0.
  int recomputed_samples = 0;
  int rocking_samples = 0;   ///< RockingModel samples whose result stands or was handed up (0 or 1)
  int linearized_samples = 0;  ///< linearized-tier samples stepped (0 or 1; a fallback recomputes
                               ///< it with the nonlinear model, which is then the rocking sample)
  int contact_samples = 0;   ///< ContactModel samples stepped in this sample (0 or 1)
  int rocking_steps = 0;     ///< RockingModel integrator steps in this sample
  int contact_steps = 0;     ///< ContactModel RK4 sub-steps in this sample
  int integrator_steps = 0;  ///< rocking_steps + contact_steps
};

/// Totals since reset(). Alarm definitions as RockingOutcome (see docs/fidelity.md for the
/// ContactModel part). Times absolute, NaN when never.
struct AdaptiveOutcome {
  bool beyond_tipping = false, committed = false, overturned = false;
  double beyond_tipping_time = std::numeric_limits<double>::quiet_NaN();
  double committed_time = std::numeric_limits<double>::quiet_NaN();
  double overturn_time = std::numeric_limits<double>::quiet_NaN();
  double uplift_time = std::numeric_limits<double>::quiet_NaN();
  double first_slip_time = std::numeric_limits<double>::quiet_NaN();
  double first_flight_time = std::numeric_limits<double>::quiet_NaN();
  double max_rotation_ratio = 0.0;
  double max_abs_slip = 0.0;
  long impacts = 0, slip_episodes = 0, flight_episodes = 0;
  long samples = 0;
  // Work. A recomputed sample (up switch) counts in both samples_rocking_model and
  // samples_contact_model, and once in samples.
  long samples_rocking_model = 0;   ///< samples stepped by RockingModel
  long samples_contact_model = 0;   ///< samples stepped by ContactModel (recomputed included)
  long rocking_steps = 0;           ///< RockingModel integrator steps (dopri5 or RK4)
  long contact_steps = 0;           ///< ContactModel RK4 sub-steps
  long recomputed_samples = 0;      ///< samples recomputed by ContactModel (one per up switch)
  long samples_linearized_model = 0;  ///< samples stepped on the linearized tier (kept or not)
  long linearized_fallbacks = 0;      ///< of which recomputed by the nonlinear model
  long model_switches = 0;
  bool sliding_ruled_out = false;   ///< static pre-check: mu_s = inf, or mu_s >= required_mu()
  /// First input sample outside the scene envelope (s), NaN while every sample was inside.
  double scene_exceeded_time = std::numeric_limits<double>::quiet_NaN();
  long samples_outside_scene = 0;   ///< input samples outside the scene envelope
};

/// Streaming shape of RockingModel / ContactModel: reset(t, ax, ay), step(ax, ay, dt).
/// step() allocates nothing (switch records reserved at construction) and does bounded work:
/// at most one RockingModel sample plus one ContactModel sample. Alarms, once latched, are never
/// revised: an up switch recomputes only the sample in which it fired, with ContactModel placed
/// exactly in the RockingModel state at the start of that sample (ContactModel::set_state).
class AdaptiveModel {
 public:
  AdaptiveModel(const Body& body, const AdaptiveSettings& settings = {});
  AdaptiveModel(const BodyParameters& body, const AdaptiveSettings& settings = {});

  void reset(double t, double ax = 0.0, double ay = 0.0);
  /// dt finite > 0 and finite inputs, else std::invalid_argument (state unchanged).
  const AdaptiveReport& step(double ax, double ay, double dt);

  /// Everything one sample carries to the next (state snapshots, issue 29): the three models and
  /// the switching state. What the constructor derives from the body and settings is not in it.
  struct Saved {
    RockingModel::Saved rock;
    bool has_lin = false;     ///< the linearized tier's model: only for an item eligible for it
    RockingModel::Saved lin;
    ContactModel::Saved contact;
    bool lin_active = false;
    ActiveModel active = ActiveModel::Rocking;
    SwitchReason initial_reason = SwitchReason::None;
    bool scene_guarantee = false;
    double t = 0.0, ax_prev = 0.0, ay_prev = 0.0;  ///< s, m/s^2
    double hold = 0.0;       ///< s
    double rock_slip = 0.0;  ///< m
    std::vector<SwitchRecord> switches;  ///< at most settings().max_switch_records
    AdaptiveReport report;
    AdaptiveOutcome outcome;
  };
  /// Reuses out's storage (no allocation once it has held as many switch records).
  void save(Saved& out) const;
  /// std::invalid_argument when in holds more switch records than this model keeps, or the
  /// linearized tier's state is there for a model not eligible for it (or missing for one that is).
  void restore(const Saved& in);

  ActiveModel active() const { return active_; }
  /// The rocking model runs on the linearized tier now (see AdaptiveSettings::linearized_max_alpha).
  bool linearized() const { return active_ == ActiveModel::Rocking && lin_active_; }
  bool linearized_eligible() const { return lin_eligible_; }
  /// Mode name of the active model ("REST", "ROCKING", "SLIDE", ...).
  const char* mode_name() const;
  ContactMode mode() const;  ///< mapped to ContactMode (RockingModel ROCKING -> Rock)
  int side() const;
  double theta() const;
  double omega() const;
  double slip() const;  ///< m, horizontal displacement of the base (constant while rocking)
  /// m/s: the base's (or the slipping pivot's) velocity on the floor; 0 while the pivot sticks.
  double slip_velocity() const;
  /// |R_x| / R_y (dimensionless): the friction coefficient the sticking base or pivot needs now,
  /// with (ax, ay) the ground's acceleration at this instant (m/s^2); +inf without a normal force.
  double friction_demand(double ax, double ay) const;
  /// The planar pair's shared friction budget (issue 51 part 4): from the next step() on, the
  /// friction this plane may use is mu_s x share, share in [0, 1] (1: today's model, bit for bit).
  /// Below 1 the rocking tier is checked against it at every sample end (SharedFrictionCone, the
  /// sample then recomputed by the contact model) and the contact model is kept (no down switch).
  void set_friction_share(double share);
  double friction_share() const { return share_; }
  double time() const { return t_; }
  const AdaptiveOutcome& outcome() const { return outcome_; }
  /// Which of its models the next step() runs: 0 the nonlinear rocking model, 1 the linearized
  /// tier, 2 the contact model. For prefetch(), read while the object is in cache.
  std::uint8_t prefetch_hint() const {
    if (settings_.fidelity == Fidelity::Contact || active_ == ActiveModel::Contact) return 2;
    return settings_.fidelity != Fidelity::Rocking && lin_active_ ? 1 : 0;
  }
  /// A hint that the model is stepped soon: starts loading the state a step touches (MonitorBatch:
  /// its objects are not in cache with thousands of items), `hint` the model prefetch_hint() named.
  /// Reads no member (one would be a cache miss itself). No effect on any result.
  void prefetch(std::uint8_t hint) const;
  const AdaptiveReport& last_report() const { return report_; }
  const std::vector<SwitchRecord>& switches() const { return switches_; }
  SwitchReason initial_reason() const { return initial_reason_; }
  /// The static pre-check (computed at construction): what friction the scene can demand.
  const SlidingBound& sliding_bound() const { return bound_; }
  const Body& body() const { return body_; }

  // ---- For MonitorBatch (monitoring/monitor_batch.hpp), which defers quiet samples of many items.
  /// The next sample may be deferred: adaptive fidelity with the pure-rocking model active at REST or
  /// OVERTURNED (not on the linearized tier), or the contact model OVERTURNED (after the sample of
  /// the overturn).
  bool rest_deferrable() const {
    if (active_ == ActiveModel::Contact)
      return settings_.fidelity != Fidelity::Rocking && contact_.mode() == ContactMode::Overturned &&
             outcome_.overturned && outcome_.committed && outcome_.beyond_tipping;
    return settings_.fidelity == Fidelity::Adaptive && !lin_active_ &&
           (rock_.mode() == Mode::Rest || (rock_.mode() == Mode::Overturned && rock_.outcome().committed));
  }
  /// n samples that step() would have spent at REST (no corner lifting, no criterion at their ends)
  /// or OVERTURNED, with every input inside the scene envelope, applied at once: t is the caller's
  /// sum time() + dt + dt ... (the same additions as step()), (ax, ay) and dt the last sample's.
  void apply_rest_samples(double t, double ax, double ay, double dt, long n);
  /// The next sample may be deferred as pure rocking (MonitorBatch's rocking lanes): adaptive
  /// fidelity, the nonlinear rocking model under dopri5 (not the linearized tier) ROCKING with no
  /// validity criterion standing, and no scene guarantee about to lapse.
  bool rocking_deferrable() const {
    return settings_.fidelity == Fidelity::Adaptive && active_ == ActiveModel::Rocking && !lin_active_ &&
           rock_.mode() == Mode::Rocking && rock_.violations() == 0 && rock_.settings().method == Method::Dopri5 &&
           rock_.settings().model == ModelKind::Nonlinear && !(scene_guarantee_ && outcome_.beyond_tipping);
  }
  /// The rocking model (nonlinear) whose state a rocking lane mirrors.
  const RockingModel& nonlinear_model() const { return rock_; }
  /// A deferred rocking sample must end with a rotation ratio above this (step() would otherwise enter
  /// the linearized tier after it); -1 when the tier cannot be entered.
  double linearized_entry_ratio() const { return lin_eligible_ ? 0.5 * settings_.linearized_max_ratio : -1.0; }
  /// n samples that step() would have run as pure rocking with no event (RockingModel::
  /// apply_rocking_samples), no validity criterion, switch margin or linearized entry at their ends, every
  /// input inside the scene envelope, applied at once: the rocking model's state and counters, this
  /// model's counters, clock and inputs (t, ax, ay, dt as in apply_rest_samples).
  void apply_rocking_samples(double t, double ax, double ay, double dt, long n, double theta, double omega,
                             double h_next, double k1_theta, double k1_omega, long integrator_steps,
                             int last_integrator_steps, double max_ratio);
  const AdaptiveSettings& settings() const { return settings_; }
  /// |P_x| / P_y of a sticking impact from pure rocking that makes corner `new_side` the pivot
  /// (geometry and restitution only): the impact slips in ContactModel when mu_s is below it.
  double impact_friction_demand(int new_side) const;

 private:
  /// RockingModel state at the start of a sample (what the up switch transfers).
  struct RockStart {
    Mode mode;
    int side;
    double theta, omega;
  };
  void count_rocking_work(const StepReport& r);
  void accumulate_rocking(const RockingModel& m, const StepReport& r);
  void accumulate_contact(const ContactReport& r, double t0, double dt, double th0, double om0,
                          int side0, ContactMode mode0);
  void contact_step(double ax, double ay, double dt);
  SwitchReason check_rocking(const RockingModel& m, const StepReport& r) const;
  bool shared_cone_exceeded(const RockingModel& rock) const;
  const RockingModel& rocking_model() const { return lin_active_ ? lin_ : rock_; }
  bool linearized_sample_stands(const StepReport& r) const;
  bool linearized_step(double ax, double ay, double dt, const RockStart& start);
  void maybe_enter_linearized(double ax, double ay);
  void switch_up(SwitchReason reason, const RockStart& start, double ax, double ay, double dt);
  void switch_down(SwitchReason reason, double ax, double ay);
  void record(double time, ActiveModel to, SwitchReason reason, double onset);

  // prefetch() loads address ranges between members (body_ .. settings_, lin_eligible_ ..
  // scene_guarantee_, t_ .. outcome_): keep these groups together when reordering.
  Body body_;
  AdaptiveSettings settings_;
  RockingModel rock_;
  ContactModel contact_;
  RockingModel lin_;          // linearized tier (analytic stepper), used only when eligible
  bool lin_eligible_ = false;
  bool lin_active_ = false;
  ActiveModel active_ = ActiveModel::Rocking;
  SwitchReason initial_reason_ = SwitchReason::None;
  SlidingBound bound_;
  bool scene_rules_out_contact_ = false;  // static pre-check passed (finite mu_s)
  bool scene_guarantee_ = false;          // ... and it still holds (input inside, |theta| < alpha)
  double t_ = 0.0, ax_prev_ = 0.0, ay_prev_ = 0.0;
  double hold_ = 0.0;
  double rock_slip_ = 0.0;  // slip while RockingModel runs (constant)
  double share_ = 1.0;      // the planar pair's share of the friction budget (set every sample)
  std::vector<SwitchRecord> switches_;  // capacity max_switch_records, reserved
  AdaptiveReport report_;
  AdaptiveOutcome outcome_;
};

}  // namespace rocking_monitor::core
