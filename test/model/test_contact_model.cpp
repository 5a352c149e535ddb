// ContactModel (issue 7): sliding, stick-slip, transitions from rest, lift-off, agreement with the
// pure-rocking model, energy, bounded work. Oracles are closed forms or independent integrations.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "rocking_monitor/model/contact_model.hpp"
#include "rocking_monitor/physics/criteria.hpp"
#include "rocking_monitor/model/rocking_model.hpp"
#include "test_helpers.hpp"

namespace rocking_monitor::core {
namespace {

constexpr double g = kGravity;

// Squat block: tan(alpha) = nu B / h = 5, far above any friction used: it can never tip.
BodyParameters squat(double mu_s, double mu_k) {
  BodyParameters b;
  b.width = 2.0;
  b.cg_height = 0.2;
  b.mu_s = mu_s;
  b.mu_k = mu_k;
  return b;
}

// Slender block: tan(alpha) = 0.2 / 0.5 = 0.4.
BodyParameters slender(double mu_s, double mu_k) {
  BodyParameters b;
  b.width = 0.4;
  b.cg_height = 0.5;
  b.mu_s = mu_s;
  b.mu_k = mu_k;
  return b;
}

TEST(ContactModel, SlidingBlockUnderConstantAccelerationMatchesClosedForm) {
  const double mu_s = 0.3, mu_k = 0.2, a = 0.5 * g, dt = 0.01;
  ContactModel m(squat(mu_s, mu_k));
  m.reset(0.0, a, 0.0);  // |A| = 0.5 > mu_s: slides from t = 0
  double max_err = 0.0;
  for (int k = 1; k <= 200; ++k) {
    const ContactReport& r = m.step(a, 0.0, dt);
    const double t = k * dt;
    // Relative to the ground the block moves backwards (u < 0 for a > 0).
    const double u_exact = -(a - mu_k * g) * t * t / 2.0;
    const double v_exact = -(a - mu_k * g) * t;
    ASSERT_EQ(r.mode, ContactMode::Slide);
    max_err = std::max({max_err, std::abs(r.slip - u_exact), std::abs(r.slip_velocity - v_exact)});
    EXPECT_DOUBLE_EQ(r.theta, 0.0);
  }
  EXPECT_LT(max_err, 1e-9);  // RK4 is exact for this quadratic; measured ~1e-13
  EXPECT_EQ(m.outcome().slip_episodes, 1);
}

TEST(ContactModel, SlideStartsExactlyWhenAbsAReachesMuS) {
  const double mu_s = 0.3, mu_k = 0.25, rate = 2.0, dt = 0.005;  // a = rate * t (m/s^3)
  for (int sign : {1, -1}) {
    ContactModel m(squat(mu_s, mu_k));
    m.reset(0.0, 0.0, 0.0);
    const double t_star = mu_s * g / rate;  // |A| = mu_s, eq. 22
    for (int k = 1; k <= 400; ++k) {
      const double t = k * dt;
      const ContactReport& r = m.step(sign * rate * t, 0.0, dt);
      if (t < t_star) {
        EXPECT_EQ(r.mode, ContactMode::Rest);
        EXPECT_EQ(r.slip, 0.0);
      }
    }
    EXPECT_NEAR(m.outcome().first_slip_time, t_star, 1e-12);
    EXPECT_EQ(m.mode(), ContactMode::Slide);
    EXPECT_EQ(sign * m.slip() < 0.0, true);
    // After onset: u'' = -(a - mu_k g sgn a), a = rate t: u = -[rate (t^3 - t*^3)/6 - ...].
    const double t = 400 * dt, s = t - t_star;
    const double u_exact = -sign * (rate * s * s * s / 6.0 + (rate * t_star - mu_k * g) * s * s / 2.0);
    EXPECT_NEAR(m.slip(), u_exact, 1e-9);
  }
}

// Independent 1-DOF stick-slip integration (block on a base with a_g = A sin(W t)), fine explicit
// steps with the stick/slip switch done at step level: reference for the piecewise solution.
struct StickSlipRef {
  std::vector<double> u;  // at sample times
  std::vector<int> stuck; // 1 if stuck at the sample
};
StickSlipRef brute_force(double A, double W, double mu_s, double mu_k, double dt, int n, int sub) {
  StickSlipRef r;
  double u = 0.0, v = 0.0;
  bool stuck = true;
  const double h = dt / sub;
  r.u.push_back(0.0);
  r.stuck.push_back(1);
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < sub; ++j) {
      const double t = k * dt + j * h;
      // Same first-order hold between samples as the model sees.
      auto a_at = [&](double tt) {
        const double a0 = A * std::sin(W * k * dt), a1 = A * std::sin(W * (k + 1) * dt);
        return a0 + (a1 - a0) * (tt - k * dt) / dt;
      };
      const double a_mid = a_at(t + 0.5 * h);
      if (stuck) {
        if (std::abs(a_mid) > mu_s * g) {
          stuck = false;
          const double acc = -a_mid + (a_mid > 0 ? 1 : -1) * mu_k * g;
          v += acc * h;
          u += 0.5 * acc * h * h;
        }
        continue;
      }
      const int sv = v > 0 ? 1 : -1;
      const double acc = -a_mid - sv * mu_k * g;
      const double v_new = v + acc * h;
      if ((v_new > 0) != (v > 0)) {  // velocity crosses zero inside the step
        const double hz = -v / acc;
        u += v * hz + 0.5 * acc * hz * hz;
        v = 0.0;
        const double a_z = a_at(t + hz);
        if (std::abs(a_z) <= mu_s * g) {
          stuck = true;
        } else {
          const double acc2 = -a_z + (a_z > 0 ? 1 : -1) * mu_k * g;
          v = acc2 * (h - hz);
          u += 0.5 * acc2 * (h - hz) * (h - hz);
        }
      } else {
        u += v * h + 0.5 * acc * h * h;
        v = v_new;
      }
    }
    r.u.push_back(u);
    r.stuck.push_back(stuck ? 1 : 0);
  }
  return r;
}

TEST(ContactModel, StickSlipUnderHarmonicInputMatchesIndependentIntegration) {
  const double mu_s = 0.3, mu_k = 0.2, A = 0.35 * g, W = 2.0 * kPi * 1.0, dt = 0.005;
  const int n = 600;  // 3 cycles
  const StickSlipRef ref = brute_force(A, W, mu_s, mu_k, dt, n, 4000);
  ContactModel m(squat(mu_s, mu_k));
  m.reset(0.0, 0.0, 0.0);
  double max_err = 0.0, u_scale = 0.0;
  int stick_mismatch = 0;
  for (int k = 1; k <= n; ++k) {
    const ContactReport& r = m.step(A * std::sin(W * k * dt), 0.0, dt);
    max_err = std::max(max_err, std::abs(r.slip - ref.u[k]));
    u_scale = std::max(u_scale, std::abs(ref.u[k]));
    if ((r.mode == ContactMode::Rest) != (ref.stuck[k] == 1)) ++stick_mismatch;
  }
  // Total slip over the last cycle (steady drift per cycle is zero by symmetry; the excursion is
  // what we compare) and the stick pattern.
  EXPECT_GT(u_scale, 0.01);
  EXPECT_LT(max_err, 1e-5 * std::max(1.0, u_scale));
  EXPECT_LE(stick_mismatch, 2);  // samples within a step of a stick/slip switch may differ
  EXPECT_GE(m.outcome().slip_episodes, 5);  // two slip episodes per cycle
  EXPECT_LE(m.outcome().slip_episodes, 6);
}

TEST(ContactModel, RestToRockExactlyAtEq19SameAsRockingModel) {
  const double rate = 1.5, dt = 0.005;
  const BodyParameters b = slender(1.0, 0.8);  // mu_s >= tan(alpha) = 0.4: rocks first
  ContactModel m(b);
  SolverSettings st;
  st.tol = 1e-10;
  RockingModel rm(b, st);
  m.reset(0.0);
  rm.reset(0.0);
  for (int k = 1; k <= 600 && m.mode() != ContactMode::Rock; ++k) {
    m.step(rate * k * dt, 0.0, dt);
    rm.step(rate * k * dt, 0.0, dt);
  }
  const double t_star = 0.4 * g / rate;  // |A| = 1/gamma = tan(alpha)
  EXPECT_EQ(m.mode(), ContactMode::Rock);
  EXPECT_NEAR(m.outcome().first_uplift_time, t_star, 1e-12);
  EXPECT_NEAR(m.outcome().first_uplift_time, rm.outcome().uplift_time, 1e-12);
  EXPECT_EQ(m.outcome().slip_episodes, 0);
}

TEST(ContactModel, RestToSlideWhenMuBelowTanAlpha) {
  const double rate = 1.5, dt = 0.005;
  ContactModel m(slender(0.3, 0.3));  // mu_s < tan(alpha) = 0.4: slides at |A| = mu_s first
  m.reset(0.0);
  for (int k = 1; k <= 500; ++k) m.step(rate * k * dt, 0.0, dt);
  EXPECT_NEAR(m.outcome().first_slip_time, 0.3 * g / rate, 1e-12);
  EXPECT_TRUE(std::isnan(m.outcome().first_uplift_time));  // a sliding block (mu_k < tan a) never tips
  EXPECT_EQ(m.mode(), ContactMode::Slide);
}

// Shenton's regimes for a sudden |A| > tan(alpha) (here the input at reset): pure rocking needs
// mu_s >= eq. 25 (which equals 1/gamma = tan(alpha) only at the threshold, eq. 26, and lies in
// (tan alpha, |A|) above it); pure sliding needs mu_k <= tan(alpha) (else the sliding block tips);
// with tan(alpha) < mu < eq. 25 neither holds: slide-rock.
TEST(ContactModel, SuddenInputSelectsRockSlideOrSlideRockAsEq25Says) {
  const double A = 0.8;  // > tan(alpha) = 0.4
  const Body probe(slender(1.0, 1.0));
  const double bound = rock_without_slip_friction(probe, probe.pivot(1), A);
  ASSERT_GT(bound, 0.4);
  ASSERT_LT(bound, A);
  auto first_mode = [&](double mu) {
    ContactModel m(slender(mu, mu));
    m.reset(0.0, A * g, 0.0);
    m.step(A * g, 0.0, 1e-4);
    return m;
  };
  {
    const ContactModel m = first_mode(0.5 * (0.4 + bound));
    EXPECT_EQ(m.outcome().slip_episodes, 1);
    EXPECT_EQ(m.outcome().first_uplift_time, 0.0);
    EXPECT_EQ(m.mode(), ContactMode::SlideRock);
  }
  {
    const ContactModel m = first_mode(bound * 1.02);
    EXPECT_EQ(m.mode(), ContactMode::Rock);
    EXPECT_EQ(m.outcome().slip_episodes, 0);
  }
  {
    const ContactModel m = first_mode(0.35);
    EXPECT_EQ(m.mode(), ContactMode::Slide);
  }
}

TEST(ContactModel, LiftOffExactlyWhenVerticalAccelerationReachesMinusG) {
  const double dt = 0.01;
  ContactModel m(slender(0.5, 0.4));
  m.reset(0.0);
  // a_yg = -2 g t: R_y = g + a_yg < 0 for t > 0.5 s.
  for (int k = 1; k <= 60; ++k) m.step(0.0, -2.0 * g * k * dt, dt);
  EXPECT_NEAR(m.outcome().first_flight_time, 0.5, 1e-12);
  EXPECT_EQ(m.mode(), ContactMode::Flight);
  // Ballistic relative to the ground: y - h = (g/3)(t - 0.5)^3 for a_yg = -2 g t.
  const double s = 0.6 - 0.5;
  EXPECT_NEAR(m.cg_height() - 0.5, g / 3.0 * s * s * s, 1e-12);
  // Exactly -g: R_y = 0, no flight (eq. 11 holds with equality), and no work loop.
  ContactModel e(slender(0.5, 0.4));
  e.reset(0.0, 0.0, -g);
  for (int k = 0; k < 100; ++k) {
    const ContactReport& r = e.step(0.0, -g, dt);
    EXPECT_EQ(r.mode, ContactMode::Rest);
  }
}

TEST(ContactModel, FlightLandsAndComesBackToRest) {
  const double dt = 0.005;
  ContactModel m(slender(0.6, 0.5));
  m.reset(0.0);
  std::vector<double> ay;
  for (int k = 1; k <= 400; ++k) {
    const double t = k * dt;
    const double a = t < 0.2 ? -1.6 * g * std::sin(kPi * t / 0.2) : 0.0;
    m.step(0.0, a, dt);
  }
  EXPECT_EQ(m.outcome().flight_episodes, 1);
  EXPECT_GE(m.outcome().impacts, 1);
  EXPECT_EQ(m.mode(), ContactMode::Rest);
  EXPECT_NEAR(m.cg_height(), 0.5, 1e-12);
}

TEST(ContactModel, HighFrictionGivesTheRockingModelThetaHistory) {
  const double alpha = 0.25, p = 2.0, dt = 0.005;
  for (double mu : {std::numeric_limits<double>::infinity(), 100.0}) {
    BodyParameters b = testing::rectangle_with(p, alpha);
    b.mu_s = mu;
    ContactSettings cs;
    cs.substeps = 32;
    ContactModel m(b, cs);
    SolverSettings st;
    st.tol = 1e-11;
    RockingModel rm(b, st);
    const GroundMotion gm = testing::one_sine_pulse(1.2 * alpha * g, 2.0 * p, dt, 6.0);
    m.reset(0.0, gm.horizontal[0], 0.0);
    rm.reset(0.0, gm.horizontal[0], 0.0);
    double max_diff = 0.0;
    for (std::size_t k = 1; k < gm.horizontal.size(); ++k) {
      m.step(gm.horizontal[k], 0.0, dt);
      rm.step(gm.horizontal[k], 0.0, dt);
      max_diff = std::max(max_diff, std::abs(m.theta() - rm.theta()));
    }
    EXPECT_GT(rm.outcome().impacts, 2);
    EXPECT_EQ(m.outcome().impacts, rm.outcome().impacts);
    EXPECT_EQ(m.outcome().slip_episodes, 0);
    EXPECT_LT(max_diff, 1e-7 * alpha) << "mu " << mu;
    RecordProperty("theta_max_diff_rad", std::to_string(max_diff));
  }
}

// Exact state transfer: ContactModel placed with set_state() in the RockingModel's state at some
// sample (pure ROCK, pivot sticking, given slip offset) and stepped with infinite (and very high)
// friction follows the RockingModel from there, to the tolerance of the test above.
TEST(ContactModel, SetIntoRockingStateFollowsRockingModel) {
  const double alpha = 0.25, p = 2.0, dt = 0.005, offset = 0.123;
  for (double mu : {std::numeric_limits<double>::infinity(), 100.0}) {
    BodyParameters b = testing::rectangle_with(p, alpha);
    b.mu_s = mu;
    ContactSettings cs;
    cs.substeps = 32;
    SolverSettings st;
    st.tol = 1e-11;
    const GroundMotion gm = testing::one_sine_pulse(1.2 * alpha * g, 2.0 * p, dt, 6.0);
    // Reference run, to pick transfer samples while rocking (early, after the first impact, late).
    RockingModel probe(b, st);
    probe.reset(0.0, gm.horizontal[0], 0.0);
    std::vector<std::size_t> starts;
    long impacts_seen = 0;
    for (std::size_t k = 1; k < gm.horizontal.size(); ++k) {
      probe.step(gm.horizontal[k], 0.0, dt);
      if (probe.mode() != Mode::Rocking) continue;
      if (starts.empty() || (probe.outcome().impacts > impacts_seen && starts.size() < 3)) {
        starts.push_back(k);
        impacts_seen = probe.outcome().impacts;
      }
    }
    ASSERT_EQ(starts.size(), 3u);
    for (std::size_t k0 : starts) {
      RockingModel rm(b, st);
      rm.reset(0.0, gm.horizontal[0], 0.0);
      for (std::size_t k = 1; k <= k0; ++k) rm.step(gm.horizontal[k], 0.0, dt);
      ASSERT_EQ(rm.mode(), Mode::Rocking);
      ContactModel m(b, cs);
      ContactOutcome kept;
      kept.impacts = 7;
      kept.samples = 11;
      m.set_state(rm.time(), rm.last_ax(), rm.last_ay(), rm.side(), rm.theta(), rm.omega(), offset,
                  kept);
      EXPECT_EQ(m.mode(), ContactMode::Rock);
      EXPECT_EQ(m.side(), rm.side());
      EXPECT_EQ(m.theta(), rm.theta());
      EXPECT_EQ(m.omega(), rm.omega());
      EXPECT_EQ(m.time(), rm.time());
      EXPECT_NEAR(m.slip(), offset, 1e-15);
      EXPECT_NEAR(m.slip_velocity(), 0.0, 1e-15);
      EXPECT_EQ(m.outcome().impacts, 7);
      EXPECT_EQ(m.outcome().samples, 11);
      const long rm_impacts0 = rm.outcome().impacts;
      double max_diff = 0.0;
      for (std::size_t k = k0 + 1; k < gm.horizontal.size(); ++k) {
        m.step(gm.horizontal[k], 0.0, dt);
        rm.step(gm.horizontal[k], 0.0, dt);
        max_diff = std::max(max_diff, std::abs(m.theta() - rm.theta()));
      }
      EXPECT_EQ(m.outcome().impacts - 7, rm.outcome().impacts - rm_impacts0) << "from " << k0;
      EXPECT_GT(rm.outcome().impacts - rm_impacts0, 0) << "from " << k0;
      EXPECT_EQ(m.outcome().slip_episodes, 0);
      EXPECT_NEAR(m.slip(), offset, 1e-9) << "sticking pivots keep the offset";
      EXPECT_LT(max_diff, 1e-7 * alpha) << "mu " << mu << " from sample " << k0;
      RecordProperty("theta_max_diff_rad_from_" + std::to_string(k0), std::to_string(max_diff));
    }
  }
}

TEST(ContactModel, SetStateRestAndInvalidArguments) {
  ContactModel m(slender(0.5, 0.4));
  m.set_state(2.0, 0.1, 0.0, 0, 0.0, 0.0, -0.25);
  EXPECT_EQ(m.mode(), ContactMode::Rest);
  EXPECT_EQ(m.time(), 2.0);
  EXPECT_NEAR(m.slip(), -0.25, 1e-15);
  for (int k = 0; k < 100; ++k) m.step(0.1, 0.0, 0.005);
  EXPECT_EQ(m.mode(), ContactMode::Rest);
  EXPECT_NEAR(m.slip(), -0.25, 1e-15);
  EXPECT_NEAR(m.time(), 2.5, 1e-12);
  const ContactModel::State before = m.state();
  EXPECT_THROW(m.set_state(0.0, 0.0, 0.0, 2, 0.1, 0.0), std::invalid_argument);
  EXPECT_THROW(m.set_state(0.0, 0.0, 0.0, 0, 0.1, 0.0), std::invalid_argument);
  EXPECT_THROW(m.set_state(0.0, 0.0, 0.0, 1, -0.1, 0.0), std::invalid_argument);
  EXPECT_THROW(m.set_state(0.0, 0.0, 0.0, -1, -2.0, 0.0), std::invalid_argument);
  EXPECT_THROW(m.set_state(0.0, NAN, 0.0, 1, 0.1, 0.0), std::invalid_argument);
  EXPECT_EQ(m.state(), before);
  EXPECT_EQ(m.mode(), ContactMode::Rest);
}

// After the excitation stops, the relative-frame energy never increases, through rocking,
// slide-rock, impacts (with friction), flight and landings.
TEST(ContactModel, EnergyNeverIncreasesWithoutExcitation) {
  struct Case {
    BodyParameters body;
    double ax_peak, ay_peak;
  };
  const std::vector<Case> cases = {
      {slender(0.45, 0.35), 0.6 * g, 0.0},   // rocks, then slide-rocks / slides
      {slender(0.3, 0.2), 0.5 * g, 0.0},     // slides
      {slender(0.6, 0.5), 0.5 * g, -1.8 * g},  // flight and landing
      {slender(0.42, 0.42), 0.7 * g, -0.5 * g},
  };
  const double dt = 0.002, t_pulse = 0.25;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    ContactModel m(cases[i].body);
    m.reset(0.0);
    double e_prev = 0.0;
    int transitions = 0;
    bool any_motion = false;
    for (int k = 1; k <= 3000; ++k) {
      const double t = k * dt;
      const double s = t < t_pulse ? std::sin(2.0 * kPi * t / t_pulse) : 0.0;
      const double sv = t < t_pulse ? std::sin(kPi * t / t_pulse) : 0.0;
      const ContactReport& r = m.step(cases[i].ax_peak * s, cases[i].ay_peak * sv, dt);
      if (r.mode != ContactMode::Rest) any_motion = true;
      const double e = m.energy();
      if (t > t_pulse + dt) {
        transitions += r.transitions;
        EXPECT_LE(e, e_prev + 1e-10) << "case " << i << " t " << t << " mode " << to_string(r.mode);
      }
      e_prev = e;
    }
    EXPECT_TRUE(any_motion) << "case " << i;
    EXPECT_GT(transitions, 0) << "case " << i;
  }
}

TEST(ContactModel, BoundedWorkAtThresholdsAndExtremeInputs) {
  ContactSettings cs;
  const double dt = 0.005;
  ContactModel m(slender(0.4, 0.4), cs);  // mu_s == tan(alpha): slide and uplift coincide
  m.reset(0.0, 0.4 * g, 0.0);
  for (int k = 0; k < 200; ++k) {
    const ContactReport& r = m.step(0.4 * g, 0.0, dt);  // exactly at both thresholds
    EXPECT_LE(r.transitions, cs.max_events_per_sample);
    EXPECT_LE(r.integrator_steps, (cs.max_events_per_sample + 1) * cs.substeps);
  }
  ContactModel f(slender(0.4, 0.3), cs);
  f.reset(0.0, 0.0, -g);
  for (int k = 0; k < 400; ++k) {
    const double ax = (k % 2 ? 1.0 : -1.0) * 3.0 * g;
    const double ay = (k % 3 == 0) ? -g : (k % 3 == 1 ? -3.0 * g : 2.0 * g);
    const ContactReport& r = f.step(ax, ay, dt);
    EXPECT_LE(r.transitions, cs.max_events_per_sample);
    EXPECT_LE(r.integrator_steps, (cs.max_events_per_sample + 1) * cs.substeps);
    EXPECT_TRUE(std::isfinite(f.theta()) && std::isfinite(f.slip()));
  }
  EXPECT_THROW(f.step(0.0, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(f.step(NAN, 0.0, 0.01), std::invalid_argument);
}

}  // namespace
}  // namespace rocking_monitor::core
