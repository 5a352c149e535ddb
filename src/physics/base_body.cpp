#include "rocking_monitor/physics/base_body.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Dense>

#include "rocking_monitor/constants.hpp"

namespace rocking_monitor::core {
namespace {

std::string fail(const std::string& field, const std::string& problem) { return field + ": " + problem; }

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

std::string validate(const BaseBodyParameters& p) {
  if (!(p.mass > 0.0) || !std::isfinite(p.mass)) return fail("mass", "must be a finite value > 0 kg");
  if (!p.centre_of_mass.allFinite()) return fail("centre_of_mass", "must be finite (m)");
  if (!(p.centre_of_mass.z() > 0.0)) return fail("centre_of_mass", "z (height above the floor) must be > 0 m");
  const std::size_t n = p.base.size();
  if (n < 3) return fail("base_polygon", "needs at least 3 vertices, found " + std::to_string(n));
  if (n > static_cast<std::size_t>(kMaxBaseVertices))
    return fail("base_polygon", "at most " + std::to_string(kMaxBaseVertices) + " vertices, found " +
                                    std::to_string(n) + " (simplify the hull)");
  double extent = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!p.base[i].allFinite()) return fail("base_polygon", "vertex " + std::to_string(i + 1) + " is not finite");
    extent = std::max(extent, (p.base[i] - p.base[0]).norm());
  }
  if (!(extent > 0.0)) return fail("base_polygon", "all vertices coincide");
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = p.base[i];
    const Eigen::Vector2d& b = p.base[(i + 1) % n];
    const Eigen::Vector2d& c = p.base[(i + 2) % n];
    if ((b - a).norm() <= 1e-9 * extent)
      return fail("base_polygon", "vertices " + std::to_string(i + 1) + " and " +
                                      std::to_string((i + 1) % n + 1) + " coincide");
    // Strictly convex and counter-clockwise: every turn to the left (a collinear vertex would make
    // an edge of zero length in the hull's sense: rocking about it is rocking about its neighbours).
    if (cross2(b - a, c - b) <= 1e-12 * extent * extent)
      return fail("base_polygon", "not strictly convex and counter-clockwise at vertex " +
                                      std::to_string((i + 1) % n + 1) + " (seen from above)");
  }
  const Eigen::Vector2d c(p.centre_of_mass.x(), p.centre_of_mass.y());
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = p.base[i];
    const Eigen::Vector2d& b = p.base[(i + 1) % n];
    if (!(cross2(b - a, c - a) > 0.0))
      return fail("centre_of_mass", "its plan position lies outside the base polygon (beyond edge " +
                                        std::to_string(i + 1) + "): the item cannot stand");
  }
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
  if (!(p.restitution_factor >= 0.0 && p.restitution_factor <= 1.0))
    return fail("restitution_factor", "must lie in [0, 1]");
  if (!(p.overturn_angle > 0.0 && p.overturn_angle <= kPi)) return fail("overturn_angle", "must lie in (0, pi] rad");
  return {};
}

BaseBody::BaseBody(const BaseBodyParameters& parameters) : params_(parameters) {
  if (const std::string e = validate(params_); !e.empty()) throw BodyError(e);
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
    min_alpha_ = std::min(min_alpha_, pv.alpha);
    max_p_ = std::max(max_p_, pv.p);
    if (pv.alpha >= params_.overturn_angle) {
      std::ostringstream m;
      m << "overturn_angle: must exceed the tipping angle of every edge (edge " << k + 1 << ": "
        << pv.alpha << " rad)";
      throw BodyError(m.str());
    }
  }
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
  p.overturn_angle = x.overturn_angle;
  return p;
}

}  // namespace rocking_monitor::core
