// The 3-D model's state, pose and the sample loop (the modes' motion in rocking_3d_edge.cpp and
// rocking_3d_vertex.cpp, landings in rocking_3d_landing.cpp, the look-ahead in rocking_3d_lookahead.cpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

#include "rocking_monitor/physics/criteria.hpp"
#include "rocking_monitor/physics/support_polygon.hpp"

#include "rocking_3d_internal.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"

namespace rocking_monitor::core {

using rocking_3d::gravity_and_inertia;
using rocking_3d::rot_z;

const char* to_string(Mode3D mode) {
  switch (mode) {
    case Mode3D::Rest: return "REST";
    case Mode3D::Edge: return "EDGE";
    case Mode3D::Vertex: return "VERTEX";
    case Mode3D::Overturned: return "OVERTURNED";
    case Mode3D::Slide: return "SLIDE";
    case Mode3D::Flight: return "FLIGHT";
  }
  return "UNKNOWN";
}


namespace {

const SolverSettings& checked_3d(const SolverSettings& s) {
  if (const std::string e = validate(s); !e.empty()) throw std::invalid_argument(e);
  if (s.method != Method::Dopri5 || s.model != ModelKind::Nonlinear)
    throw std::invalid_argument("Rocking3DModel: only the nonlinear model with dopri5 is available in 3-D");
  return s;
}

}  // namespace

Rocking3DModel::Rocking3DModel(const BaseBody& body, const SolverSettings& settings)
    : Rocking3DModel(body, settings, true) {}

Rocking3DModel::Rocking3DModel(const BaseBody& body, const SolverSettings& settings, bool with_probe)
    : body_(body), settings_(checked_3d(settings)) {
  central_inverse_ = body_.central_inertia_per_mass().inverse();
  const std::vector<Eigen::Vector2d>& support = body_.parameters().support;
  placed_support_.reserve(support.size());
  contact_whole_ = support.empty() || first_outside(body_.whole_base(), support, 0.0) < 0;
  whole_margin_ = inside_margin(body_.whole_base(), body_.centre_of_mass().head<2>());
  derive_contact();
  if (with_probe) probe_.reset(new Rocking3DModel(body, settings, false));
  reset(0.0);
}

// What the model keeps of its body's contact: made at construction and again when a support's cut
// of the base moves with the item (rocking_3d_support.cpp).
void Rocking3DModel::derive_contact() {
  hull_ = &body_.contact_hull();
  set_face(face_);
  double size = 0.0;
  for (const BaseVertex& v : hull().vertices) size = std::max(size, v.radius);
  floor_tol_ = 1e-9 * size;
  stop_speed_ = 1e-6 * kGravity / body_.max_p();
  friction_.clear();
  slide_first_.clear();
  for (const HullFace& f : hull().faces) {
    std::vector<Eigen::Vector2d> polygon;
    for (int k = 0; k < f.body->vertex_count(); ++k) polygon.push_back(f.body->vertex(k).position.head<2>());
    friction_.emplace_back(polygon);
    double tan_min = std::numeric_limits<double>::infinity();
    for (int k = 0; k < f.body->vertex_count(); ++k) tan_min = std::min(tan_min, f.body->edge(k).pivot.tan_alpha);
    slide_first_.push_back(tan_min);
  }
}

void Rocking3DModel::reset(double t, const Eigen::Vector3d& a) {
  mode_ = Mode3D::Rest;
  contact_ = -1;
  set_face(0);
  theta_ = omega_ = 0.0;
  y_.setZero();
  y_(0) = 1.0;
  pivot_world_.setZero();
  yaw_ = 0.0;
  shift_.setZero();
  fit_contact(shift_, yaw_);
  t_ = t;
  a_prev_ = a;
  report_ = StepReport{};
  outcome_ = RockingOutcome{};
  outcome3_ = Rocking3DOutcome{};
  last_probe_t_ = -1e300;
  dopri5_.reset(0.05 / body_.max_p());
  vector_.reset(0.05 / body_.max_p());
  slide_stepper_.reset(0.05 / body_.max_p());
  slip_stepper_.reset(0.05 / body_.max_p());
  flight_stepper_.reset(0.05 / body_.max_p());
  yf_.setZero();
  pivot_slipping_ = false;
  ys_.setZero();
  slide_.setZero();
  lip_held_ = -1;
  transition_count_ = 0;
  pivot_outside_cone_ = pivot_pulled_ = false;
}

void Rocking3DModel::save(Saved& out) const {
  out.mode = mode_;
  out.contact = contact_;
  out.face = face_;
  out.theta = theta_;
  out.omega = omega_;
  out.y = y_;
  out.pivot_world = pivot_world_;
  out.yaw = yaw_;
  out.shift = shift_;
  out.fit_yaw = fit_yaw_;
  out.fit_shift = fit_shift_;
  out.t = t_;
  out.a_prev = a_prev_;
  std::copy(std::begin(armed_), std::end(armed_), std::begin(out.armed));
  out.report = report_;
  out.outcome = outcome_;
  out.outcome_3d = outcome3_;
  dopri5_.save(out.dopri5);
  vector_.save(out.vector);
  out.last_probe_t = last_probe_t_;
  out.slide = slide_;
  slide_stepper_.save(out.slide_stepper);
  out.pivot_outside_cone = pivot_outside_cone_;
  out.pivot_pulled = pivot_pulled_;
  out.pivot_slipping = pivot_slipping_;
  out.slip_state = ys_;
  out.slip_direction = slip_dir_;
  slip_stepper_.save(out.slip_stepper);
  out.lip_held = lip_held_;
  out.flight = yf_;
  flight_stepper_.save(out.flight_stepper);
}

void Rocking3DModel::restore(const Saved& in) {
  if (in.face < 0 || in.face >= static_cast<int>(hull().faces.size()))
    throw std::invalid_argument("Rocking3DModel::restore: face " + std::to_string(in.face) + " is not a face of this body's hull");
  const std::vector<int>& lips = body_.parameters().support_lips;
  if (in.lip_held != -1 && (in.mode != Mode3D::Slide || std::find(lips.begin(), lips.end(), in.lip_held) == lips.end()))
    throw std::invalid_argument("Rocking3DModel::restore: lip_held " + std::to_string(in.lip_held) +
                                " is not a lip of this body's support holding a slide");
  fit_contact(in.fit_shift, in.fit_yaw, false);  // the contact the state was in (a support's cut follows it)
  mode_ = in.mode;
  contact_ = in.contact;
  set_face(in.face);
  theta_ = in.theta;
  omega_ = in.omega;
  y_ = in.y;
  pivot_world_ = in.pivot_world;
  yaw_ = in.yaw;
  shift_ = in.shift;
  t_ = in.t;
  a_prev_ = in.a_prev;
  std::copy(std::begin(in.armed), std::end(in.armed), std::begin(armed_));
  report_ = in.report;
  outcome_ = in.outcome;
  outcome3_ = in.outcome_3d;
  dopri5_.restore(in.dopri5);
  vector_.restore(in.vector);
  last_probe_t_ = in.last_probe_t;
  slide_ = in.slide;
  slide_stepper_.restore(in.slide_stepper);
  pivot_outside_cone_ = in.pivot_outside_cone;
  pivot_pulled_ = in.pivot_pulled;
  pivot_slipping_ = in.pivot_slipping;
  ys_ = in.slip_state;
  slip_dir_ = in.slip_direction;
  slip_stepper_.restore(in.slip_stepper);
  lip_held_ = in.lip_held;
  yf_ = in.flight;
  flight_stepper_.restore(in.flight_stepper);
}

Eigen::Matrix3d Rocking3DModel::yaw_matrix() const { return rot_z(yaw_); }

Eigen::Vector3d Rocking3DModel::to_footprint(const Eigen::Vector3d& world) const {
  return yaw_ == 0.0 ? world : Eigen::Vector3d(rot_z(-yaw_) * world);
}

Eigen::Matrix3d Rocking3DModel::vertex_rotation(const Vec7& y) const {
  return rocking_3d::quaternion_rotation(y);
}

// EDGE and REST are stated in the current face's floor frame (face 0: the item frame); a point x of
// the item frame is at rotation_face * (F x + f) + translation_face with F, f the face's frame.
Eigen::Matrix3d Rocking3DModel::rotation() const {
  Eigen::Matrix3d r;
  switch (mode_) {
    case Mode3D::Edge: {
      const BaseEdge& e = fb().edge(contact_);
      r = yaw_matrix() * Eigen::AngleAxisd(theta_, e.axis).toRotationMatrix();
      break;
    }
    case Mode3D::Vertex: return vertex_rotation(y_);
    case Mode3D::Flight: return rocking_3d::quaternion_rotation(yf_);
    default: r = yaw_matrix();
  }
  return face_ == 0 ? r : Eigen::Matrix3d(r * fc().rotation);
}

Eigen::Vector3d Rocking3DModel::translation() const {
  const Eigen::Vector3d shift3(shift_.x(), shift_.y(), 0.0);
  switch (mode_) {
    case Mode3D::Edge: {
      const Eigen::Vector3d& a = fb().vertex(fb().edge(contact_).a).position;
      // footprint(a + R_e (x - a)): x -> Rz R_e x + Rz (a - R_e a) + shift
      const Eigen::Matrix3d re = Eigen::AngleAxisd(theta_, fb().edge(contact_).axis).toRotationMatrix();
      const Eigen::Vector3d t = yaw_matrix() * (a - re * a) + shift3;
      return face_ == 0 ? t : Eigen::Vector3d(t + yaw_matrix() * (re * fc().offset));
    }
    case Mode3D::Vertex: return pivot_world_ - vertex_rotation(y_) * hv(contact_).position;
    case Mode3D::Flight: return Eigen::Vector3d(yf_.segment<3>(7)) - rotation() * body_.centre_of_mass();
    default: return face_ == 0 ? shift3 : Eigen::Vector3d(shift3 + yaw_matrix() * fc().offset);
  }
}

Eigen::Vector3d Rocking3DModel::contact_point() const {
  if (mode_ == Mode3D::Vertex) return hv(contact_).position;
  if (mode_ == Mode3D::Edge) return hv(fc().hull_vertex[static_cast<std::size_t>(fb().edge(contact_).a)]).position;
  return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
}

// The centre of mass's velocity relative to the floor (world): a slide's, the turn's about the edge or
// the pivot (and the pivot's slip), the flight's; m/s.
Eigen::Vector3d Rocking3DModel::centre_velocity() const {
  switch (mode_) {
    case Mode3D::Slide: return Eigen::Vector3d(slide_(0), slide_(1), 0.0);
    case Mode3D::Flight: return yf_.tail<3>();
    case Mode3D::Edge: {
      const Eigen::Matrix3d r = rotation();
      const Eigen::Vector3d t = translation();
      const Eigen::Vector3d a = r * hv(fc().hull_vertex[static_cast<std::size_t>(fb().edge(contact_).a)]).position + t;
      return angular_velocity().cross(r * body_.centre_of_mass() + t - a);
    }
    case Mode3D::Vertex: {
      const Eigen::Vector3d v = angular_velocity().cross(rotation() * body_.centre_of_mass() + translation() - pivot_world_);
      return pivot_slipping_ ? Eigen::Vector3d(v + Eigen::Vector3d(ys_(9), ys_(10), 0.0)) : v;
    }
    default: return Eigen::Vector3d::Zero();
  }
}

Eigen::Vector3d Rocking3DModel::angular_velocity() const {
  if (mode_ == Mode3D::Edge) return yaw_matrix() * (omega_ * fb().edge(contact_).axis);
  if (mode_ == Mode3D::Vertex) return y_.tail<3>();
  if (mode_ == Mode3D::Flight) return yf_.segment<3>(4);
  return Eigen::Vector3d::Zero();
}

double Rocking3DModel::tilt() const {
  if (mode_ == Mode3D::Overturned) return body_.overturn_angle();
  if (face_ == 0 && mode_ == Mode3D::Edge) return theta_;
  if (face_ == 0 && (mode_ == Mode3D::Rest || mode_ == Mode3D::Slide)) return 0.0;
  return std::acos(std::clamp(rotation()(2, 2), -1.0, 1.0));
}


void Rocking3DModel::go_to_rest() {
  fit_contact(shift_, yaw_);  // (the footprint may have moved: a support's cut follows it)
  mode_ = Mode3D::Rest;
  contact_ = -1;
  theta_ = omega_ = 0.0;
  dopri5_.invalidate();
  vector_.invalidate();
  slide_stepper_.invalidate();
  pivot_slipping_ = false;
  lip_held_ = -1;
  if (!body_.parameters().support_lips.empty()) note_lip_overhang();
}

void Rocking3DModel::set_edge_state(int edge, double theta, double omega) {
  if (edge < 0 || edge >= fb().vertex_count() || !std::isfinite(theta) || !std::isfinite(omega) ||
      theta < 0.0)
    throw std::invalid_argument("set_edge_state: edge index, theta >= 0 and omega finite");
  mode_ = Mode3D::Edge;
  contact_ = edge;
  theta_ = theta;
  omega_ = omega;
  dopri5_.invalidate();
}

void Rocking3DModel::set_vertex_state(int vertex, const Eigen::Quaterniond& rotation,
                                      const Eigen::Vector3d& omega) {
  if (vertex < 0 || vertex >= body_.vertex_count() || face_ != 0 || !omega.allFinite())
    throw std::invalid_argument("set_vertex_state: base vertex index (from the base) and omega finite");
  const Eigen::Matrix3d r = rotation.normalized().toRotationMatrix();
  enter_vertex(vertex, yaw_matrix() * hv(vertex).position + Eigen::Vector3d(shift_.x(), shift_.y(), 0.0),
               r, omega);
}

Eigen::Vector3d Rocking3DModel::edge_normal(int edge) const {
  return yaw_ == 0.0 ? fb().edge(edge).normal : Eigen::Vector3d(yaw_matrix() * fb().edge(edge).normal);
}

void Rocking3DModel::apply_rest_samples(double t, const Eigen::Vector3d& a, double dt, long n) {
  // What n calls of step() do at REST without a lift (or OVERTURNED and committed): a fresh report,
  // the clock, the last input, the sample count.
  report_ = StepReport{};
  sample_dt_ = dt;
  lifts_ = 0;
  slide_lifts_ = 0;
  slip_switches_ = 0;
  slip_steps_ = 0;
  t_ = t;
  a_prev_ = a;
  outcome_.samples += n;
}

// ---------------------------------------------------------------- the sample

// COMMITTED at the sample's end (t_ + dt; t_ is advanced after).
void Rocking3DModel::note_committed(double dt) {
  // About a base edge with no hull face before the side, COMMITTED has the planar closed form; on a
  // hull face or an edge whose face across lies flat before the side, passing the edge is a landing
  // on that face, not an overturn: looked ahead as on a corner.
  const bool closed_form = mode_ == Mode3D::Edge && face_ == 0 && !(fc().fold[static_cast<std::size_t>(contact_)] < body_.overturn_angle());
  if (closed_form && !outcome_.committed) {
    const OverturnMargin m = overturn_margin(fb().edge(contact_).pivot, 1, ModelKind::Nonlinear, theta_, omega_);
    if (m.committed) {
      outcome_.committed = true;
      outcome_.committed_time = t_ + dt;
      report_.committed_entered = true;
    }
  } else if ((mode_ == Mode3D::Vertex || mode_ == Mode3D::Edge || mode_ == Mode3D::Flight) && !closed_form && !outcome_.committed && probe_ &&
             t_ + dt - last_probe_t_ >= kProbeInterval &&
             margin().committed) {
    last_probe_t_ = t_ + dt;
    if (falls_if_shaking_stops(t_ + dt)) {
      outcome_.committed = true;
      outcome_.committed_time = t_ + dt;
      report_.committed_entered = true;
    }
  } else if (mode_ == Mode3D::Overturned && !outcome_.committed) {
    outcome_.committed = true;
    outcome_.committed_time = outcome_.overturn_time;
    report_.committed_entered = true;
  }
}

// REST: whichever the input brings first in [tau, dt]: an edge lifting, the demand leaving the friction
// cone, or the floor dropping faster than gravity (flight first on a tie: its normal force is gone).
// False where nothing does (the body rests through the sample).
bool Rocking3DModel::leave_rest(const GroundInput3& in, double& tau, double dt) {
  const double lift = find_uplift(in, tau, dt), slip = find_slip(in, tau, dt), fly = flight_onset(in, tau, dt);
  if (!std::isfinite(lift) && !std::isfinite(slip) && !std::isfinite(fly)) return false;
  if (fly <= lift && fly <= slip) {
    tau = fly;
    enter_flight(tau);
    note_transition(Mode3D::Rest, Transition3D::LiftOff, tau);
  } else if (slip < lift) {
    tau = slip;
    start_slide(tau);
    note_transition(Mode3D::Rest, Transition3D::SlipOnset, tau);
    hold_if_pressed(-in.at(tau).head<2>(), tau);  // (begun against a lip that it presses)
  } else {
    tau = lift;
    start_motion(in, tau);
    note_transition(Mode3D::Rest, Transition3D::Uplift, tau);
  }
  return true;
}

const StepReport& Rocking3DModel::step(const Eigen::Vector3d& a, double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt) || !a.allFinite())
    throw std::invalid_argument("Rocking3DModel::step: dt must be finite and > 0 and the acceleration finite");
  report_ = StepReport{};
  sample_dt_ = dt;
  lifts_ = 0;
  slide_lifts_ = 0;
  slip_switches_ = 0;
  slip_steps_ = 0;
  lip_face_hits_ = 0;
  GroundInput3 in;
  in.a0 = a_prev_;
  in.slope = (a - a_prev_) / dt;
  double tau = 0.0;
  int events = 0;
  auto on_side = [&] {
    return face_ != 0 && mode_ != Mode3D::Vertex && mode_ != Mode3D::Flight && tilt() >= body_.overturn_angle();
  };
  while (tau < dt && mode_ != Mode3D::Overturned) {
    if (mode_ == Mode3D::Rest) {
      if (!leave_rest(in, tau, dt)) break;
      ++events;
    }
    Event e = Event::None;
    int other = -1;
    if (mode_ == Mode3D::Edge) e = advance_edge(in, tau, dt, other);
    else if (mode_ == Mode3D::Vertex) e = advance_vertex(in, tau, dt, other);
    else if (mode_ == Mode3D::Flight) e = advance_flight(in, tau, dt, other);
    else if (mode_ == Mode3D::Slide) {
      const double fly = flight_onset(in, tau, dt);
      e = advance_slide(in, tau, std::min(dt, fly));
      if (e == Event::None && tau >= fly) e = Event::Flight;
    }
    // Off the base, lying on the side (the item base's tilt at the overturn angle) is OVERTURNED
    // as on the base: checked where the motion stops (a step's end, an event, a landing).
    if (e != Event::Overturn && on_side()) e = Event::Overturn;
    if (e == Event::None) break;
    handle_event(e, other, in, tau);
    if (mode_ == Mode3D::Overturned) break;
    if (on_side()) {
      const Mode3D from = mode_;
      overturn_at(tau);
      note_transition(from, Transition3D::Overturn, tau);
      break;
    }
    if (++events >= settings_.max_events_per_sample) {
      // Bounded work per sample: the body is put down flat for the rest of the sample, unless it is
      // beyond its tipping point (a see-saw on the edge it falls over, its landings ever faster):
      // put down flat from there it would stand again, so it overturns where the bound stops it.
      const Mode3D from = mode_;
      if ((mode_ == Mode3D::Edge || mode_ == Mode3D::Vertex || mode_ == Mode3D::Flight) && rotation_ratio() > 1.0) {
        overturn_at(tau);
        ++outcome3_.forced_overturns;
        note_transition(from, Transition3D::ForcedOverturn, tau);
        break;
      }
      if (mode_ == Mode3D::Flight) put_down_from_flight();  // (under its lowest point, not where it took off)
      go_to_rest();
      report_.forced_rest = true;
      ++outcome_.forced_rest_captures;
      note_transition(from, Transition3D::ForcedRest, tau);
      break;
    }
  }
  note_committed(dt);
  t_ += dt;
  a_prev_ = a;
  ++outcome_.samples;
  outcome_.integrator_steps += report_.integrator_steps;
  return report_;
}

}  // namespace rocking_monitor::core
