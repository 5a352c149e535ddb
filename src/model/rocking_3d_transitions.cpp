// The 3-D model's transitions: what each located event leads to, and its record (when, from, to, why),
// in the shape of the planar adaptive model's switches (adaptive_model.cpp).
#include <cmath>

#include "rocking_monitor/model/rocking_3d_model.hpp"

namespace rocking_monitor::core {

const char* to_string(Transition3D r) {
  switch (r) {
    case Transition3D::Uplift: return "uplift";
    case Transition3D::SlipOnset: return "slip onset (the demand left the friction cone)";
    case Transition3D::Stick: return "stick (the slip stopped, the static law holds)";
    case Transition3D::SlideToEdge: return "slide to an edge (the centre of pressure reached it)";
    case Transition3D::EdgeToVertex: return "an end of the edge lifted (corner wobble)";
    case Transition3D::Landing: return "landing (sticking impact)";
    case Transition3D::LandingSlides: return "landing that friction could not stop: slides on";
    case Transition3D::LandingPivotSlips: return "landing with a slipping pivot (followed as sticking)";
    case Transition3D::LandingCornerSlips: return "landing on a corner that friction could not stop: slide-rocks on";
    case Transition3D::RestCapture: return "rest capture";
    case Transition3D::Degenerate: return "degenerate pivot motion: rest";
    case Transition3D::ForcedRest: return "forced rest (events per sample bound)";
    case Transition3D::ForcedOverturn: return "overturned at the events per sample bound, beyond its tipping point";
    case Transition3D::FellOffSupport: return "fell off its support";
    case Transition3D::TripsOverLip: return "tripped over a lip (pivots on the base at the lip)";
    case Transition3D::HeldByLip: return "held by a lip (slides along it)";
    case Transition3D::LeavesLip: return "the lip let go (the demand turned away from it)";
    case Transition3D::LipFace: return "a lifted corner met a lip's face (impact; pivoting on)";
    case Transition3D::SlidesOverSupportEdge: return "braking would tip it over the support's edge (slide-rock over the edge; followed as sliding)";
    case Transition3D::PivotSlips: return "the pivot's reaction left the friction cone (slide-rock; followed as sticking)";
    case Transition3D::PivotSticks: return "the slipping pivot stopped and the static law holds";
    case Transition3D::PivotLifts: return "the pivot's normal reaction vanished (flight; followed as sticking)";
    case Transition3D::LiftOff: return "lift-off (the floor's normal force vanished): flight";
    case Transition3D::Overturn: return "overturned";
  }
  return "unknown";
}

void Rocking3DModel::note_transition(Mode3D from, Transition3D reason, double tau) {
  ++outcome3_.transitions;
  // A new contact starts inside the cone, except after a landing already counted with a slipping pivot;
  // an end of the edge lifting keeps the other end's slip (the same contact goes on).
  if (reason != Transition3D::PivotSlips && reason != Transition3D::PivotLifts && reason != Transition3D::PivotSticks &&
      reason != Transition3D::EdgeToVertex && reason != Transition3D::SlidesOverSupportEdge &&
      reason != Transition3D::HeldByLip && reason != Transition3D::LeavesLip && reason != Transition3D::LipFace) {
    pivot_outside_cone_ = reason == Transition3D::LandingPivotSlips;
    pivot_pulled_ = false;
  }
  if (transition_count_ >= kMaxTransitionRecords) return;
  const bool has_contact = mode_ == Mode3D::Edge || mode_ == Mode3D::Vertex;
  transitions_[static_cast<std::size_t>(transition_count_++)] = {t_ + tau, from, mode_, reason, has_contact ? contact_ : -1};
}

void Rocking3DModel::overturn_at(double tau) {
  if (!outcome3_.fell_off_support && pivot_on_support_edge()) {  // over the support's edge: off it
    outcome3_.fell_off_support = true;
    outcome3_.fell_off_time = t_ + tau;
  }
  note_ratio();
  mode_ = Mode3D::Overturned;
  outcome_.overturned = true;
  outcome_.overturn_time = t_ + tau;
  report_.overturned = true;
}

// The consequence of the event `e` located at tau (`other`: the edge-to-vertex's vertex, or the
// landing's touching vertex, as advance_edge / advance_vertex name it), and its record.
void Rocking3DModel::handle_event(Event e, int other, const GroundInput3& in, double tau) {
  const Mode3D from = mode_;
  switch (e) {
    case Event::Overturn:
      overturn_at(tau);
      note_transition(from, outcome3_.fell_off_support ? Transition3D::FellOffSupport : Transition3D::Overturn, tau);
      return;
    case Event::Stick:
      go_to_rest();  // the slip stopped and the static law holds: at rest where it slid to
      ++outcome3_.sticks;
      note_transition(from, Transition3D::Stick, tau);
      return;
    case Event::Degenerate:
      go_to_rest();
      report_.rest_capture = true;
      ++outcome_.rest_captures;
      note_transition(from, Transition3D::Degenerate, tau);
      return;
    case Event::Lift:
      if (from == Mode3D::Slide) {
        slide_to_edge(in, tau);
        note_transition(from, Transition3D::SlideToEdge, tau);
      } else {
        enter_vertex_from_edge(other);
        note_transition(from, Transition3D::EdgeToVertex, tau);
      }
      return;
    case Event::Flight:
      enter_flight(tau);
      note_transition(from, Transition3D::LiftOff, tau);
      return;
    case Event::Lip:
      switch (meet_lip(lip_met_, tau)) {
        case 1: note_transition(from, Transition3D::TripsOverLip, tau); return;
        case 0: note_transition(from, Transition3D::HeldByLip, tau); return;
        case 2: note_transition(from, Transition3D::Stick, tau); return;
        default: return;  // beyond the lip's end: nothing met (counted)
      }
    default:
      land(other, tau);  // EDGE: -1 back flat on the face, -2 the face across comes flat; VERTEX: the vertex
      note_transition(from, landing_reason_, tau);
      return;
  }
}

}  // namespace rocking_monitor::core
