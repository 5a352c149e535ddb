// Coulomb friction over a sliding, turning base (issue 51): closed forms, an independent brute-force
// integral, the translation limit and the dissipation of every load.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "rocking_monitor/physics/base_friction.hpp"

namespace rocking_monitor::core {
namespace {

std::vector<Eigen::Vector2d> friction_square(double a) {
  return {{0.0, 0.0}, {a, 0.0}, {a, a}, {0.0, a}};
}

std::vector<Eigen::Vector2d> friction_ngon(int n, double r, const Eigen::Vector2d& c = Eigen::Vector2d::Zero()) {
  std::vector<Eigen::Vector2d> p;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n;
    p.push_back(c + r * Eigen::Vector2d(std::cos(t), std::sin(t)));
  }
  return p;
}

bool friction_inside(const std::vector<Eigen::Vector2d>& p, const Eigen::Vector2d& x) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector2d e = p[(i + 1) % p.size()] - p[i], d = x - p[i];
    if (e.x() * d.y() - e.y() * d.x() < 0.0) return false;
  }
  return true;
}

// Independent: the midpoint rule on an m x m grid over the bounding box, point by point.
FrictionLoad friction_brute_force(const std::vector<Eigen::Vector2d>& p, const BaseFriction& f,
                                  const Eigen::Vector2d& v, double spin, const Eigen::Vector2d& ref,
                                  const Eigen::Vector2d& pc, int m) {
  Eigen::Vector2d lo = p[0], hi = p[0];
  for (const auto& x : p) { lo = lo.cwiseMin(x); hi = hi.cwiseMax(x); }
  const Eigen::Vector2d h = (hi - lo) / m;
  FrictionLoad out;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      const Eigen::Vector2d x = lo + Eigen::Vector2d((i + 0.5) * h.x(), (j + 0.5) * h.y());
      if (!friction_inside(p, x)) continue;
      const Eigen::Vector2d r = x - ref;
      const Eigen::Vector2d slip = v + spin * Eigen::Vector2d(-r.y(), r.x());
      if (slip.norm() == 0.0) continue;
      const double w = f.pressure(x, pc) * h.x() * h.y();
      const Eigen::Vector2d df = -w * slip.normalized();
      out.force += df;
      out.torque += r.x() * df.y() - r.y() * df.x();
    }
  return out;
}

TEST(BaseFriction, ASquareTurningAboutItsCentreMeetsTheClosedFormTorque) {
  // Uniform pressure, pure rotation about the centre: torque = mu N <|r|>, and the mean distance of a
  // square of side a from its centre is a (sqrt(2) + ln(1 + sqrt(2))) / 6.
  const double a = 0.7;
  const BaseFriction f(friction_square(a));
  const Eigen::Vector2d c(a / 2, a / 2);
  for (double spin : {2.5, -0.3}) {
    const FrictionLoad l = f.load(Eigen::Vector2d::Zero(), spin, c, c);
    const double expected = a * (std::sqrt(2.0) + std::log(1.0 + std::sqrt(2.0))) / 6.0;
    EXPECT_NEAR(l.torque, spin > 0 ? -expected : expected, 1e-14);
    EXPECT_NEAR(l.force.norm(), 0.0, 1e-14);
  }
}

TEST(BaseFriction, ADiscTurningAboutItsCentreMeetsTwoThirdsMuNR) {
  // The example: (2/3) mu N R; a 128-gon of circumradius R is a disc to O(1/n^2).
  const double r = 0.25;
  const BaseFriction f(friction_ngon(128, r, Eigen::Vector2d(0.1, -0.2)));
  const Eigen::Vector2d c(0.1, -0.2);
  const FrictionLoad l = f.load(Eigen::Vector2d::Zero(), 1.0, c, c);
  EXPECT_NEAR(-l.torque / (2.0 * r / 3.0), 1.0, 4e-4);
  // The polygon's own value converges to the disc's: 512 sides are 16 times closer.
  const BaseFriction f512(friction_ngon(512, r, c));
  const double e128 = std::abs(-l.torque / (2.0 * r / 3.0) - 1.0);
  const double e512 = std::abs(-f512.load(Eigen::Vector2d::Zero(), 1.0, c, c).torque / (2.0 * r / 3.0) - 1.0);
  EXPECT_NEAR(e128 / e512, 16.0, 0.1);
}

TEST(BaseFriction, PureTranslationIsCoulombAtTheCentreOfPressure) {
  const BaseFriction f({{0.0, 0.0}, {0.6, 0.0}, {0.5, 0.4}, {0.1, 0.5}});
  const Eigen::Vector2d v(0.3, -0.4), ref(0.2, 0.2), pc(0.3, 0.25);
  const FrictionLoad l = f.load(v, 0.0, ref, pc);
  EXPECT_NEAR((l.force + v.normalized()).norm(), 0.0, 1e-15);
  const Eigen::Vector2d d = pc - ref;
  EXPECT_NEAR(l.torque, d.x() * l.force.y() - d.y() * l.force.x(), 1e-15);
  // A vanishing spin (the centre of rotation far away) tends to the same load.
  const FrictionLoad s = f.load(v, 1e-7, ref, pc);
  EXPECT_NEAR((s.force - l.force).norm(), 0.0, 1e-6);
  EXPECT_NEAR(s.torque - l.torque, 0.0, 1e-6);
}

TEST(BaseFriction, AgreesWithABruteForceIntegralOnRandomBasesAndMotions) {
  std::mt19937 rng(51);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  for (int trial = 0; trial < 12; ++trial) {
    // A random convex polygon: sorted angles on an ellipse.
    const int n = 3 + trial % 6;
    std::vector<double> ang;
    for (int i = 0; i < n; ++i) ang.push_back(M_PI * (u(rng) + 1.0));
    std::sort(ang.begin(), ang.end());
    std::vector<Eigen::Vector2d> p;
    for (double t : ang) p.emplace_back(0.4 * std::cos(t), 0.25 * std::sin(t));
    const BaseFriction f(p);
    const Eigen::Vector2d ref = f.centroid() + Eigen::Vector2d(0.02 * u(rng), 0.02 * u(rng));
    const Eigen::Vector2d pc = f.centroid() + Eigen::Vector2d(0.03 * u(rng), 0.02 * u(rng));
    // The centre of rotation inside, near and far (> 10 sizes: the quadrature branch).
    const double spin = 2.0 * u(rng);
    const double scale = trial % 3 == 0 ? 0.05 : trial % 3 == 1 ? 0.3 : 8.0;
    const Eigen::Vector2d v(scale * u(rng), scale * u(rng));
    const FrictionLoad a = f.load(v, spin, ref, pc);
    const FrictionLoad b = friction_brute_force(p, f, v, spin, ref, pc, 1500);
    const double err = std::max((a.force - b.force).norm(), std::abs(a.torque - b.torque) / 0.3);
    worst = std::max(worst, err);
    EXPECT_LT(err, 2e-3) << "trial " << trial;
  }
  RecordProperty("worst_difference", std::to_string(worst));
}

TEST(BaseFriction, TheFarCentreQuadratureJoinsTheClosedForm) {
  const BaseFriction f({{0.0, 0.0}, {0.5, 0.0}, {0.6, 0.3}, {0.2, 0.45}});
  const Eigen::Vector2d ref = f.centroid(), pc = f.centroid() + Eigen::Vector2d(0.02, -0.01);
  double size = 0.0;
  for (const Eigen::Vector2d& x : {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.5, 0.0), Eigen::Vector2d(0.6, 0.3),
                                   Eigen::Vector2d(0.2, 0.45)})
    size = std::max(size, (x - f.centroid()).norm());
  // spin 1, |v| = distance of the centre of rotation from ref: just inside 10 sizes (the closed form)
  // against the line through two loads just outside (the quadrature), extrapolated to the same point.
  const FrictionLoad in = f.load(Eigen::Vector2d(0.0, 9.999 * size), 1.0, ref, pc);
  const FrictionLoad o1 = f.load(Eigen::Vector2d(0.0, 10.001 * size), 1.0, ref, pc);
  const FrictionLoad o2 = f.load(Eigen::Vector2d(0.0, 10.003 * size), 1.0, ref, pc);
  EXPECT_NEAR((in.force - (2.0 * o1.force - o2.force)).norm(), 0.0, 1e-8);
  EXPECT_NEAR(in.torque - (2.0 * o1.torque - o2.torque), 0.0, 1e-8 * size);
}

TEST(BaseFriction, FrictionNeverDoesPositiveWork) {
  // The power of friction, F . v + torque * spin, is minus the integral of mu p |slip| <= 0.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const BaseFriction f(friction_ngon(7, 0.3));
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector2d v(u(rng), u(rng)), ref(0.05 * u(rng), 0.05 * u(rng)), pc(0.05 * u(rng), 0.05 * u(rng));
    const double spin = 5.0 * u(rng);
    const FrictionLoad l = f.load(v, spin, ref, pc);
    EXPECT_LE(l.force.dot(v) + l.torque * spin, 1e-12);
    EXPECT_LE(l.force.norm(), 1.0 + 1e-12);
  }
}

}  // namespace
}  // namespace rocking_monitor::core
