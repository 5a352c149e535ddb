#include "rocking_monitor/physics/base_body.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Dense>

#include <Eigen/Geometry>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/physics/contact_hull.hpp"
#include "rocking_monitor/physics/convex_polyhedron.hpp"
#include "rocking_monitor/physics/support_polygon.hpp"

namespace rocking_monitor::core {
namespace {

std::string fail(const std::string& field, const std::string& problem) { return field + ": " + problem; }

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

std::string validate_body(const BaseBodyParameters& p, bool must_stand);
double hull_tolerance(const BaseBodyParameters& p);

// The support (issue 51): a valid polygon under the centre of mass, overlapping the base.
std::string support_problem(const BaseBodyParameters& p) {
  if (p.support.empty()) return {};
  if (p.support.size() > static_cast<std::size_t>(kMaxBaseVertices))
    return "at most " + std::to_string(kMaxBaseVertices) + " vertices, found " + std::to_string(p.support.size());
  if (const std::string problem = polygon_problem(p.support); !problem.empty()) return problem;
  if (!p.hull.empty()) {
    // A pedestal within the base: every pivot is on the pedestal's edge, so no hull point beyond it
    // can come down onto the pedestal (docs/rocking_3d.md); on a wider plinth the hull's other faces
    // would land on it beyond the base.
    if (const int i = first_outside(p.support, p.base, hull_tolerance(p)); i >= 0)
      return "with a hull, the support must lie within base_polygon (a pedestal under a scanned body): vertex " +
             std::to_string(i + 1) + " lies beyond the base, where the hull's other faces could land on it " +
             "(not modelled yet)";
  }
  if (!(inside_margin(p.support, p.centre_of_mass.head<2>()) > 0.0))
    return "the centre of mass's plan position lies off the support: the item would fall at once";
  if (clip_convex(p.base, p.support).empty()) return "does not overlap the base polygon";
  return {};
}

// The lips (issue 51): edges of the support, each once, with the base within them (a lip under the
// base would hold nothing: the base already reaches beyond it).
std::string lips_problem(const BaseBodyParameters& p) {
  if (p.support_lips.empty()) return {};
  if (p.support.empty()) return "needs a support (the lips are along its edges)";
  const int n = static_cast<int>(p.support.size());
  std::vector<bool> seen(static_cast<std::size_t>(n), false);
  for (const int k : p.support_lips) {
    if (k < 0 || k >= n)
      return "edge " + std::to_string(k + 1) + " is not an edge of the support (1 to " + std::to_string(n) + ")";
    if (seen[static_cast<std::size_t>(k)]) return "edge " + std::to_string(k + 1) + " is listed twice";
    seen[static_cast<std::size_t>(k)] = true;
    const Eigen::Vector2d& a = p.support[static_cast<std::size_t>(k)];
    const Eigen::Vector2d d = p.support[static_cast<std::size_t>((k + 1) % n)] - a;
    for (std::size_t i = 0; i < p.base.size(); ++i)
      if (cross2(d, p.base[i] - a) < -1e-9 * d.norm() * d.norm())
        return "edge " + std::to_string(k + 1) + ": base_polygon vertex " + std::to_string(i + 1) +
               " lies beyond it (the lip would stand under the item)";
  }
  return {};
}

}  // namespace

std::string validate(const BaseBodyParameters& p) { return validate_body(p, true); }

namespace {

std::string validate_body(const BaseBodyParameters& p, bool must_stand) {
  if (!(p.mass > 0.0) || !std::isfinite(p.mass)) return fail("mass", "must be a finite value > 0 kg");
  if (!p.centre_of_mass.allFinite()) return fail("centre_of_mass", "must be finite (m)");
  if (!(p.centre_of_mass.z() > 0.0)) return fail("centre_of_mass", "z (height above the floor) must be > 0 m");
  const std::size_t n = p.base.size();
  if (n < 3) return fail("base_polygon", "needs at least 3 vertices, found " + std::to_string(n));
  if (n > static_cast<std::size_t>(kMaxBaseVertices))
    return fail("base_polygon", "at most " + std::to_string(kMaxBaseVertices) + " vertices, found " +
                                    std::to_string(n) + " (simplify the hull)");
  if (const std::string problem = polygon_problem(p.base); !problem.empty()) return fail("base_polygon", problem);
  const Eigen::Vector2d c(p.centre_of_mass.x(), p.centre_of_mass.y());
  for (std::size_t i = 0; i < n && must_stand; ++i) {
    const Eigen::Vector2d& a = p.base[i];
    const Eigen::Vector2d& b = p.base[(i + 1) % n];
    if (!(cross2(b - a, c - a) > 0.0))
      return fail("centre_of_mass", "its plan position lies outside the base polygon (beyond edge " +
                                        std::to_string(i + 1) + "): the item cannot stand");
  }
  if (const std::string e = support_problem(p); !e.empty()) return fail("support", e);
  if (const std::string e = lips_problem(p); !e.empty()) return fail("support_lips", e);
  if (!(p.support_lip_height >= 0.0 && std::isfinite(p.support_lip_height)))
    return fail("support_lip_height", "must be a finite value >= 0 m");
  if (p.support_lip_height > 0.0 && p.support_lips.empty())
    return fail("support_lip_height", "needs support_lips (the support's edges with a lip)");
  const Eigen::Matrix3d& I = p.central_inertia;
  if (!I.allFinite()) return fail("central_inertia", "must be finite (kg m^2)");
  const double scale = I.diagonal().cwiseAbs().maxCoeff();
  if (!(scale > 0.0) || (I - I.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
    return fail("central_inertia", "must be a symmetric matrix with a positive diagonal");
  const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues();
  if (!(ev.minCoeff() > 0.0)) return fail("central_inertia", "must be positive definite");
  // A rigid body's principal moments obey the triangle inequality (each <= the sum of the others).
  if (ev(2) > ev(0) + ev(1) + 1e-9 * scale)
    return fail("central_inertia", "principal moments violate I3 <= I1 + I2 (no rigid body has them)");
  if (!(p.mu_s >= 0.0)) return fail("mu_s", "must be >= 0 (or .inf: not given)");
  if (!std::isnan(p.mu_k) && !(p.mu_k >= 0.0 && std::isfinite(p.mu_k)))
    return fail("mu_k", "must be a finite value >= 0 (or not given: mu_s)");
  if (!(p.restitution_factor >= 0.0 && p.restitution_factor <= 1.0))
    return fail("restitution_factor", "must lie in [0, 1]");
  if (!(p.overturn_angle > 0.0 && p.overturn_angle <= kPi)) return fail("overturn_angle", "must lie in (0, pi] rad");
  // On its pedestal a scanned body's other faces cannot land up to 90 degrees of tilt (the hull above
  // the base's plane, the pedestal below it): beyond, they could come down on the pedestal's top.
  if (!p.hull.empty() && !p.support.empty() && p.overturn_angle > 0.5 * kPi)
    return fail("overturn_angle", "with a hull on a support, must be at most pi/2 rad (beyond, the hull's other "
                                  "faces could land on the pedestal's top: not modelled)");
  if (p.hull.size() > static_cast<std::size_t>(kMaxBaseVertices))
    return fail("hull", "at most " + std::to_string(kMaxBaseVertices) + " points, found " +
                            std::to_string(p.hull.size()) + " (simplify the hull)");
  double size = 0.0;
  for (const auto& b : p.base) size = std::max(size, (b - p.base[0]).norm());
  for (std::size_t i = 0; i < p.hull.size(); ++i) {
    if (!p.hull[i].allFinite()) return fail("hull", "point " + std::to_string(i + 1) + " is not finite");
    size = std::max(size, p.hull[i].norm());
  }
  for (std::size_t i = 0; i < p.hull.size(); ++i)
    if (p.hull[i].z() < -1e-9 * size) {
      std::ostringstream m;
      m << "point " << i + 1 << " lies below the floor (z = " << p.hull[i].z() << " m)";
      return fail("hull", m.str());
    }
  return {};
}

// The hull's tolerance: points this close to a face's plane lie on it (far below a scan's
// resolution, above rounding), m.
double hull_tolerance(const BaseBodyParameters& p) {
  double size = 0.0;
  for (const auto& h : p.hull) size = std::max(size, (h - p.centre_of_mass).norm());
  for (const auto& b : p.base) size = std::max(size, (Eigen::Vector3d(b.x(), b.y(), 0.0) - p.centre_of_mass).norm());
  return 1e-9 * size;
}

BaseVertex hull_vertex(const Eigen::Vector3d& position, const Eigen::Vector3d& c, const Eigen::Matrix3d& central) {
  BaseVertex v;
  v.position = position;
  v.to_centre = c - v.position;
  // Parallel axis: I_P = I_c + m (|r|^2 1 - r r^T).
  v.inertia = central + (v.to_centre.squaredNorm() * Eigen::Matrix3d::Identity() - v.to_centre * v.to_centre.transpose());
  v.inertia_inverse = v.inertia.inverse();
  v.radius = v.to_centre.norm();
  v.alpha = std::atan2(std::hypot(v.to_centre.x(), v.to_centre.y()), v.to_centre.z());
  return v;
}

}  // namespace

int ContactHull::face_down(const Eigen::Matrix3d& rotation) const {
  int best = 0;
  double lowest = 2.0;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    // The face's outward normal in the item frame is rotation^T (-z) in its own frame.
    const double nz = (rotation * (faces[f].rotation.transpose() * -Eigen::Vector3d::UnitZ())).z();
    if (nz < lowest) { lowest = nz; best = static_cast<int>(f); }
  }
  return best;
}

bool ContactHull::face_with_edge(int a, int b, const Eigen::Matrix3d& rotation, int& face, int& edge) const {
  double best = 1e300;
  face = edge = -1;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const std::vector<int>& hv = faces[f].hull_vertex;
    const int n = static_cast<int>(hv.size());
    for (int k = 0; k < n; ++k) {
      const int u = hv[static_cast<std::size_t>(k)], w = hv[static_cast<std::size_t>((k + 1) % n)];
      if (!((u == a && w == b) || (u == b && w == a))) continue;
      if (!(faces[f].body->edge(k).pivot.alpha > 0.0)) continue;  // the centre of mass is beyond it
      const double up = (rotation * (faces[f].rotation.transpose() * Eigen::Vector3d::UnitZ())).z();
      const double tilt = std::acos(std::clamp(up, -1.0, 1.0));
      if (tilt < best) { best = tilt; face = static_cast<int>(f); edge = k; }
    }
  }
  return face >= 0;
}

BaseBody BaseBody::face(const BaseBodyParameters& parameters) { return BaseBody(parameters, false); }

BaseBody BaseBody::on_support(const std::vector<Eigen::Vector2d>& placed) const {
  BaseBodyParameters moved = params_;
  moved.base = whole_base_;
  moved.support = placed;
  moved.hull.clear();  // (on a support the contact is the base's cut: the hull was checked at load)
  moved.support_lips.clear();  // (checked at load; a corner swung over a lip may lie beyond it now)
  BaseBody body(moved, true);
  body.params_.support = params_.support;
  body.params_.hull = params_.hull;
  body.params_.support_lips = params_.support_lips;
  return body;
}
BaseBody::BaseBody(const BaseBodyParameters& parameters) : BaseBody(parameters, true) {}

BaseBody::BaseBody(const BaseBodyParameters& parameters, bool must_stand) : params_(parameters) {
  if (const std::string e = validate_body(params_, must_stand); !e.empty()) throw BodyError(e);
  whole_base_ = params_.base;
  if (!params_.support.empty()) {
    // The contact is the base where it lies on the support (a pedestal smaller than the base bounds it).
    params_.base = clip_convex(params_.base, params_.support);
    if (const std::string e = validate_body(params_, must_stand); !e.empty())
      throw BodyError("support: the base's contact with it: " + e);
  }
  central_ = params_.central_inertia / params_.mass;
  const int n = static_cast<int>(params_.base.size());
  const Eigen::Vector3d& c = params_.centre_of_mass;
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  vertices_.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    BaseVertex& v = vertices_[static_cast<std::size_t>(i)];
    v.position = Eigen::Vector3d(params_.base[static_cast<std::size_t>(i)].x(),
                                 params_.base[static_cast<std::size_t>(i)].y(), 0.0);
    v.to_centre = c - v.position;
    // Parallel axis: I_P = I_c + m (|r|^2 1 - r r^T).
    v.inertia = central_ + (v.to_centre.squaredNorm() * Eigen::Matrix3d::Identity() -
                            v.to_centre * v.to_centre.transpose());
    v.inertia_inverse = v.inertia.inverse();
    v.radius = v.to_centre.norm();
    v.alpha = std::atan2(std::hypot(v.to_centre.x(), v.to_centre.y()), v.to_centre.z());
    centroid_ += v.position / n;
  }
  edges_.resize(static_cast<std::size_t>(n));
  min_alpha_ = kPi;
  for (int k = 0; k < n; ++k) {
    BaseEdge& e = edges_[static_cast<std::size_t>(k)];
    e.a = k;
    e.b = (k + 1) % n;
    const Eigen::Vector3d d = vertex(e.b).position - vertex(e.a).position;
    e.length = d.norm();
    e.axis = d / e.length;
    e.normal = e.axis.cross(z);
    // The centre of mass seen in the plane normal to the edge: R and alpha of the planar pivot.
    const Eigen::Vector3d r = c - vertex(e.a).position;
    const Eigen::Vector3d r_perp = r - r.dot(e.axis) * e.axis;
    const double inward = -r_perp.dot(e.normal);  // > 0: the centre of mass is inside the base
    Pivot& pv = e.pivot;
    pv.alpha = std::atan2(inward, r_perp.z());
    pv.radius = std::hypot(inward, r_perp.z());
    pv.inertia = e.axis.dot(central_ * e.axis) + pv.radius * pv.radius;
    pv.p2 = kGravity * pv.radius / pv.inertia;
    pv.p = std::sqrt(pv.p2);
    pv.sin_alpha = std::sin(pv.alpha);
    pv.cos_alpha = std::cos(pv.alpha);
    pv.tan_alpha = inward / r_perp.z();
    pv.gamma = r_perp.z() / inward;
    pv.nu = std::numeric_limits<double>::quiet_NaN();  // no base width along one line here
    pv.restitution = std::numeric_limits<double>::quiet_NaN();  // the 3-D impact law decides
    // (a hull face's edges beyond the centre of mass have alpha <= 0: not a tipping angle)
    if (pv.alpha > 0.0) min_alpha_ = std::min(min_alpha_, pv.alpha);
    else stands_ = false;
    max_p_ = std::max(max_p_, pv.p);
    if (must_stand && pv.alpha >= params_.overturn_angle) {
      std::ostringstream m;
      m << "overturn_angle: must exceed the tipping angle of every edge (edge " << k + 1 << ": "
        << pv.alpha << " rad)";
      throw BodyError(m.str());
    }
  }
  if (must_stand && !params_.hull.empty() && !params_.support.empty()) {
    // The hull's own checks (its base a face of it, the centre of mass inside), as without the support.
    BaseBodyParameters whole = parameters;
    whole.support.clear();
    // (not the overturn angle: it is the pedestal's edges that tip the body, at smaller angles than
    // the whole base's edges, which the body never rocks on)
    whole.overturn_angle = kPi;
    const BaseBody check(whole);
  }
  if (must_stand) build_contact_hull();
}

namespace {

// Without a hull in the parameters: the base's vertices, each a neighbour of every other, and the
// base as the only face.
std::shared_ptr<ContactHull> base_only_hull(const std::vector<BaseVertex>& vertices, const BaseBody& base) {
  auto hull = std::make_shared<ContactHull>();
  const int n = static_cast<int>(vertices.size());
  hull->vertices = vertices;
  hull->neighbours.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (j != i) hull->neighbours[static_cast<std::size_t>(i)].push_back(j);
  HullFace f;
  f.body = std::make_shared<const BaseBody>(base);
  for (int k = 0; k < n; ++k) {
    f.hull_vertex.push_back(k);
    f.across.push_back(-1);
    f.fold.push_back(std::numeric_limits<double>::infinity());
  }
  hull->faces.push_back(std::move(f));
  return hull;
}

// The convex polyhedron of the base's vertices (first, in order) and the hull's points; origin[i]:
// the hull point (1-based) input point i is, -1 for a base vertex.
ConvexPolyhedron hull_polyhedron(const BaseBodyParameters& p, double tol, std::vector<int>& origin) {
  std::vector<Eigen::Vector3d> pts;
  for (const auto& b : p.base) pts.emplace_back(b.x(), b.y(), 0.0);
  // (a hull point at a base vertex is that vertex: a mesh's hull lists the base's corners too)
  origin.assign(pts.size(), -1);
  for (std::size_t i = 0; i < p.hull.size(); ++i) {
    const Eigen::Vector3d& h = p.hull[i];
    if (std::none_of(pts.begin(), pts.end(), [&](const Eigen::Vector3d& q) { return (q - h).norm() <= tol; })) {
      pts.push_back(h);
      origin.push_back(static_cast<int>(i) + 1);
    }
  }
  try {
    return convex_polyhedron(pts, tol);
  } catch (const std::invalid_argument& e) {
    throw BodyError(std::string("hull: ") + e.what());
  }
}

// The base is a face of the hull: its vertices are the hull's first n, in order, and the face on
// the floor has exactly them; the centre of mass is inside. Returns the base's face.
int checked_base_face(const ConvexPolyhedron& poly, int n, double tol, const std::vector<int>& origin,
                      const Eigen::Vector3d& c) {
  for (int i = 0; i < n; ++i)
    if (i >= static_cast<int>(poly.source.size()) || poly.source[static_cast<std::size_t>(i)] != i)
      throw BodyError("hull: base_polygon vertex " + std::to_string(i + 1) + " is not a corner of the hull");
  if (static_cast<int>(poly.points.size()) > kMaxBaseVertices)
    throw BodyError("hull: " + std::to_string(poly.points.size()) + " vertices, at most " +
                    std::to_string(kMaxBaseVertices) + " (simplify the hull)");
  int base_face = -1;
  for (std::size_t f = 0; f < poly.faces.size(); ++f)
    if (poly.faces[f].normal.z() < -1.0 + 1e-12) base_face = static_cast<int>(f);
  if (base_face < 0 || static_cast<int>(poly.faces[static_cast<std::size_t>(base_face)].vertices.size()) != n) {
    for (std::size_t i = 0; i < poly.points.size(); ++i)
      if (std::abs(poly.points[i].z()) <= tol && static_cast<int>(i) >= n)
        throw BodyError("hull: point " + std::to_string(origin[static_cast<std::size_t>(poly.source[i])]) +
                        " lies on the floor outside base_polygon (the base is the hull's face on the floor)");
    throw BodyError("hull: base_polygon is not the hull's face on the floor");
  }
  for (const auto& f : poly.faces)
    if (!(f.normal.dot(c) < f.offset - tol))
      throw BodyError("hull: the centre of mass is not inside the hull");
  return base_face;
}

// A face other than the base as a body standing on it: the item rotated so that the face lies on
// the floor, its vertices `verts` the face's base polygon.
void stand_on_face(const PolyhedronFace& pf, const std::vector<int>& verts, const ConvexPolyhedron& poly,
                   const BaseBodyParameters& params, HullFace& h) {
  h.rotation = Eigen::Quaterniond::FromTwoVectors(pf.normal, -Eigen::Vector3d::UnitZ()).toRotationMatrix();
  h.offset = Eigen::Vector3d(0.0, 0.0, pf.offset);
  BaseBodyParameters fp = params;
  fp.hull.clear();
  fp.base.clear();
  for (int v : verts) {
    const Eigen::Vector3d x = h.rotation * poly.points[static_cast<std::size_t>(v)] + h.offset;
    fp.base.emplace_back(x.x(), x.y());
  }
  fp.centre_of_mass = h.rotation * params.centre_of_mass + h.offset;
  fp.central_inertia = h.rotation * params.central_inertia * h.rotation.transpose();
  fp.overturn_angle = kPi;
  try {
    h.body = std::make_shared<const BaseBody>(BaseBody::face(fp));
  } catch (const BodyError& e) {
    throw BodyError(std::string("hull: a face is degenerate (") + e.what() + ")");
  }
}

// Face f's edges: the face across each (its slot) and the fold angle to it.
void face_edges(const ConvexPolyhedron& poly, int f, const std::vector<int>& slot, HullFace& h) {
  const PolyhedronFace& pf = poly.faces[static_cast<std::size_t>(f)];
  const std::vector<int>& verts = h.hull_vertex;
  const int m = static_cast<int>(verts.size());
  for (int k = 0; k < m; ++k) {
    // Face edge k runs verts[k] -> verts[k+1] from above, verts[k+1] -> verts[k] from outside.
    const int g = poly.face_across(f, verts[static_cast<std::size_t>((k + 1) % m)], verts[static_cast<std::size_t>(k)]);
    h.across.push_back(g < 0 ? -1 : slot[static_cast<std::size_t>(g)]);
    h.fold.push_back(g < 0 ? std::numeric_limits<double>::infinity()
                           : std::acos(std::clamp(pf.normal.dot(poly.faces[static_cast<std::size_t>(g)].normal), -1.0, 1.0)));
  }
}

}  // namespace

void BaseBody::build_contact_hull() {
  const int n = vertex_count();
  BaseBody base = *this;
  base.params_.hull.clear();
  // On a support (a pedestal within the base with a hull) the contact is the base's cut alone.
  if (params_.hull.empty() || !params_.support.empty()) {
    hull_ = base_only_hull(vertices_, base);
    return;
  }
  auto hull = std::make_shared<ContactHull>();
  hull->from_hull = true;
  const double tol = hull_tolerance(params_);
  std::vector<int> origin;
  const ConvexPolyhedron poly = hull_polyhedron(params_, tol, origin);
  const Eigen::Vector3d& c = params_.centre_of_mass;
  const int base_face = checked_base_face(poly, n, tol, origin, c);
  for (const auto& p : poly.points) hull->vertices.push_back(hull_vertex(p, c, central_));
  hull->neighbours = poly.neighbours;
  // Faces: the base first, then the others in the hull's order.
  std::vector<int> order{base_face};
  for (int f = 0; f < static_cast<int>(poly.faces.size()); ++f)
    if (f != base_face) order.push_back(f);
  std::vector<int> slot(poly.faces.size());
  for (std::size_t i = 0; i < order.size(); ++i) slot[static_cast<std::size_t>(order[i])] = static_cast<int>(i);
  for (int f : order) {
    const PolyhedronFace& pf = poly.faces[static_cast<std::size_t>(f)];
    HullFace h;
    // Counter-clockwise from outside is clockwise from above in the face's floor frame: reversed.
    std::vector<int> verts(pf.vertices.rbegin(), pf.vertices.rend());
    if (f == base_face) {
      // the base's own order (vertex k of the base is hull vertex k)
      verts.clear();
      for (int i = 0; i < n; ++i) verts.push_back(i);
      h.body = std::make_shared<const BaseBody>(base);
    } else {
      stand_on_face(pf, verts, poly, params_, h);
    }
    h.hull_vertex = verts;
    face_edges(poly, f, slot, h);
    hull->faces.push_back(std::move(h));
  }
  hull_ = std::move(hull);
}

BaseBodyParameters box_base_body(const BodyParameters& x, double depth, double nu_y,
                                 double radius_of_gyration_y) {
  const Body planar(x);  // validates x
  const double b = x.width, d = depth, h = x.cg_height;
  if (!(d > 0.0) || !std::isfinite(d)) throw BodyError("depth: must be a finite value > 0 m");
  if (!(nu_y > 0.0 && nu_y < 1.0)) throw BodyError("eccentricity_y: must lie in (0, 1)");
  const double ig = planar.radius_of_gyration();
  const double ix = std::isnan(radius_of_gyration_y)
                        ? std::sqrt((d * d + 4.0 * h * h) / 12.0)
                        : radius_of_gyration_y;
  if (!(ix > 0.0)) throw BodyError("radius_of_gyration_y: must be > 0 m");
  BaseBodyParameters p;
  p.mass = 1.0;
  p.centre_of_mass = Eigen::Vector3d(x.nu1 * b, nu_y * d, h);
  p.central_inertia = Eigen::Vector3d(ix * ix, ig * ig, (b * b + d * d) / 12.0).asDiagonal();
  p.base = {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(b, 0.0), Eigen::Vector2d(b, d),
            Eigen::Vector2d(0.0, d)};
  p.mu_s = x.mu_s;
  p.mu_k = x.mu_k;
  p.overturn_angle = x.overturn_angle;
  return p;
}

}  // namespace rocking_monitor::core
