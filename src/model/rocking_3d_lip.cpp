// Lips along a support's edges (issue 51): a stop at the support's top, low beside the item, that the
// base cannot slide across. A slide that meets it trips over it (the plastic impact at the lip's
// foot: the body pivots on the base's corner or edge there, as a box sliding into a kerb does) or,
// where that impact would lift nothing, is held: it slides on along the lip, the lip taking the part
// of the demand that presses the base into it, until the demand turns away. At rest against a lip the
// static law leaves that part to the lip as well. Overturning over a lipped edge is a fall off the
// support as over any of its edges.
#include <algorithm>
#include <cmath>
#include <limits>

#include "rocking_3d_internal.hpp"
#include "rocking_monitor/integrate/event_location.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"

namespace rocking_monitor::core {

using rocking_3d::rot2;
using rocking_3d::rot_z;

namespace {

constexpr double kTouchPerTol = 10.0;  // a base corner this many contact tolerances from a lip touches it

}  // namespace

// Outward unit normal of the support's edge `lip` (world; the support is fixed on the floor).
Eigen::Vector2d Rocking3DModel::lip_normal(int lip) const {
  const std::vector<Eigen::Vector2d>& s = body_.parameters().support;
  const std::size_t k = static_cast<std::size_t>(lip);
  const Eigen::Vector2d d = (s[(k + 1) % s.size()] - s[k]).normalized();
  return Eigen::Vector2d(d.y(), -d.x());
}

// How far the base's nearest corner lies inside lip k's line with the footprint turned by r and
// shifted by `shift` (world), m (< 0: beyond it).
double Rocking3DModel::lip_depth(int k, const Eigen::Matrix2d& r, const Eigen::Vector2d& shift) const {
  const Eigen::Vector2d n = lip_normal(k);
  const double line = body_.parameters().support[static_cast<std::size_t>(k)].dot(n);
  double depth = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& b : body_.whole_base()) depth = std::min(depth, line - (r * b + shift).dot(n));
  return depth;
}

// How far the base's nearest corner lies inside the lipped edges' lines at the slide state y, m (< 0
// beyond one), from where it lay at the step's start if beyond (lip_floor_); `lip`: which. The lip
// holding the base is left out (it slides along it). +inf without.
double Rocking3DModel::lip_gap(const Vec6& y, int& lip) const {
  lip = -1;
  double best = std::numeric_limits<double>::infinity();
  const std::vector<int>& lips = body_.parameters().support_lips;
  if (lips.empty()) return best;
  const Eigen::Matrix2d r = rot2(y(5));
  const Eigen::Vector2d shift = y.segment<2>(3);
  for (const int k : lips) {
    if (k == lip_held_) continue;
    const double g = lip_depth(k, r, shift) - lip_floor_[k];
    if (g < best) {
      best = g;
      lip = k;
    }
  }
  return best;
}

// How far the point x (world) lies inside the lips it moves towards (`moving`: its direction; m, < 0
// beyond one): a slipping pivot (slide-rock on a corner) stops at a lip. +inf without.
double Rocking3DModel::point_lip_gap(const Eigen::Vector2d& x, const Eigen::Vector2d& moving) const {
  double best = std::numeric_limits<double>::infinity();
  for (const int k : body_.parameters().support_lips) {
    const Eigen::Vector2d n = lip_normal(k);
    if (moving.dot(n) > 0.0) best = std::min(best, (body_.parameters().support[static_cast<std::size_t>(k)] - x).dot(n));
  }
  return best;
}

// The slide step starts: how far beyond each lip the base lies now (0 within it).
void Rocking3DModel::note_lip_floors() {
  const Eigen::Matrix2d r = rot2(slide_(5));
  const Eigen::Vector2d shift = slide_.segment<2>(3);
  for (const int k : body_.parameters().support_lips) lip_floor_[k] = std::min(0.0, lip_depth(k, r, shift));
}

// Flat again (rest, or a slide's step): how far a corner lies beyond a lip (max_lip_overhang).
void Rocking3DModel::note_lip_overhang() {
  const Eigen::Matrix2d r = rot2(yaw_);
  for (const int k : body_.parameters().support_lips)
    outcome3_.max_lip_overhang = std::max(outcome3_.max_lip_overhang, -lip_depth(k, r, shift_));
}

// The lip the base lies against (its nearest corner within kTouchPerTol tolerances, at the current
// footprint) that `push` (a horizontal velocity or demand, world) presses the base into; -1: none.
int Rocking3DModel::lip_touched(const Eigen::Vector2d& push) const {
  const Eigen::Matrix2d r = rot2(yaw_);
  for (const int k : body_.parameters().support_lips)
    if (push.dot(lip_normal(k)) > 0.0 && lip_depth(k, r, shift_) <= kTouchPerTol * floor_tol_) return k;
  return -1;
}

// The ground's horizontal acceleration the floor's friction must give the body (the static law's
// demand, m/s^2): the lips the base lies against (or the one holding it) take the part that presses
// it into them. The demand's excess over the cone stays convex in the input (a norm of the
// tangential part and of the positive normal part), as find_slip's bracketing needs.
Eigen::Vector2d Rocking3DModel::lip_demand(const Eigen::Vector3d& a) const {
  Eigen::Vector2d d = a.head<2>();
  if (body_.parameters().support_lips.empty() || lip_held_ >= 0) return held_demand(a);
  for (int pass = 0; pass < 2; ++pass) {  // (two lips meet at a corner of the support)
    const int k = lip_touched(-d);
    if (k < 0) break;
    const Eigen::Vector2d n = lip_normal(k);
    d -= d.dot(n) * n;
  }
  return d;
}

// The demand while sliding: the ground's horizontal acceleration, less the part the lip holding the
// base takes (the part that presses it against the lip, -a into it).
Eigen::Vector2d Rocking3DModel::held_demand(const Eigen::Vector3d& a) const {
  Eigen::Vector2d d = a.head<2>();
  if (lip_held_ < 0) return d;
  const Eigen::Vector2d n = lip_normal(lip_held_);
  if (d.dot(n) < 0.0) d -= d.dot(n) * n;
  return d;
}

// Held by a lip: how hard it pushes (the body's acceleration into the lip without it, m/s^2; < 0: the
// demand turned away, the lip lets go).
double Rocking3DModel::lip_push(const GroundInput3& in, double t, const Vec6& y) const {
  double torque;
  const Eigen::Vector2d f = slide_friction(in, t, y, torque);
  return (f - in.at(t).head<2>()).dot(lip_normal(lip_held_));
}

// The lip takes the base's motion into it and its turning (exact where the base's edge lies along the
// lip; a corner against it would turn about it, which is not modelled): kinetic energy only falls.
void Rocking3DModel::hold_on_lip(int lip) {
  const Eigen::Vector2d n = lip_normal(lip);
  const double into = slide_.head<2>().dot(n);
  if (into > 0.0) slide_.head<2>() -= into * n;
  slide_(2) = 0.0;
  lip_held_ = lip;
  slide_stepper_.invalidate();
  ++outcome3_.lip_holds;
}

// A slide begun against a lip (from rest, or after a landing) that presses into it: held.
void Rocking3DModel::hold_if_pressed(const Eigen::Vector2d& push, double tau) {
  if (body_.parameters().support_lips.empty() || mode_ != Mode3D::Slide) return;
  const int k = lip_touched(push);
  if (k < 0) return;
  hold_on_lip(k);
  note_transition(Mode3D::Slide, Transition3D::HeldByLip, tau);
}

// The slide met lip `lip` at tau (slide_ is the state there). Returns 1: it tripped over it (EDGE or
// VERTEX); 0: held, sliding along it; 2: stopped in the corner of two lips (REST); -1: the corner that
// met the lip's line lies beyond the lip's end (past the support's corner): nothing there, counted.
int Rocking3DModel::meet_lip(int lip, double tau) {
  note_slide();
  fit_contact(shift_, yaw_);  // (the cut where it meets the lip: it may pivot on one of its corners)
  const Eigen::Matrix2d r = rot2(yaw_);
  const std::vector<Eigen::Vector2d>& s = body_.parameters().support;
  const Eigen::Vector2d a = s[static_cast<std::size_t>(lip)], b = s[(static_cast<std::size_t>(lip) + 1) % s.size()];
  const Eigen::Vector2d n = lip_normal(lip);
  int p = 0;
  double nearest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < fb().vertex_count(); ++i) {
    const double g = (a - (r * fb().vertex(i).position.head<2>() + shift_)).dot(n);
    if (g < nearest) {
      nearest = g;
      p = i;
    }
  }
  const Eigen::Vector2d world = r * fb().vertex(p).position.head<2>() + shift_;
  const double along = (world - a).dot(b - a) / (b - a).squaredNorm();
  if (along < -1e-9 || along > 1.0 + 1e-9) {
    ++outcome3_.lip_ends_passed;
    return -1;
  }
  if (trip_over_lip(lip, p, r, tau)) return 1;
  const int before = lip_held_;
  hold_on_lip(lip);
  if (before >= 0 && before != lip) {
    // Into the corner of two lips: the first one's push is taken too (perpendicular lips: no motion left).
    const Eigen::Vector2d m = lip_normal(before);
    if (slide_.head<2>().dot(m) > 0.0) slide_.head<2>() -= slide_.head<2>().dot(m) * m;
    if (slide_.head<2>().norm() <= kTouchPerTol * floor_tol_ / std::max(sample_dt_, 1e-9)) {
      go_to_rest();
      return 2;
    }
  }
  return 0;
}

// The plastic impact at the lip's foot (issue 40's law with base corner p sticking, the lip holding
// the corners that lie on it): the body pivots on p (its angular momentum about p kept) or on a base
// edge through p (about that edge). Of these, the motion that lifts every corner (or leaves it on the
// floor), moves none on the lip into it and keeps the most energy (Carnot: the law's projection).
// False when none lifts a corner by the contact tolerance under gravity (a grazing meeting, which no
// hop resolves): the lip then holds the base. (The lip is low: a corner the motion swings across its
// line in the air passes over it, and lands on it.)
bool Rocking3DModel::trip_over_lip(int lip, int p, const Eigen::Matrix2d& r, double tau) {
  const Eigen::Vector3d c = fb().centre_of_mass(), pp = fb().vertex(p).position;
  const Eigen::Matrix3d& jc = fb().central_inertia_per_mass();
  const Eigen::Vector2d u_fp = r.transpose() * slide_.head<2>();
  const Eigen::Vector3d v0(u_fp.x(), u_fp.y(), 0.0);
  const Eigen::Vector3d h = jc * Eigen::Vector3d(0.0, 0.0, slide_(2)) + (c - pp).cross(v0);
  const Eigen::Vector2d n2 = r.transpose() * lip_normal(lip);
  const Eigen::Vector3d nf(n2.x(), n2.y(), 0.0);
  const double line = (pp.head<2>()).dot(n2);
  auto admissible = [&](const Eigen::Vector3d& w, double& rise) {
    const double eps = w.norm() * floor_tol_;
    rise = 0.0;
    for (int i = 0; i < fb().vertex_count(); ++i) {
      const Eigen::Vector3d x = fb().vertex(i).position, v = w.cross(x - pp);
      if (v.z() < -eps) return false;
      if (line - x.head<2>().dot(n2) <= kTouchPerTol * floor_tol_ && v.dot(nf) > eps) return false;
      rise = std::max(rise, v.z());
    }
    return true;
  };
  const double graze = 2.0 * kGravity * floor_tol_;
  double best_energy = 0.0, rise = 0.0;
  int best = -2;
  Eigen::Vector3d best_w = Eigen::Vector3d::Zero();
  const Eigen::Matrix3d jp = inertia_about(jc, c, pp);
  const Eigen::Vector3d wv = jp.ldlt().solve(h);
  if (admissible(wv, rise) && rise * rise >= graze) {
    best = -1;
    best_w = wv;
    best_energy = rotation_energy(jp, wv);
  }
  for (int k = 0; k < fb().vertex_count(); ++k) {
    const BaseEdge& e = fb().edge(k);
    if (e.a != p && e.b != p) continue;
    const double w = e.axis.dot(h) / e.pivot.inertia;  // (about the edge's line: the same through p)
    if (!(w > 0.0) || !admissible(w * e.axis, rise) || rise * rise < graze) continue;
    const double energy = 0.5 * e.pivot.inertia * w * w;
    if (energy > best_energy) {
      best = k;
      best_w = w * e.axis;
      best_energy = energy;
    }
  }
  if (best == -2) return false;
  // The lip's foot takes the impulse; along the lip it is the floor's friction at p.
  const Eigen::Vector3d impulse = best_w.cross(c - pp) - v0;
  const double along = (impulse - impulse.dot(nf) * nf).norm();
  if (along > body_.parameters().mu_s * std::max(impulse.z(), 0.0)) ++outcome3_.lip_slipping_trips;
  lip_held_ = -1;
  if (best == -1) {
    const Eigen::Vector2d pw = r * pp.head<2>() + shift_;
    enter_vertex(fc().hull_vertex[static_cast<std::size_t>(p)], Eigen::Vector3d(pw.x(), pw.y(), 0.0), rot_z(yaw_),
                 yaw_matrix() * best_w);
  } else {
    mode_ = Mode3D::Edge;
    contact_ = best;
    theta_ = 0.0;
    omega_ = best_w.norm();
    dopri5_.invalidate();
  }
  ++outcome3_.lip_trips;
  report_.uplift = true;
  if (std::isnan(outcome_.uplift_time)) outcome_.uplift_time = t_ + tau;
  return true;
}

// Pivoting on a corner (VERTEX, sticking) with the state y: how far the base's corners lifted less
// than the lips' height lie inside the lipped edges, from where they lay at the step's start if beyond
// (face_floor_), m; `corner`, `lip`: which. +inf without such a corner.
double Rocking3DModel::lip_face_gap(const Vec7& y, int& corner, int& lip) const {
  corner = lip = -1;
  double best = std::numeric_limits<double>::infinity();
  const Eigen::Matrix3d r = vertex_rotation(y);
  for (const int k : body_.parameters().support_lips) {
    int c;
    const double g = low_corner_depth(r, k, false, c) - face_floor_[k];
    if (g < best) {
      best = g;
      corner = c;
      lip = k;
    }
  }
  return best;
}

// Pivoting on a corner in pose r: how far the base's corners lower than the lips' height lie inside lip
// k's line, the nearest of them (`corner`), m; +inf without one. with_pivot: the pivot counts too.
double Rocking3DModel::low_corner_depth(const Eigen::Matrix3d& r, int k, bool with_pivot, int& corner) const {
  const Eigen::Vector3d pivot = hv(contact_).position;
  const std::vector<Eigen::Vector2d>& base = body_.whole_base();
  const Eigen::Vector2d n = lip_normal(k);
  const double line = body_.parameters().support[static_cast<std::size_t>(k)].dot(n);
  double depth = std::numeric_limits<double>::infinity();
  corner = -1;
  for (std::size_t i = 0; i < base.size(); ++i) {
    const Eigen::Vector3d rel = Eigen::Vector3d(base[i].x(), base[i].y(), 0.0) - pivot;
    if (!with_pivot && rel.squaredNorm() <= floor_tol_ * floor_tol_) continue;
    const Eigen::Vector3d x = r * rel + pivot_world_;
    if (!(x.z() < body_.parameters().support_lip_height)) continue;
    const double g = line - x.head<2>().dot(n);
    if (g < depth) {
      depth = g;
      corner = static_cast<int>(i);
    }
  }
  return depth;
}

// The first instant in [t0, t1] of the sticking vertex stepper's last step at which a lifted corner
// lower than the lips meets a lip's face (a contact tolerance beyond it, or beyond where it lay at t0),
// located on the dense output; `corner` -1: none (then t1). Bounded per sample (kMaxLipFaceHits).
double Rocking3DModel::lip_face_in_step(double t0, double t1, double t_tol, int& corner, int& lip) {
  corner = lip = -1;
  if (body_.parameters().support_lips.empty() || !(body_.parameters().support_lip_height > 0.0) || face_ != 0) return t1;
  if (lip_face_hits_ >= kMaxLipFaceHits) return t1;
  const Eigen::Matrix3d r0 = vertex_rotation(Vec7(vector_.eval(t0)));
  for (const int k : body_.parameters().support_lips) {  // where each lip's low corners lay at t0 (<= 0)
    int c;
    face_floor_[k] = std::min(0.0, low_corner_depth(r0, k, true, c));
  }
  auto g = [&](double t) {
    int c, l;
    return lip_face_gap(Vec7(vector_.eval(t)), c, l) + floor_tol_;
  };
  double t_prev = t0, g_prev = g(t0);
  for (int k = 1; k <= kVertexProbes; ++k) {
    const double tk = t0 + (t1 - t0) * k / kVertexProbes;
    const double gk = g(tk);
    if (gk <= 0.0 && g_prev > 0.0) {
      const double tc = bracketed_root(g, t_prev, tk, g_prev, gk, t_tol);
      lip_face_gap(Vec7(vector_.eval(tc)), corner, lip);
      if (++lip_face_hits_ >= kMaxLipFaceHits) ++outcome3_.lip_faces_not_followed;
      return tc;
    }
    t_prev = tk;
    g_prev = gk;
  }
  return t1;
}

// A lifted corner meets the lip's face (pivoting on a corner, the pivot sticking): the plastic
// frictionless impact there stops the corner's motion into the lip, w+ = w - lambda J_p^-1 a with
// a = (x - p) x n, lambda = (w . a) / (a . J_p^-1 a): kinetic energy only falls.
void Rocking3DModel::hit_lip_face(int corner, int lip, double tau) {
  const Eigen::Matrix3d r = vertex_rotation(y_);
  const Eigen::Vector2d& b = body_.whole_base()[static_cast<std::size_t>(corner)];
  const Eigen::Vector3d lever = r * (Eigen::Vector3d(b.x(), b.y(), 0.0) - hv(contact_).position);
  const Eigen::Vector2d n2 = lip_normal(lip);
  const Eigen::Vector3d a = lever.cross(Eigen::Vector3d(n2.x(), n2.y(), 0.0));
  const Eigen::Matrix3d jp = r * hv(contact_).inertia * r.transpose();
  const Eigen::Vector3d ja = jp.ldlt().solve(a);
  const Eigen::Vector3d w = y_.tail<3>();
  const double into = w.dot(a);
  if (!(into > 0.0)) return;
  y_.tail<3>() = w - into / a.dot(ja) * ja;
  vector_.invalidate();
  ++outcome3_.lip_face_impacts;
  note_transition(Mode3D::Vertex, Transition3D::LipFace, tau);
}

}  // namespace rocking_monitor::core
