// Tests of the Nigam-Jennings oscillator recursion and the offline response spectrum against closed-form
// solutions of the damped oscillator (Chopra, Dynamics of Structures, ch. 3-4), not against the code itself.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/motion/response_spectrum.hpp"

namespace rmc = rocking_monitor::core;

namespace {

constexpr double kSpectrumPi = rmc::kPi;

struct OscillatorCase {
  double period;   // s
  double damping;  // -
  double dt;       // s
};

// Large dt on purpose: the recursion must be exact for piecewise-linear input whatever dt is,
// including dt larger than the period.
const OscillatorCase kExactCases[] = {
    {1.0, 0.05, 0.1},  {0.05, 0.05, 0.1}, {2.0, 0.0, 0.1},
    {0.5, 0.2, 0.1},   {10.0, 0.05, 0.1}, {0.3, 0.02, 0.037},
};

class SpectrumNigamJenningsExact : public ::testing::TestWithParam<OscillatorCase> {};

// Ground acceleration a constant a from t = 0 (every sample equal), oscillator at rest:
//   u(t) = -a/w^2 (1 - e^{-z w t} (cos wd t + z/sqrt(1-z^2) sin wd t)),   u'(t) = -(a/wd) e^{-z w t} sin wd t.
TEST_P(SpectrumNigamJenningsExact, StepResponseMatchesClosedForm) {
  const OscillatorCase p = GetParam();
  const double a = 3.0;  // m/s^2
  const std::size_t n = static_cast<std::size_t>(std::lround(20.0 / p.dt)) + 1;
  const std::vector<double> accel(n, a);
  std::vector<double> u, v;
  rmc::oscillator_response(accel, p.dt, p.period, p.damping, u, v);

  const double w = 2.0 * kSpectrumPi / p.period;
  const double root = std::sqrt(1.0 - p.damping * p.damping);
  const double wd = w * root;
  const double u_scale = a / (w * w);
  const double v_scale = a / wd;
  double max_u_err = 0.0, max_v_err = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = p.dt * static_cast<double>(i);
    const double e = std::exp(-p.damping * w * t);
    const double u_exact = -u_scale * (1.0 - e * (std::cos(wd * t) + p.damping / root * std::sin(wd * t)));
    const double v_exact = -v_scale * e * std::sin(wd * t);
    max_u_err = std::max(max_u_err, std::abs(u[i] - u_exact) / u_scale);
    max_v_err = std::max(max_v_err, std::abs(v[i] - v_exact) / v_scale);
  }
  EXPECT_LT(max_u_err, 1e-12);
  EXPECT_LT(max_v_err, 1e-12);
}

// Ground acceleration a ramp a(t) = r t (exactly piecewise linear), oscillator at rest:
//   u(t) = -(r/w^2) [ t - 2z/w + e^{-z w t} (2z/w cos wd t - (1 - 2z^2)/wd sin wd t) ]
// (particular solution -(r/w^2)(t - 2z/w) plus the free vibration making u(0) = u'(0) = 0).
// Unlike the step, the ramp weighs a_i and a_{i+1} differently, so it checks b11, b12, b21, b22 separately.
TEST_P(SpectrumNigamJenningsExact, RampResponseMatchesClosedForm) {
  const OscillatorCase p = GetParam();
  const double r = 0.7;  // m/s^3
  const double duration = 20.0;
  const std::size_t n = static_cast<std::size_t>(std::lround(duration / p.dt)) + 1;
  std::vector<double> accel(n);
  for (std::size_t i = 0; i < n; ++i) accel[i] = r * p.dt * static_cast<double>(i);
  std::vector<double> u, v;
  rmc::oscillator_response(accel, p.dt, p.period, p.damping, u, v);

  const double z = p.damping;
  const double w = 2.0 * kSpectrumPi / p.period;
  const double wd = w * std::sqrt(1.0 - z * z);
  const double k = r / (w * w);
  // Errors relative to the size of the response: u grows to ~k t; its velocity terms are ~w u before they
  // cancel to the drift velocity k, so rounding in v is relative to w * u_scale, not to k.
  const double u_scale = k * std::max(duration, 1.0 / w);
  const double v_scale = w * u_scale;
  double max_u_err = 0.0, max_v_err = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = p.dt * static_cast<double>(i);
    const double e = std::exp(-z * w * t);
    const double c = std::cos(wd * t), s = std::sin(wd * t);
    const double u_exact = -k * (t - 2.0 * z / w + e * (2.0 * z / w * c - (1.0 - 2.0 * z * z) / wd * s));
    // derivative of the bracket: 1 + e [(-z w)(2z/w c - (1-2z^2)/wd s) - 2z wd/w s - (1-2z^2) c]
    const double v_exact =
        -k * (1.0 + e * (-z * w * (2.0 * z / w * c - (1.0 - 2.0 * z * z) / wd * s) - 2.0 * z * wd / w * s -
                         (1.0 - 2.0 * z * z) * c));
    max_u_err = std::max(max_u_err, std::abs(u[i] - u_exact) / u_scale);
    max_v_err = std::max(max_v_err, std::abs(v[i] - v_exact) / v_scale);
  }
  EXPECT_LT(max_u_err, 1e-12);
  EXPECT_LT(max_v_err, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Cases, SpectrumNigamJenningsExact, ::testing::ValuesIn(kExactCases),
                         [](const ::testing::TestParamInfo<OscillatorCase>& info) {
                           // e.g. "T0p5_z0p05_dt0p1": readable names in the ctest listing
                           auto f = [](double v) {
                             std::string s = std::to_string(v);
                             s.erase(s.find_last_not_of('0') + 1);
                             if (!s.empty() && s.back() == '.') s.pop_back();
                             for (char& c : s) if (c == '.') c = 'p';
                             return s;
                           };
                           return "T" + f(info.param.period) + "_z" + f(info.param.damping) + "_dt" +
                                  f(info.param.dt) + "_" + std::to_string(info.index);
                         });

// Long period with a fine dt is where the B coefficients suffer cancellation (terms ~2z/(w^3 dt) cancelling
// to ~dt^2); the long-double evaluation keeps the ramp response exact to 1e-11 even at w dt = 6e-4
// (measured 5e-13; evaluating the same formulas in double gives 9e-10).
TEST(SpectrumNigamJennings, LongPeriodFineStepStaysAccurate) {
  const double period = 10.0, z = 0.05, dt = 0.001, r = 0.5, duration = 20.0;
  const std::size_t n = static_cast<std::size_t>(std::lround(duration / dt)) + 1;
  std::vector<double> accel(n);
  for (std::size_t i = 0; i < n; ++i) accel[i] = r * dt * static_cast<double>(i);
  std::vector<double> u, v;
  rmc::oscillator_response(accel, dt, period, z, u, v);
  const double w = 2.0 * kSpectrumPi / period;
  const double wd = w * std::sqrt(1.0 - z * z);
  const double k = r / (w * w);
  double max_err = 0.0, max_u = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = dt * static_cast<double>(i);
    const double e = std::exp(-z * w * t);
    const double u_exact =
        -k * (t - 2.0 * z / w + e * (2.0 * z / w * std::cos(wd * t) - (1.0 - 2.0 * z * z) / wd * std::sin(wd * t)));
    max_err = std::max(max_err, std::abs(u[i] - u_exact));
    max_u = std::max(max_u, std::abs(u_exact));
  }
  EXPECT_LT(max_err / max_u, 1e-11);
}

// Harmonic ground acceleration a_g = a0 sin(W t) from rest. Exact solution of u'' + 2zwu' + w^2u = p0 sin(Wt),
// p0 = -a0 (Chopra Eq. 3.2.1-3.2.4): u = e^{-zwt}(A cos wd t + B sin wd t) + C sin Wt + D cos Wt with
//   C = ust (1 - r^2)/den, D = -ust 2 z r/den, den = (1 - r^2)^2 + (2 z r)^2, ust = p0/w^2, r = W/w,
//   A = -D, B = (z w A - C W)/wd  (from u(0) = u'(0) = 0).
// Steady-state amplitude: |u| = a0/w^2 / sqrt(den)  (= a0/(2 z w^2) at resonance).
struct HarmonicExact {
  double a0, W, w, z;
  double operator()(double t) const {
    const double r = W / w;
    const double den = (1.0 - r * r) * (1.0 - r * r) + (2.0 * z * r) * (2.0 * z * r);
    const double ust = -a0 / (w * w);
    const double c = ust * (1.0 - r * r) / den;
    const double d = -ust * 2.0 * z * r / den;
    const double wd = w * std::sqrt(1.0 - z * z);
    const double a = -d;
    const double b = (z * w * a - c * W) / wd;
    return std::exp(-z * w * t) * (a * std::cos(wd * t) + b * std::sin(wd * t)) + c * std::sin(W * t) +
           d * std::cos(W * t);
  }
  double steady_amplitude() const {
    const double r = W / w;
    return a0 / (w * w) / std::sqrt((1.0 - r * r) * (1.0 - r * r) + (2.0 * z * r) * (2.0 * z * r));
  }
};

// Error budget for the sine tests (dt = 0.005 s, W = 2 pi): the sampled sine is linearly interpolated,
// which scales its harmonic content by ~1 - (W dt)^2/12 = 1 - 8e-5, and sample maxima miss the true
// peak by at most 1 - cos(pi dt/T) <= 1.2e-4 (T >= 1 s). Tolerances below are ~5x that.
std::vector<double> sampled_sine(double a0, double W, double dt, double duration) {
  const std::size_t n = static_cast<std::size_t>(std::lround(duration / dt)) + 1;
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) a[i] = a0 * std::sin(W * dt * static_cast<double>(i));
  return a;
}

TEST(SpectrumHarmonic, ResonantBuildUpAndSteadyState) {
  const double a0 = 0.5, W = 2.0 * kSpectrumPi, dt = 0.005, duration = 80.0;
  const double period = 1.0, z = 0.05, w = 2.0 * kSpectrumPi / period;
  const std::vector<double> accel = sampled_sine(a0, W, dt, duration);
  std::vector<double> u, v;
  rmc::oscillator_response(accel, dt, period, z, u, v);
  const HarmonicExact exact{a0, W, w, z};
  const double amp = exact.steady_amplitude();
  ASSERT_NEAR(amp, a0 / (w * w) / (2.0 * z), 1e-15);  // resonance: a0/w^2/(2 zeta)

  // Whole history against the exact transient + steady-state solution.
  double max_err = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) max_err = std::max(max_err, std::abs(u[i] - exact(dt * i)));
  EXPECT_LT(max_err / amp, 5e-4);

  // Late time (transient e^{-z w t} < 1e-8 after 60 s): amplitude = a0/(2 zeta w^2) to 0.1 %.
  double late = 0.0;
  for (std::size_t i = static_cast<std::size_t>(70.0 / dt); i < u.size(); ++i) late = std::max(late, std::abs(u[i]));
  EXPECT_NEAR(late / amp, 1.0, 1e-3);

  // Build-up: each cycle's peak follows the envelope amp (1 - e^{-zeta w t}). That envelope is itself the
  // light-damping approximation (it ignores wd != w and the z/sqrt(1-z^2) sin term, < 0.3 % of amp here),
  // hence 1 % of amp.
  for (int cycle = 0; cycle < 20; ++cycle) {
    const std::size_t begin = static_cast<std::size_t>(std::lround(cycle / dt));
    const std::size_t end = static_cast<std::size_t>(std::lround((cycle + 1) / dt));
    std::size_t at = begin;
    for (std::size_t i = begin; i < end; ++i)
      if (std::abs(u[i]) > std::abs(u[at])) at = i;
    const double envelope = amp * (1.0 - std::exp(-z * w * dt * static_cast<double>(at)));
    EXPECT_NEAR(std::abs(u[at]), envelope, 0.01 * amp) << "cycle " << cycle;
  }
  // After 5 cycles the response must have passed 1 - e^{-zeta w 5} = 79 % of the steady state, not more than 81 %.
  const rmc::ResponseSpectrum first5 =
      rmc::response_spectrum(std::vector<double>(accel.begin(), accel.begin() + std::lround(5.0 / dt) + 1), dt,
                             {period}, z);
  EXPECT_NEAR(first5.sd[0] / amp, 1.0 - std::exp(-z * w * 5.0), 0.01);
}

TEST(SpectrumHarmonic, OffResonanceSteadyStateAmplitude) {
  const double a0 = 0.5, W = 2.0 * kSpectrumPi, dt = 0.005, duration = 90.0, z = 0.05;
  const std::vector<double> accel = sampled_sine(a0, W, dt, duration);
  for (double period : {0.5, 2.0, 1.1}) {  // frequency ratios r = 0.5, 2, 1.1
    const double w = 2.0 * kSpectrumPi / period;
    std::vector<double> u, v;
    rmc::oscillator_response(accel, dt, period, z, u, v);
    const HarmonicExact exact{a0, W, w, z};
    double late = 0.0;
    for (std::size_t i = static_cast<std::size_t>(80.0 / dt); i < u.size(); ++i) late = std::max(late, std::abs(u[i]));
    EXPECT_NEAR(late / exact.steady_amplitude(), 1.0, 1e-3) << "T = " << period;
  }
}

// Ricker acceleration pulse a(t) = A (1 - 2 c s^2) e^{-c s^2}, s = t - t1, c = (pi f)^2; its displacement is
// the Gaussian d(t) = -A/(2c) e^{-c s^2} (quiet before and after), so PGA = A and PGD = A/(2 pi^2 f^2).
std::vector<double> ricker(double amplitude, double f, double t1, double dt, double duration) {
  const std::size_t n = static_cast<std::size_t>(std::lround(duration / dt)) + 1;
  std::vector<double> a(n);
  const double c = kSpectrumPi * kSpectrumPi * f * f;
  for (std::size_t i = 0; i < n; ++i) {
    const double s = dt * static_cast<double>(i) - t1;
    a[i] = amplitude * (1.0 - 2.0 * c * s * s) * std::exp(-c * s * s);
  }
  return a;
}

TEST(SpectrumOffline, ShortAndLongPeriodLimits) {
  const double A = 2.0, f = 1.0, dt = 0.002;
  const std::vector<double> accel = ricker(A, f, 5.0, dt, 30.0);
  const std::vector<double> periods = {0.01, 200.0};
  const rmc::ResponseSpectrum rs = rmc::response_spectrum(accel, dt, periods, 0.05);
  // Rigid limit: a stiff oscillator follows the ground, so PSA -> PGA (quasi-static error ~(f T)^2).
  EXPECT_NEAR(rs.psa[0] / A, 1.0, 5e-3);
  // Flexible limit: a very soft oscillator stays put, so Sd -> PGD (error ~2 zeta w / W + content below w).
  EXPECT_NEAR(rs.sd[1] / (A / (2.0 * kSpectrumPi * kSpectrumPi * f * f)), 1.0, 1e-2);
}

TEST(SpectrumOffline, OrdinatesAreConsistent) {
  const double dt = 0.005;
  const std::vector<double> accel = ricker(1.5, 2.0, 3.0, dt, 15.0);
  const std::vector<double> periods = rmc::log_spaced_periods(0.05, 5.0, 12);
  const rmc::ResponseSpectrum rs = rmc::response_spectrum(accel, dt, periods, 0.07);
  ASSERT_EQ(rs.periods, periods);
  EXPECT_EQ(rs.damping, 0.07);
  for (std::size_t j = 0; j < periods.size(); ++j) {
    const double w = 2.0 * kSpectrumPi / periods[j];
    std::vector<double> u, v;
    rmc::oscillator_response(accel, dt, periods[j], 0.07, u, v);
    double max_u = 0.0, max_v = 0.0;
    for (std::size_t i = 0; i < u.size(); ++i) {
      max_u = std::max(max_u, std::abs(u[i]));
      max_v = std::max(max_v, std::abs(v[i]));
    }
    EXPECT_DOUBLE_EQ(rs.sd[j], max_u);
    EXPECT_DOUBLE_EQ(rs.sv[j], max_v);
    EXPECT_NEAR(rs.psv[j], w * max_u, 1e-12 * w * max_u);
    EXPECT_NEAR(rs.psa[j], w * w * max_u, 1e-12 * w * w * max_u);
  }
}

TEST(SpectrumOffline, ComponentOverloadUsesItsDt) {
  rmc::Component c;
  c.dt = 0.01;
  c.accel = ricker(1.0, 1.0, 2.0, c.dt, 8.0);
  const std::vector<double> periods = {0.2, 1.0};
  const rmc::ResponseSpectrum a = rmc::response_spectrum(c, periods);
  const rmc::ResponseSpectrum b = rmc::response_spectrum(c.accel, c.dt, periods, rmc::kDefaultSpectralDamping);
  EXPECT_EQ(a.sd, b.sd);
  EXPECT_EQ(a.damping, 0.05);
}

TEST(SpectrumOffline, LogSpacedPeriods) {
  const std::vector<double> p = rmc::log_spaced_periods();
  ASSERT_EQ(p.size(), 100u);
  EXPECT_EQ(p.front(), 0.02);
  EXPECT_EQ(p.back(), 10.0);
  const double ratio = std::pow(10.0 / 0.02, 1.0 / 99.0);
  for (std::size_t i = 1; i < p.size(); ++i) EXPECT_NEAR(p[i] / p[i - 1], ratio, 1e-12);
  EXPECT_EQ(rmc::log_spaced_periods(0.1, 1.0, 1), std::vector<double>{0.1});
  EXPECT_THROW(rmc::log_spaced_periods(0.0, 1.0, 5), std::invalid_argument);
  EXPECT_THROW(rmc::log_spaced_periods(2.0, 1.0, 5), std::invalid_argument);
  EXPECT_THROW(rmc::log_spaced_periods(0.1, 1.0, 0), std::invalid_argument);
}

TEST(SpectrumOffline, RejectsInvalidParameters) {
  const std::vector<double> a = {0.0, 1.0, 0.0};
  EXPECT_THROW(rmc::response_spectrum(a, 0.01, {0.0}), std::invalid_argument);
  EXPECT_THROW(rmc::response_spectrum(a, 0.01, {-1.0}), std::invalid_argument);
  EXPECT_THROW(rmc::response_spectrum(a, 0.0, {1.0}), std::invalid_argument);
  EXPECT_THROW(rmc::response_spectrum(a, 0.01, {1.0}, 1.0), std::invalid_argument);
  EXPECT_THROW(rmc::response_spectrum(a, 0.01, {1.0}, -0.1), std::invalid_argument);
  EXPECT_THROW(rmc::nigam_jennings_coefficients(1.0, 0.05, std::nan("")), std::invalid_argument);
}

}  // namespace
