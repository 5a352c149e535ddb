// Body geometry, validation and the impact law (paper eqs. 4-5, 28-38).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "rocking_monitor/physics/body.hpp"
#include "rocking_monitor/physics/impact.hpp"
#include "rocking_monitor/model/rocking_model.hpp"
#include "test_helpers.hpp"

namespace rocking_monitor::core {
namespace {

using testing::deg;

TEST(Body, DerivedPivotGeometry) {
  BodyParameters p;
  p.width = 0.6;
  p.cg_height = 1.0;
  p.nu1 = 0.3;
  const Body b(p);
  EXPECT_NEAR(b.pivot(1).alpha, std::atan(0.3 * 0.6 / 1.0), 1e-15);   // eq. 4
  EXPECT_NEAR(b.pivot(-1).alpha, std::atan(0.7 * 0.6 / 1.0), 1e-15);  // eq. 5
  EXPECT_NEAR(b.pivot(1).radius, std::sqrt(0.18 * 0.18 + 1.0), 1e-15);
  const double ig2 = (0.36 + 4.0) / 12.0;  // rectangle B x 2h
  EXPECT_NEAR(b.radius_of_gyration(), std::sqrt(ig2), 1e-15);
  EXPECT_NEAR(b.pivot(-1).inertia, ig2 + 0.42 * 0.42 + 1.0, 1e-14);  // eq. 28
  EXPECT_NEAR(b.pivot(1).p2, kGravity * b.pivot(1).radius / (ig2 + 0.18 * 0.18 + 1.0), 1e-13);
  EXPECT_NEAR(b.pivot(1).gamma, 1.0 / (0.3 * 0.6), 1e-13);  // eq. 17
}

TEST(Body, SymmetricRectangleHasHousnerFrequency) {
  // p^2 = 3 g / (4 R) for a homogeneous rectangle rocking about a corner.
  const Body b(testing::rectangle_with(2.0, deg(15)));
  EXPECT_NEAR(b.pivot(1).p, 2.0, 1e-12);
  EXPECT_NEAR(b.pivot(-1).p, 2.0, 1e-12);
  EXPECT_NEAR(b.pivot(1).alpha, deg(15), 1e-14);
}

TEST(Body, InvalidFieldsAreNamedWithTheirValue) {
  auto message = [](BodyParameters p) {
    try {
      Body b(p);
    } catch (const BodyError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  BodyParameters ok;
  ok.width = 0.5;
  ok.cg_height = 1.0;
  auto with = [&](auto mutate) { BodyParameters p = ok; mutate(p); return message(p); };
  EXPECT_EQ(message(ok), "accepted");
  EXPECT_NE(with([](auto& p) { p.width = 0.0; }).find("width = 0"), std::string::npos);
  EXPECT_NE(with([](auto& p) { p.width = -2.5; }).find("width = -2.5"), std::string::npos);
  EXPECT_NE(with([](auto& p) { p.cg_height = std::nan(""); }).find("cg_height = nan"), std::string::npos);
  EXPECT_NE(with([](auto& p) { p.nu1 = 1.0; }).find("nu1 = 1"), std::string::npos);
  EXPECT_NE(with([](auto& p) { p.nu1 = 0.0; }).find("nu1 = 0"), std::string::npos);
  EXPECT_NE(with([](auto& p) { p.radius_of_gyration = -0.1; }).find("radius_of_gyration = -0.1"), std::string::npos);
  EXPECT_NE(with([](auto& p) { p.mu_s = -0.3; }).find("mu_s = -0.3"), std::string::npos);
  EXPECT_NE(with([](auto& p) { p.mu_s = std::nan(""); }).find("mu_s = nan"), std::string::npos);
  EXPECT_NE(with([](auto& p) { p.restitution = 1.5; }).find("restitution = 1.5"), std::string::npos);
}

TEST(Impact, SymmetricRectangleGivesHousnersRatio) {
  for (double a : {deg(5), deg(10), deg(15), deg(25), deg(35)}) {
    const Body b(testing::rectangle_with(3.0, a));
    const double housner = 1.0 - 1.5 * std::sin(a) * std::sin(a);
    EXPECT_NEAR(b.pivot(1).restitution, housner, 1e-13) << "alpha " << a;
    EXPECT_NEAR(b.pivot(-1).restitution, housner, 1e-13);
    const double ig2 = b.radius_of_gyration() * b.radius_of_gyration();
    EXPECT_NEAR(impact_energy_ratio(ig2, b.cg_height(), b.width(), 0.5), housner * housner, 1e-13);
  }
}

// Independent derivation: angular momentum about the new pivot from the rigid-body kinematics
// (I_g w + m r x v) equals I_new w' (eqs. 27-30), and E'/E follows.
TEST(Impact, AsymmetricRatiosFromAngularMomentumBothDirections) {
  BodyParameters p;
  p.width = 0.8;
  p.cg_height = 1.1;
  p.nu1 = 0.25;
  p.radius_of_gyration = 0.55;
  const Body b(p);
  const double ig2 = 0.55 * 0.55, h = 1.1, B = 0.8;
  for (int new_side : {1, -1}) {
    // Old pivot is the other corner. Corner 1 at x=0, corner 2 at x=B, CoM at (nu1 B, h).
    const double x_new = new_side > 0 ? 0.0 : B, x_old = new_side > 0 ? B : 0.0;
    const double gx = 0.25 * B, gy = h;
    const double w = 1.0;  // rad/s about the old pivot
    const double vx = -w * (gy - 0.0), vy = w * (gx - x_old);  // v = w k x r_(G/old)
    const double rx = gx - x_new, ry = gy;
    const double h_new = ig2 * w + (rx * vy - ry * vx);
    const double i_new = ig2 + rx * rx + ry * ry;
    const double i_old = ig2 + (gx - x_old) * (gx - x_old) + gy * gy;
    const double ratio = h_new / i_new / w;
    EXPECT_NEAR(b.pivot(new_side).restitution, ratio, 1e-14) << "new pivot " << new_side;
    const double nu_s = b.pivot(new_side).nu;
    EXPECT_NEAR(impact_velocity_ratio(ig2, h, B, nu_s), ratio, 1e-14);  // eq. 34
    EXPECT_NEAR(impact_energy_ratio(ig2, h, B, nu_s), i_new * ratio * ratio / i_old, 1e-14);  // eq. 38
  }
  // The two velocity ratios differ for an eccentric body; eq. 38 is the same both ways.
  EXPECT_GT(std::abs(b.pivot(1).restitution - b.pivot(-1).restitution), 0.01);
  EXPECT_NEAR(impact_energy_ratio(ig2, h, B, 0.25), impact_energy_ratio(ig2, h, B, 0.75), 1e-15);
}

TEST(Impact, ModelAppliesTheRatioOfTheNewPivotAndTheUserOverride) {
  BodyParameters p;
  p.width = 0.5;
  p.cg_height = 1.0;
  p.nu1 = 0.35;
  for (double user : {std::numeric_limits<double>::quiet_NaN(), 0.93}) {
    p.restitution = user;
    const Body b(p);
    SolverSettings s;
    s.tol = 1e-12;
    RockingModel m(b, s);
    // About to land on corner 2 -> 1? Rocking about corner 1 (theta > 0) moving back down.
    const double w = -0.4;
    m.set_state(1e-7, w);
    m.step(0.0, 0.0, 1e-6);
    ASSERT_EQ(m.outcome().impacts, 1);
    ASSERT_EQ(m.side(), -1);
    const double expected = std::isnan(user) ? b.pivot(-1).restitution : user;
    // omega changes by at most theta''*dt ~ 1e-5 rad/s within the step.
    EXPECT_NEAR(m.omega() / w, expected, 1e-4);
  }
}

// restitution_shift (an ensemble's spread around eq. 34): added to each pivot's own eq. 34 ratio, so
// the two pivots keep their difference; clipped to [0, 1]; outside [-1, 1] refused by name.
TEST(Impact, RestitutionShiftMovesEachPivotsEq34RatioAndIsClipped) {
  BodyParameters p;
  p.width = 0.8;
  p.cg_height = 1.1;
  p.nu1 = 0.25;
  p.radius_of_gyration = 0.55;
  const Body nominal(p);
  for (double shift : {-0.05, 0.03}) {
    p.restitution_shift = shift;
    const Body b(p);
    for (int side : {1, -1}) {
      const double eq34 = impact_velocity_ratio(0.55 * 0.55, 1.1, 0.8, nominal.pivot(side).nu);
      EXPECT_NEAR(b.pivot(side).restitution, eq34 + shift, 1e-15) << side;
    }
  }
  p.restitution_shift = 0.9;  // eq. 34 here is ~0.7-0.8: the sum is clipped to 1
  EXPECT_EQ(Body(p).pivot(1).restitution, 1.0);
  p.restitution = 0.5;  // with a given ratio the shift moves it
  p.restitution_shift = -0.6;
  EXPECT_EQ(Body(p).pivot(-1).restitution, 0.0);
  p.restitution_shift = 1.5;
  EXPECT_NE(validate(p).find("restitution_shift = 1.5"), std::string::npos) << validate(p);
}

}  // namespace
}  // namespace rocking_monitor::core
