#include "rocking_monitor/physics/base_friction.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace rocking_monitor::core {
namespace {

double friction_cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }
Eigen::Vector2d friction_perp(const Eigen::Vector2d& a) { return Eigen::Vector2d(-a.y(), a.x()); }  // z x a

// Gauss-Legendre on [0, 1], 6 points (exact to degree 11).
constexpr double kGx[6] = {0.033765242898423975, 0.16939530676686776, 0.38069040695840156,
                           0.61930959304159844, 0.83060469323313224, 0.96623475710157603};
constexpr double kGw[6] = {0.085662246189585173, 0.18038078652406930, 0.23395696728634552,
                           0.23395696728634552, 0.18038078652406930, 0.085662246189585173};

// Beyond this many base sizes from the centroid the instantaneous centre is far: the closed form's
// triangles grow with the distance and cancel (rounding ~ eps (distance / size)^3), while the slip
// direction over the base is smooth enough for a 6 x 6 Gauss rule (test: 1e-7 at 10 sizes).
constexpr double kFarCentre = 10.0;

}  // namespace

BaseFriction::BaseFriction(const std::vector<Eigen::Vector2d>& polygon)
    : v_(polygon), n_(static_cast<int>(polygon.size())) {
  // Area, centroid and second moment of area of the polygon (shoelace forms).
  double a2 = 0.0;
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (int i = 0; i < n_; ++i) {
    const Eigen::Vector2d& p = v_[static_cast<std::size_t>(i)];
    const Eigen::Vector2d& q = v_[static_cast<std::size_t>((i + 1) % n_)];
    const double w = friction_cross(p, q);
    a2 += w;
    c += w * (p + q);
  }
  area_ = 0.5 * a2;
  centroid_ = c / (3.0 * a2);
  Eigen::Matrix2d s = Eigen::Matrix2d::Zero();
  for (int i = 0; i < n_; ++i) {
    const Eigen::Vector2d p = v_[static_cast<std::size_t>(i)] - centroid_;
    const Eigen::Vector2d q = v_[static_cast<std::size_t>((i + 1) % n_)] - centroid_;
    const double w = friction_cross(p, q);
    s(0, 0) += w * (p.x() * p.x() + p.x() * q.x() + q.x() * q.x()) / 12.0;
    s(1, 1) += w * (p.y() * p.y() + p.y() * q.y() + q.y() * q.y()) / 12.0;
    s(0, 1) += w * (2.0 * p.x() * p.y() + p.x() * q.y() + q.x() * p.y() + 2.0 * q.x() * q.y()) / 24.0;
    size_ = std::max(size_, p.norm());
  }
  s(1, 0) = s(0, 1);
  second_moment_inverse_ = s.inverse();
}

Eigen::Vector2d BaseFriction::gradient(const Eigen::Vector2d& pressure_centre) const {
  // int p (x - g) dA = S k = P - g (per unit N) fixes the slope of the linear law.
  return second_moment_inverse_ * (pressure_centre - centroid_);
}

double BaseFriction::pressure(const Eigen::Vector2d& x, const Eigen::Vector2d& pressure_centre) const {
  return 1.0 / area_ + gradient(pressure_centre).dot(x - centroid_);
}

FrictionLoad BaseFriction::load(const Eigen::Vector2d& v, double spin, const Eigen::Vector2d& ref,
                                const Eigen::Vector2d& pressure_centre) const {
  FrictionLoad out;
  const double speed = v.norm();
  if (spin == 0.0) {
    // Pure translation: every point slips along v; the force acts at the centre of pressure.
    if (speed == 0.0) return out;
    out.force = -v / speed;
    out.torque = friction_cross(pressure_centre - ref, out.force);
    return out;
  }
  // Turning about the instantaneous centre O: ref's velocity spin z x (ref - O) = v.
  const Eigen::Vector2d centre = ref + friction_perp(v) / spin;
  const Eigen::Vector2d k = gradient(pressure_centre);
  if ((centre - centroid_).norm() > kFarCentre * size_) return by_quadrature(centre, spin, ref, k);
  return from_centre(centre, spin, ref, k, 1.0 / area_ + k.dot(centre - centroid_));
}

// The closed form (see the header): per edge A -> B, the signed triangle (O, A, B) with w = A - O +
// t (B - A) = x e + d n (e the edge's direction, n = z x e), slip direction sign(spin) z x w / |w|.
FrictionLoad BaseFriction::from_centre(const Eigen::Vector2d& o, double spin, const Eigen::Vector2d& ref,
                                       const Eigen::Vector2d& k, double p_o) const {
  FrictionLoad out;
  const Eigen::Vector2d b = o - ref;
  for (int i = 0; i < n_; ++i) {
    const Eigen::Vector2d& pa = v_[static_cast<std::size_t>(i)];
    const Eigen::Vector2d& pb = v_[static_cast<std::size_t>((i + 1) % n_)];
    const double len = (pb - pa).norm();
    const Eigen::Vector2d e = (pb - pa) / len, n = friction_perp(e);
    const double d = (pa - o).dot(n);
    if (std::abs(d) <= 1e-14 * len) continue;  // O on the edge's line: a triangle of zero area
    const double x0 = (pa - o).dot(e), x1 = x0 + len, ad = std::abs(d);
    auto prim = [&](double x, double& i0, double& i1, double& i2, double& j0, double& j1) {
      const double r = std::hypot(x, d), as = std::asinh(x / ad);
      i0 = as;
      i1 = r;
      i2 = 0.5 * (x * r - d * d * as);
      j0 = 0.5 * (x * r + d * d * as);
      j1 = r * r * r / 3.0;
    };
    double a0, a1, a2, a3, a4, c0, c1, c2, c3, c4;
    prim(x0, a0, a1, a2, a3, a4);
    prim(x1, c0, c1, c2, c3, c4);
    const double i0 = c0 - a0, i1 = c1 - a1, i2 = c2 - a2, j0 = c3 - a3, j1 = c4 - a4;
    const double ke = k.dot(e), kn = k.dot(n), be = b.dot(e), bn = b.dot(n);
    const double al0 = 0.5 * p_o + d * kn / 3.0, al1 = ke / 3.0;
    const double be0 = p_o / 3.0 + 0.25 * d * kn, be1 = 0.25 * ke;
    out.force += d * (n * (al0 * i1 + al1 * i2) - d * e * (al0 * i0 + al1 * i1));
    out.torque += d * (d * bn * al0 * i0 + (be * al0 + d * bn * al1) * i1 + be * al1 * i2 + be0 * j0 + be1 * j1);
  }
  const double s = spin > 0.0 ? 1.0 : -1.0;
  out.force *= s;
  out.torque *= s;
  return out;
}

// A far centre: the triangles from the centroid, each by a collapsed (Duffy) 6 x 6 Gauss rule.
FrictionLoad BaseFriction::by_quadrature(const Eigen::Vector2d& o, double spin, const Eigen::Vector2d& ref,
                                         const Eigen::Vector2d& k) const {
  FrictionLoad out;
  const double s = spin > 0.0 ? 1.0 : -1.0;
  for (int i = 0; i < n_; ++i) {
    const Eigen::Vector2d a = v_[static_cast<std::size_t>(i)] - centroid_;
    const Eigen::Vector2d e = v_[static_cast<std::size_t>((i + 1) % n_)] - v_[static_cast<std::size_t>(i)];
    const double jac = friction_cross(a, e);
    for (int q = 0; q < 6; ++q) {
      const Eigen::Vector2d w = a + kGx[q] * e;
      for (int r = 0; r < 6; ++r) {
        const Eigen::Vector2d x = centroid_ + kGx[r] * w;
        const Eigen::Vector2d dir = s * friction_perp(x - o).normalized();
        const double weight = kGw[q] * kGw[r] * kGx[r] * jac * (1.0 / area_ + k.dot(x - centroid_));
        out.force -= weight * dir;
        out.torque -= weight * friction_cross(x - ref, dir);
      }
    }
  }
  return out;
}

}  // namespace rocking_monitor::core
