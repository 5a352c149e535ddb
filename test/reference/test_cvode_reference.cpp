// Independent cross-check of the package's reference integrator: dopri5 at tight tolerance
// against SUNDIALS CVODE (Adams, rtol = atol = 1e-13) driving the same hybrid model
// (cvode_rocking.hpp: its own equations, event roots, impact law and rest capture) on free
// rocking, one-sine pulses near the overturning boundary and real records.
//
// Agreement asserted, sample by sample (dopri5 tol = 1e-10):
//   * the same number of impacts, the same uplift and the same rest captures in every sample;
//   * the first impact time of every sample within kTimeTol = 1e-7 s, overturn time within 1e-7 s;
//   * the largest local maximum of |theta|/alpha in every sample within kRatioTol = 1e-6, the run's
//     max |theta|/alpha within 1e-6, the uplift time within 1e-12 s, the same overturn decision
//     (local maxima below 1e-3 alpha are not compared, see kPeakFloor).
// Free rocking, pulses and the Rinaldi record must agree over the whole run. Long records that
// keep a body rocking near rest excite a sensitive (chaotic) response: differences of 1e-10 s grow
// past 1e-7 s within a few seconds of near-grazing impacts, so those must agree on every sample
// up to a stated number of impacts (20) and on the outcome of the whole record (overturn
// decision, max |theta|/alpha within 0.1 %). The measured worst differences and the agreement
// horizon are printed (docs/performance.md quotes them).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "bench_common.hpp"
#include "cvode_rocking.hpp"
#include "rocking_monitor/model/rocking_model.hpp"

#ifndef ROCKING_RECORDS_DIR
#define ROCKING_RECORDS_DIR "../shared/records"
#endif

namespace rocking_monitor {
namespace {

namespace rb = bench;
using namespace core;
using reference::CvodeResult;
using reference::CvodeRocking;
using reference::SampleSummary;

constexpr double kTimeTol = 1e-7;   // s
constexpr double kRatioTol = 1e-6;  // |theta|/alpha
// Local maxima of |theta| below 1e-3 alpha are not compared: an excursion that small (a few
// microradians) can rise and fall back inside one integrator step, where neither method is
// required to report it (event detection looks at the sign of omega at the step ends).
constexpr double kPeakFloor = 1e-3;
constexpr double kDopriTol = 1e-10;
constexpr double kCvodeRtol = 1e-13;
constexpr double kCvodeAtol = 1e-13;  // x alpha (theta) and x p alpha (omega)

struct CoreRun {
  std::vector<SampleSummary> samples;
  RockingOutcome outcome;
};

CoreRun run_core(const Body& body, ModelKind model, const GroundMotion& g, double theta0) {
  SolverSettings s;
  s.method = Method::Dopri5;
  s.model = model;
  s.tol = kDopriTol;
  RockingModel m(body, s);
  m.reset(g.t0, g.horizontal[0], g.ay(0));
  if (theta0 != 0.0) m.set_state(theta0, 0.0);
  CoreRun r;
  for (std::size_t k = 1; k < g.size(); ++k) {
    const StepReport& rep = m.step(g.horizontal[k], g.ay(k), g.dt);
    SampleSummary sum;
    sum.impacts = rep.impacts;
    sum.first_impact_time = rep.first_impact_time;
    sum.peak_ratio = rep.peak_ratio;
    sum.uplift = rep.uplift;
    sum.rest_capture = rep.rest_capture;
    r.samples.push_back(sum);
    if (m.mode() == Mode::Overturned) break;
  }
  r.outcome = m.outcome();
  return r;
}

struct Agreement {
  double max_dt_impact = 0.0;  ///< over the compared samples, s
  double max_d_peak = 0.0;     ///< over the compared samples, |theta|/alpha
  long impacts = 0;            ///< impacts inside the compared samples
  long peaks = 0;
  /// End time of the last sample before the first disagreement beyond the tolerances (or of the
  /// whole run when they agree throughout).
  double horizon = 0.0;
  bool whole_run = true;
};

bool same_sample(const SampleSummary& x, const SampleSummary& y) {
  if (x.impacts != y.impacts || x.rest_capture != y.rest_capture || x.uplift != y.uplift) return false;
  if (x.impacts > 0 && !(std::abs(x.first_impact_time - y.first_impact_time) <= kTimeTol)) return false;
  if (std::max(x.peak_ratio, y.peak_ratio) < kPeakFloor) return true;
  return std::abs(x.peak_ratio - y.peak_ratio) <= kRatioTol;
}

// Walks the two runs sample by sample up to the first disagreement.
Agreement agreement(const CoreRun& a, const CvodeResult& b, const GroundMotion& g) {
  Agreement ag;
  ag.horizon = g.t0;
  const std::size_t n = std::min(a.samples.size(), b.samples.size());
  for (std::size_t k = 0; k < n; ++k) {
    const SampleSummary& x = a.samples[k];
    const SampleSummary& y = b.samples[k];
    if (!same_sample(x, y)) {
      ag.whole_run = false;
      std::printf("[ first difference ] sample ending %.4f s: dopri5 %d impacts (first %.9f, peak "
                  "%.7f, rest %d, uplift %d), CVODE %d (first %.9f, peak %.7f, rest %d, uplift %d)\n",
                  g.t0 + static_cast<double>(k + 1) * g.dt, x.impacts, x.first_impact_time,
                  x.peak_ratio, x.rest_capture, x.uplift, y.impacts, y.first_impact_time,
                  y.peak_ratio, y.rest_capture, y.uplift);
      break;
    }
    ag.horizon = g.t0 + static_cast<double>(k + 1) * g.dt;
    ag.impacts += y.impacts;
    if (x.impacts > 0)
      ag.max_dt_impact = std::max(ag.max_dt_impact, std::abs(x.first_impact_time - y.first_impact_time));
    if (std::max(x.peak_ratio, y.peak_ratio) >= kPeakFloor) {
      ++ag.peaks;
      ag.max_d_peak = std::max(ag.max_d_peak, std::abs(x.peak_ratio - y.peak_ratio));
    }
  }
  if (a.samples.size() != b.samples.size()) ag.whole_run = false;
  return ag;
}

/// Runs both and checks that they agree on every sample up to at least `min_impacts` impacts,
/// or over the whole run (and on the outcome) when min_impacts < 0.
Agreement cross_check(const std::string& what, const Body& body, ModelKind model,
                      const GroundMotion& g, double theta0 = 0.0, long min_impacts = -1) {
  const CoreRun a = run_core(body, model, g, theta0);
  CvodeRocking cv(body, model, kCvodeRtol, kCvodeAtol);
  const CvodeResult b = cv.run(g, theta0);
  const Agreement ag = agreement(a, b, g);
  std::printf("[ agreement ] %-38s %s %7.3f s: %3ld of %3zu impacts (max |dt| %.1e s), %3ld "
              "peaks (max |d theta/alpha| %.1e); overturned %d/%d; max ratio %.8f/%.8f\n",
              what.c_str(), ag.whole_run ? "whole run" : "until    ", ag.horizon, ag.impacts,
              b.impact_times.size(), ag.max_dt_impact, ag.peaks, ag.max_d_peak,
              a.outcome.overturned, b.overturned, a.outcome.max_rotation_ratio, b.max_ratio);
  EXPECT_LE(ag.max_dt_impact, kTimeTol) << what;
  EXPECT_LE(ag.max_d_peak, kRatioTol) << what;
  if (min_impacts < 0) {
    EXPECT_TRUE(ag.whole_run) << what << ": runs differ after " << ag.horizon << " s";
    EXPECT_EQ(a.outcome.overturned, b.overturned) << what;
    if (a.outcome.overturned && b.overturned) {
      EXPECT_NEAR(a.outcome.overturn_time, b.overturn_time, kTimeTol) << what;
    }
    EXPECT_EQ(a.outcome.impacts, static_cast<long>(b.impact_times.size())) << what;
    EXPECT_EQ(a.outcome.rest_captures, b.rest_captures) << what;
    EXPECT_NEAR(a.outcome.max_rotation_ratio, b.max_ratio, kRatioTol) << what;
    if (!std::isnan(b.uplift_time) || !std::isnan(a.outcome.uplift_time)) {
      EXPECT_NEAR(a.outcome.uplift_time, b.uplift_time, 1e-12) << what;
    }
  } else {
    EXPECT_GE(ag.impacts, std::min<long>(min_impacts, static_cast<long>(b.impact_times.size())))
        << what << ": agreement lost after " << ag.horizon << " s";
    // Beyond the horizon the runs may separate, but not on these cases' outcome.
    EXPECT_EQ(a.outcome.overturned, b.overturned) << what;
    EXPECT_NEAR(a.outcome.max_rotation_ratio, b.max_ratio, 1e-3 * b.max_ratio) << what;
  }
  return ag;
}

// ------------------------------------------------------------------ free rocking
// NOTES.md example: p = 2 rad/s, alpha = 15 deg, released at alpha/2: 64 impacts then rest
// capture (the Zeno tail has impacts under 1 ms apart, several per 5 ms sample).
TEST(CvodeReference, FreeRockingNonlinearUntilRest) {
  const Body body(rb::rectangle_with(2.0, rb::deg(15)));
  const GroundMotion g = rb::zeros(0.005, 12.0);
  const Agreement ag = cross_check("free rocking, nonlinear", body, ModelKind::Nonlinear, g,
                                   0.5 * rb::deg(15));
  EXPECT_EQ(ag.impacts, 64);
}

TEST(CvodeReference, FreeRockingLinearizedUntilRest) {
  const Body body(rb::rectangle_with(2.0, rb::deg(15)));
  const Agreement ag = cross_check("free rocking, linearized", body, ModelKind::Linearized,
                                   rb::zeros(0.005, 12.0), 0.5 * rb::deg(15));
  EXPECT_EQ(ag.impacts, 64);
}

TEST(CvodeReference, FreeRockingEccentricBody) {
  // nu1 = 0.4: alpha, p and the eq. 34 ratio differ between the two corners.
  BodyParameters bp;
  bp.width = 0.5;
  bp.cg_height = 0.9;
  bp.nu1 = 0.4;
  const Body body(bp);
  const Agreement ag = cross_check("free rocking, eccentric", body, ModelKind::Nonlinear,
                                   rb::zeros(0.005, 8.0), -0.3 * body.pivot(-1).alpha);
  EXPECT_GT(ag.impacts, 20);
}

// ------------------------------------------------------------------ one-sine pulses
class CvodePulse : public ::testing::TestWithParam<std::tuple<ModelKind, double, double>> {};

TEST_P(CvodePulse, ImpactsPeaksAndOverturnAgree) {
  const auto [model, wp, factor] = GetParam();
  const double p = 2.5, alpha = rb::deg(12), w = wp * p;
  const Body body(rb::rectangle_with(p, alpha));
  const double ap = factor * rb::pulse_min_amplitude_ratio(wp) * alpha * kGravity;
  const GroundMotion g = rb::one_sine_pulse(ap, w, 0.005, 2.0 * kPi / w + 10.0);
  char what[96];
  std::snprintf(what, sizeof what, "pulse %s wp/p=%g a=%.3f a_min", to_string(model), wp, factor);
  cross_check(what, body, model, g);
}

INSTANTIATE_TEST_SUITE_P(
    NearBoundary, CvodePulse,
    ::testing::Combine(::testing::Values(ModelKind::Nonlinear, ModelKind::Linearized),
                       ::testing::Values(2.0, 4.0), ::testing::Values(0.997, 1.003, 1.3)),
    [](const auto& info) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%s_wp%d_a%04d", to_string(std::get<0>(info.param)),
                    static_cast<int>(std::get<1>(info.param)),
                    static_cast<int>(std::lround(1000 * std::get<2>(info.param))));
      return std::string(buf);
    });

// ------------------------------------------------------------------ real records
std::string records_dir() {
  if (const char* env = std::getenv("ROCKING_RECORDS_DIR")) return env;
  return ROCKING_RECORDS_DIR;
}

TEST(CvodeReference, RealRecordRinaldiWithVertical) {
  const std::string dir = records_dir() + "/northridge_1994";
  if (!std::filesystem::exists(dir + "/Rinaldi228.AT2")) {
    GTEST_SKIP() << "records not found in " << records_dir() << " (set ROCKING_RECORDS_DIR)";
  }
  const std::vector<Component> h = read_record(dir + "/Rinaldi228.AT2");
  const std::vector<Component> v = read_record(dir + "/RinaldiUP.AT2");
  const GroundMotion g = make_ground_motion(h.front(), &v.front(), 1.0);
  BodyParameters bp;  // eccentric cabinet: 0.4 m x 1.2 m, nu1 = 0.4
  bp.width = 0.4;
  bp.cg_height = 0.6;
  bp.nu1 = 0.4;
  const Body body(bp);
  cross_check("Rinaldi 228 + UP, nonlinear", body, ModelKind::Nonlinear, g);
  cross_check("Rinaldi 228 + UP, linearized", body, ModelKind::Linearized, g);
}

TEST(CvodeReference, RealRecordsSeveralBodies) {
  const std::string dir = records_dir();
  const std::vector<std::string> files = {
      "landers_1992/RSN879_LANDERS_LCN345.AT2",
      "imperial_valley_1979/RSN180_IMPVALL.H_H-E05140.AT2",
      "kobe_1995/RSN1120_KOBE_TAK090.AT2",
  };
  if (!std::filesystem::exists(dir + "/" + files.front())) {
    GTEST_SKIP() << "records not found in " << dir << " (set ROCKING_RECORDS_DIR)";
  }
  const std::vector<std::pair<double, double>> bodies = {{0.3, 0.6}, {0.6, 0.9}};  // B, h
  for (const std::string& f : files) {
    const GroundMotion g = rb::load_record(dir + "/" + f);
    for (const auto& [b, h] : bodies) {
      BodyParameters bp;
      bp.width = b;
      bp.cg_height = h;
      char what[128];
      std::snprintf(what, sizeof what, "%s B=%.1f h=%.1f",
                    std::filesystem::path(f).stem().string().c_str(), b, h);
      cross_check(what, Body(bp), ModelKind::Nonlinear, g, 0.0, 20);
    }
  }
}

}  // namespace
}  // namespace rocking_monitor
