#pragma once

#include <cstdint>
#include <limits>

#include "rocking_monitor/integrate/analytic_stepper.hpp"
#include "rocking_monitor/physics/body.hpp"
#include "rocking_monitor/physics/criteria.hpp"
#include "rocking_monitor/integrate/dopri5_stepper.hpp"
#include "rocking_monitor/integrate/rk4_stepper.hpp"
#include "rocking_monitor/integrate/solver_settings.hpp"

namespace rocking_monitor::core {

enum class Mode : std::uint8_t {
  Rest,        ///< both corners on the ground
  Rocking,     ///< rotating about corner 1 (theta > 0) or corner 2 (theta < 0)
  Overturned,  ///< lies on its side (|theta| reached the overturn angle); final
};
const char* to_string(Mode mode);

/// What happened during the last input sample.
struct StepReport {
  bool uplift = false;            ///< left REST during this sample
  int impacts = 0;                ///< pivot switches during this sample
  bool rest_capture = false;      ///< returned to REST by the rest-capture rule
  bool forced_rest = false;       ///< the per-sample event bound was hit (see SolverSettings)
  bool beyond_tipping_entered = false;  ///< |theta| passed alpha for the first time
  bool committed_entered = false;       ///< became committed for the first time
  bool overturned = false;              ///< reached the overturn angle during this sample
  std::uint8_t violation_onsets = 0;    ///< bit (1 << Criterion): became violated at sample end
  int integrator_steps = 0;             ///< accepted + rejected steps (cost)
  /// Absolute time of the first impact in this sample, s (NaN if none).
  double first_impact_time = std::numeric_limits<double>::quiet_NaN();
  /// Largest local maximum of |theta|/alpha located inside this sample (0 if none).
  double peak_ratio = 0.0;
};

/// Everything a run has established so far (latched; reset() clears it). Times are absolute (s);
/// NaN when it never happened.
struct RockingOutcome {
  bool beyond_tipping = false;   ///< |theta| passed alpha of the active pivot at least once
  bool committed = false;        ///< at some instant the body would have fallen without excitation
  bool overturned = false;       ///< landed on its side
  double max_rotation_ratio = 0.0;  ///< max |theta| / alpha of the pivot it occurred on
  int max_rotation_side = 0;        ///< that pivot (+1 corner 1, -1 corner 2, 0 never rocked)
  long impacts = 0;
  long rest_captures = 0;
  long forced_rest_captures = 0;
  long integrator_steps = 0;
  long samples = 0;
  double uplift_time = std::numeric_limits<double>::quiet_NaN();
  double beyond_tipping_time = std::numeric_limits<double>::quiet_NaN();
  double committed_time = std::numeric_limits<double>::quiet_NaN();
  double overturn_time = std::numeric_limits<double>::quiet_NaN();
};

/// The hybrid rocking state machine of one body: REST -> ROCKING (about corner 1 or 2) ->
/// IMPACT (pivot switch, eq. 34) -> ... -> REST again or OVERTURNED.
///
/// Streaming use: reset(t0, a_h, a_v) with the first input sample, then step(a_h, a_v, dt) for
/// each following sample; the ground acceleration is linear between samples (first-order hold).
/// step() does no allocation and bounded work (see SolverSettings::max_events_per_sample).
class RockingModel {
 public:
  /// Throws BodyError / std::invalid_argument for an invalid body or settings.
  RockingModel(const BodyParameters& body, const SolverSettings& settings);
  RockingModel(const Body& body, const SolverSettings& settings);

  /// Back to REST at time t (s) with the current ground acceleration (m/s^2); clears the outcome.
  void reset(double t, double ax = 0.0, double ay = 0.0);

  /// Advances one input sample: the ground acceleration goes linearly from the previous sample
  /// to (ax, ay) (m/s^2, vertical positive up) over dt seconds. dt must be finite and > 0 and the
  /// inputs finite (std::invalid_argument otherwise; the state is then unchanged).
  const StepReport& step(double ax, double ay, double dt);

  /// Puts the body in a given rocking state (tests and free-rocking studies). theta != 0 picks the
  /// pivot; theta == 0 with omega != 0 rocks about the pivot omega moves away from.
  void set_state(double theta, double omega);

  /// Everything one sample carries to the next (state snapshots, issue 29): restore(save()) into a
  /// model of the same body and settings continues bit for bit as the original would.
  struct Saved {
    Mode mode = Mode::Rest;
    int side = 0;
    double theta = 0.0, omega = 0.0;  ///< rad, rad/s
    double t = 0.0;                   ///< s
    double ax_prev = 0.0, ay_prev = 0.0;  ///< m/s^2
    std::uint8_t violations = 0;
    StepReport report;
    RockingOutcome outcome;
    Dopri5Stepper::Saved dopri5;
  };
  void save(Saved& out) const;
  void restore(const Saved& in);

  Mode mode() const { return mode_; }
  int side() const { return side_; }          ///< active pivot, 0 at rest
  double theta() const { return theta_; }     ///< rad, counter-clockwise positive
  double omega() const { return omega_; }     ///< rad/s
  double time() const { return t_; }         ///< s, time of the last sample
  double last_ax() const { return ax_prev_; }
  double last_ay() const { return ay_prev_; }
  /// |theta| / alpha of the active pivot (0 at rest).
  double rotation_ratio() const;
  /// Energy distance to overturning if the shaking stopped now (+1 at rest, < 0 committed).
  OverturnMargin margin() const;
  /// Ground reaction per unit mass at the last sample (rocking only; centripetal terms included).
  ContactReaction reaction() const { return reaction_at(ax_prev_, ay_prev_); }
  /// Bit (1 << Criterion) set while that pure-rocking condition is violated (at the last sample).
  std::uint8_t violations() const { return violations_; }
  const StepReport& last_report() const { return report_; }
  const RockingOutcome& outcome() const { return outcome_; }
  const Body& body() const { return body_; }
  const SolverSettings& settings() const { return settings_; }
  const Dopri5Stepper& dopri5() const { return dopri5_; }

  // ---- For BatchRocking (model/batch_rocking.hpp), which steps many bodies with SIMD and keeps
  // this class as the authority. Both do exactly what step(ax, ay, dt) does in the cases they are
  // meant for, without allocation; they do not validate (the batch validated the sample).

  /// A sample in which a body at REST stays at rest (the caller has shown that no corner lifts
  /// anywhere in the sample): advances time and the last inputs, re-evaluates the criteria.
  const StepReport& advance_at_rest(double ax, double ay, double dt);

  /// n samples at REST that BatchRocking kept for this body (no corner lifted, no criterion
  /// violated at any of their ends), applied at once: the time (the caller's sum t_ + dt + dt...,
  /// the same additions as step()), the last inputs and the sample count. No allocation. Also
  /// n samples of a body OVERTURNED before them (committed latched): step() does the same then.
  void apply_rest_samples(double t, double ax, double ay, long n);

  /// A sample in which a ROCKING body took dopri5 steps elsewhere, with the same arithmetic as
  /// step(), and nothing happened (no impact, overturn, turning point, first passage beyond
  /// alpha): sets theta, omega, the controller's next step size and FSAL derivative, the step
  /// count and the largest |theta|/alpha at step ends, then finishes the sample as step() does.
  /// end_clear: the caller has shown that at the sample end no criterion is violated (ground
  /// reaction > 0, sliding not checked) and the body is not committed (or already was): the
  /// criteria and the committed test, whose outcome is then known (nothing), are not evaluated.
  const StepReport& commit_rocking_sample(double ax, double ay, double dt, double theta,
                                          double omega, double h_next, double k1_theta,
                                          double k1_omega, int integrator_steps,
                                          double max_ratio, bool end_clear = false);

  /// n such samples (each one end_clear) that BatchRocking kept in its lanes, applied at once: the
  /// state after the last (theta, omega, controller), the time (the caller's sum t_ + dt + dt...,
  /// the same additions as step()), the last inputs, the step counts (total and the last sample's)
  /// and the largest |theta|/alpha over them. Leaves the model exactly as n calls of
  /// commit_rocking_sample(..., end_clear = true) would. No allocation.
  void apply_rocking_samples(double t, double ax, double ay, double dt, long n, double theta,
                             double omega, double h_next, double k1_theta, double k1_omega,
                             long integrator_steps, int last_integrator_steps, double max_ratio);

 private:
  void finish_sample(const GroundInput& in, double ax, double ay, double dt, bool end_clear = false);
  enum class Event { None, Impact, Overturn, Degenerate };
  double find_uplift(const GroundInput& in, double tau, double tau_end, int& side) const;
  void start_rocking(const GroundInput& in, double tau, int side);
  Event advance_rocking(const GroundInput& in, double& tau, double tau_end);
  bool apply_impact(const GroundInput& in, double tau);
  void go_to_rest();
  void update_criteria(const GroundInput& in, double tau);
  ContactReaction reaction_at(double ax, double ay) const;
  template <class Stepper>
  Event handle_step(const Stepper& stepper, const Pivot& pv, double& tau);

  Body body_;
  SolverSettings settings_;
  Dopri5Stepper dopri5_;
  Rk4Stepper rk4_;
  AnalyticStepper analytic_;

  Mode mode_ = Mode::Rest;
  int side_ = 0;
  double theta_ = 0.0, omega_ = 0.0;
  double t_ = 0.0;           // time of the last sample
  double ax_prev_ = 0.0, ay_prev_ = 0.0;
  double sample_dt_ = 0.0;   // dt of the sample being stepped
  std::uint8_t violations_ = 0;
  StepReport report_;
  RockingOutcome outcome_;
};

}  // namespace rocking_monitor::core
