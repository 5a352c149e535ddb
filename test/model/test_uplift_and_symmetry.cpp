// Uplift from rest exactly at eq. 19, mirror symmetry, energy conservation between impacts.
#include <gtest/gtest.h>

#include <cmath>

#include "rocking_monitor/physics/criteria.hpp"
#include "rocking_monitor/model/rocking_model.hpp"
#include "rocking_monitor/monitoring/simulation.hpp"
#include "test_helpers.hpp"

namespace rocking_monitor::core {
namespace {

BodyParameters eccentric_body(double nu1) {
  BodyParameters p;
  p.width = 0.6;
  p.cg_height = 0.9;
  p.nu1 = nu1;
  return p;
}

// Holds a constant ground acceleration for a while; returns the model.
RockingModel hold(const BodyParameters& b, ModelKind model, double ax, double ay) {
  SolverSettings s;
  s.model = model;
  RockingModel m(b, s);
  m.reset(0.0, ax, ay);
  for (int k = 0; k < 50; ++k) m.step(ax, ay, 0.01);
  return m;
}

TEST(Uplift, HappensExactlyAtEq19ForBothSignsOfAnEccentricBody) {
  const BodyParameters b = eccentric_body(0.3);
  for (double ay : {0.0, 0.3 * kGravity, -0.4 * kGravity}) {
    for (int sign : {1, -1}) {
      const double nu_s = sign > 0 ? 0.3 : 0.7;  // eqs. 12-13
      const double gamma = b.cg_height / (nu_s * b.width);  // eq. 17
      const double threshold = (ay + kGravity) / gamma;       // |A| = 1/gamma, eq. 19
      const RockingModel below = hold(b, ModelKind::Nonlinear, sign * threshold * (1 - 1e-9), ay);
      EXPECT_EQ(below.mode(), Mode::Rest) << "sign " << sign << " ay " << ay;
      EXPECT_TRUE(std::isnan(below.outcome().uplift_time));
      const RockingModel above = hold(b, ModelKind::Nonlinear, sign * threshold * (1 + 1e-9), ay);
      EXPECT_EQ(above.mode(), Mode::Rocking) << "sign " << sign << " ay " << ay;
      EXPECT_EQ(above.side(), sign);
      EXPECT_EQ(sign * above.theta() > 0.0, true);
    }
  }
}

TEST(Uplift, LinearizedModelUsesItsOwnThresholdAlpha) {
  const BodyParameters b = eccentric_body(0.3);
  const double alpha1 = std::atan(0.3 * 0.6 / 0.9);
  EXPECT_EQ(hold(b, ModelKind::Linearized, alpha1 * kGravity * (1 - 1e-9), 0.0).mode(), Mode::Rest);
  EXPECT_EQ(hold(b, ModelKind::Linearized, alpha1 * kGravity * (1 + 1e-9), 0.0).mode(), Mode::Rocking);
}

TEST(Uplift, OnsetInsideASampleIsLocatedOnTheRamp) {
  // Ground acceleration ramps linearly from 0 to 2x the threshold over one 0.1 s sample:
  // the body lifts half way through.
  const BodyParameters b = eccentric_body(0.4);
  const double threshold = kGravity * 0.4 * 0.6 / 0.9;
  SolverSettings s;
  RockingModel m(b, s);
  m.reset(5.0, 0.0, 0.0);
  m.step(2.0 * threshold, 0.0, 0.1);
  EXPECT_NEAR(m.outcome().uplift_time, 5.05, 1e-12);
}

// Body nu1 under a(t) is the mirror image of body 1 - nu1 under -a(t).
TEST(Symmetry, MirrorBodyUnderMirroredInputRocksTheOtherWay) {
  GroundMotion g;
  g.dt = 0.005;
  for (int i = 0; i < 2000; ++i) {
    const double t = i * g.dt;
    g.horizontal.push_back(4.0 * std::sin(7.0 * t) * std::exp(-0.3 * t) + 1.5 * std::sin(17.0 * t));
    g.vertical.push_back(2.0 * std::sin(11.0 * t + 0.3));
  }
  GroundMotion mirrored = g;
  for (double& a : mirrored.horizontal) a = -a;
  for (Method method : {Method::Dopri5, Method::Rk4, Method::Analytic}) {
    SolverSettings s;
    s.method = method;
    s.model = method == Method::Analytic ? ModelKind::Linearized : ModelKind::Nonlinear;
    const SimulationResult a = simulate(Body(eccentric_body(0.3)), s, g, true);
    const SimulationResult b = simulate(Body(eccentric_body(0.7)), s, mirrored, true);
    ASSERT_EQ(a.history.size(), b.history.size());
    ASSERT_GE(a.outcome.impacts, 2) << "the test input must make the body rock";
    EXPECT_EQ(a.outcome.impacts, b.outcome.impacts);
    EXPECT_EQ(a.outcome.overturned, b.outcome.overturned);
    EXPECT_NEAR(a.outcome.max_rotation_ratio, b.outcome.max_rotation_ratio, 1e-9);
    EXPECT_EQ(a.outcome.max_rotation_side, -b.outcome.max_rotation_side);
    for (std::size_t i = 0; i < a.history.size(); ++i) {
      ASSERT_NEAR(a.history[i].theta, -b.history[i].theta, 1e-9) << to_string(method) << " i " << i;
      ASSERT_EQ(a.history[i].side, -b.history[i].side);
    }
  }
}

// Between impacts and without excitation, E = I w^2 / 2 + g R cos(alpha - s theta) is conserved.
TEST(Energy, ConservedBetweenImpactsWithoutExcitation) {
  BodyParameters b = eccentric_body(0.35);
  const Body body(b);
  for (Method method : {Method::Dopri5, Method::Rk4}) {
    SolverSettings s;
    s.method = method;
    s.tol = 1e-10;
    s.substeps = 8;
    RockingModel m(body, s);
    m.set_state(0.8 * body.pivot(1).alpha, 0.0);
    auto energy = [&] {
      const Pivot& pv = body.pivot(m.side());
      return 0.5 * pv.inertia * m.omega() * m.omega() +
             kGravity * pv.radius * std::cos(pv.alpha - m.side() * m.theta());
    };
    double e0 = energy();
    double worst = 0.0;
    int segments = 0;
    for (int k = 0; k < 4000 && m.mode() == Mode::Rocking; ++k) {
      const StepReport& r = m.step(0.0, 0.0, 0.002);
      if (m.mode() != Mode::Rocking) break;
      if (r.impacts > 0) {
        // The impact removes energy: E' - E_pot = (eq. 38) * (E - E_pot) at theta = 0.
        e0 = energy();
        ++segments;
        continue;
      }
      worst = std::max(worst, std::abs(energy() - e0) / (kGravity * body.pivot(1).radius));
    }
    EXPECT_GT(segments, 5);
    EXPECT_LT(worst, method == Method::Dopri5 ? 1e-9 : 1e-9) << to_string(method);
  }
}

}  // namespace
}  // namespace rocking_monitor::core
