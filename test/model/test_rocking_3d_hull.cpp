// The 3-D model on a body's whole convex hull (issue 40 part 3): a hexagonal prism rolls over its
// sides as the classic rolling polygon does (energy conserved between landings, each landing keeping
// (i^2 + a^2 cos 60) / (i^2 + a^2) of the angular velocity, so the number of sides it rolls over
// and where it comes to rest follow in closed form), and a hull that adds nothing below the side
// (a box's eight corners) leaves every motion as the base alone gives it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "test_helpers.hpp"

namespace rocking_monitor::core {
namespace {

constexpr double kA = 0.1, kLength = 0.5;  // circumradius and length of the prism, m

BaseBodyParameters hexagonal_prism(double overturn_angle) {
  BaseBodyParameters p = testing::hexagonal_prism(kA, kLength);
  p.overturn_angle = overturn_angle;
  return p;
}

struct Rolled {
  int sides = 0;           // hull landings
  double tilt = 0.0;       // final tilt of the base, rad
  bool overturned = false;
  bool at_rest = false;
  double worst_energy = 0.0;  // largest relative error of the closed-form energy between landings
  double off_plane = 0.0;     // largest |omega_x| + |omega_z|, rad/s
};

// Rolls the prism about its long edge x = a/2 from flat with kinetic energy ke0 (J/kg), no shaking.
Rolled roll(double ke0, double overturn_angle) {
  const BaseBody body(hexagonal_prism(overturn_angle));
  Rocking3DModel m(body, testing::tight_settings());
  const double io = 5.0 * kA * kA / 12.0 + kA * kA;  // about the edge, per unit mass
  m.set_edge_state(1, 0.0, std::sqrt(2.0 * ke0 / io));
  const double ap = kA * std::sqrt(3.0) / 2.0;
  // Every landing is flat on a side with the centre of mass at the apothem and the new pivot 60
  // degrees round from the old: kinetic energy after = r^2 before.
  const double r = (5.0 / 12.0 + 0.5) / (5.0 / 12.0 + 1.0);
  Rolled out;
  for (int k = 0; k < 4000 && m.mode() != Mode3D::Rest && m.mode() != Mode3D::Overturned; ++k) {
    m.step(Eigen::Vector3d::Zero(), 0.002);
    const Eigen::Vector3d w = m.angular_velocity();
    out.off_plane = std::max(out.off_plane, std::abs(w.x()) + std::abs(w.z()));
    if (m.mode() != Mode3D::Edge) continue;
    const double e = m.kinetic_energy() + kGravity * (m.rotation() * body.centre_of_mass() + m.translation()).z();
    const double expect = kGravity * ap + ke0 * std::pow(r, 2.0 * static_cast<double>(m.outcome().impacts));
    out.worst_energy = std::max(out.worst_energy, std::abs(e - expect) / expect);
  }
  out.sides = static_cast<int>(m.outcome_3d().hull_landings);
  out.tilt = m.tilt();
  out.overturned = m.mode() == Mode3D::Overturned;
  out.at_rest = m.mode() == Mode3D::Rest;
  EXPECT_EQ(m.outcome_3d().max_landing_violation, 0.0);
  EXPECT_LE(m.outcome_3d().max_impact_energy_ratio, r * r + 1e-9);
  return out;
}

TEST(Rocking3DHull, AHexagonalPrismRollsOverAsManySidesAsItsEnergyCarriesIt) {
  const double ap = kA * std::sqrt(3.0) / 2.0;
  const double over_top = kGravity * (kA - ap);  // kinetic energy that lifts the centre over an edge
  const double r2 = std::pow((5.0 / 12.0 + 0.5) / (5.0 / 12.0 + 1.0), 2.0);
  for (int expected : {0, 1, 2}) {
    // between rolling over `expected` sides and one more: the middle of the interval in log energy
    const double ke0 = over_top / std::pow(r2, expected - 0.5);
    const Rolled c = roll(ke0, kPi);
    const std::string what = std::to_string(expected) + " sides";
    EXPECT_EQ(c.sides, expected) << what;
    EXPECT_TRUE(c.at_rest) << what;
    EXPECT_NEAR(c.tilt, expected * kPi / 3.0, 1e-9) << what;  // lying on the side it reached
    EXPECT_LT(c.worst_energy, 1e-8) << what;
    EXPECT_LT(c.off_plane, 1e-12) << what;  // the motion stays in the hexagon's plane
  }
}

TEST(Rocking3DHull, LyingBeyondTheOverturnAngleOnAnotherSideIsOverturned) {
  const double ap = kA * std::sqrt(3.0) / 2.0;
  const double over_top = kGravity * (kA - ap);
  const double r2 = std::pow((5.0 / 12.0 + 0.5) / (5.0 / 12.0 + 1.0), 2.0);
  // one side (tilt 60 degrees): at rest there, not overturned; two sides (120): overturned
  const Rolled one = roll(over_top / std::pow(r2, 0.5), kPi / 2.0);
  EXPECT_FALSE(one.overturned);
  EXPECT_TRUE(one.at_rest);
  EXPECT_EQ(one.sides, 1);
  const Rolled two = roll(over_top / std::pow(r2, 1.5), kPi / 2.0);
  EXPECT_TRUE(two.overturned);
}

// A box's hull (its eight corners) adds no contact before the box lies on its side: with it, every
// motion is the base alone's, turned and oblique shaking included.
TEST(Rocking3DHull, ABoxWithItsCornersAsHullMovesAsItsBaseAlone) {
  BodyParameters x;
  x.width = 0.4;
  x.cg_height = 0.5;
  x.nu1 = 0.4;
  x.radius_of_gyration = std::sqrt((0.4 * 0.4 + 4 * 0.5 * 0.5) / 12.0);
  BaseBodyParameters base = box_base_body(x, 0.3, 0.55, std::nan(""));
  BaseBodyParameters hull = base;
  for (int i = 0; i < 8; ++i)
    hull.hull.emplace_back(i & 1 ? 0.4 : 0.0, i & 2 ? 0.3 : 0.0, i & 4 ? 1.0 : 0.0);
  int rocked = 0, overturned = 0;
  for (double azimuth : {0.0, 0.5, 1.1})
    for (double amp : {0.35, 0.5, 0.7}) {
      Rocking3DModel a(BaseBody(base), testing::tight_settings());
      Rocking3DModel b(BaseBody(hull), testing::tight_settings());
      const double dt = 0.005, f = 1.5;
      for (double t = 0.0; t < 6.0; t += dt) {
        const double g = t < 1.0 / f ? amp * kGravity * std::sin(2.0 * kPi * f * t) : 0.0;
        const Eigen::Vector3d acc(g * std::cos(azimuth), g * std::sin(azimuth), 0.2 * g);
        a.step(acc, dt);
        b.step(acc, dt);
      }
      const std::string what = "azimuth " + std::to_string(azimuth) + ", " + std::to_string(amp) + " g";
      EXPECT_EQ(a.outcome().overturned, b.outcome().overturned) << what;
      if (a.outcome().overturned) EXPECT_EQ(a.outcome().overturn_time, b.outcome().overturn_time) << what;
      EXPECT_EQ(a.outcome().impacts, b.outcome().impacts) << what;
      EXPECT_NEAR(a.outcome().max_rotation_ratio, b.outcome().max_rotation_ratio, 1e-12) << what;
      EXPECT_EQ(a.mode(), b.mode()) << what;
      EXPECT_EQ(b.outcome_3d().hull_landings, 0) << what;
      rocked += a.outcome().impacts > 0;
      overturned += a.outcome().overturned;
    }
  EXPECT_GE(rocked, 4);
  EXPECT_GE(overturned, 1);
}

}  // namespace
}  // namespace rocking_monitor::core
