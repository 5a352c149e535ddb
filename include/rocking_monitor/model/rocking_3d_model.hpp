#pragma once

// Rigid-body rocking in 3-D on a convex polygonal base (issue 27), beside the planar RockingModel
// it generalises; with a hull (issue 40 part 3) the body rolls over its hull's faces, edges and
// vertices: every hull face is a base it may rest or rock on (EDGE about a face's edge lands on the
// face across it when that face comes flat), every hull vertex a pivot. Modes: REST; EDGE (rocking about one hull edge: the planar equation of motion
// with that edge's alpha, R, p and the ground acceleration projected onto the edge's outward
// normal, integrated by the same Dopri5Stepper and event scan as RockingModel); VERTEX (pivoting
// on one hull vertex without slip: 3 rotational degrees of freedom, the corner wobble);
// OVERTURNED. Transitions: uplift from rest about the edge or vertex whose moment first lifts the
// base; EDGE -> VERTEX when one end of the edge would be pulled off the floor (its reaction turns
// negative); landings (physics/impact_3d.hpp: the plastic impact over every base point on the floor
// at that instant) when the base comes back flat (EDGE, theta -> 0) or a vertex touches down (VERTEX). The ground frame is non-inertial: gravity plus the ground's
// acceleration act at the centre of mass. SLIDE (issue 51): flat on a face, sliding in any horizontal
// direction and turning about the vertical under one isotropic Coulomb law over the face's contact
// polygon (physics/base_friction.hpp); slip onset and stick are located exactly in the sample.
// Landings where the sticking impact needs more friction than mu_s are decided by the frictional
// impact (physics/frictional_impact.hpp). Slide-rock on a vertex (issue 51 part 2): where the sticking
// pivot's reaction leaves the friction cone the vertex slips on the floor under kinetic friction
// mu_k against its slip (rocking_3d_vertex_slip.cpp) until it sticks again under the static law, lands
// or lifts. On an edge, slide-rock is not modelled yet: the onset is located and named (PivotSlips)
// and the edge followed as sticking. FLIGHT (rocking_3d_flight.cpp): where the floor's normal force
// vanishes the body flies free of torque until a hull point lands (the same impact law).
//
// Frames: the item's floor frame at rest (x, y horizontal, z up); the body keeps a footprint
// (yaw and shift on the floor) that changes only when it turns while pivoting on a vertex.

#include <array>
#include <cstdint>
#include <limits>
#include <cmath>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rocking_monitor/integrate/dopri5_stepper.hpp"
#include "rocking_monitor/integrate/dopri5_vector.hpp"
#include "rocking_monitor/integrate/solver_settings.hpp"
#include "rocking_monitor/model/rocking_3d_outcome.hpp"
#include "rocking_monitor/model/rocking_model.hpp"
#include "rocking_monitor/physics/base_body.hpp"
#include "rocking_monitor/physics/base_friction.hpp"
#include "rocking_monitor/physics/contact_hull.hpp"
#include "rocking_monitor/physics/frictional_impact.hpp"
#include "rocking_monitor/physics/impact_3d.hpp"

namespace rocking_monitor::core {

struct StepEvents;  // integrate/event_location.hpp
struct RockingOde;  // physics/dynamics.hpp

/// Ground acceleration over one sample, linear in the local time (first-order hold), m/s^2.
struct GroundInput3 {
  Eigen::Vector3d a0 = Eigen::Vector3d::Zero();     ///< x, y horizontal, z vertical (up)
  Eigen::Vector3d slope = Eigen::Vector3d::Zero();  ///< m/s^3
  Eigen::Vector3d at(double tau) const { return a0 + slope * tau; }
};

class Rocking3DModel {
 public:
  /// Throws std::invalid_argument for invalid settings (the body was validated by BaseBody).
  Rocking3DModel(const BaseBody& body, const SolverSettings& settings);
  Rocking3DModel(const Rocking3DModel&) = delete;
  Rocking3DModel& operator=(const Rocking3DModel&) = delete;

  /// REST at time t with the current ground acceleration (m/s^2); clears the outcome.
  void reset(double t, const Eigen::Vector3d& a = Eigen::Vector3d::Zero());

  /// One input sample: ground acceleration linear from the previous sample to `a` over dt s.
  /// dt finite > 0 and `a` finite, else std::invalid_argument (state unchanged). No allocation.
  const StepReport& step(const Eigen::Vector3d& a, double dt);

  /// Whether step() would only count time at the current state: REST (as long as no edge lifts) or
  /// OVERTURNED with its levels latched. MonitorBatch then defers its quiet samples.
  bool rest_deferrable() const {
    // (off the base the batch's uplift thresholds, the base's, do not hold)
    return (mode_ == Mode3D::Rest && face_ == 0) || (mode_ == Mode3D::Overturned && outcome_.committed);
  }
  /// n samples that step() would have spent at REST without an edge lifting (or OVERTURNED), applied
  /// at once: t is the caller's sum time() + dt + dt ... (the same additions as step()), `a` and dt
  /// the last sample's.
  void apply_rest_samples(double t, const Eigen::Vector3d& a, double dt, long n);
  /// Outward normal of base edge k in the world frame (the footprint's yaw applied), unit.
  Eigen::Vector3d edge_normal(int edge) const;

  /// Rocking about edge k at theta (> 0) and omega (tests, free rocking).
  void set_edge_state(int edge, double theta, double omega);
  /// Pivoting on vertex v with the body turned by `rotation` about it (from its rest pose) and
  /// angular velocity `omega` (world, rad/s) (tests).
  void set_vertex_state(int vertex, const Eigen::Quaterniond& rotation, const Eigen::Vector3d& omega);

  /// Everything one sample carries to the next (state snapshots, issue 29); see RockingModel::Saved.
  struct Saved {
    Mode3D mode = Mode3D::Rest;
    int contact = -1;
    int face = 0;                                             ///< the hull face of EDGE and REST
    double theta = 0.0, omega = 0.0;                          ///< EDGE: rad, rad/s
    Eigen::Matrix<double, 7, 1> y = Eigen::Matrix<double, 7, 1>::Zero();  ///< VERTEX: q (w, x, y, z), omega (rad/s)
    Eigen::Vector3d pivot_world = Eigen::Vector3d::Zero();    ///< m
    double yaw = 0.0;                                         ///< rad
    Eigen::Vector2d shift = Eigen::Vector2d::Zero();          ///< m
    double fit_yaw = 0.0;                                     ///< rad: the footprint a support's cut of the base was made for
    Eigen::Vector2d fit_shift = Eigen::Vector2d::Zero();      ///< m: ditto
    double t = 0.0;                                           ///< s
    Eigen::Vector3d a_prev = Eigen::Vector3d::Zero();         ///< m/s^2
    bool armed[kMaxBaseVertices] = {};
    StepReport report;
    RockingOutcome outcome;
    Rocking3DOutcome outcome_3d;
    Dopri5Stepper::Saved dopri5;
    Dopri5Vector<7>::Saved vector;
    double last_probe_t = -1e300;  ///< s: when COMMITTED on a corner was last looked ahead for
    Eigen::Matrix<double, 6, 1> slide = Eigen::Matrix<double, 6, 1>::Zero();  ///< SLIDE: u (m/s), spin (rad/s), shift (m), yaw (rad)
    Dopri5Vector<6>::Saved slide_stepper;
    bool pivot_outside_cone = false;  ///< EDGE, VERTEX: the pivot's reaction is outside the cone (onset counted)
    bool pivot_slipping = false;      ///< VERTEX: the pivot slips (slip_state holds the motion)
    bool pivot_pulled = false;        ///< EDGE, VERTEX: outside the cone, the normal force negative (counted)
    Eigen::Matrix<double, 11, 1> slip_state = Eigen::Matrix<double, 11, 1>::Zero();  ///< q, omega (rad/s), pivot (m), its velocity (m/s)
    Eigen::Vector2d slip_direction = Eigen::Vector2d::UnitX();  ///< the slip's direction while its speed is 0
    Dopri5Vector<11>::Saved slip_stepper;
    int lip_held = -1;                ///< SLIDE: the support's edge whose lip holds the base (0-based), -1: none
    /// FLIGHT: q (w, x, y, z), omega (rad/s), centre of mass (m), its velocity (m/s), world frame
    Eigen::Matrix<double, 13, 1> flight = Eigen::Matrix<double, 13, 1>::Zero();
    Dopri5Vector<13>::Saved flight_stepper;
  };
  void save(Saved& out) const;
  void restore(const Saved& in);

  Mode3D mode() const { return mode_; }
  /// The hull face the body rests or rocks on (REST, EDGE; 0: the base), or that it left (VERTEX).
  int face() const { return face_; }
  /// The active edge (EDGE: of face()) or hull vertex (VERTEX; vertex k < n is base vertex k); -1 otherwise.
  int contact() const { return mode_ == Mode3D::Edge || mode_ == Mode3D::Vertex ? contact_ : -1; }
  /// contact() numbered as the item's base polygon: on a support the contact is the base cut where it
  /// lies on the support, whose edges and vertices are the base's own (their index in the catalogue's
  /// base polygon) or lie on the support's edge (-1). Without a support, contact().
  int base_contact() const;
  /// The pivot (VERTEX) or the rocking edge's start (EDGE) in the item frame, m; NaN otherwise.
  Eigen::Vector3d contact_point() const;
  double theta() const { return mode_ == Mode3D::Edge ? theta_ : 0.0; }  ///< EDGE: rad
  double omega() const { return mode_ == Mode3D::Edge ? omega_ : 0.0; }  ///< EDGE: rad/s
  /// SLIDE: the centre of mass's horizontal velocity relative to the floor (world frame), m/s.
  Eigen::Vector2d slip_velocity() const {
    return mode_ == Mode3D::Slide ? Eigen::Vector2d(slide_.head<2>()) : Eigen::Vector2d::Zero();
  }
  /// VERTEX: the slipping pivot's velocity on the floor (world), m/s; zero when it sticks.
  Eigen::Vector2d pivot_slip_velocity() const {
    return mode_ == Mode3D::Vertex && pivot_slipping_ ? Eigen::Vector2d(ys_.segment<2>(9)) : Eigen::Vector2d::Zero();
  }
  /// The centre of mass's velocity relative to the floor (world), m/s (zero at rest and overturned).
  Eigen::Vector3d centre_velocity() const;
  /// Puts the body in flight: turned by `rotation` from its rest pose, centre of mass at `centre` (m,
  /// world) moving with `velocity` (m/s), angular velocity `omega` (rad/s, world) (tests). The body
  /// must clear the floor; std::invalid_argument otherwise.
  void set_flight_state(const Eigen::Quaterniond& rotation, const Eigen::Vector3d& centre, const Eigen::Vector3d& velocity,
                        const Eigen::Vector3d& omega);
  /// SLIDE: the turning rate about the vertical, rad/s.
  double spin() const { return mode_ == Mode3D::Slide ? slide_(2) : 0.0; }
  /// Horizontal displacement of the centre of mass from where it stood at reset() while flat on the
  /// base (REST, SLIDE; the footprint's shift and yaw applied), m.
  Eigen::Vector2d slip() const;
  /// How far the centre of mass's plan position lies inside the support's edge, m (the live margin to
  /// falling off; < 0 beyond it); +inf without a support.
  double support_margin() const;
  /// Puts the body flat on its base sliding with `u` (m/s, world) and `spin` (rad/s) (tests).
  void set_slide_state(const Eigen::Vector2d& u, double spin);
  /// The body's pose: a body point x (floor frame at rest) is now at rotation() * x + translation().
  Eigen::Matrix3d rotation() const;
  Eigen::Vector3d translation() const;
  /// Angular velocity in the world (ground) frame, rad/s.
  Eigen::Vector3d angular_velocity() const;
  /// Tilt of the base from the floor, rad.
  double tilt() const;
  /// EDGE: theta / alpha of the edge; VERTEX: how far the centre of mass has turned towards the
  /// vertical through the vertex, as a fraction of the way (1 above it, > 1 beyond); 0 at rest;
  /// OVERTURNED: the largest reached on the way over.
  double rotation_ratio() const;
  /// Energy distance to overturning if the shaking stopped now, in units of the energy that lifts
  /// the body from rest to its tipping point (+1 at rest, < 0 committed). EDGE: the planar margin
  /// about the edge; VERTEX: kinetic plus potential energy against the centre of mass standing
  /// straight above the vertex (necessary for falling over it, not sufficient: the body may pass by).
  OverturnMargin margin() const;
  bool committed_now() const { return margin().committed; }
  /// Kinetic energy per unit mass, J/kg.
  double kinetic_energy() const;
  double time() const { return t_; }
  const StepReport& last_report() const { return report_; }
  const RockingOutcome& outcome() const { return outcome_; }
  const Rocking3DOutcome& outcome_3d() const { return outcome3_; }
  /// The first kMaxTransitionRecords transitions since reset(), in order (not carried by save()/restore():
  /// a resumed model lists the transitions after the resumption).
  static constexpr int kMaxTransitionRecords = 64;
  int transition_records() const { return transition_count_; }
  const Transition3DRecord& transition(int i) const { return transitions_[static_cast<std::size_t>(i)]; }
  const BaseBody& body() const { return body_; }

 private:
  using Vec7 = Eigen::Matrix<double, 7, 1>;
  Rocking3DModel(const BaseBody& body, const SolverSettings& settings, bool with_probe);
  enum class Event { None, Impact, Overturn, Lift, Degenerate, Stick, Lip, Flight };
  using Vec6 = Eigen::Matrix<double, 6, 1>;

  Eigen::Matrix3d yaw_matrix() const;
  Eigen::Vector3d to_footprint(const Eigen::Vector3d& world) const;  ///< rotate a world vector
  GroundInput edge_input(const GroundInput3& in, int edge) const;
  double uplift_at(const GroundInput3& in, int edge, double tau) const;
  double find_uplift(const GroundInput3& in, double tau, double tau_end) const;
  void start_motion(const GroundInput3& in, double tau);
  bool leave_rest(const GroundInput3& in, double& tau, double dt);
  void endpoint_reactions(int edge, double theta, double omega, double theta_ddot,
                          const Eigen::Vector3d& a_footprint, double& fa, double& fb) const;
  double end_rise(int edge, double theta, double omega, const Eigen::Vector3d& a_footprint, int stays) const;
  Event advance_edge(const GroundInput3& in, double& tau, double tau_end, int& lift_vertex);
  void note_edge_peaks(const StepEvents& ev, double alpha);
  void note_committed(double dt);
  double edge_lift_margin(const GroundInput3& in, const RockingOde& ode, double t, double theta, double omega,
                          int& stays) const;
  bool edge_lifts(const GroundInput3& in, const RockingOde& ode, double t_start, double th_start, double om_start,
                  double t_end_step, double t_tol, double& tau, int& lift_vertex);
  Event advance_vertex(const GroundInput3& in, double& tau, double tau_end, int& touching);
  void enter_vertex_from_edge(int vertex);
  void enter_vertex(int vertex, const Eigen::Vector3d& pivot_world, const Eigen::Matrix3d& rotation,
                    const Eigen::Vector3d& omega_world);
  void enter_edge_from_pose(int face, int edge, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& pivot_world,
                            int pivot_vertex, double omega_axis);
  void land(int touching, double tau);
  // Transitions (rocking_3d_transitions.cpp): the event's consequence and its record.
  void handle_event(Event e, int other, const GroundInput3& in, double tau);
  void note_transition(Mode3D from, Transition3D reason, double tau);
  void overturn_at(double tau);
  // A landing's pose, contact set and body, and what decides it (rocking_3d_landing.cpp).
  struct LandingScene {
    const Eigen::Matrix3d& r;        // the pose (item frame)
    const LandingContacts& set;      // the closing contact set
    const int* hull_index;           // contact k's hull vertex
    int down;                        // the face the body lies on or over
    bool flat_edge;                  // EDGE back flat on its face
    int face_before;
    double tau;
    const Landing* law;              // issue 40's sticking answer
    const LandingBody* body;         // the body before
    bool needs_friction = false;     // the sticking answer needs more than mu_s (or has no solution)
    bool solved = false;             // the frictional impact was solved (into `friction`)
    bool frictional = false;         // ... and converged: its answer is followed
    FrictionalLanding friction;
  };
  const std::vector<int>* landing_pose(int touching, Eigen::Matrix3d& r, Eigen::Vector3d& t, Eigen::Vector3d& omega);
  void closing_contacts(int touching, const Eigen::Matrix3d& r, const Eigen::Vector3d& t,
                        const std::vector<int>* landing_face, LandingContacts& set, int* hull_index) const;
  void see_saw_rule(const LandingBody& lb, const LandingContacts& set, const int* hull_index, double kappa,
                    Landing& chosen, Eigen::Vector3d& w);
  bool friction_decides(const Landing& law, double demand) const;
  void solve_friction(LandingScene& scene);
  bool keeps_loaded_pivot(const LandingScene& scene) const;
  void continue_after_landing(LandingScene& scene, const Landing& chosen, const Eigen::Vector3d& w, double kappa);
  void place_flat(const Eigen::Matrix3d& rotation, int vertex, const Eigen::Vector3d& point, int face);
  void slide_after_landing(const Eigen::Matrix3d& rotation, int vertex, const Eigen::Vector3d& point, int face,
                           const Eigen::Vector2d& u, double spin, double tau);
  void slip_after_landing(const LandingScene& scene);
  double capture_energy(const BaseVertex& v) const;
  void capture_rest(const Eigen::Matrix3d& rotation, int vertex, const Eigen::Vector3d& point, int face);
  double face_tilt(const Eigen::Matrix3d& rotation, int face) const;
  const ContactHull& hull() const { return *hull_; }
  // The current face and its base, cached: the per-step code reads them many times (without the
  // cache the pointer chase cost 4-10 % on records, rocking_benchmarks item3d).
  const HullFace& fc() const { return *face_ptr_; }
  const BaseBody& fb() const { return *face_body_; }  ///< the current face as a base
  void set_face(int face) {
    face_ = face;
    face_ptr_ = &hull().faces[static_cast<std::size_t>(face)];
    face_body_ = face_ptr_->body.get();
  }
  const BaseVertex& hv(int i) const { return hull().vertices[static_cast<std::size_t>(i)]; }
  double ratio_of(const Vec7& y) const;
  double ratio_about(const Eigen::Matrix3d& r, int vertex) const;
  double rise_rate(const Vec7& y) const;
  void record_impact(double tau, double energy_before);
  // The pivot's reaction while rocking (rocking_3d_pivot.cpp).
  Eigen::Vector3d edge_reaction(const GroundInput3& in, double t, double theta, double omega) const;
  Eigen::Vector3d vertex_reaction(const GroundInput3& in, double t, const Vec7& y) const;
  Eigen::Vector3d vertex_reaction(const GroundInput3& in, double t, const Vec7& y, const Vec7& dy) const;
  Eigen::Vector3d pivot_reaction(const GroundInput3& in, double t) const;
  double cone_margin(const Eigen::Vector3d& f) const;
  double watch_pivot(const GroundInput3& in, double t0, double t1, double t_tol, double& lift_at);
  double pivot_change_in_step(const GroundInput3& in, double t0, double t1, double t_tol, bool& lifts, bool& flies);
  // Slide-rock on a vertex (rocking_3d_vertex_slip.cpp).
  using Vec11 = Eigen::Matrix<double, 11, 1>;
  double slip_dynamics(const GroundInput3& in, double t, const Vec11& y, Eigen::Vector3d& w_dot,
                       Eigen::Vector2d& u_dot) const;
  double slip_accelerations(const GroundInput3& in, double t, const Vec11& y, const Eigen::Vector2d& dir,
                            Eigen::Vector3d& w_dot, Eigen::Vector2d& u_dot) const;
  Eigen::Vector2d starting_slip_direction(const GroundInput3& in, double t, const Eigen::Vector2d& guess) const;
  void slip_rhs(const GroundInput3& in, double t, const Vec11& y, Vec11& dy) const;
  void begin_slip(const GroundInput3& in, double tau);
  bool slip_presses_neighbour(const GroundInput3& in, double tau) const;
  double slip_end(const GroundInput3& in, double t0, double t1, double t_tol, bool& lifts) const;
  void end_slip(const GroundInput3& in, double tau, bool lifts);
  void hold_slip(const GroundInput3& in, double tau);
  void sync_slip();
  void aim_slip_ref();
  static constexpr int kVertexProbes = 4;
  template <class Rot>
  double touchdown_in_step(const Rot& rot, const Vec7& y0, const Eigen::Vector3d* up, double t0, double t1,
                           double t_tol, int& touching) const;
  template <class Rot>
  Event vertex_event_in_step(const Rot& rot, const Vec7& y0, const Vec7& y1, double t0, double t1, double t_tol,
                             int& touching, double& t_event, Eigen::Vector3d& up_end) const;
  template <class Rot>
  double support_touchdown(const Rot& rot, double t0, double t1, double t_tol) const;
  template <class Rot>
  Event refit_in_step(const Rot& rot, const Vec7& y0, const Vec7& y1, double t0, double t1, double t_tol,
                      Event event, int& touching, double& t_event, Eigen::Vector3d& up_end);
  template <class Rot>
  void note_vertex_peak(const Rot& rot, const Vec7& y0, const Vec7& y_stop, double t0, double t_stop, double t_tol);
  template <int N, class Rhs>
  Event vertex_motion(Dopri5Vector<N>& stepper, Eigen::Matrix<double, N, 1>& state, const Rhs& f,
                      const Eigen::Matrix<double, N, 1>& atol, const GroundInput3& in, double& tau,
                      double tau_end, int& touching, bool& switched);
  void go_to_rest();
  void note_ratio();
  void vertex_rhs(const GroundInput3& in, double t, const Vec7& y, Vec7& dy) const;
  Eigen::Matrix3d vertex_rotation(const Vec7& y) const;
  // SLIDE (rocking_3d_slide.cpp).
  double find_slip(const GroundInput3& in, double tau, double tau_end) const;
  double static_excess(const Eigen::Vector3d& a, double mu) const;
  void start_slide(double tau);
  Event advance_slide(const GroundInput3& in, double& tau, double tau_end);
  bool slide_step_events(const GroundInput3& in, double& tau, double t_start, double rho, int& restarts, Event& e);
  bool slide_event(const GroundInput3& in, double tau, double ts, double tl, double tm, double tr, int& restarts,
                   Event& e);
  Vec6 slide_atol() const;
  void aim_slide_ref(const GroundInput3& in, double tau, double rho);
  void slide_to_event(double tau, double t_start);
  void slide_rhs(const GroundInput3& in, double t, const Vec6& y, Vec6& dy) const;
  Eigen::Vector2d slide_friction(const GroundInput3& in, double t, const Vec6& y, double& torque) const;
  Eigen::Vector2d lift_friction(const GroundInput3& in, double t, const Vec6& y) const;
  double slide_lift(const GroundInput3& in, double t, const Vec6& y) const;
  // On a support (rocking_3d_support.cpp).
  double support_margin_of(const Vec6& y) const;
  void derive_contact();
  bool fit_contact(const Eigen::Vector2d& shift, double yaw, bool check_com = true);
  bool refit_on_vertex(const Vec7& y, const Vec7& arm);
  double support_lift(const GroundInput3& in, double t, const Vec6& y, bool over, double margin) const;
  bool pivot_on_support_edge() const;
  void slide_to_edge(const GroundInput3& in, double tau);
  void fall_off_support(double tau, double t_start);
  void note_over_support_edge(double t_over, double t_end);
  void note_slide();
  // Lips along the support's edges (rocking_3d_lip.cpp).
  Eigen::Vector2d lip_normal(int lip) const;
  double lip_depth(int k, const Eigen::Matrix2d& r, const Eigen::Vector2d& shift) const;
  double lip_gap(const Vec6& y, int& lip) const;
  void note_lip_floors();
  void note_lip_overhang();
  double lip_face_gap(const Vec7& y, int& corner, int& lip) const;
  double low_corner_depth(const Eigen::Matrix3d& r, int k, bool with_pivot, int& corner) const;
  double lip_face_in_step(double t0, double t1, double t_tol, int& corner, int& lip);
  void hit_lip_face(int corner, int lip, double tau);
  double point_lip_gap(const Eigen::Vector2d& x, const Eigen::Vector2d& moving) const;
  int lip_touched(const Eigen::Vector2d& push) const;
  Eigen::Vector2d lip_demand(const Eigen::Vector3d& a) const;
  Eigen::Vector2d held_demand(const Eigen::Vector3d& a) const;
  double lip_push(const GroundInput3& in, double t, const Vec6& y) const;
  void hold_on_lip(int lip);
  void hold_if_pressed(const Eigen::Vector2d& push, double tau);
  int meet_lip(int lip, double tau);
  bool trip_over_lip(int lip, int p, const Eigen::Matrix2d& r, double tau);
  // FLIGHT (rocking_3d_flight.cpp).
  using Vec13 = Eigen::Matrix<double, 13, 1>;
  // Without a friction coefficient the body is the paper's pure-rocking body (no slide, no flight: a
  // vanishing normal reaction stays a counted onset, as in the planar pair); on a support the cut of
  // the base would move with the flying body.
  bool follows_flight() const { return std::isfinite(body_.parameters().mu_s) && body_.parameters().support.empty(); }
  double flight_onset(const GroundInput3& in, double tau, double tau_end) const;
  double lift_in_step(const GroundInput3& in, double t0, double t1, double t_tol, double lift_at) const;
  void enter_flight(double tau);
  void fly(const Vec13& y);
  Eigen::Vector3d free_spin_rate(const Eigen::Matrix3d& r, const Eigen::Vector3d& w) const;
  void flight_rhs(const GroundInput3& in, double t, const Vec13& y, Vec13& dy) const;
  double lowest_point(const Vec13& y, int& lowest) const;
  double flight_touchdown(const Vec13& y0, double t0, double t1, double t_tol, int& touching) const;
  Event advance_flight(const GroundInput3& in, double& tau, double tau_end, int& touching);
  void flight_pose(Eigen::Matrix3d& r, Eigen::Vector3d& t) const;
  double free_rise(const GroundInput3& in, double t, const Eigen::Matrix3d& r, const Eigen::Vector3d& w,
                   const Eigen::Vector3d& to_pivot) const;
  double flight_energy(int& lowest) const;
  void put_down_from_flight();
  double mu_k() const { return std::isnan(body_.parameters().mu_k) ? body_.parameters().mu_s : body_.parameters().mu_k; }

  BaseBody body_;
  SolverSettings settings_;
  Dopri5Stepper dopri5_;     // EDGE: the planar stepper
  Dopri5Vector<7> vector_;   // VERTEX: quaternion + angular velocity
  Dopri5Vector<6> slide_stepper_;  // SLIDE: slip velocity, spin, shift, yaw
  std::vector<BaseFriction> friction_;  // per hull face, its contact polygon (made once)
  std::vector<double> slide_first_;     // per hull face, the smallest tan(alpha) of its edges: no lift below it
  Vec6 slide_ = Vec6::Zero();      // SLIDE: u (world, m/s), spin (rad/s), shift (m), yaw (rad)
  Eigen::Vector3d slide_ref_ = Eigen::Vector3d::Zero();  // SLIDE: the generalised velocity at the step start (stick event)
  int lip_held_ = -1;  // SLIDE: the support's edge whose lip holds the base (it slides along it, not turning)
  int lip_met_ = -1;   // the lip the last slide step's event met (advance_slide -> handle_event)
  // Per support edge, how far beyond its lip the base already lay at the slide step's start (m, <= 0):
  // a corner that landed over a (low) lip, having swung across it in the air, lies on the lip; the
  // slide may not carry it further out.
  double lip_floor_[kMaxBaseVertices] = {};
  double face_floor_[kMaxBaseVertices] = {};  // the same for corners pivoting on a corner (lip_face_in_step)
  static constexpr int kMaxLipFaceHits = 16;  // per sample
  int lip_face_hits_ = 0;

  Mode3D mode_ = Mode3D::Rest;
  int contact_ = -1;
  int face_ = 0;
  const ContactHull* hull_ = nullptr;  // body_'s (fixed for the model's life)
  const HullFace* face_ptr_ = nullptr;
  const BaseBody* face_body_ = nullptr;
  double theta_ = 0.0, omega_ = 0.0;   // EDGE
  Vec7 y_ = Vec7::Zero();              // VERTEX: q (w, x, y, z), omega (world)
  Eigen::Vector3d pivot_world_ = Eigen::Vector3d::Zero();  // VERTEX
  double yaw_ = 0.0;                   // footprint
  Eigen::Vector2d shift_ = Eigen::Vector2d::Zero();
  // On a support: the footprint the contact (body_'s base, the whole base where it lies on the
  // support) was cut for, the support seen from the item there, and whether that is the whole base.
  double fit_yaw_ = 0.0;
  Eigen::Vector2d fit_shift_ = Eigen::Vector2d::Zero();
  std::vector<Eigen::Vector2d> placed_support_;
  bool contact_whole_ = true;
  double whole_margin_ = 0.0;  // m: the centre of mass's plan position inside the whole base's edges
  double t_ = 0.0;
  Eigen::Vector3d a_prev_ = Eigen::Vector3d::Zero();
  double sample_dt_ = 0.0;
  bool armed_[kMaxBaseVertices] = {};
  static constexpr int kMaxLiftsPerSample = 8;
  int lifts_ = 0;                      // EDGE -> VERTEX switches in the current sample
  // Slides ended by an edge lifting in the current sample: where friction can tip the body (mu_k above
  // an edge's tan alpha) the real motion is slide-rock, not modelled; after one such end the sample
  // keeps the body from slipping again (rest and rocking as before issue 51), which bounds the work.
  int slide_lifts_ = 0;
  double floor_tol_ = 0.0;             // m: a base point this close to the floor is on it
  StepReport report_;
  RockingOutcome outcome_;
  Rocking3DOutcome outcome3_;
  std::array<Transition3DRecord, kMaxTransitionRecords> transitions_{};
  int transition_count_ = 0;
  bool pivot_outside_cone_ = false;  // EDGE, VERTEX: the onset is counted, not again until back inside
  bool pivot_pulled_ = false;        // ... and its normal force negative (pulled_pivots counted)
  // VERTEX slide-rock: the slipping pivot's motion (q, omega, pivot x y, its velocity) on its own
  // stepper; y_ and pivot_world_ follow it at every step's end, so that every measure reads them.
  bool pivot_slipping_ = false;
  Vec11 ys_ = Vec11::Zero();
  Eigen::Vector2d slip_dir_ = Eigen::Vector2d::UnitX();  // the slip's direction while its speed is 0
  Eigen::Vector2d slip_ref_ = Eigen::Vector2d::UnitX();  // the slip's velocity at the step's start (stop event)
  Dopri5Vector<11> slip_stepper_;
  // FLIGHT: q, omega, centre of mass, its velocity (world) on its own stepper.
  Vec13 yf_ = Vec13::Zero();
  Dopri5Vector<13> flight_stepper_;
  Eigen::Matrix3d central_inverse_ = Eigen::Matrix3d::Identity();  // (J_c / m)^-1 in the item frame
  double stop_speed_ = 0.0;  // m/s: a slipping pivot slower than this has stopped (1e-6 g / p)
  // Bounded work: at most kMaxSlipSwitches slips begun or ended in one sample (then followed as sticking).
  static constexpr int kMaxSlipSwitches = 4;
  int slip_switches_ = 0;
  static constexpr int kMaxSlipSteps = 500;
  int slip_steps_ = 0;  // the slipping pivot's steps in the current sample
  Transition3D landing_reason_ = Transition3D::Landing;  // set by land(): how the landing ended
  // VERTEX: COMMITTED (it would overturn if the shaking stopped now) has no closed form on a corner
  // as it has about an edge: once the energy could carry the centre of mass over the corner, the free
  // motion is stepped ahead on this copy of the model (made with it, so no allocation per sample),
  // every kProbeInterval s at most, for up to kProbeHorizon s.
  bool falls_if_shaking_stops(double t_now);
  std::unique_ptr<Rocking3DModel> probe_;
  double last_probe_t_ = -1e300;
  static constexpr double kProbeHorizon = 3.0, kProbeStep = 0.02, kProbeInterval = 0.02;  // s
};

}  // namespace rocking_monitor::core
