// Contact criteria (eqs. 11-26) against the rocking dynamics, and the screening criteria (eqs. 1-2).
#include <gtest/gtest.h>

#include <cmath>

#include "rocking_monitor/physics/criteria.hpp"
#include "rocking_monitor/monitoring/simulation.hpp"
#include "test_helpers.hpp"

namespace rocking_monitor::core {
namespace {

using testing::deg;

// Eq. 25 (paper's algebra) equals |R_x|/R_y from the rocking dynamics at the onset of rocking
// (theta = 0, omega = 0, theta'' from the equation of motion), for both pivots, with vertical shaking.
TEST(ContactCriteria, Eq25MatchesTheReactionOfTheDynamicsAtOnset) {
  BodyParameters p;
  p.width = 0.7;
  p.cg_height = 0.95;
  p.nu1 = 0.3;
  p.radius_of_gyration = 0.45;
  const Body b(p);
  for (int side : {1, -1}) {
    const Pivot& pv = b.pivot(side);
    for (double ay : {0.0, 0.25 * kGravity, -0.3 * kGravity}) {
      for (double factor : {1.0, 1.3, 2.0, 4.0}) {
        const double abs_a = factor * pv.tan_alpha;
        const double ax = side * abs_a * (ay + kGravity);
        GroundInput in;
        in.ax0 = ax;
        in.ay0 = ay;
        const RockingOde ode{&pv, side, ModelKind::Nonlinear, in};
        const double acc = ode.angular_acceleration(0.0, 0.0);
        const ContactReaction r = rocking_reaction(pv, side, 0.0, 0.0, acc, ax, ay);
        EXPECT_NEAR(rock_without_slip_friction(b, pv, abs_a), std::abs(r.rx) / r.ry, 1e-12)
            << "side " << side << " ay " << ay << " factor " << factor;
      }
      // At the uplift threshold eq. 25 reduces to eq. 26: mu >= 1/gamma.
      EXPECT_NEAR(rock_without_slip_friction(b, pv, pv.tan_alpha), 1.0 / pv.gamma, 1e-14);
    }
  }
}

// For a symmetric homogeneous block eq. 24 reduces to Shenton's eq. 23.
TEST(ContactCriteria, Eq24ReducesToShentonsEq23ForASymmetricBlock) {
  BodyParameters p;
  p.width = 0.5;
  p.cg_height = 0.8;
  const Body b(p);
  const double gamma = 2.0 * 0.8 / 0.5;
  for (double mu : {0.4, 0.6, 0.9}) {
    const double a23 = ((4 * gamma * gamma + 1) * mu - 3 * gamma) / ((gamma * gamma + 4) - 3 * gamma * mu);
    if (a23 <= 0.0) continue;
    EXPECT_NEAR(rock_without_slip_friction(b, b.pivot(1), a23), mu, 1e-12) << mu;
  }
}

TEST(ContactCriteria, RestConditions) {
  BodyParameters p;
  p.width = 0.5;
  p.cg_height = 1.0;
  p.mu_s = 0.2;
  const Body b(p);
  EXPECT_FALSE(free_flight(-kGravity));      // eq. 11 holds with equality
  EXPECT_TRUE(free_flight(-kGravity * 1.01));
  EXPECT_FALSE(slides_from_rest(b, 0.2 * kGravity * 0.999, 0.0));  // eq. 22
  EXPECT_TRUE(slides_from_rest(b, -0.2 * kGravity * 1.001, 0.0));
  EXPECT_TRUE(slides_from_rest(b, 0.2 * 0.5 * kGravity * 1.001, -0.5 * kGravity));
  EXPECT_EQ(tipping_side(0.0), 1);  // eq. 12 uses a_xg >= 0
  EXPECT_EQ(tipping_side(-1e-12), -1);
}

// The model records violations (time and criterion) and keeps going.
TEST(ContactCriteria, ModelRecordsViolationsAndKeepsRocking) {
  BodyParameters p;
  p.width = 0.6;
  p.cg_height = 0.8;
  p.mu_s = 0.3;  // below 1/gamma = 0.375: slides before it can rock (eq. 26)
  GroundMotion g;
  g.dt = 0.01;
  for (int i = 0; i < 400; ++i) {
    const double t = i * g.dt;
    g.horizontal.push_back(0.45 * kGravity * std::sin(2 * kPi * 1.0 * t));
    g.vertical.push_back(t > 3.0 && t < 3.2 ? -1.2 * kGravity : 0.0);
  }
  const SimulationResult r = simulate(Body(p), SolverSettings{}, g);
  bool slide_rest = false, slide_uplift = false, flight = false;
  double first_slide = -1, first_flight = -1;
  for (const Violation& v : r.violations) {
    if (v.criterion == Criterion::SlideFromRest && !slide_rest) { slide_rest = true; first_slide = v.time; }
    if (v.criterion == Criterion::SlideAtUplift) slide_uplift = true;
    if (v.criterion == Criterion::FreeFlight && !flight) { flight = true; first_flight = v.time; }
  }
  EXPECT_TRUE(slide_rest);
  EXPECT_TRUE(slide_uplift);
  EXPECT_TRUE(flight);
  // |a| first exceeds 0.3 g at t = asin(0.3/0.45) / (2 pi) = 0.116 s: reported at the next sample.
  EXPECT_NEAR(first_slide, 0.12, 1e-9);
  // The vertical pulse (-1.2 g after t = 3 s) lifts the body off at the first sample after 3 s.
  EXPECT_NEAR(first_flight, 3.01, 1e-9);
  EXPECT_GT(r.outcome.impacts, 0);  // the rocking model kept running
}

TEST(ContactCriteria, SlideWhileRockingUsesTheCentripetalTerms) {
  // Rocking fast about corner 1 at theta = 0.5 alpha without excitation: R_x comes from the
  // angular acceleration and the centripetal term; check against a finite-difference of the CoM path.
  const Body b(testing::rectangle_with(3.0, deg(15)));
  const Pivot& pv = b.pivot(1);
  const double th = 0.5 * pv.alpha, om = -0.7;
  GroundInput in;
  const RockingOde ode{&pv, 1, ModelKind::Nonlinear, in};
  const double acc = ode.angular_acceleration(0.0, th);
  const ContactReaction r = rocking_reaction(pv, 1, th, om, acc, 0.0, 0.0);
  auto pos = [&](double dt, double& x, double& y) {
    const double t2 = th + om * dt + 0.5 * acc * dt * dt;  // exact to O(dt^3) for the 2nd difference
    x = pv.radius * std::sin(pv.alpha - t2);
    y = pv.radius * std::cos(pv.alpha - t2);
  };
  const double h = 1e-4;
  double xm, ym, x0, y0, xp, yp;
  pos(-h, xm, ym);
  pos(0, x0, y0);
  pos(h, xp, yp);
  EXPECT_NEAR(r.rx, (xp - 2 * x0 + xm) / (h * h), 1e-5);
  EXPECT_NEAR(r.ry, kGravity + (yp - 2 * y0 + ym) / (h * h), 1e-5);
  EXPECT_TRUE(slides_while_rocking(r, 0.9 * std::abs(r.rx) / r.ry));
  EXPECT_FALSE(slides_while_rocking(r, 1.1 * std::abs(r.rx) / r.ry));
}

TEST(ScreeningCriteria, HousnerAndIshiyamaVariants) {
  // Housner's S_v for a slender block is close to its small-angle form alpha sqrt(4 g R / 3)... check
  // the exact relation S_v^2 cos^2(alpha) = (8/3) g r (1 - cos alpha) and the slender limit.
  const double alpha = 0.05, r = 1.3;
  const double sv = housner_pseudo_velocity(alpha, r);
  EXPECT_NEAR(sv * sv * std::cos(alpha) * std::cos(alpha), 8.0 / 3.0 * kGravity * r * (1 - std::cos(alpha)), 1e-12);
  EXPECT_NEAR(sv, alpha * std::sqrt(4.0 / 3.0 * kGravity * r), 2e-3 * sv);

  BodyParameters p;
  p.width = 0.6;
  p.cg_height = 1.0;
  p.nu1 = 0.3;
  const Body b(p);
  const ScreeningThresholds t = screening_thresholds(b);
  // Ishiyama (symmetric): a >= (B / 2h) g; velocity 0.4 S_v(alpha = atan(B/2h), r = sqrt(B^2+4h^2)/2).
  EXPECT_NEAR(t.ishiyama.acceleration, 0.3 * kGravity, 1e-12);
  EXPECT_NEAR(t.ishiyama.velocity, 0.4 * housner_pseudo_velocity(std::atan(0.3), 0.5 * std::hypot(0.6, 2.0)), 1e-12);
  // B' = 2 nu_min B: the acceleration threshold is the uplift threshold of the weak corner (eq. 19).
  EXPECT_NEAR(t.ishiyama_equivalent.acceleration, kGravity * b.pivot(1).tan_alpha, 1e-12);
  EXPECT_NEAR(t.ishiyama_equivalent.velocity,
              0.4 * housner_pseudo_velocity(b.pivot(1).alpha, b.pivot(1).radius), 1e-12);
  // The paper's proposal halves the velocity coefficient and keeps the symmetric geometry.
  EXPECT_NEAR(t.proposed.velocity, 0.5 * t.ishiyama.velocity, 1e-14);
  EXPECT_NEAR(t.proposed.acceleration, t.ishiyama.acceleration, 1e-14);
  // Predictions need both conditions.
  const ScreeningPrediction none = screening_prediction(t, 10.0, 0.0, 0.0);
  EXPECT_FALSE(none.ishiyama);
  const ScreeningPrediction both = screening_prediction(t, 10.0, 10.0, 10.0);
  EXPECT_TRUE(both.ishiyama && both.ishiyama_equivalent && both.proposed && both.housner);
  const ScreeningPrediction mid = screening_prediction(t, 0.32 * kGravity, 0.9 * t.ishiyama.velocity, 0.0);
  EXPECT_FALSE(mid.ishiyama);
  EXPECT_TRUE(mid.proposed);
}

}  // namespace
}  // namespace rocking_monitor::core
