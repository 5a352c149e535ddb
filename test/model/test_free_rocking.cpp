// Free rocking (no ground motion) against the closed forms in ../shared/paper/NOTES.md.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rocking_monitor/model/rocking_model.hpp"
#include "test_helpers.hpp"

namespace rocking_monitor::core {
namespace {

using testing::deg;

struct FreeRun {
  std::vector<double> impact_times;  // s
  std::vector<double> peaks;         // |theta|/alpha between impacts (after each impact)
  double rest_time = -1.0;
  long steps = 0;
  long impacts = 0;
};

FreeRun run_free(const BodyParameters& body, const SolverSettings& s, double theta0, double dt,
                 double t_end, std::size_t n_impacts) {
  RockingModel m(body, s);
  m.set_state(theta0, 0.0);
  FreeRun r;
  double peak = 0.0;
  const auto n = static_cast<long>(t_end / dt);
  for (long k = 0; k < n; ++k) {
    const StepReport& rep = m.step(0.0, 0.0, dt);
    if (rep.impacts > 0 && r.impact_times.size() < n_impacts) {
      r.impact_times.push_back(rep.first_impact_time);
      if (r.impact_times.size() > 1) r.peaks.push_back(peak);
      peak = 0.0;
    }
    peak = std::max(peak, rep.peak_ratio);
    if (m.mode() == Mode::Rest && r.rest_time < 0.0) r.rest_time = m.time();
  }
  r.steps = m.outcome().integrator_steps;
  r.impacts = m.outcome().impacts;
  return r;
}

// NOTES.md example: p = 2 rad/s, alpha = 15 deg, theta0 = alpha/2, Housner's eta.
const double kP = 2.0;
const double kAlpha = deg(15);

double linear_half_period(double phi) { return 2.0 / kP * std::acosh(1.0 / (1.0 - phi)); }

// phi_n = 1 - sqrt(1 - r^n [1 - (1 - phi_0)^2]), r = eta^2 (NOTES.md).
double linear_amplitude(double phi0, double r, int n) {
  return 1.0 - std::sqrt(1.0 - std::pow(r, n) * (1.0 - (1.0 - phi0) * (1.0 - phi0)));
}

// Nonlinear half period by quadrature of the energy integral, independent of any integrator:
// T/2 = 2 int_0^theta_n dtheta / omega, omega^2 = 2 p^2 (cos(alpha - theta_n) - cos(alpha - theta)),
// with theta = theta_n (1 - u^2) to remove the end singularity; midpoint rule.
double nonlinear_half_period(double theta_n) {
  const int n = 200000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double u = (i + 0.5) / n;
    const double th = theta_n * (1.0 - u * u);
    const double w = std::sqrt(2.0 * kP * kP * (std::cos(kAlpha - theta_n) - std::cos(kAlpha - th)));
    sum += 2.0 * theta_n * u / w;
  }
  return 2.0 * sum / n;
}

class FreeRockingLinearized : public ::testing::TestWithParam<Method> {};

TEST_P(FreeRockingLinearized, ImpactTimesAndAmplitudesMatchClosedForm) {
  SolverSettings s;
  s.method = GetParam();
  s.model = ModelKind::Linearized;
  s.tol = 1e-11;
  s.substeps = 10;
  const BodyParameters body = testing::rectangle_with(kP, kAlpha);
  const double eta = 1.0 - 1.5 * std::sin(kAlpha) * std::sin(kAlpha);
  const FreeRun run = run_free(body, s, 0.5 * kAlpha, 1e-3, 4.0, 4);
  ASSERT_EQ(run.impact_times.size(), 4u);
  // Table in NOTES.md: 0.37298, 0.28657, 0.22367 and half periods 1.04284, 0.86874, 0.74195.
  const double table_phi[] = {0.5, 0.37298, 0.28657, 0.22367};
  const double table_half[] = {1.31696, 1.04284, 0.86874, 0.74195};
  for (int n = 0; n < 4; ++n) {
    const double phi = linear_amplitude(0.5, eta * eta, n);
    EXPECT_NEAR(phi, table_phi[n], 6e-6);
    EXPECT_NEAR(linear_half_period(phi), table_half[n], 6e-6);
  }
  // Impact k happens after the quarter period and k-1 half periods of decaying amplitude.
  double t = linear_half_period(0.5) / 2.0;
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(run.impact_times[k], t, 1e-8) << "impact " << k + 1;
    if (k < 3) {
      const double phi = linear_amplitude(0.5, eta * eta, k + 1);
      EXPECT_NEAR(run.peaks[k], phi, 1e-8) << "amplitude after impact " << k + 1;
      t += linear_half_period(phi);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllMethods, FreeRockingLinearized,
                         ::testing::Values(Method::Analytic, Method::Dopri5, Method::Rk4),
                         [](const auto& info) { return std::string(to_string(info.param)); });

TEST(FreeRockingLinearized, QuarterPeriodFormulaForSeveralReleaseAngles) {
  SolverSettings s;
  s.method = Method::Analytic;
  s.model = ModelKind::Linearized;
  const BodyParameters body = testing::rectangle_with(3.0, deg(20));
  const double alpha = deg(20);
  for (double phi0 : {0.05, 0.3, 0.7, 0.95}) {
    RockingModel m(body, s);
    m.set_state(-phi0 * alpha, 0.0);  // corner 2 as well
    double t_imp = -1.0;
    for (int k = 0; k < 100000 && t_imp < 0.0; ++k) {
      const StepReport& r = m.step(0.0, 0.0, 1e-3);
      if (r.impacts > 0) t_imp = r.first_impact_time;
    }
    // T = (4/p) acosh(1 / (1 - theta0/alpha)); the first impact is at T/4.
    EXPECT_NEAR(t_imp, std::acosh(1.0 / (1.0 - phi0)) / 3.0, 1e-10) << "phi0 " << phi0;
  }
}

class FreeRockingNonlinear : public ::testing::TestWithParam<Method> {};

TEST_P(FreeRockingNonlinear, ImpactTimesAndEnergyMapMatchQuadrature) {
  SolverSettings s;
  s.method = GetParam();
  s.model = ModelKind::Nonlinear;
  s.tol = 1e-11;
  s.substeps = 10;
  const BodyParameters body = testing::rectangle_with(kP, kAlpha);
  const double eta = 1.0 - 1.5 * std::sin(kAlpha) * std::sin(kAlpha);
  const double r = eta * eta;
  const FreeRun run = run_free(body, s, 0.5 * kAlpha, 1e-3, 4.0, 4);
  ASSERT_EQ(run.impact_times.size(), 4u);
  // Quadrature reproduces the NOTES.md table (5 digits) ...
  EXPECT_NEAR(nonlinear_half_period(0.5 * kAlpha), 1.31961, 6e-6);
  // ... and the exact energy map gives the amplitudes: cos(a - th') = cos a + r (cos(a - th) - cos a).
  const double table_phi[] = {0.37338, 0.28708, 0.22418};
  const double table_half[] = {1.04652, 0.87266, 0.74583};
  double th = 0.5 * kAlpha;
  double t = nonlinear_half_period(th) / 2.0;
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(run.impact_times[k], t, 1e-7) << "impact " << k + 1;
    if (k < 3) {
      th = kAlpha - std::acos(std::cos(kAlpha) + r * (std::cos(kAlpha - th) - std::cos(kAlpha)));
      EXPECT_NEAR(th / kAlpha, table_phi[k], 6e-6);
      EXPECT_NEAR(run.peaks[k], th / kAlpha, 1e-8) << "amplitude after impact " << k + 1;
      const double half = nonlinear_half_period(th);
      EXPECT_NEAR(half, table_half[k], 6e-6);
      t += half;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(NonlinearMethods, FreeRockingNonlinear,
                         ::testing::Values(Method::Dopri5, Method::Rk4),
                         [](const auto& info) { return std::string(to_string(info.param)); });

// Impacts accumulate (Zeno): NOTES.md says about 9.9 s for this body. The rest-capture rule must
// end the sequence close to the accumulation time with bounded work.
TEST(RestCapture, FreeRockingComesToRestAtTheAccumulationTime) {
  const double eta = 1.0 - 1.5 * std::sin(kAlpha) * std::sin(kAlpha);
  double t_inf = linear_half_period(0.5) / 2.0;
  for (int n = 1; n < 2000; ++n) t_inf += linear_half_period(linear_amplitude(0.5, eta * eta, n));
  // NOTES.md's "about 9.9 s" counts a full first half period (as if released by an impact):
  EXPECT_NEAR(t_inf + linear_half_period(0.5) / 2.0, 9.9, 0.05);
  for (Method method : {Method::Analytic, Method::Dopri5, Method::Rk4}) {
    SolverSettings s;
    s.method = method;
    s.model = ModelKind::Linearized;
    const FreeRun run = run_free(testing::rectangle_with(kP, kAlpha), s, 0.5 * kAlpha, 0.005, 15.0, 0);
    EXPECT_GT(run.rest_time, 0.0) << to_string(method);
    // The impacts left after the capture (KE < 1e-6 of the tipping energy) would take ~10 ms.
    EXPECT_GT(run.rest_time, t_inf - 0.02) << to_string(method);
    EXPECT_LT(run.rest_time, t_inf + 0.005) << to_string(method);
    // KE after the last impact is below 1e-6 of the tipping energy: about 64 impacts here.
    EXPECT_GE(run.impacts, 55) << to_string(method);
    EXPECT_LE(run.impacts, 75) << to_string(method);
    EXPECT_LT(run.steps, 20000) << to_string(method);
  }
}

}  // namespace
}  // namespace rocking_monitor::core
