// Static pre-check of issue 7 (sliding_bound): the friction a scene envelope can demand.
// Oracles: eqs. 22 and 26 of the paper (closed form), the rocking reactions computed by
// RockingModel (independent code: the dynamics, not the bound's term-by-term algebra), the
// integrated angular velocity (energy argument), and ContactModel, the richest model, which must
// never slide, slip or fly when mu_s meets the bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "rocking_monitor/model/adaptive_model.hpp"
#include "rocking_monitor/model/contact_model.hpp"
#include "rocking_monitor/model/rocking_model.hpp"
#include "rocking_monitor/physics/sliding_bound.hpp"

namespace rm = rocking_monitor::core;

namespace {

constexpr double kG = 9.80665;

struct NamedBody {
  const char* name;
  rm::BodyParameters p;
};

std::vector<NamedBody> bodies() {
  auto make = [](double b, double h, double nu) {
    rm::BodyParameters p;
    p.width = b;
    p.cg_height = h;
    p.nu1 = nu;
    return p;
  };
  return {{"cabinet", make(0.6, 0.9, 0.5)},
          {"eccentric shelving", make(0.5, 1.0, 0.3)},
          {"slender vase", make(0.2, 0.4, 0.5)},
          {"eccentric squat box", make(1.2, 0.5, 0.35)}};
}

// Band-limited random input (12 sines, 0.5-8 Hz, random phases), tapered in over 1 s, scaled so
// that max |a| is exactly `peak` (inside the envelope `peak` <= limit).
std::vector<double> random_input(unsigned seed, double peak, double dt, double duration) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double f[12], ph[12], amp[12];
  for (int k = 0; k < 12; ++k) {
    f[k] = 0.5 + 7.5 * u(rng);
    ph[k] = 2.0 * M_PI * u(rng);
    amp[k] = 0.2 + u(rng);
  }
  const auto n = static_cast<std::size_t>(duration / dt) + 1;
  std::vector<double> a(n, 0.0);
  double m = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    const double taper = t < 1.0 ? 0.5 * (1.0 - std::cos(M_PI * t)) : 1.0;
    for (int k = 0; k < 12; ++k) a[i] += taper * amp[k] * std::sin(2.0 * M_PI * f[k] * t + ph[k]);
    m = std::max(m, std::abs(a[i]));
  }
  for (double& v : a) v *= peak / m;
  return a;
}

}  // namespace

TEST(SlidingBound, ReducesToEq22BelowUpliftAndToEq26AtUplift) {
  for (const auto& nb : bodies()) {
    const rm::Body body(nb.p);
    const double tmin = std::min(body.pivot(1).tan_alpha, body.pivot(-1).tan_alpha);
    const double tmax = std::max(body.pivot(1).tan_alpha, body.pivot(-1).tan_alpha);
    // Envelope that cannot uplift either corner: the bound is A_max = H / (g - V) (eq. 22).
    const double v = 0.1 * kG, h_low = 0.8 * tmin * (kG - v);
    const rm::SlidingBound low = rm::sliding_bound(body, {h_low, v});
    EXPECT_FALSE(low.can_rock) << nb.name;
    EXPECT_FALSE(low.flight_possible) << nb.name;
    EXPECT_NEAR(low.rest, h_low / (kG - v), 1e-15) << nb.name;
    EXPECT_NEAR(low.required_mu(), h_low / (kG - v), 1e-15) << nb.name;
    // Envelope that uplifts: at rest |A| stops at 1/gamma = tan(alpha_s) (eq. 26); rocking and
    // the impacts can demand more.
    const double h_high = 1.5 * tmax * (kG - v);
    const rm::SlidingBound high = rm::sliding_bound(body, {h_high, v});
    EXPECT_TRUE(high.can_rock) << nb.name;
    EXPECT_NEAR(high.rest, tmax, 1e-15) << nb.name;
    EXPECT_GE(high.required_mu(), tmax) << nb.name;
    EXPECT_GE(high.required_mu(), high.impact) << nb.name;
    // a_yg may reach -g (eq. 11), or no horizontal limit: nothing is ruled out.
    EXPECT_TRUE(rm::sliding_bound(body, {h_low, kG}).flight_possible) << nb.name;
    EXPECT_TRUE(std::isinf(rm::sliding_bound(body, {h_low, kG}).required_mu())) << nb.name;
    EXPECT_TRUE(std::isinf(rm::sliding_bound(body, {}).required_mu())) << nb.name;
    EXPECT_TRUE(std::isinf(
        rm::sliding_bound(body, {std::numeric_limits<double>::infinity(), v}).required_mu()));
    // Monotone in the envelope.
    EXPECT_LE(rm::sliding_bound(body, {0.9 * h_high, v}).required_mu(), high.required_mu());
  }
}

TEST(SlidingBound, Eq22AndEq26DecideTheContactModelExactly) {
  // The richest model, constant / ramped input: mu_s just above the bound never slides, just
  // below it slides (the bound is the exact threshold where the paper gives one).
  for (const auto& nb : bodies()) {
    const rm::Body body(nb.p);
    const double tmin = std::min(body.pivot(1).tan_alpha, body.pivot(-1).tan_alpha);
    const double v = 0.1 * kG, h = 0.8 * tmin * (kG - v);
    const double mu_rest = rm::sliding_bound(body, {h, v}).required_mu();
    for (double factor : {1.001, 0.999}) {
      rm::BodyParameters p = nb.p;
      p.mu_s = factor * mu_rest;
      rm::ContactModel c(p);
      c.reset(0.0);
      for (int i = 1; i <= 400; ++i) c.step(std::min(1.0, i / 200.0) * h, -v, 0.005);
      EXPECT_EQ(c.outcome().slip_episodes > 0, factor < 1.0) << nb.name << " x" << factor;
    }
    // Uplift ramp on the side of the smaller tan(alpha), slow enough that |A| moves by 1e-5 per
    // sample: at uplift the friction demand is 1/gamma of that corner (eq. 26). With mu_s 2 % above
    // it the pivot sticks as rocking starts (the ramp stops at uplift); 2 % below it, it slips.
    const int side = body.pivot(1).tan_alpha <= body.pivot(-1).tan_alpha ? 1 : -1;
    for (double factor : {1.02, 0.98}) {
      rm::BodyParameters p = nb.p;
      p.mu_s = factor * tmin;
      rm::ContactModel c(p);
      c.reset(0.0);
      double a = 0.0;
      for (int i = 1; i <= 200000 && std::isnan(c.outcome().first_uplift_time) &&
                      c.outcome().slip_episodes == 0;
           ++i) {
        a = std::min(1.1 * tmin * kG, a + 1e-5 * kG);
        c.step(side * a, 0.0, 0.005);
      }
      const bool uplifted = !std::isnan(c.outcome().first_uplift_time);
      if (factor > 1.0) {
        EXPECT_TRUE(uplifted) << nb.name;
        EXPECT_EQ(c.outcome().slip_episodes, 0) << nb.name;
        EXPECT_NEAR(a / kG, tmin, 2e-5) << nb.name;  // eq. 19
      } else {
        EXPECT_GT(c.outcome().slip_episodes, 0) << nb.name;
      }
    }
  }
}

TEST(SlidingBound, RockingReactionsNeverExceedTheBound) {
  // Grid over rotation, angular velocity and the envelope; reactions from RockingModel.
  double worst_tightness = 1.0;
  for (const auto& nb : bodies()) {
    const rm::Body body(nb.p);
    for (double hg : {0.3, 0.5, 0.8}) {
      const double h = hg * kG, v = 0.15 * kG;
      const rm::SlidingBound b = rm::sliding_bound(body, {h, v});
      if (!b.can_rock || b.flight_possible) continue;
      double worst = 0.0;
      for (int side : {1, -1}) {
        const rm::Pivot& pv = body.pivot(side);
        const double wmax = b.omega_max[side > 0 ? 0 : 1];
        rm::RockingModel m(body, rm::SolverSettings{});
        for (int i = 0; i <= 20; ++i) {
          const double theta = side * (1e-6 + (pv.alpha - 2e-6) * i / 20.0);
          for (int j = -10; j <= 10; ++j) {
            for (int k = -4; k <= 4; ++k) {
              for (int l = -2; l <= 2; ++l) {
                m.reset(0.0, h * k / 4.0, v * l / 2.0);
                m.set_state(theta, wmax * j / 10.0);
                ASSERT_EQ(m.side(), side);
                const rm::ContactReaction r = m.reaction();
                ASSERT_GT(r.ry, 0.0) << nb.name;
                const double ratio = std::abs(r.rx) / r.ry;
                ASSERT_LE(ratio, b.rocking * (1.0 + 1e-12)) << nb.name << " theta " << theta;
                worst = std::max(worst, ratio);
              }
            }
          }
        }
      }
      worst_tightness = std::min(worst_tightness, worst / b.rocking);
      // Conservative, but not vacuous: the grid reaches a good part of the bound.
      EXPECT_GT(worst / b.rocking, 0.9) << nb.name << " " << hg << " g";
    }
  }
  std::printf("[ measured ] grid max |R_x|/R_y over the bound: >= %.3f\n", worst_tightness);
}

TEST(SlidingBound, AngularVelocityStaysBelowTheEnergyBound) {
  // Integrated rocking (RockingModel, dopri5) under random inputs that fill the envelope; the
  // energy argument bounds |omega| while |theta| < alpha.
  double tight = 0.0;
  int rocked = 0;
  for (const auto& nb : bodies()) {
    const rm::Body body(nb.p);
    const double tmax = std::max(body.pivot(1).tan_alpha, body.pivot(-1).tan_alpha);
    for (double scale : {1.2, 2.0, 3.0}) {
      const double h = scale * tmax * kG * 0.85, v = 0.15 * kG;
      const rm::SlidingBound b = rm::sliding_bound(body, {h, v});
      for (unsigned seed = 1; seed <= 4; ++seed) {
        const auto ax = random_input(seed, h, 0.005, 20.0);
        const auto ay = random_input(seed + 100, v, 0.005, 20.0);
        rm::RockingModel m(body, rm::SolverSettings{});
        m.reset(0.0, ax[0], ay[0]);
        for (std::size_t i = 1; i < ax.size(); ++i) {
          m.step(ax[i], ay[i], 0.005);
          if (m.outcome().beyond_tipping || m.mode() == rm::Mode::Overturned) break;
          if (m.mode() == rm::Mode::Rocking) {
            const double w = b.omega_max[m.side() > 0 ? 0 : 1];
            ASSERT_LE(std::abs(m.omega()), w) << nb.name << " seed " << seed << " t " << m.time();
            tight = std::max(tight, std::abs(m.omega()) / w);
          }
        }
        rocked += std::isnan(m.outcome().uplift_time) ? 0 : 1;
      }
    }
  }
  EXPECT_GT(rocked, 20);
  std::printf("[ measured ] %d runs rocked; max |omega| / omega_max = %.3f\n", rocked, tight);
}

TEST(SlidingBound, ContactModelNeverSlidesSlipsOrFliesWhenMuMeetsTheBound) {
  int runs = 0, rocked = 0;
  for (const auto& nb : bodies()) {
    const rm::Body body0(nb.p);
    const double tmax = std::max(body0.pivot(1).tan_alpha, body0.pivot(-1).tan_alpha);
    for (double scale : {0.7, 1.2, 2.0}) {
      const double h = scale * tmax * kG * 0.85, v = 0.15 * kG;
      rm::BodyParameters p = nb.p;
      p.mu_s = rm::sliding_bound(body0, {h, v}).required_mu();
      if (std::isinf(p.mu_s)) continue;  // the envelope allows lift-off: nothing to test
      for (unsigned seed = 1; seed <= 3; ++seed) {
        const auto ax = random_input(seed, h, 0.005, 20.0);
        const auto ay = random_input(seed + 100, v, 0.005, 20.0);
        rm::ContactModel c(p);
        c.reset(0.0, ax[0], ay[0]);
        for (std::size_t i = 1; i < ax.size(); ++i) {
          c.step(ax[i], ay[i], 0.005);
          if (c.outcome().max_rotation_ratio > 1.0) break;  // the guarantee ends at alpha
          ASSERT_EQ(c.outcome().slip_episodes, 0) << nb.name << " x" << scale << " t " << c.time();
          ASSERT_EQ(c.outcome().flight_episodes, 0) << nb.name << " x" << scale;
        }
        ++runs;
        rocked += std::isnan(c.outcome().first_uplift_time) ? 0 : 1;
      }
    }
  }
  EXPECT_GT(runs, 20);
  EXPECT_GT(rocked, 15);
  std::printf("[ measured ] %d ContactModel runs (%d rocked) at mu_s = bound: no slip, no flight\n",
              runs, rocked);
}

TEST(SlidingBound, AdaptiveModelUnderTheGuaranteeNeverRunsTheContactModel) {
  rm::BodyParameters p = bodies()[2].p;  // slender vase
  const rm::Body body0(p);
  const double h = 0.3 * kG, v = 0.1 * kG;
  p.mu_s = 1.05 * rm::sliding_bound(body0, {h, v}).required_mu();
  const auto ax = random_input(7, 0.999 * h, 0.005, 20.0);  // inside the envelope
  const auto ay = random_input(107, 0.999 * v, 0.005, 20.0);
  auto run = [&](rm::Fidelity f, rm::SceneEnvelope scene, double spike_at) {
    rm::AdaptiveSettings s;
    s.fidelity = f;
    s.scene = scene;
    rm::AdaptiveModel m(p, s);
    m.reset(0.0, ax[0], ay[0]);
    for (std::size_t i = 1; i < ax.size(); ++i) {
      const double t = 0.005 * static_cast<double>(i);
      m.step(std::abs(t - spike_at) < 1e-9 ? 1.5 * h : ax[i], ay[i], 0.005);
    }
    return m;
  };
  const rm::AdaptiveModel guarded = run(rm::Fidelity::Adaptive, {h, v}, -1.0);
  const rm::AdaptiveModel contact = run(rm::Fidelity::Contact, {h, v}, -1.0);
  EXPECT_EQ(guarded.initial_reason(), rm::SwitchReason::SceneRulesOutContact);
  EXPECT_TRUE(guarded.outcome().sliding_ruled_out);
  EXPECT_FALSE(std::isnan(guarded.outcome().uplift_time));  // it did rock
  EXPECT_EQ(guarded.outcome().samples_contact_model, 0);
  EXPECT_EQ(guarded.outcome().model_switches, 0);
  EXPECT_EQ(guarded.outcome().samples_outside_scene, 0);
  EXPECT_EQ(contact.outcome().slip_episodes, 0);
  EXPECT_EQ(guarded.outcome().beyond_tipping, contact.outcome().beyond_tipping);
  EXPECT_EQ(guarded.outcome().overturned, contact.outcome().overturned);
  // Impact counts differ by the integrators' handling of the Zeno tail before rest capture.
  EXPECT_NEAR(guarded.outcome().impacts, contact.outcome().impacts, 3);
  EXPECT_NEAR(guarded.outcome().max_rotation_ratio, contact.outcome().max_rotation_ratio, 1e-4);
  std::printf("[ measured ] vase mu_s %.3f, scene %.1f/%.1f m/s^2: %ld impacts, max theta/alpha %.4f "
              "(contact %.4f), contact samples 0\n",
              p.mu_s, h, v, guarded.outcome().impacts, guarded.outcome().max_rotation_ratio,
              contact.outcome().max_rotation_ratio);

  // A sample outside the envelope ends the guarantee (counted, timed); the item keeps running.
  const rm::AdaptiveModel spiked = run(rm::Fidelity::Adaptive, {h, v}, 5.0);
  EXPECT_EQ(spiked.outcome().samples_outside_scene, 1);
  EXPECT_NEAR(spiked.outcome().scene_exceeded_time, 5.0, 1e-9);

  // Unknown scene: the same item starts as "pure rocking valid" and the margins apply.
  const rm::AdaptiveModel unknown = run(rm::Fidelity::Adaptive, {}, -1.0);
  EXPECT_EQ(unknown.initial_reason(), rm::SwitchReason::PureRockingValid);
  EXPECT_FALSE(unknown.outcome().sliding_ruled_out);

  rm::AdaptiveSettings bad;
  bad.scene.horizontal = -1.0;
  EXPECT_THROW(rm::AdaptiveModel(p, bad), std::invalid_argument);
  bad.scene.horizontal = NAN;
  EXPECT_THROW(rm::AdaptiveModel(p, bad), std::invalid_argument);
}
