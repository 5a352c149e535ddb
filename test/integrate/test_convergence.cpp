// Order of convergence of each method against exact solutions of the same discrete problem.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rocking_monitor/integrate/analytic_stepper.hpp"
#include "rocking_monitor/integrate/dopri5_stepper.hpp"
#include "rocking_monitor/integrate/rk4_stepper.hpp"
#include "rocking_monitor/monitoring/simulation.hpp"
#include "test_helpers.hpp"

namespace rocking_monitor::core {
namespace {

using testing::deg;

const BodyParameters kBody = testing::rectangle_with(3.0, deg(10));

// Fixed steps of a formula against the closed form of the linearized equation (no events).
template <class Step>
std::vector<double> fixed_step_errors(const Step& step, std::initializer_list<int> counts) {
  const Body body(kBody);
  const Pivot& pv = body.pivot(1);
  GroundInput in;
  in.ax0 = 0.4 * kGravity;
  in.ax_slope = -0.5;
  const RockingOde ode{&pv, 1, ModelKind::Linearized, in};
  AnalyticStepper exact;
  exact.step(ode, 0.0, 0.01, 0.05, 0.5);
  std::vector<double> errors;
  for (int n : counts) {
    double th = 0.01, om = 0.05;
    const double h = 0.5 / n;
    for (int i = 0; i < n; ++i) step(ode, i * h, th, om, h, th, om);
    errors.push_back(std::abs(th - exact.theta1()));
  }
  return errors;
}

TEST(Convergence, Rk4StepIsFourthOrder) {
  const auto e = fixed_step_errors(&Rk4Stepper::single_step, {16, 32, 64});
  EXPECT_NEAR(std::log2(e[0] / e[1]), 4.0, 0.2);
  EXPECT_NEAR(std::log2(e[1] / e[2]), 4.0, 0.1);
}

TEST(Convergence, Dopri5StepIsFifthOrder) {
  Dopri5Stepper dp;
  const auto e = fixed_step_errors(
      [&dp](const RockingOde& ode, double t, double th, double om, double h, double& tho, double& omo) {
        dp.single_step(ode, t, th, om, h, tho, omo);
      },
      {16, 32, 64});
  EXPECT_NEAR(std::log2(e[0] / e[1]), 5.0, 0.2);
  EXPECT_NEAR(std::log2(e[1] / e[2]), 5.0, 0.1);
}

// A burst that lifts the body, passes alpha and makes one impact, sampled at 0.05 s.
GroundMotion burst(double dt) {
  GroundMotion g;
  g.dt = dt;
  const int n = static_cast<int>(std::lround(1.0 / dt)) + 1;
  for (int i = 0; i < n; ++i) {
    const double t = i * dt;
    g.horizontal.push_back(0.5 * kGravity * std::sin(2.0 * kPi * t) * std::sin(kPi * t / 2.0));
  }
  return g;
}

SimulationResult run(const GroundMotion& g, Method m, int substeps, double tol = 1e-8) {
  SolverSettings s;
  s.method = m;
  s.model = ModelKind::Linearized;
  s.substeps = substeps;
  s.tol = tol;
  return simulate(Body(kBody), s, g, true);
}

double final_theta(const GroundMotion& g, Method m, int substeps, double tol = 1e-8) {
  return run(g, m, substeps, tol).history.back().theta;
}

// The whole hybrid run (uplift, impact located inside a sample) converges to the exact answer.
TEST(Convergence, HybridRunsConvergeToTheClosedFormThroughImpacts) {
  const GroundMotion g = burst(0.05);
  const SimulationResult exact = run(g, Method::Analytic, 1);
  ASSERT_EQ(exact.outcome.impacts, 1);
  ASSERT_TRUE(exact.outcome.beyond_tipping);
  const double th = exact.history.back().theta;
  // rk4: 16x fewer sub-steps -> 16^4 = 65536x the error; allow a factor 4 of pre-asymptotic slack.
  const double e2 = std::abs(final_theta(g, Method::Rk4, 2) - th);
  const double e32 = std::abs(final_theta(g, Method::Rk4, 32) - th);
  EXPECT_LT(e32, e2 / 16000.0);
  // dopri5: the error stays within a small multiple of the tolerance (theta ~ 0.25 rad here).
  for (double tol : {1e-6, 1e-8, 1e-10, 1e-12}) {
    EXPECT_LT(std::abs(final_theta(g, Method::Dopri5, 1, tol) - th), 10.0 * tol + 1e-13) << tol;
  }
}

// With the input given only at samples (first-order hold), the answer converges at second order
// in the sample interval to the answer for the continuous input.
TEST(Convergence, FirstOrderHoldIsSecondOrderInTheSampleInterval) {
  const double ref = final_theta(burst(0.0005), Method::Analytic, 1);
  const double e1 = std::abs(final_theta(burst(0.02), Method::Analytic, 1) - ref);
  const double e2 = std::abs(final_theta(burst(0.01), Method::Analytic, 1) - ref);
  const double e4 = std::abs(final_theta(burst(0.005), Method::Analytic, 1) - ref);
  EXPECT_NEAR(std::log2(e1 / e2), 2.0, 0.25);
  EXPECT_NEAR(std::log2(e2 / e4), 2.0, 0.25);
}

}  // namespace
}  // namespace rocking_monitor::core
