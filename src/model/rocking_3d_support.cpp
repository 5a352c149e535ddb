// The 3-D model on a support that ends (issue 51): the contact is the base where it lies on the
// support's top, and it follows the item as the item slides or turns there; the margin to the edge;
// the uplift while sliding (braking over the support's edge is recorded); an overturn about the
// support's edge is a fall off it.
#include <algorithm>
#include <cmath>
#include <limits>

#include "rocking_3d_internal.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/physics/support_polygon.hpp"

namespace rocking_monitor::core {

using rocking_3d::rot2;

namespace {

Eigen::Vector2d outward(const Eigen::Vector2d& from, const Eigen::Vector2d& to) {  // of a ccw polygon's edge
  const Eigen::Vector2d d = (to - from).normalized();
  return Eigen::Vector2d(d.y(), -d.x());
}

}  // namespace

double Rocking3DModel::support_margin_of(const Vec6& y) const {
  const std::vector<Eigen::Vector2d>& support = body_.parameters().support;
  if (support.empty()) return std::numeric_limits<double>::infinity();
  // (with a support the body slides on its base, face 0, whose frame is the item's: its hull never lands)
  return inside_margin(support, rot2(y(5)) * fb().centre_of_mass().head<2>() + y.segment<2>(3));
}

double Rocking3DModel::support_margin() const {
  if (body_.parameters().support.empty()) return std::numeric_limits<double>::infinity();
  return inside_margin(body_.parameters().support, (rotation() * body_.centre_of_mass() + translation()).head<2>());
}

// The cut is made again where the footprint (shift_, yaw_) has moved since it was last made: where the
// item comes to rest and where a slide ends on an edge; pivoting on a corner where it has turned
// (refit_on_vertex); never while it rocks on an edge (tilting about a line of the support keeps the
// cut) or slides (the friction's pressure is spread over the cut where the slide began: cutting at
// every step's end made a box sliding over its plinth's edge cost three times as much, rocking_sim on
// Northridge Jensen). Nothing is made while the whole base stays on the support (a plinth larger than
// the base, away from its edge): the usual case allocates nothing. check_com: the item flat there
// must have its centre of mass on the support (else it fell off: the last cut stays).
bool Rocking3DModel::fit_contact(const Eigen::Vector2d& shift, double yaw, bool check_com) {
  const std::vector<Eigen::Vector2d>& support = body_.parameters().support;
  if (support.empty() || (shift == fit_shift_ && yaw == fit_yaw_)) return false;
  const Eigen::Matrix2d back = rot2(-yaw);
  placed_support_.clear();
  for (const Eigen::Vector2d& s : support) placed_support_.push_back(back * (s - shift));
  const bool whole = first_outside(body_.whole_base(), placed_support_, 0.0) < 0;
  // (fit_shift_, fit_yaw_: the footprint the contact holds for, as snapshots restore it)
  if (whole && contact_whole_) {
    fit_shift_ = shift;
    fit_yaw_ = yaw;
    return false;
  }
  // A body with a hull stands on a pedestal within its base (BaseBody refuses others at load): every
  // edge of the contact is the pedestal's, and a hull point can come down only beyond it. Once a slide
  // or a turn has carried the base so that the pedestal reaches beyond one of the base's edges, the
  // body may pivot on that edge, and the hull's face across it could land on the pedestal there: not
  // modelled (the body rocks on the base's cut), counted.
  if (!body_.parameters().hull.empty() && first_outside(placed_support_, body_.whole_base(), floor_tol_) >= 0)
    ++outcome3_.pedestal_beyond_base;
  // Off the support the item has fallen (the slide's margin event): its last cut stays.
  if (check_com && !(inside_margin(placed_support_, body_.centre_of_mass().head<2>()) > 0.0)) return false;
  try {
    body_ = body_.on_support(placed_support_);
  } catch (const BodyError&) {
    return false;  // a cut the base validation refuses (more than kMaxBaseVertices): the last cut stays
  }
  contact_whole_ = whole;
  fit_shift_ = shift;
  fit_yaw_ = yaw;
  derive_contact();
  if (mode_ == Mode3D::Slide) slide_stepper_.invalidate();  // its derivative was the old cut's
  return true;
}

// Pivoting on a corner (VERTEX, sticking) the body also turns about the vertical: the support, fixed
// on the floor, then lies under the base elsewhere than where the cut was made, and the cut's
// corners (body points) are no longer the support's. The support is seen in the base's plane as
// that plane's unfolding onto the floor about the line where the two meet (through the pivot): the
// pose in which the support's corner that touches the base next lies where the base meets it. Where
// that footprint has moved (by more than a tenth of the contact tolerance at the support's corners)
// the contact is cut again from it: the support's corners now under the base are landing points,
// the base's corners now beyond its edge are not. A pure tilt keeps the footprint: no cut. Returns
// whether the cut changed; contact_ is then the pivot's number in the new cut, and armed_ those
// vertices above the floor at `arm` (the motion's state where the touchdown search starts).
bool Rocking3DModel::refit_on_vertex(const Vec7& y, const Vec7& arm) {
  const std::vector<Eigen::Vector2d>& support = body_.parameters().support;
  if (support.empty() || face_ != 0 || contact_ < 0 || mode_ != Mode3D::Vertex || pivot_slipping_) return false;
  const Eigen::Matrix3d r = vertex_rotation(y);
  const Eigen::Vector3d pivot = hv(contact_).position;
  const Eigen::Vector3d line = r.col(2).cross(Eigen::Vector3d::UnitZ());  // where the base's plane meets the floor
  const Eigen::Vector3d seen = r.transpose() * line;                      // that line in the base's plane
  double yaw = line.norm() > 1e-12 ? std::atan2(line.y(), line.x()) - std::atan2(seen.y(), seen.x())
                                   : std::atan2(r(1, 0), r(0, 0));
  yaw = fit_yaw_ + std::remainder(yaw - fit_yaw_, 2.0 * kPi);
  const Eigen::Vector2d shift = pivot_world_.head<2>() - rot2(yaw) * pivot.head<2>();
  double reach = 0.0;
  for (const Eigen::Vector2d& s : support) reach = std::max(reach, (s - fit_shift_).norm());
  if ((shift - fit_shift_).norm() + std::abs(yaw - fit_yaw_) * reach <= 0.1 * floor_tol_) return false;
  // Tipping over the support's edge (the centre of mass beyond it, seen from above): the last cut stays.
  const Eigen::Vector3d com = r * (body_.centre_of_mass() - pivot) + pivot_world_;
  if (!(inside_margin(support, com.head<2>()) > 0.0)) return false;
  if (!fit_contact(shift, yaw, false)) return false;
  int k = 0;  // the pivot in the new cut (it lies on the support: a vertex of the cut still)
  for (int i = 1; i < fb().vertex_count(); ++i)
    if ((fb().vertex(i).position - pivot).norm() < (fb().vertex(k).position - pivot).norm()) k = i;
  contact_ = fc().hull_vertex[static_cast<std::size_t>(k)];
  const Eigen::Matrix3d ra = vertex_rotation(arm);
  const double eps = 3.0 * floor_tol_;  // (as enter_vertex arms them)
  for (int i = 0; i < static_cast<int>(hull().vertices.size()); ++i)
    armed_[i] = i != contact_ && (ra * (hv(i).position - hv(contact_).position)).z() > eps;
  ++outcome3_.vertex_refits;
  return true;
}

// Sliding on a support: the uplift (eq. 19 about a line, as slide_lift's about an edge) about the
// lines of the whole base (`over` false), fixed in the item frame, or about the support's edges
// (`over` true), which move with the slide. While it slides the item tips only about its own base's
// lines, as without a support; the support's edges bound the slide where the centre of mass passes
// them (fell off). A body braking within mu_k h of the support's edge would start to tip over it
// while its base slides on across it: that slide-rock over the edge is not modelled (a sticking
// impact onto the edge would take energy the real motion keeps), so it is located and recorded
// (Transition3D::SlidesOverSupportEdge) and followed as sliding. margin: support_margin_of(y), which
// the slide has at hand (used with `over`).
double Rocking3DModel::support_lift(const GroundInput3& in, double t, const Vec6& y, bool over, double margin) const {
  const double az = in.at(t).z(), h = body_.centre_of_mass().z();
  if (kGravity + az > 0.0) {
    // The friction is at most mu_k N: no line lifts while the centre of mass is more than mu_k h
    // inside every one (the slide-first rule for any slip and spin; saves the friction and the loop).
    const double inside = over ? margin : whole_margin_;
    if (inside > mu_k() * h * (1.0 + 1e-9)) return over ? mu_k() * h - inside : -1.0;
  }
  const Eigen::Vector2d f = lift_friction(in, t, y);
  const Eigen::Matrix2d r = rot2(y(5)), back = r.transpose();
  const Eigen::Vector2d c = body_.centre_of_mass().head<2>();
  auto lift = [&](const Eigen::Vector2d& q, const Eigen::Vector2d& n) {  // the line through q, outward n (item frame)
    const double inward = (q - c).dot(n);
    return (-f.dot(r * n) * h - (kGravity + az) * inward) / std::hypot(inward, h);
  };
  double best = -std::numeric_limits<double>::infinity();
  if (!over) {
    const std::vector<Eigen::Vector2d>& base = body_.whole_base();
    for (std::size_t k = 0; k < base.size(); ++k)
      best = std::max(best, lift(base[k], outward(base[k], base[(k + 1) % base.size()])));
    return best;
  }
  const std::vector<Eigen::Vector2d>& support = body_.parameters().support;
  const Eigen::Vector2d shift = y.segment<2>(3);
  for (std::size_t k = 0; k < support.size(); ++k) {
    const Eigen::Vector2d a = back * (support[k] - shift), b = back * (support[(k + 1) % support.size()] - shift);
    best = std::max(best, lift(a, outward(a, b)));
  }
  return best;
}

// Whether the pivot (EDGE: the edge's middle; VERTEX on the base: the vertex) lies on the support's
// edge as the cut was made: an overturn about it carries the item off its support.
bool Rocking3DModel::pivot_on_support_edge() const {
  const std::vector<Eigen::Vector2d>& support = body_.parameters().support;
  if (support.empty() || face_ != 0 || contact_ < 0) return false;
  Eigen::Vector2d p;
  if (mode_ == Mode3D::Edge) {
    const BaseEdge& e = fb().edge(contact_);
    p = 0.5 * (fb().vertex(e.a).position + fb().vertex(e.b).position).head<2>();
  } else if (mode_ == Mode3D::Vertex && contact_ < fb().vertex_count()) {
    p = fb().vertex(contact_).position.head<2>();
  } else {
    return false;
  }
  // the support as the item saw it when the cut was made, in the item frame
  const Eigen::Vector2d world = rot2(fit_yaw_) * p + fit_shift_;
  return std::abs(inside_margin(support, world)) <= floor_tol_;
}

// On a support the contact is cut from the base, and numbered as the cut: which of the base's own
// edges (EDGE) or vertices (VERTEX) it is, as the catalogue numbers them, or -1 on the support's edge.
int Rocking3DModel::base_contact() const {
  const int k = contact();
  if (k < 0 || body_.parameters().support.empty() || face_ != 0) return k;
  const std::vector<Eigen::Vector2d>& base = body_.whole_base();
  const int n = static_cast<int>(base.size());
  if (mode_ == Mode3D::Vertex) {
    if (k >= fb().vertex_count()) return k;  // (on a support the contact hull is the cut: not reached)
    for (int j = 0; j < n; ++j)
      if ((base[static_cast<std::size_t>(j)] - fb().vertex(k).position.head<2>()).norm() <= floor_tol_) return j;
    return -1;
  }
  const BaseEdge& e = fb().edge(k);
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector2d& w = base[static_cast<std::size_t>(j)];
    const Eigen::Vector2d nj = outward(w, base[static_cast<std::size_t>((j + 1) % n)]);
    if (std::abs((fb().vertex(e.a).position.head<2>() - w).dot(nj)) <= floor_tol_ &&
        std::abs((fb().vertex(e.b).position.head<2>() - w).dot(nj)) <= floor_tol_)
      return j;
  }
  return -1;
}

}  // namespace rocking_monitor::core
