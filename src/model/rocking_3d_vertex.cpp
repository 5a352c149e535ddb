// The 3-D model pivoting on a base vertex: Euler's equations about the vertex, the quaternion, and the
// first touchdown of another base point.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <Eigen/Dense>

#include "rocking_3d_internal.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/integrate/event_location.hpp"
#include "rocking_monitor/physics/support_polygon.hpp"

namespace rocking_monitor::core {

using rocking_3d::gravity_and_inertia;
using rocking_3d::rot_z;

// ---------------------------------------------------------------- VERTEX

void Rocking3DModel::vertex_rhs(const GroundInput3& in, double t, const Vec7& y, Vec7& dy) const {
  const BaseVertex& v = hv(contact_);
  const Eigen::Quaterniond q = Eigen::Quaterniond(y(0), y(1), y(2), y(3)).normalized();
  const Eigen::Matrix3d r = q.toRotationMatrix();
  const Eigen::Vector3d w = y.tail<3>();
  // Euler's equations about the fixed vertex, in the body's frame (J constant there, no turned
  // tensors to form): J wb' = Mb - wb x J wb, w' = R wb' (R wb' = (R wb)' - w x w = (R wb)').
  const Eigen::Vector3d wb = r.transpose() * w;
  const Eigen::Vector3d gb = r.transpose() * gravity_and_inertia(in.at(t));
  const Eigen::Vector3d mb = v.to_centre.cross(gb) - wb.cross(v.inertia * wb);
  dy.tail<3>() = r * (v.inertia_inverse * mb);
  dy.head<4>() = rocking_3d::quaternion_rate(w, y);
}

void Rocking3DModel::enter_vertex(int vertex, const Eigen::Vector3d& pivot_world,
                                  const Eigen::Matrix3d& rotation, const Eigen::Vector3d& omega_world) {
  mode_ = Mode3D::Vertex;
  contact_ = vertex;
  pivot_world_ = Eigen::Vector3d(pivot_world.x(), pivot_world.y(), 0.0);
  const Eigen::Quaterniond q(rotation);
  y_ << q.w(), q.x(), q.y(), q.z(), omega_world;
  vector_.invalidate();
  pivot_slipping_ = false;  // (a new pivot sticks until its reaction leaves the cone)
  // A vertex on the floor now may only trigger an impact after it has been off the floor (it is
  // an end of the edge just left, or a neighbour of a flat base).
  // (A vertex within floor_tol_ of the floor is on it: the pose at an event is exact to the
  // integrator's tolerance only.)
  const double eps = 3.0 * floor_tol_;  // (a landing's set is within floor_tol_ of the floor, seen from any of its points within 2 floor_tol_)
  const int n = static_cast<int>(hull().vertices.size());
  for (int i = 0; i < n; ++i) {
    const double z = (rotation * (hv(i).position - hv(vertex).position)).z();
    armed_[i] = i != vertex && z > eps;
  }
}

void Rocking3DModel::enter_vertex_from_edge(int vertex) {
  const BaseEdge& e = fb().edge(contact_);
  const Eigen::Matrix3d r = rotation();
  const Eigen::Vector3d w = yaw_matrix() * (omega_ * e.axis);
  const Eigen::Vector3d p =
      yaw_matrix() * fb().vertex(vertex).position + Eigen::Vector3d(shift_.x(), shift_.y(), 0.0);
  ++outcome3_.edge_to_vertex;
  enter_vertex(fc().hull_vertex[static_cast<std::size_t>(vertex)], p, r, w);
}

// The body rests on edge `edge` of hull face `face` (both ends on the floor) with pose `rotation` (of
// the item frame) and angular velocity omega_axis about the edge: the footprint (yaw, shift) and
// theta follow from the pose. pivot_vertex: the face's vertex at pivot_world.
void Rocking3DModel::enter_edge_from_pose(int face, int edge, const Eigen::Matrix3d& item_rotation,
                                          const Eigen::Vector3d& pivot_world, int pivot_vertex,
                                          double omega_axis) {
  set_face(face);
  const Eigen::Matrix3d rotation = face == 0 ? item_rotation : Eigen::Matrix3d(item_rotation * fc().rotation.transpose());
  const BaseEdge& e = fb().edge(edge);
  Eigen::Vector3d axis_w = rotation * e.axis;
  axis_w.z() = 0.0;  // both ends on the floor (to the event tolerance)
  axis_w.normalize();
  const Eigen::Vector3d normal_w = axis_w.cross(Eigen::Vector3d::UnitZ());
  const Eigen::Vector3d base_normal = rotation.col(2);
  // (within the face's range: from flat to the face across lying flat; rounding may step past it)
  const double theta = std::clamp(std::atan2(base_normal.dot(normal_w), base_normal.z()), 0.0,
                                  std::min(fc().fold[static_cast<std::size_t>(edge)], kPi));
  const Eigen::Matrix3d flat = Eigen::AngleAxisd(-theta, axis_w).toRotationMatrix() * rotation;
  yaw_ = std::atan2(flat(1, 0), flat(0, 0));
  // The pivot vertex keeps its place on the floor.
  const Eigen::Vector3d placed = yaw_matrix() * fb().vertex(pivot_vertex).position;
  shift_ = Eigen::Vector2d(pivot_world.x() - placed.x(), pivot_world.y() - placed.y());
  mode_ = Mode3D::Edge;
  contact_ = edge;
  theta_ = theta;
  omega_ = omega_axis;
  dopri5_.invalidate();
}

namespace {

// An unarmed vertex below the floor that sinks through the probe interval [ta, tb] (from the step's
// start t0): it may have hopped up and come back inside it (a hop lower than the arming height);
// then the touchdown is where it came back through the floor, after the top of the hop. The top is
// scanned, and located on the rise rate where it lies before the scan's first point. Below the
// floor all along, the touchdown is at the top (where it turns down), or at ta where it never rose.
// (Put at ta while the vertex still rose, the law gave it no impulse and it landed again at that
// instant, until the events bound put the body down flat: the urn on its pedestal at UCLA Grounds.)
template <class Z, class Rate>
double hop_touchdown(const Z& z_at, const Rate& rate, double t0, double ta, double tb, double z0, double zb,
                     double t_tol) {
  constexpr int kScan = 16;
  double t_top = t0, z_top = z0;
  for (int m = 1; m <= kScan; ++m) {
    const double tm = t0 + (tb - t0) * m / kScan;
    const double zm = z_at(tm);
    if (zm > z_top) {
      z_top = zm;
      t_top = tm;
    }
  }
  if (t_top == t0) {
    const double t_scan = t0 + (tb - t0) / kScan, r0 = rate(t0), r1 = rate(t_scan);
    if (r0 > 0.0 && r1 < 0.0) {
      t_top = bracketed_root(rate, t0, t_scan, r0, r1, t_tol);
      z_top = z_at(t_top);
    } else if (!(z_top > 0.0)) {
      return ta;  // it never rose
    }
  }
  return z_top > 0.0 ? bracketed_root(z_at, t_top, tb, z_top, zb, t_tol) : t_top;
}

}  // namespace

// The first touchdown of a hull vertex beside the pivot inside the step [t0, t1], on the dense output
// `rot`, probed at kVertexProbes so that a grazing dip inside the step is not missed (up[k]: the
// rotation's vertical row at probe k, once for all vertices); +inf and touching -1 if none.
template <class Rot>
double Rocking3DModel::touchdown_in_step(const Rot& rot, const Vec7& y0, const Eigen::Vector3d* up, double t0,
                                         double t1, double t_tol, int& touching) const {
  const BaseVertex& pivot = hv(contact_);
  const double eps = 3.0 * floor_tol_;  // (a landing's set is within floor_tol_ of the floor, seen from any of its points within 2 floor_tol_)
  const double sink = 10.0 * floor_tol_;  // an unarmed vertex this far below the floor touches down
  auto height = [&](const Vec7& y, int i) { return (vertex_rotation(y) * (hv(i).position - pivot.position)).z(); };
  double t_event = std::numeric_limits<double>::infinity();
  touching = -1;
  for (int i : hull().neighbours[static_cast<std::size_t>(contact_)]) {
    const Eigen::Vector3d offset = hv(i).position - pivot.position;
    double ta = t0, za = up[0].dot(offset);
    for (int k = 1; k <= kVertexProbes; ++k) {
      const double tb = k == kVertexProbes ? t1 : t0 + (t1 - t0) * k / kVertexProbes;
      const double zb = up[k].dot(offset);
      const bool armed = armed_[i] || za > eps;
      // An unarmed vertex that sinks clearly below the floor is a touchdown too (the pivot
      // turned the wrong way for the vertex it left): resolved as an impact. One below the floor
      // that rises is not: the pivot just left, a few nm below by the located landing's pose, or
      // a point a cut made below the floor (on a support, where the body turned within the step).
      // Taken for a touchdown it landed without an impulse, again and again, until the events
      // bound put the body down flat.
      if ((armed && zb <= 0.0 && za > 0.0) || (zb < -sink && zb < za)) {
        auto z_at = [&](double t) { return height(rot(t), i); };
        // (its rise rate: the dense output's angular velocity at the vertex)
        auto rate = [&](double t) {
          const Vec7 y = rot(t);
          return y.tail<3>().cross(vertex_rotation(y) * offset).z();
        };
        const double te = za > 0.0 ? bracketed_root(z_at, ta, tb, za, zb, t_tol)
                                   : hop_touchdown(z_at, rate, t0, ta, tb, height(y0, i), zb, t_tol);
        if (te < t_event) {
          t_event = te;
          touching = i;
        }
        break;
      }
      ta = tb;
      za = zb;
    }
  }
  return t_event;
}

// The first event inside the step: a touchdown (Impact, `touching`) or the overturn, at t_event; up_end:
// the rotation's vertical row at the step's end (arming).
template <class Rot>
Rocking3DModel::Event Rocking3DModel::vertex_event_in_step(const Rot& rot, const Vec7& y0, const Vec7& y1, double t0,
                                                           double t1, double t_tol, int& touching, double& t_event,
                                                           Eigen::Vector3d& up_end) const {
  Eigen::Vector3d up[kVertexProbes + 1];
  for (int k = 0; k <= kVertexProbes; ++k) {
    const Vec7 yk = k == 0 ? y0 : k == kVertexProbes ? y1 : rot(t0 + (t1 - t0) * k / kVertexProbes);
    up[k] = vertex_rotation(yk).row(2).transpose();
  }
  up_end = up[kVertexProbes];
  t_event = touchdown_in_step(rot, y0, up, t0, t1, t_tol, touching);
  Event event = touching >= 0 ? Event::Impact : Event::None;
  const double cos_over = std::cos(body_.overturn_angle());
  const double c1 = vertex_rotation(y1)(2, 2) - cos_over;
  if (c1 <= 0.0) {
    const double c0 = vertex_rotation(y0)(2, 2) - cos_over;
    const double te = c0 > 0.0 ? bracketed_root([&](double t) { return vertex_rotation(rot(t))(2, 2) - cos_over; },
                                                 t0, t1, c0, c1, t_tol)
                               : t0;
    if (te < t_event) {
      t_event = te;
      event = Event::Overturn;
    }
  }
  return event;
}

// On a support, the first instant in [t0, t1] at which a corner of the support (fixed on the floor,
// beneath the base) meets the base's plane, probed as touchdown_in_step probes; +inf if none. The
// dense output is evaluated once per probe for all corners (the base's normal there), and only for a
// corner beneath the base at t1.
template <class Rot>
double Rocking3DModel::support_touchdown(const Rot& rot, double t0, double t1, double t_tol) const {
  const Eigen::Vector3d pivot = hv(contact_).position;
  const Eigen::Matrix3d r1 = vertex_rotation(rot(t1));
  double probe_t[kVertexProbes + 1];
  Eigen::Vector3d normal[kVertexProbes + 1];  // the base's normal (world) at the probes
  bool probed = false;
  double t_first = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& s : body_.parameters().support) {
    const Eigen::Vector3d from_pivot = Eigen::Vector3d(s.x(), s.y(), 0.0) - pivot_world_;
    if (from_pivot.norm() <= floor_tol_) continue;  // the pivot's own corner
    const Eigen::Vector3d seen = r1.transpose() * from_pivot + pivot;
    if (!(inside_margin(body_.whole_base(), seen.head<2>()) >= 0.0)) continue;
    if (!probed) {
      for (int k = 0; k <= kVertexProbes; ++k) {
        probe_t[k] = k == kVertexProbes ? t1 : t0 + (t1 - t0) * k / kVertexProbes;
        normal[k] = (k == kVertexProbes ? r1 : vertex_rotation(rot(probe_t[k]))).col(2);
      }
      probed = true;
    }
    // how far the corner lies inside the body, through the base's plane (item frame), m
    auto depth = [&](double t) { return vertex_rotation(rot(t)).col(2).dot(from_pivot) + pivot.z(); };
    double da = normal[0].dot(from_pivot) + pivot.z();
    if (da > floor_tol_) { t_first = std::min(t_first, t0); continue; }  // inside already: lands now
    for (int k = 1; k <= kVertexProbes; ++k) {
      const double db = normal[k].dot(from_pivot) + pivot.z();
      if (db > 0.0 && da <= 0.0) {
        t_first = std::min(t_first, bracketed_root(depth, probe_t[k - 1], probe_t[k], da, db, t_tol));
        break;
      }
      da = db;
    }
  }
  return t_first;
}

// On a support, pivoting on a corner: the touchdown searched again with the contact cut where the body
// is when a corner of the support meets its base (that corner is then the cut's, and lands there), or
// where it is at the touchdown or the step's end (the cut kept where the body has turned to). Each cut
// moves the touchdown a little: up to four, each where the last one's touchdown is (with two, a
// corner landed up to 19 um off the pedestal's corner).
template <class Rot>
Rocking3DModel::Event Rocking3DModel::refit_in_step(const Rot& rot, const Vec7& y0, const Vec7& y1, double t0,
                                                    double t1, double t_tol, Event event, int& touching,
                                                    double& t_event, Eigen::Vector3d& up_end) {
  if (body_.parameters().support.empty() || face_ != 0) return event;
  const double t_end = event == Event::None ? t1 : t_event;
  const double t_corner = support_touchdown(rot, t0, t_end, t_tol);
  constexpr int kCutsPerStep = 4;
  for (int pass = 0; pass < kCutsPerStep; ++pass) {
    const double t_fit = pass == 0 && std::isfinite(t_corner) ? t_corner : event == Event::Impact ? t_event : t1;
    if (!refit_on_vertex(rot(t_fit), y0)) break;
    event = vertex_event_in_step(rot, y0, y1, t0, t1, t_tol, touching, t_event, up_end);
  }
  return event;
}

// A turning point of the centre of mass in [t0, t_stop] (before any event): the peak of the rotation
// ratio, located on the dense output as the planar model locates omega = 0.
template <class Rot>
void Rocking3DModel::note_vertex_peak(const Rot& rot, const Vec7& y0, const Vec7& y_stop, double t0, double t_stop,
                                      double t_tol) {
  const double g0 = rise_rate(y0), g1 = rise_rate(y_stop);
  if (!(g0 > 0.0 && g1 <= 0.0)) return;
  const double tp = bracketed_root([&](double t) { return rise_rate(rot(t)); }, t0, t_stop, g0, g1, t_tol);
  Vec7 yp = rot(tp);
  yp.head<4>().normalize();
  const double ratio = ratio_of(yp);
  report_.peak_ratio = std::max(report_.peak_ratio, ratio);
  if (ratio > outcome_.max_rotation_ratio) {
    outcome_.max_rotation_ratio = ratio;
    outcome_.max_rotation_side = contact_ + 1;
  }
  outcome3_.max_tilt = std::max(outcome3_.max_tilt, std::acos(std::clamp(vertex_rotation(yp)(2, 2), -1.0, 1.0)));
}

// Steps the motion on a vertex (state: the sticking pivot's q, omega; or the slipping pivot's q, omega,
// pivot, velocity) to the first touchdown, overturn, or a slip beginning or ending (switched: the other
// stepper goes on from tau).
template <int N, class Rhs>
Rocking3DModel::Event Rocking3DModel::vertex_motion(Dopri5Vector<N>& stepper, Eigen::Matrix<double, N, 1>& state,
                                                    const Rhs& f, const Eigen::Matrix<double, N, 1>& atol,
                                                    const GroundInput3& in, double& tau, double tau_end, int& touching,
                                                    bool& switched) {
  using State = Eigen::Matrix<double, N, 1>;
  const double t_tol = 1e-12 * std::max(sample_dt_, 1e-6);
  const double eps = 3.0 * floor_tol_;
  // the rotation's part of the dense output
  auto rot = [&](double t) { return Vec7(stepper.eval(t).template head<7>()); };
  auto settle = [&](const State& y) {
    state = y;
    state.template head<4>().normalize();
    if constexpr (N == 11) sync_slip();
  };
  while (tau < tau_end) {
    const Vec7 y0 = state.template head<7>();
    if constexpr (N == 7) refit_on_vertex(y0, y0);  // (on a support: where the body has turned on it)
    if constexpr (N == 11) aim_slip_ref();
    report_.integrator_steps += stepper.step(f, tau, state, tau_end, settings_.tol, atol);
    const double t0 = stepper.t0(), t1 = stepper.t1();
    const Vec7 y1 = stepper.y1().template head<7>();
    double t_event;
    Eigen::Vector3d up_end;
    Event event = vertex_event_in_step(rot, y0, y1, t0, t1, t_tol, touching, t_event, up_end);
    if constexpr (N == 7) event = refit_in_step(rot, y0, y1, t0, t1, t_tol, event, touching, t_event, up_end);
    double t_stop = event == Event::None ? t1 : t_event;
    int lip_corner = -1, lip = -1;  // a lifted corner meeting a lip's face first (support_lip_height)
    if constexpr (N == 7) t_stop = lip_face_in_step(t0, t_stop, t_tol, lip_corner, lip);
    if (lip_corner >= 0) event = Event::None;
    note_vertex_peak(rot, y0, event == Event::None && lip_corner < 0 ? y1 : rot(t_stop), t0, t_stop, t_tol);
    // A slip beginning (sticking) or ending (slipping), or the body leaving the floor, before the
    // step's end or event: from there on the other stepper, or flight.
    bool lifts, flies;
    const double t_switch = pivot_change_in_step(in, t0, t_stop, t_tol, lifts, flies);
    // Bounded work: a slip that needs more than kMaxSlipSteps steps in one sample (the 2-D law near
    // zero speed can be stiff) is held from the step's end, counted.
    if constexpr (N == 11) {
      if (!std::isfinite(t_switch) && ++slip_steps_ > kMaxSlipSteps) {
        settle(stepper.y1());
        stepper.invalidate();
        tau = t1;
        note_ratio();
        hold_slip(in, tau);
        switched = true;
        return Event::None;
      }
    }
    if (std::isfinite(t_switch)) {
      settle(stepper.eval(t_switch));
      stepper.invalidate();
      tau = t_switch;
      note_ratio();
      if (flies) return Event::Flight;
      if constexpr (N == 7) begin_slip(in, tau);
      else end_slip(in, tau, lifts);
      switched = true;
      return Event::None;
    }
    if (event == Event::None && lip_corner < 0) {
      settle(stepper.y1());
      tau = t1;
      for (int i : hull().neighbours[static_cast<std::size_t>(contact_)])
        if (!armed_[i] && up_end.dot(hv(i).position - hv(contact_).position) > eps) armed_[i] = true;
      note_ratio();
      continue;
    }
    settle(stepper.eval(t_stop));
    stepper.invalidate();
    tau = t_stop;
    note_ratio();
    if (lip_corner < 0) return event;
    hit_lip_face(lip_corner, lip, tau);  // (and the motion goes on)
  }
  return Event::None;
}

Rocking3DModel::Event Rocking3DModel::advance_vertex(const GroundInput3& in, double& tau, double tau_end,
                                                     int& touching) {
  const double alpha = body_.min_alpha(), p = body_.max_p();
  // (the slipping pivot's place to the tolerance of the body's size, its speed to that per 1/p)
  const double length = hv(contact_).radius;
  for (;;) {
    bool switched = false;
    Event e;
    if (!pivot_slipping_) {
      Vec7 atol;
      atol << Eigen::Vector4d::Constant(settings_.tol * alpha), Eigen::Vector3d::Constant(settings_.tol * p * alpha);
      auto f = [&](double t, const Vec7& y, Vec7& dy) { vertex_rhs(in, t, y, dy); };
      e = vertex_motion(vector_, y_, f, atol, in, tau, tau_end, touching, switched);
    } else {
      Vec11 atol;
      atol << Eigen::Vector4d::Constant(settings_.tol * alpha), Eigen::Vector3d::Constant(settings_.tol * p * alpha),
          Eigen::Vector2d::Constant(settings_.tol * length), Eigen::Vector2d::Constant(settings_.tol * p * length);
      auto f = [&](double t, const Vec11& y, Vec11& dy) { slip_rhs(in, t, y, dy); };
      const double t_start = tau;
      const Eigen::Vector2d p_start = ys_.segment<2>(7);
      e = vertex_motion(slip_stepper_, ys_, f, atol, in, tau, tau_end, touching, switched);
      outcome3_.pivot_slip_time += tau - t_start;
      outcome3_.pivot_slip_distance += (ys_.segment<2>(7) - p_start).norm();
    }
    if (!switched || mode_ != Mode3D::Vertex) return e;
  }
}

}  // namespace rocking_monitor::core
