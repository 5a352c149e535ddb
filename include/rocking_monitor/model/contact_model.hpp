#pragma once
// Full planar contact model of a free-standing rigid body (issue 7, part 1): REST, SLIDE, ROCK,
// SLIDE-ROCK, FREE FLIGHT and OVERTURNED, with impacts and landings. See docs/contact_model.md.

#include <array>
#include <cstdint>
#include <limits>

#include "rocking_monitor/physics/body.hpp"
#include "rocking_monitor/physics/dynamics.hpp"

namespace rocking_monitor::core {

enum class ContactMode : std::uint8_t {
  Rest,        ///< both corners on the floor, sticking (eq. 22 holds)
  Slide,       ///< both corners on the floor, sliding with kinetic friction mu_k
  Rock,        ///< rotating about a corner that sticks (the core's RockingOde)
  SlideRock,   ///< rotating about a corner that slips (friction mu_k R_y against the slip)
  Flight,      ///< no contact (R_y would be < 0, eq. 11): ballistic relative to the ground
  Overturned,  ///< |theta| reached the overturn angle; final
};
const char* to_string(ContactMode mode);
/// The body turns about a corner (sticking or slipping).
constexpr bool pivoting(ContactMode m) { return m == ContactMode::Rock || m == ContactMode::SlideRock; }

struct ContactSettings {
  /// Classical RK4 sub-steps per input sample (events located on the re-stepped RK4 solution).
  int substeps = 16;
  /// Rest capture after an impact, as in SolverSettings: |omega'| < ratio * p * alpha -> flat.
  double rest_capture_ratio = 1e-3;
  /// Bound on mode transitions in one input sample; beyond it the body is put at REST (forced).
  int max_events_per_sample = 200;
};

/// What happened during the last input sample, and the state at its end.
struct ContactReport {
  ContactMode mode = ContactMode::Rest;
  int side = 0;                 ///< active corner (+1 corner 1, -1 corner 2), 0 when flat/flying
  double slip = 0.0;            ///< u, horizontal displacement of the base relative to the ground, m
  double slip_velocity = 0.0;   ///< u', m/s (velocity of the contact corner / of the base)
  double theta = 0.0;           ///< rad
  int slip_episodes = 0;        ///< entries into SLIDE or SLIDE-ROCK from a non-slipping mode
  int impacts = 0;              ///< pivot switches at theta = 0 and landings from flight
  int flight_episodes = 0;      ///< entries into FLIGHT
  int transitions = 0;          ///< mode changes (events) in this sample
  bool overturned = false;      ///< reached the overturn angle during this sample
  bool forced_rest = false;     ///< the per-sample event bound was hit
  int integrator_steps = 0;     ///< RK4 sub-steps (cost)
};

/// Totals since reset().
struct ContactOutcome {
  long slip_episodes = 0, impacts = 0, flight_episodes = 0, forced_rests = 0, samples = 0;
  bool overturned = false;
  double max_abs_slip = 0.0;      ///< m
  double max_rotation_ratio = 0.0;  ///< max |theta| / alpha(side), sampled at sub-steps
  double first_slip_time = std::numeric_limits<double>::quiet_NaN();
  double first_uplift_time = std::numeric_limits<double>::quiet_NaN();
  double first_flight_time = std::numeric_limits<double>::quiet_NaN();
  double overturn_time = std::numeric_limits<double>::quiet_NaN();
};

/// Hybrid contact state machine of one body. Same streaming shape as RockingModel:
/// reset(t0, a_h, a_v), then step(a_h, a_v, dt) per input sample, ground acceleration linear in
/// between. step() does no allocation and bounded work.
///
/// Internal state X = (x, x', theta, omega, y, y'): centre of mass relative to the ground frame
/// (origin at corner 1's rest position), per unit mass. Reported slip u is derived from it
/// (displacement of the base corner on the side of theta; both corners agree at theta = 0).
class ContactModel {
 public:
  using State = std::array<double, 6>;

  ContactModel(const BodyParameters& body, const ContactSettings& settings = {});
  ContactModel(const Body& body, const ContactSettings& settings = {});

  void reset(double t, double ax = 0.0, double ay = 0.0);
  /// dt finite > 0 and finite inputs, else std::invalid_argument (state unchanged).
  const ContactReport& step(double ax, double ay, double dt);
  /// n samples of an OVERTURNED body applied at once (what n calls of step() do then: count time
  /// and samples): t the caller's sum time() + dt + ..., (ax, ay) and dt those of the last sample.
  void apply_overturned_samples(double t, double ax, double ay, double dt, long n);

  /// Exact state transfer (used by AdaptiveModel to take over from RockingModel): places the
  /// body at time t (s), with the current ground acceleration (ax, ay) (the start of the next
  /// first-order-hold sample), in
  ///  * REST (side == 0; theta and omega must be 0): flat, nothing moving, or
  ///  * pure ROCK about corner `side` (+1 corner 1, -1 corner 2) with (theta, omega): the pivot
  ///    sticks on the floor, slip velocity exactly zero, centre of mass on the rocking manifold
  ///    (y_pivot = 0, x and y velocities from omega); side * theta >= 0, |theta| < overturn angle.
  /// `slip` is the base's horizontal offset u (m), kept while the pivot sticks. Friction and
  /// lift-off are not checked here: the next step() exits ROCK at once if |R_x| > mu_s R_y or
  /// R_y < 0 (the caller places only valid pure-rocking states). Only the mechanical state, the
  /// time and the previous input change; the outcome counters (outcome()) are kept, or replaced by
  /// `outcome` in the second overload; last_report() is cleared to describe the placed state.
  /// Invalid arguments: std::invalid_argument, state unchanged.
  void set_state(double t, double ax, double ay, int side, double theta, double omega,
                 double slip = 0.0);
  void set_state(double t, double ax, double ay, int side, double theta, double omega,
                 double slip, const ContactOutcome& outcome);

  /// Everything one sample carries to the next (state snapshots, issue 29); see RockingModel::Saved.
  struct Saved {
    ContactMode mode = ContactMode::Rest;
    int side = 0, sigma = 0;
    double pivot_x = 0.0;  ///< m
    State x{};             ///< (x, x', theta, omega, y, y'), m, m/s, rad, rad/s
    double t = 0.0, ax_prev = 0.0, ay_prev = 0.0, dt = 0.0;  ///< s, m/s^2, s
    ContactReport report;
    ContactOutcome outcome;
  };
  void save(Saved& out) const;
  void restore(const Saved& in);

  ContactMode mode() const { return mode_; }
  int side() const { return side_; }
  double theta() const { return x_[2]; }
  double omega() const { return x_[3]; }
  double slip() const;           ///< u, m
  double slip_velocity() const;  ///< u', m/s
  double cg_height() const { return x_[4]; }  ///< y of the centre of mass, m
  const State& state() const { return x_; }
  double time() const { return t_; }
  /// Mechanical energy per unit mass in the ground frame without excitation:
  /// (x'^2 + y'^2 + i_g^2 omega^2)/2 + g y, J/kg.
  double energy() const;
  double mu_k() const { return mu_k_; }
  /// In ROCK: the ground's reaction on the sticking pivot now (per unit mass, m/s^2), with the last
  /// input; as RockingModel::reaction() gives it for the same state (the nonlinear equation).
  ContactReaction rock_reaction() const;
  /// The planar pair's shared friction budget (issue 51 part 4, monitoring/friction_share.hpp):
  /// from the next step() on, mu_s and mu_k are the body's times `share` in [0, 1] (1: the body's
  /// own, exactly). The pair sets it before every sample from its state, so it is not saved.
  void set_friction_share(double share);
  double friction_share() const { return share_; }
  const ContactReport& last_report() const { return report_; }
  const ContactOutcome& outcome() const { return outcome_; }
  const Body& body() const { return body_; }

 private:
  enum Ev : int { kNone = -1, kImpact, kOverturn, kFlight, kSlipOrStick, kLanding, kCount };
  // What the equations of motion of ROCK (the ground reaction) and SLIDE-ROCK (the normal force, in
  // ry) give besides the derivative; the lift-off and slip events need the same, per unit mass, m/s^2.
  struct Support {
    double rx = 0.0, ry = 0.0;
  };
  void derivative(const GroundInput& in, double tau, const State& s, State& d, Support* support = nullptr) const;
  // One classical RK4 step of length h from (tau, s0), its first stage k1 = derivative(in, tau, s0) given.
  void rk4_from(const GroundInput& in, double tau, const State& s0, const State& k1, double h, State& out) const;
  // support: what derivative() gave at (tau, s).
  void event_values(unsigned want, const GroundInput& in, double tau, const State& s, double (&f)[kCount],
                    const Support& support) const;
  double find_rest_exit(const GroundInput& in, double tau, double tau_end, unsigned& fired,
                        int& up_side) const;
  void leave_rest(const GroundInput& in, double tau, unsigned fired, int up_side);
  int advance(const GroundInput& in, double& tau, double tau_end);
  void handle_event(int ev, const GroundInput& in, double tau);
  void impact(int corner, const GroundInput& in, double tau, bool from_flight);
  void set_mode(ContactMode m, int side, int sigma, double tau);
  void enter_flat(const GroundInput& in, double tau);
  void enter_pivot(int side, const GroundInput& in, double tau);
  int consistent_sigma(int side, const GroundInput& in, double tau) const;
  void project_rock();
  void corner(int c, const State& s, double& rx, double& ry) const;  // CoM -> corner, rotated
  bool rock_friction_ok(const GroundInput& in, double tau, int side, double& rx) const;
  double slide_rock_theta_ddot(int side, int sigma, double G, const State& s, double& normal) const;

  Body body_;
  ContactSettings settings_;
  double mu_s_ = 0.0, mu_k_ = 0.0, ig2_ = 0.0;
  double mu_s_body_ = 0.0, mu_k_body_ = 0.0, share_ = 1.0;  // the body's own, and the pair's share
  ContactMode mode_ = ContactMode::Rest;
  int side_ = 0;
  int sigma_ = 0;        // slip direction of the base / pivot (+1: +x relative to the ground)
  double pivot_x_ = 0.0; // x of the sticking pivot in ROCK
  State x_{};
  double t_ = 0.0, ax_prev_ = 0.0, ay_prev_ = 0.0, dt_ = 0.0;
  ContactReport report_;
  ContactOutcome outcome_;
};

}  // namespace rocking_monitor::core
