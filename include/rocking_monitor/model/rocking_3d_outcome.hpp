#pragma once

// What the 3-D model reports (model/rocking_3d_model.hpp): its modes, its named transitions (each
// located, named and recorded with its reason, as the planar adaptive model's SwitchReason) and the
// outcome it adds to RockingOutcome.

#include <cstdint>
#include <limits>

namespace rocking_monitor::core {

enum class Mode3D : std::uint8_t { Rest, Edge, Vertex, Overturned, Slide, Flight };
const char* to_string(Mode3D mode);

/// Why the 3-D model changed mode: every transition is located (its instant inside the sample), named
/// and recorded with its reason, as the planar adaptive model's switches are (SwitchReason).
enum class Transition3D : std::uint8_t {
  Uplift,             ///< REST -> EDGE or VERTEX: an edge's uplift condition (eq. 19 about it) met
  SlipOnset,          ///< REST -> SLIDE: the demand left the friction cone |a_h| <= mu_s (g + a_z)
  Stick,              ///< SLIDE -> REST: the slip stopped and the static law holds
  SlideToEdge,        ///< SLIDE -> EDGE: the centre of pressure reached an edge (the pivot sticks)
  EdgeToVertex,       ///< EDGE -> VERTEX: an end of the rocking edge lifted (corner wobble)
  Landing,            ///< a landing under issue 40's sticking impact (-> EDGE, VERTEX or REST)
  LandingSlides,      ///< a landing whose friction could not stop the base: SLIDE on
  LandingPivotSlips,  ///< a landing friction decided with a slipping pivot (followed as sticking)
  LandingCornerSlips, ///< FLIGHT -> VERTEX: a landing on one corner that friction could not stop: it slide-rocks on
  RestCapture,        ///< a landing with almost no energy left: REST (the Zeno rule)
  Degenerate,         ///< -> REST: a degenerate pivot motion (rocking_3d_vertex.cpp)
  ForcedRest,         ///< -> REST: the bound on events per sample
  FellOffSupport,     ///< -> OVERTURNED: the centre of mass passed the support's edge sliding, or it tipped over that edge
  TripsOverLip,       ///< SLIDE -> EDGE or VERTEX: the base met a lip and pivots on it (the plastic impact)
  // Not a mode change (from == to): where the rocking model stops being exact (slide-rock and flight
  // are not modelled in 3-D yet; the motion after is followed as rocking on a sticking pivot).
  PivotSlips,         ///< EDGE, VERTEX: the pivot's reaction left the friction cone (slide-rock)
  PivotLifts,         ///< EDGE, VERTEX: the pivot's normal reaction vanished (flight)
  PivotSticks,        ///< VERTEX: the slipping pivot stopped and the static law holds
  SlidesOverSupportEdge,  ///< SLIDE: braking would tip it over the support's edge (slide-rock over it; followed as sliding)
  HeldByLip,          ///< SLIDE: a lip holds the base: it slides along the lip (met sliding, or slipping from rest against it)
  LeavesLip,          ///< SLIDE: the lip no longer pushes (the demand turned away from it): free again
  LipFace,            ///< VERTEX: a lifted corner below the lips' height met a lip's face (an impact; the pivot goes on)
  LiftOff,            ///< REST, SLIDE, EDGE, VERTEX -> FLIGHT: the floor's normal force vanished (it drops faster than gravity)
  Overturn,           ///< -> OVERTURNED: lying on its side, or over the tipping point
  ForcedOverturn,     ///< -> OVERTURNED: the bound on events per sample, beyond the tipping point
};
const char* to_string(Transition3D reason);

/// One transition: when (s), from and to which mode, why, and the contact after (edge or hull vertex
/// index; -1 at rest, sliding or overturned).
struct Transition3DRecord {
  double time = 0.0;
  Mode3D from = Mode3D::Rest;
  Mode3D to = Mode3D::Rest;
  Transition3D reason = Transition3D::Uplift;
  int contact = -1;
};


/// What the 3-D model adds to RockingOutcome.
struct Rocking3DOutcome {
  long edge_to_vertex = 0;        ///< an end of the rocking edge lifted: corner wobble began
  long vertex_impacts = 0;        ///< impacts while pivoting on a vertex
  long flat_impacts = 0;          ///< impacts of the whole base (edge rocking back to flat)
  double max_tilt = 0.0;          ///< largest tilt of the base from the floor, rad
  /// Largest kinetic energy after / before of any impact (<= 1 by the law; tests check it).
  double max_impact_energy_ratio = 0.0;
  /// Largest violation of the impact law's complementarity at any landing, m/s (0: every landing
  /// had an admissible solution; > 0 only where rounding or a degenerate contact set left none).
  double max_landing_violation = 0.0;
  /// Largest horizontal / normal impulse of any landing: the friction coefficient the sticking
  /// impact needs. Above the item's mu_s friction decides the landing (frictional_landings).
  double max_friction_demand = 0.0;
  /// Landings whose friction demand exceeded the item's mu_s: the real body slid there.
  long slipping_landings = 0;
  // Friction at landings (issue 51 part 3): where the sticking law needs more than mu_s or has no
  // solution, the frictional plastic impact (physics/frictional_impact.hpp) decides.
  long frictional_landings = 0;   ///< landings friction decided (solved where the answer can change what follows)
  long landing_slides = 0;        ///< of those, the ones after which the base slides on flat (SLIDE)
  /// Of those, the ones after which a pivot slips (or the body leaves the floor): slide-rock in 3-D is
  /// not modelled, the sticking answer is followed there.
  long pivot_slip_landings = 0;
  long unresolved_landings = 0;   ///< the frictional law, solved, did not converge: the sticking answer followed
  /// Landings onto a hull face other than the one rocked on (the body rolled over its hull).
  long hull_landings = 0;
  /// Rest captures on a hull face other than the base (a state the monitor reports).
  long rests_off_base = 0;
  /// See-saws on a tilted edge put onto the edge by the Zeno rule (rocking_3d_landing.cpp).
  long edge_captures = 0;
  // Sliding (issue 51): flat on a face, slipping and turning under Coulomb friction.
  long slides = 0;                ///< slip onsets (REST -> SLIDE)
  long sticks = 0;                ///< slips that came to rest under the static law (SLIDE -> REST)
  /// Sliding ended by an edge lifting (the centre of pressure reached the edge): rocking begins with
  /// the pivot sticking (the sticking impact of issue 40); rocking on a slipping pivot is not modelled.
  long slide_to_rock = 0;
  double first_slip_time = std::numeric_limits<double>::quiet_NaN();  ///< s
  double max_slip = 0.0;          ///< largest horizontal displacement of the centre of mass while sliding, m
  double max_slip_speed = 0.0;    ///< largest slip speed of the centre of mass, m/s (at step ends)
  double max_twist = 0.0;         ///< largest |yaw| of the footprint, rad
  double slip_time = 0.0;         ///< time spent sliding, s
  /// The item fell off its plinth, shelf or pedestal: its centre of mass passed the support's edge
  /// while sliding, or it overturned about that edge (it counts OVERTURNED, at that instant).
  bool fell_off_support = false;
  double fell_off_time = std::numeric_limits<double>::quiet_NaN();  ///< s
  /// Slides in which braking would have tipped the item over the support's edge (its centre of mass
  /// within mu_k h of it): the slide-rock over the edge is not modelled, the slide goes on flat.
  long slides_over_support_edge = 0;
  /// A body with a hull on a pedestal: contacts cut where a slide or a turn on a corner had carried
  /// the base so that the pedestal reaches beyond the base's edge. Pivoting on that edge, the hull's face across it could
  /// land on the pedestal: not modelled (the body rocks on the base's cut).
  long pedestal_beyond_base = 0;
  /// On a support: cuts made again while pivoting on a corner, where the body had turned about the
  /// vertical so that the support lay otherwise under its base (rocking_3d_support.cpp).
  long vertex_refits = 0;
  /// Samples that reached the bound on events beyond the tipping point (a see-saw on the edge it
  /// falls over): it overturns there (Transition3D::ForcedOverturn) instead of being put down flat.
  long forced_overturns = 0;
  // Lips along the support's edges (support_lips).
  long lip_trips = 0;             ///< slides that met a lip and tripped over it (pivoting on the base's corner or edge there)
  long lip_holds = 0;             ///< slides held by a lip (sliding along it): met it without tripping, or began against it
  /// Trips over a lip whose sticking pivot needed more friction than mu_s at the lip's foot (the
  /// sticking answer followed, as at landings where the frictional impact is not solved).
  long lip_slipping_trips = 0;
  /// Base corners that met a lipped edge's line beyond the lip's end (past the support's corner, the
  /// base overhanging the next edge): nothing is met there; while that corner lies beyond the line the
  /// lip is not watched.
  long lip_ends_passed = 0;
  /// The most a base corner lay beyond a lip while flat, m: a corner the rocking swings across a lip's
  /// line in the air (turning on a corner) passes over it (the lip is low) and lands on it; no slide
  /// carries it further.
  double max_lip_overhang = 0.0;
  /// Pivoting on a corner, a lifted corner below the lip's height (support_lip_height) met a lip's
  /// face: the plastic frictionless impact there (the pivot sticking) stopped its motion into the lip.
  long lip_face_impacts = 0;
  /// Samples where the bound on lip-face impacts (a corner pressed on the lip's face, met again and
  /// again) was reached: the corner was not watched for the rest of the sample.
  long lip_faces_not_followed = 0;
  // The pivot while rocking (EDGE, VERTEX): the floor's reaction on the body against the friction cone
  // |F_h| <= mu_s F_z, from the equations of motion at each step's end (onsets located on the dense
  // output). Beyond it the real body slide-rocks (or flies); the model follows a sticking pivot.
  double max_pivot_friction_demand = 0.0;  ///< largest |F_h| / F_z of the pivot's reaction while rocking
  long pivot_slips = 0;           ///< onsets of a slipping pivot (Transition3D::PivotSlips)
  long pivot_lifts = 0;           ///< onsets of a pivot pulled off the floor (Transition3D::PivotLifts)
  double first_pivot_slip_time = std::numeric_limits<double>::quiet_NaN();  ///< s (slip or lift)
  // Slide-rock on a vertex: the pivot slipping (VERTEX).
  long pivot_sticks = 0;          ///< slipping vertex pivots that stuck again (Transition3D::PivotSticks)
  double pivot_slip_time = 0.0;   ///< time a vertex pivot spent slipping, s
  double pivot_slip_distance = 0.0;  ///< path of slipping vertex pivots on the floor, m (at step ends)
  /// Slips not started because the sample's bound on them was reached (followed as sticking).
  long pivot_slips_not_followed = 0;
  /// A pivot followed as sticking outside the cone (an edge's slide-rock, or at the bound on slips)
  /// whose normal force then turned negative (at a step's end): held on the floor by a pull no floor
  /// exerts, where the real body slide-rocks and may leave the floor. Episodes, not flown.
  long pulled_pivots = 0;
  // Free flight (issue 51 part 2): the floor's normal force vanished (REST, SLIDE: g + a_z <= 0; EDGE,
  // VERTEX: the pivot's normal reaction). Followed without a support; on one, counted as pivot_lifts.
  long flights = 0;               ///< lift-offs into FLIGHT (Transition3D::LiftOff)
  double first_flight_time = std::numeric_limits<double>::quiet_NaN();  ///< s
  double flight_time = 0.0;       ///< time spent in flight, s
  double max_flight_height = 0.0; ///< largest height of the body's lowest point above the floor in flight, m (at step ends)
  long flight_landings = 0;       ///< landings from flight (the impact law over the points that touch)
  /// Of those, the ones on a single corner whose frictional impact left it slipping: followed, the
  /// corner slide-rocking on (Transition3D::LandingCornerSlips; counted in frictional_landings too).
  long corner_slip_landings = 0;
  long transitions = 0;           ///< mode transitions (the first kMaxTransitionRecords are kept: transitions())
};

}  // namespace rocking_monitor::core
