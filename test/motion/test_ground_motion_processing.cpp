// Tests of baseline correction, integration, peak ground motion and the streaming intensity monitor,
// against closed forms (and, for the streaming monitor, against the offline functions).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/motion/ground_motion_integration.hpp"
#include "rocking_monitor/motion/peak_ground_motion.hpp"
#include "rocking_monitor/motion/response_spectrum.hpp"
#include "rocking_monitor/motion/streaming_intensity.hpp"

namespace rmc = rocking_monitor::core;

namespace {

constexpr double kPi = rmc::kPi;

std::size_t samples_for(double duration, double dt) { return static_cast<std::size_t>(std::lround(duration / dt)) + 1; }

double max_abs(const std::vector<double>& x) {
  double m = 0.0;
  for (double v : x) m = std::max(m, std::abs(v));
  return m;
}

// ------------------------------------------------------------------ integration

// a = A sin(W t) from rest: v = A/W (1 - cos W t), d = A/W t - A/W^2 sin W t.
// The trapezoidal sum of a sampled sine is known in closed form: it equals the exact integral times
// (h/2) cot(h/2), h = W dt (= 1 - h^2/12 - ...), which pins down that the method IS the trapezoidal rule.
TEST(GroundMotionProcessingIntegration, SineMatchesClosedForms) {
  const double A = 1.7, W = 2.0 * kPi * 1.3, dt = 0.004, duration = 10.0;
  const std::size_t n = samples_for(duration, dt);
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) a[i] = A * std::sin(W * dt * i);
  std::vector<double> v, d;
  rmc::integrate_acceleration(a, dt, v, d);
  ASSERT_EQ(v.size(), n);
  ASSERT_EQ(d.size(), n);

  const double h = W * dt;
  const double trapezoid_factor = (h / 2.0) / std::tan(h / 2.0);
  const double v_scale = 2.0 * A / W;
  const double d_scale = A / W * duration;
  const double tol_v = 1.05 * h * h / 12.0 * v_scale;  // |1 - factor| <= 1.05 h^2/12 for small h
  const double tol_d = 1.05 * h * h / 12.0 * d_scale;  // d's error is the integral of v's
  for (std::size_t i = 0; i < n; ++i) {
    const double t = dt * i;
    const double v_exact = A / W * (1.0 - std::cos(W * t));
    const double d_exact = A / W * t - A / (W * W) * std::sin(W * t);
    ASSERT_NEAR(v[i], trapezoid_factor * v_exact, 1e-12 * v_scale) << "t = " << t;
    ASSERT_NEAR(v[i], v_exact, tol_v) << "t = " << t;
    ASSERT_NEAR(d[i], d_exact, tol_d) << "t = " << t;
  }
}

// A linear acceleration is piecewise linear, so both integrals are exact: v = c0 t + c1 t^2/2, d = c0 t^2/2 + c1 t^3/6.
TEST(GroundMotionProcessingIntegration, LinearAccelerationIsIntegratedExactly) {
  const double c0 = -0.3, c1 = 0.11, dt = 0.05;
  const std::size_t n = samples_for(30.0, dt);
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) a[i] = c0 + c1 * dt * i;
  std::vector<double> v, d;
  rmc::integrate_acceleration(a, dt, v, d);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = dt * i;
    EXPECT_NEAR(v[i], c0 * t + c1 * t * t / 2.0, 1e-12 * 50.0);
    EXPECT_NEAR(d[i], c0 * t * t / 2.0 + c1 * t * t * t / 6.0, 1e-12 * 500.0);
  }
}

TEST(GroundMotionProcessingIntegration, RejectsBadDt) {
  std::vector<double> v, d;
  EXPECT_THROW(rmc::integrate_acceleration({1.0, 2.0}, 0.0, v, d), std::invalid_argument);
  EXPECT_THROW(rmc::integrate_acceleration({1.0, 2.0}, -0.01, v, d), std::invalid_argument);
  EXPECT_THROW(rmc::integrate_ground_motion(std::vector<double>{1.0, 2.0}, std::nan("")), std::invalid_argument);
}

// ------------------------------------------------------------------ baseline correction

std::vector<double> test_signal(std::size_t n, double dt) {  // arbitrary, not orthogonal to a line
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = dt * i;
    a[i] = 0.8 * std::sin(2.0 * kPi * 0.7 * t) * std::exp(-0.1 * t) + 0.2 * std::cos(2.0 * kPi * 2.3 * t);
  }
  return a;
}

TEST(GroundMotionProcessingBaseline, RemovesAnAddedLinearTrendExactly) {
  const double dt = 0.01;
  const std::size_t n = samples_for(40.0, dt);
  const std::vector<double> clean = test_signal(n, dt);
  std::vector<double> trended = clean;
  std::vector<double> trend_only(n);
  for (std::size_t i = 0; i < n; ++i) {
    trend_only[i] = 0.05 - 0.004 * dt * i;  // offset 0.05 m/s^2, drift -0.004 m/s^3
    trended[i] += trend_only[i];
  }
  std::vector<double> corrected_clean = clean;
  rmc::remove_polynomial_trend(corrected_clean, 1);
  rmc::remove_polynomial_trend(trended, 1);
  rmc::remove_polynomial_trend(trend_only, 1);
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_NEAR(trended[i], corrected_clean[i], 1e-12);  // the added line leaves no trace
    ASSERT_NEAR(trend_only[i], 0.0, 1e-12);
  }
  // What is left has no mean and no linear trend: sum r = 0, sum t r = 0.
  double s0 = 0.0, s1 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    s0 += trended[i];
    s1 += trended[i] * (static_cast<double>(i) / (n - 1) - 0.5);
  }
  EXPECT_NEAR(s0, 0.0, 1e-9);
  EXPECT_NEAR(s1, 0.0, 1e-9);
}

TEST(GroundMotionProcessingBaseline, HigherOrdersRemoveTheirPolynomials) {
  const double dt = 0.02;
  const std::size_t n = samples_for(60.0, dt);
  for (int order = 0; order <= 4; ++order) {
    std::vector<double> y(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double t = dt * i;
      y[i] = 0.3 - 0.01 * t;
      if (order < 1) y[i] = 0.3;
      if (order >= 2) y[i] += 2e-4 * t * t;
      if (order >= 3) y[i] -= 3e-6 * t * t * t;
      if (order >= 4) y[i] += 1e-8 * t * t * t * t;
    }
    rmc::remove_polynomial_trend(y, order);
    EXPECT_LT(max_abs(y), 1e-11) << "order " << order;
  }
  // A line is not removed by a mean (order 0) correction.
  std::vector<double> line(n);
  for (std::size_t i = 0; i < n; ++i) line[i] = 0.01 * dt * i;
  rmc::remove_polynomial_trend(line, 0);
  EXPECT_NEAR(max_abs(line), 0.01 * 60.0 / 2.0, 1e-9);
  EXPECT_THROW(rmc::polynomial_trend(line, 11), std::invalid_argument);
  EXPECT_THROW(rmc::polynomial_trend(line, -1), std::invalid_argument);
  EXPECT_TRUE(rmc::polynomial_trend({}, 1).empty());
  EXPECT_EQ(rmc::polynomial_trend({4.0}, 3), std::vector<double>{4.0});  // degree clamped to n - 1
}

// Displacement fit (Ancheta et al. 2013): an acceleration whose double integral is c2 t^2 + ... + c6 t^6
// is pure "drift" to the fit and must be removed, leaving only the O(dt^2) discretisation residue.
TEST(GroundMotionProcessingBaseline, DisplacementFitRemovesPolynomialDrift) {
  const double dt = 0.01, T = 20.0;
  const std::size_t n = samples_for(T, dt);
  const double c[7] = {0.0, 0.0, 2e-3, -3e-4, 2e-5, -6e-7, 7e-9};
  std::vector<double> a(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = dt * i;
    for (int k = 2; k <= 6; ++k) a[i] += k * (k - 1) * c[k] * std::pow(t, k - 2);
  }
  rmc::BaselineOptions opt;
  opt.accel_poly_order = -1;  // only the displacement fit
  opt.disp_poly_order = 6;
  const rmc::GroundMotionHistories h = rmc::integrate_ground_motion(a, dt, opt);
  EXPECT_LT(max_abs(h.accel), 1e-5 * max_abs(a));
  double d_raw = 0.0;
  for (int k = 2; k <= 6; ++k) d_raw = std::max(d_raw, std::abs(c[k] * std::pow(T, k)));
  EXPECT_LT(max_abs(h.disp), 1e-6 * d_raw);
  EXPECT_EQ(h.vel.front(), 0.0);
  EXPECT_EQ(h.disp.front(), 0.0);

  EXPECT_THROW(rmc::displacement_fit_acceleration(a, dt, 1), std::invalid_argument);
  opt.disp_poly_order = 1;
  EXPECT_THROW(rmc::integrate_ground_motion(a, dt, opt), std::invalid_argument);
}

// A constant acceleration offset c integrates exactly to c t^2 / 2, which lies in the span of the displacement
// fit (t^2..t^6): with the fit on (and the acceleration fit off) the offset must leave no trace, although
// uncorrected it would be 0.5 * 0.003 * 30^2 = 1.35 m of fake displacement, 13x the pulse's PGD.
TEST(GroundMotionProcessingBaseline, DisplacementFitRemovesAnAccelerationOffset) {
  const double dt = 0.005, f = 1.0, t1 = 5.0, A = 2.0, T = 30.0, offset = 0.003;
  const std::size_t n = samples_for(T, dt);
  const double cc = kPi * kPi * f * f;
  std::vector<double> clean(n), shifted(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = dt * i - t1;
    clean[i] = A * (1.0 - 2.0 * cc * s * s) * std::exp(-cc * s * s);
    shifted[i] = clean[i] + offset;
  }
  rmc::BaselineOptions opt;
  opt.accel_poly_order = -1;
  opt.disp_poly_order = 6;
  const rmc::GroundMotionHistories hc = rmc::integrate_ground_motion(clean, dt, opt);
  const rmc::GroundMotionHistories hs = rmc::integrate_ground_motion(shifted, dt, opt);
  const double pgd = A / (2.0 * cc);
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_NEAR(hs.disp[i], hc.disp[i], 1e-9 * pgd) << "t = " << dt * i;
    ASSERT_NEAR(hs.accel[i], hc.accel[i], 1e-9 * A) << "t = " << dt * i;
  }
  std::vector<double> v_raw, d_raw;
  rmc::integrate_acceleration(shifted, dt, v_raw, d_raw);
  EXPECT_GT(max_abs(d_raw), 10.0 * pgd);  // what the fit removed
}

// ------------------------------------------------------------------ peak ground motion

// Ricker acceleration a = A (1 - 2c s^2) e^{-c s^2}, s = t - t1, c = (pi f)^2, integrates in closed form to
//   v = A s e^{-c s^2}            -> PGV = A e^{-1/2} / (sqrt(2) pi f) at s = +-1/(sqrt(2) pi f)
//   d = -A/(2c) e^{-c s^2} (+ e^{-c t1^2} ~ 0) -> PGD = A / (2 pi^2 f^2) at s = 0.
rmc::Component ricker_component(double A, double f, double t1, double dt, double duration, double t0 = 0.0) {
  rmc::Component comp;
  comp.dt = dt;
  comp.t0 = t0;
  comp.label = "synthetic-ricker";
  const std::size_t n = samples_for(duration, dt);
  comp.accel.resize(n);
  const double c = kPi * kPi * f * f;
  for (std::size_t i = 0; i < n; ++i) {
    const double s = dt * i - t1;
    comp.accel[i] = A * (1.0 - 2.0 * c * s * s) * std::exp(-c * s * s);
  }
  return comp;
}

TEST(GroundMotionProcessingPeaks, RickerPulseMatchesClosedForm) {
  const double A = 2.5, f = 1.2, t1 = 6.0, dt = 0.002, t0 = 100.0;
  const rmc::Component comp = ricker_component(A, f, t1, dt, 20.0, t0);
  const rmc::PeakGroundMotion pk = rmc::peak_ground_motion(comp);

  EXPECT_DOUBLE_EQ(pk.pga.value, A);
  EXPECT_NEAR(pk.pga.time, t0 + t1, 1e-9);
  EXPECT_EQ(pk.pga.index, static_cast<std::size_t>(std::lround(t1 / dt)));

  // Trapezoidal integration of this smooth pulse errs by ~dt^2/12 |a'| ~ 1e-5 of PGV; 1e-3 is generous.
  const double pgv = A * std::exp(-0.5) / (std::sqrt(2.0) * kPi * f);
  const double s_v = 1.0 / (std::sqrt(2.0) * kPi * f);
  EXPECT_NEAR(pk.pgv.value / pgv, 1.0, 1e-3);
  EXPECT_LT(std::min(std::abs(pk.pgv.time - (t0 + t1 - s_v)), std::abs(pk.pgv.time - (t0 + t1 + s_v))), 2 * dt);

  const double pgd = A / (2.0 * kPi * kPi * f * f);
  EXPECT_NEAR(pk.pgd.value / pgd, 1.0, 1e-3);
  EXPECT_NEAR(pk.pgd.time, t0 + t1, 2 * dt);
}

TEST(GroundMotionProcessingPeaks, AbsolutePeakTakesFirstOfEqualMagnitudes) {
  const rmc::PeakValue p = rmc::absolute_peak({0.0, -3.0, 1.0, 3.0}, 0.5, 10.0);
  EXPECT_EQ(p.value, 3.0);
  EXPECT_EQ(p.index, 1u);
  EXPECT_EQ(p.time, 10.5);
  const rmc::PeakValue empty = rmc::absolute_peak({}, 0.5, 10.0);
  EXPECT_EQ(empty.value, 0.0);
  EXPECT_EQ(empty.time, 10.0);
}

// ------------------------------------------------------------------ streaming versus offline

// Windowed linear sine sweep 0.5 -> 5 Hz between 2 s and 22 s (quiet start), Hann-tapered.
rmc::Component sweep_component(double dt) {
  rmc::Component comp;
  comp.dt = dt;
  comp.label = "synthetic-sweep";
  const double t_start = 2.0, length = 20.0, f0 = 0.5, f1 = 5.0, amp = 3.0;
  const std::size_t n = samples_for(30.0, dt);
  comp.accel.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = dt * i - t_start;
    if (s <= 0.0 || s >= length) continue;
    const double phase = 2.0 * kPi * (f0 * s + 0.5 * (f1 - f0) / length * s * s);
    const double window = 0.5 * (1.0 - std::cos(2.0 * kPi * s / length));
    comp.accel[i] = amp * window * std::sin(phase);
  }
  return comp;
}

rmc::StreamingIntensity run_stream(const rmc::Component& comp, rmc::StreamingIntensityConfig cfg) {
  cfg.dt = comp.dt;
  rmc::StreamingIntensity stream(cfg);
  for (double a : comp.accel) stream.push(a);
  return stream;
}

// Documented in streaming_intensity.hpp: PGA identical; PSV (raw oscillator input) identical to rounding;
// PGV differs from the offline (linear-baseline) PGV by at most ~sqrt(2) wc PGD (to first order the
// high-passed velocity is v - sqrt(2) wc d), and by <= 1 % on oscillatory records without a net
// displacement pulse (measured <= 0.25 % on windowed sweeps).
constexpr double kStreamingPgvSweepTolerance = 0.01;

void expect_stream_matches_offline(const rmc::Component& comp, double corner_hz, bool displacement_pulse) {
  rmc::StreamingIntensityConfig cfg;  // defaults: 0.02-10 s grid, 5 %
  cfg.velocity_highpass_hz = corner_hz;
  const rmc::StreamingIntensity stream = run_stream(comp, cfg);
  const rmc::PeakGroundMotion offline = rmc::peak_ground_motion(comp);
  const rmc::ResponseSpectrum rs = rmc::response_spectrum(comp, cfg.periods, cfg.damping);

  EXPECT_EQ(stream.sample_count(), comp.accel.size());
  EXPECT_EQ(stream.pga(), offline.pga.value);
  EXPECT_DOUBLE_EQ(stream.pga_time() + comp.t0, offline.pga.time);

  ASSERT_EQ(stream.psv().size(), rs.psv.size());
  for (std::size_t j = 0; j < rs.psv.size(); ++j) {
    EXPECT_NEAR(stream.psv()[j], rs.psv[j], 1e-12 * rs.psv[j]) << "T = " << rs.periods[j];
  }
  if (displacement_pulse) {
    const double bound = std::sqrt(2.0) * 2.0 * kPi * corner_hz * offline.pgd.value;
    EXPECT_LE(std::abs(stream.pgv() - offline.pgv.value), bound) << "corner " << corner_hz << " Hz";
  } else {
    EXPECT_NEAR(stream.pgv() / offline.pgv.value, 1.0, kStreamingPgvSweepTolerance) << "corner " << corner_hz << " Hz";
  }
}

// The Ricker acceleration pulse has a one-sided Gaussian displacement pulse: the worst case for a high-pass
// (measured PGV +14 % at 0.1 Hz for f = 1 Hz, i.e. 0.44 of the bound; +3.8 % at 0.02 Hz).
TEST(GroundMotionStreaming, MatchesOfflineOnRickerPulse) {
  for (double f : {1.0, 3.0}) {
    for (double corner : {0.02, 0.1}) {
      expect_stream_matches_offline(ricker_component(2.0, f, 5.0, 0.005, 25.0, 3.0), corner, true);
    }
  }
}

TEST(GroundMotionStreaming, MatchesOfflineOnWindowedSweep) {
  for (double corner : {0.02, 0.1}) expect_stream_matches_offline(sweep_component(0.005), corner, false);
}

// Optional high-pass on the oscillator input. It removes a sensor offset present from switch-on completely
// (steady-state start), and on the sweep it stays within 1 % of the offline spectrum for T <= 1 s
// (measured <= 0.52 %, corner 0.1 Hz). Without it, the offset deflects the raw oscillators statically by
// a_off/w^2 and the switch-on overshoot nearly doubles that: documented PSV error <= 2 a_off/w.
TEST(GroundMotionStreaming, OscillatorHighPassRejectsOffsetAndKeepsShortPeriods) {
  const rmc::Component clean = sweep_component(0.005);
  const double a_off = 0.05;  // m/s^2 sensor offset, present from switch-on
  rmc::Component offset = clean;
  for (double& a : offset.accel) a += a_off;
  rmc::StreamingIntensityConfig cfg;
  cfg.oscillator_highpass_hz = 0.1;
  const rmc::StreamingIntensity filtered = run_stream(offset, cfg);
  const rmc::StreamingIntensity filtered_clean = run_stream(clean, cfg);
  const rmc::StreamingIntensity raw = run_stream(offset, rmc::StreamingIntensityConfig{});
  const rmc::ResponseSpectrum rs = rmc::response_spectrum(clean, cfg.periods, cfg.damping);
  for (std::size_t j = 0; j < rs.periods.size(); ++j) {
    EXPECT_NEAR(filtered.psv()[j], filtered_clean.psv()[j], 1e-9 * rs.psv[j]) << "T = " << rs.periods[j];
    if (rs.periods[j] <= 1.0) {
      EXPECT_NEAR(filtered.psv()[j] / rs.psv[j], 1.0, 0.01) << "T = " << rs.periods[j];
    }
    const double w = 2.0 * kPi / rs.periods[j];
    EXPECT_LE(raw.psv()[j], rs.psv[j] + 2.0 * a_off / w) << "T = " << rs.periods[j];
  }
  // At 10 s the raw oscillator clearly feels the offset: more than the static a_off/w (measured 1.76 a_off/w).
  const std::size_t last = rs.periods.size() - 1;
  const double w = 2.0 * kPi / rs.periods[last];
  EXPECT_GT(raw.psv()[last] - rs.psv[last], a_off / w);
  // The velocity filter ignores the offset in both cases (steady-state start).
  EXPECT_NEAR(filtered.pgv(), raw.pgv(), 1e-12);
}

// A 2nd-order Butterworth high-pass after integration: a constant offset from switch-on gives exactly zero
// velocity, and an offset step a0 gives the impulse response of a0 / (s^2 + sqrt(2) wc s + wc^2), whose
// peak is a0 e^{-pi/4} / wc, then decays with time constant sqrt(2)/wc (plain integration: 0.05 m/s^2 * 290 s).
TEST(GroundMotionStreaming, SensorOffsetDoesNotAccumulate) {
  const double dt = 0.01, a0 = 0.05, fc = 0.1, wc = 2.0 * kPi * fc;
  rmc::StreamingIntensityConfig cfg;
  cfg.dt = dt;
  cfg.periods = {0.5, 2.0};
  cfg.velocity_highpass_hz = fc;
  rmc::StreamingIntensity stream(cfg);
  for (int i = 0; i < 1000; ++i) stream.push(a0);
  EXPECT_EQ(stream.pgv(), 0.0);

  stream.reset();
  double late = 0.0;
  for (int i = 0; i < 30000; ++i) {
    stream.push(i * dt >= 10.0 ? a0 : 0.0);
    if (i * dt >= 280.0) late = std::max(late, std::abs(stream.velocity()));
  }
  const double peak = a0 * std::exp(-kPi / 4.0) / wc;
  EXPECT_NEAR(stream.pgv() / peak, 1.0, 2e-3);  // bilinear transform error ~(pi fc dt)^2, sample max ~(wc dt)^2
  EXPECT_NEAR(stream.pgv_time(), 10.0 + (kPi / 4.0) * std::sqrt(2.0) / wc, 2 * dt);
  EXPECT_LT(late, 1e-9 * peak);  // e^{-wc t/sqrt 2} after 270 s is ~1e-52: only rounding left
}

// Gain of the velocity path at frequency f: 1/(2 pi f) (integration) times |Butterworth HP| = 1/sqrt(1 + (fc/f)^4).
// The bilinear transform maps digital f to analog tan(pi f dt)/(pi dt), so the digital gain is exactly
//   (dt/2) cot(pi f dt) / sqrt(1 + (tan(pi fc dt)/tan(pi f dt))^4)        (corner pre-warped);
// the late-time sample maximum may miss the crest by up to 1 - cos(pi f dt).
TEST(GroundMotionStreaming, VelocityFilterIsButterworthHighPassedIntegral) {
  const double dt = 0.01, fc = 0.1, A = 1.0;
  for (double f : {0.1, 0.3, 2.0, 7.0}) {
    rmc::StreamingIntensityConfig cfg;
    cfg.dt = dt;
    cfg.periods = {1.0};
    cfg.velocity_highpass_hz = fc;
    rmc::StreamingIntensity stream(cfg);
    double late = 0.0;
    const int n = static_cast<int>(std::lround(200.0 / dt));
    for (int i = 0; i < n; ++i) {
      stream.push(A * std::sin(2.0 * kPi * f * dt * i));
      if (i * dt > 150.0) late = std::max(late, std::abs(stream.velocity()));
    }
    const double tan_f = std::tan(kPi * f * dt), tan_c = std::tan(kPi * fc * dt);
    const double digital = A * (dt / 2.0) / tan_f / std::sqrt(1.0 + std::pow(tan_c / tan_f, 4.0));
    const double crest_miss = 1.0 - std::cos(kPi * f * dt);
    EXPECT_LE(late / digital, 1.0 + 1e-9) << "f = " << f;
    EXPECT_GE(late / digital, 1.0 - crest_miss - 1e-9) << "f = " << f;
    // and the analog target, to the bilinear warping (pi f dt)^2/3 plus the crest miss
    const double analog = A / (2.0 * kPi * f) / std::sqrt(1.0 + std::pow(fc / f, 4.0));
    EXPECT_NEAR(late / analog, 1.0, std::pow(kPi * f * dt, 2.0) / 3.0 * 1.1 + crest_miss) << "f = " << f;
  }
}

TEST(GroundMotionStreaming, ResetReproducesAndBuffersStayPut) {
  const rmc::Component comp = ricker_component(1.0, 2.0, 3.0, 0.01, 10.0);
  rmc::StreamingIntensityConfig cfg;
  cfg.dt = comp.dt;
  cfg.periods = rmc::log_spaced_periods(0.05, 5.0, 20);
  rmc::StreamingIntensity stream(cfg);
  const double* psv_data = stream.psv().data();
  for (double a : comp.accel) stream.push(a);
  const std::vector<double> first = stream.psv();
  const double pgv = stream.pgv(), pga = stream.pga();
  EXPECT_GT(pgv, 0.0);

  stream.reset();
  EXPECT_EQ(stream.sample_count(), 0u);
  EXPECT_EQ(stream.pga(), 0.0);
  EXPECT_EQ(stream.pgv(), 0.0);
  EXPECT_EQ(max_abs(stream.psv()), 0.0);
  for (double a : comp.accel) stream.push(a);
  EXPECT_EQ(stream.psv(), first);
  EXPECT_EQ(stream.pgv(), pgv);
  EXPECT_EQ(stream.pga(), pga);
  EXPECT_EQ(stream.psv().data(), psv_data);  // updated in place, never reallocated
}

TEST(GroundMotionStreaming, RejectsInvalidConfigurationAndSamples) {
  rmc::StreamingIntensityConfig cfg;
  EXPECT_THROW(rmc::StreamingIntensity{cfg}, std::invalid_argument);  // dt unset
  cfg.dt = 0.01;
  cfg.velocity_highpass_hz = 60.0;  // above Nyquist (50 Hz)
  EXPECT_THROW(rmc::StreamingIntensity{cfg}, std::invalid_argument);
  cfg.velocity_highpass_hz = 0.0;
  EXPECT_THROW(rmc::StreamingIntensity{cfg}, std::invalid_argument);
  cfg.velocity_highpass_hz = 0.1;
  cfg.periods = {1.0, -2.0};
  EXPECT_THROW(rmc::StreamingIntensity{cfg}, std::invalid_argument);
  cfg.periods = {1.0};
  cfg.damping = 1.0;
  EXPECT_THROW(rmc::StreamingIntensity{cfg}, std::invalid_argument);
  cfg.damping = 0.05;
  rmc::StreamingIntensity stream(cfg);
  stream.push(0.5);
  EXPECT_THROW(stream.push(std::nan("")), std::invalid_argument);
  EXPECT_EQ(stream.sample_count(), 1u);
  EXPECT_EQ(stream.pga(), 0.5);
}

}  // namespace
