// The fragility study: each run is the study's own case on the scaled record, the records land
// exactly on the PGV levels, threads do not change the result, and the fit follows the runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "rocking_monitor/motion/component.hpp"
#include "rocking_monitor/study/fragility_io.hpp"
#include "rocking_monitor/study/fragility_study.hpp"
#include "rocking_monitor/study/study_runner.hpp"

namespace rocking_monitor::core::study {
namespace {

// One-sine pulses of different frequencies: a record set whose PGV is known and positive.
std::vector<StudyRecord> pulses() {
  std::vector<StudyRecord> out;
  for (double f : {0.7, 1.0, 1.6, 2.5}) {
    Component c;
    c.dt = 0.005;
    c.label = "H";
    c.file = "pulse_" + std::to_string(f);
    for (int i = 0; i <= 1200; ++i) {
      const double t = i * c.dt;
      c.accel.push_back(t <= 1.0 / f ? 3.0 * std::sin(2.0 * 3.141592653589793 * f * t) : 0.0);
    }
    out.push_back(make_study_record(c, nullptr, "pulses", c.file, "H", c.file));
  }
  return out;
}

std::vector<StudyBody> bodies() {
  std::vector<StudyBody> b(2);
  b[0].name = "vase";
  b[0].parameters.width = 0.15;
  b[0].parameters.cg_height = 0.35;
  b[1].name = "shelf";
  b[1].parameters.width = 0.3;
  b[1].parameters.cg_height = 0.9;
  b[1].parameters.nu1 = 0.3;
  return b;
}

TEST(FragilityStudy, RunsAreTheStudysCasesOnRecordsScaledToThePgvLevels) {
  const std::vector<StudyRecord> recs = pulses();
  FragilityOptions o;
  o.levels = 6;
  o.pgv_min = 0.05;
  o.pgv_max = 1.5;
  o.bootstrap = 50;
  o.threads = 1;
  const FragilityResult r = run_fragility(bodies(), recs, o);
  ASSERT_EQ(r.runs.size(), 2u * recs.size() * 2u * 6u);
  const std::vector<double> levels = geometric_spacing(0.05, 1.5, 6);
  std::size_t fell = 0;
  for (const FragilityRun& run : r.runs) {
    // The IM of a run is its PGV level (the scale makes it so; scaling is linear).
    const std::size_t l = static_cast<std::size_t>(std::lround(std::log(run.im / 0.05) / std::log(1.5 / 0.05) * 5));
    EXPECT_NEAR(run.im / levels[l], 1.0, 1e-12);
    // The outcome is run_case's on the scaled record.
    StudyRecord s = recs[run.record];
    for (double& a : s.horizontal) a *= run.scale;
    for (double& a : s.corrected) a *= run.scale;
    s.pga *= run.scale;
    s.pgv *= run.scale;
    const CaseResult c = run_case(Body(bodies()[run.body].parameters), s, run.polarity, true, o.settings, std::nan(""));
    EXPECT_EQ(c.outcome.overturned, run.overturned);
    fell += run.overturned;
  }
  EXPECT_GT(fell, 0u);
  EXPECT_LT(fell, r.runs.size());
  // Two threads: the same runs, the same fits.
  o.threads = 2;
  const FragilityResult r2 = run_fragility(bodies(), recs, o);
  ASSERT_EQ(r2.runs.size(), r.runs.size());
  for (std::size_t i = 0; i < r.runs.size(); ++i) EXPECT_EQ(r2.runs[i].overturned, r.runs[i].overturned);
  for (std::size_t b = 0; b < r.bodies.size(); ++b) {
    EXPECT_EQ(r2.bodies[b].fit.median, r.bodies[b].fit.median);
    EXPECT_EQ(r2.bodies[b].band.upper, r.bodies[b].band.upper);
  }
  // The fit is the maximum of the runs' likelihood: moving the median or beta by 2 % lowers it.
  for (const BodyFragility& f : r.bodies) {
    ASSERT_TRUE(f.fitted) << f.note;
    auto ll = [&](double median, double beta) {
      LognormalFragility g = f.fit;
      g.median = median;
      g.beta = beta;
      double sum = 0.0;
      for (const FragilityRun& run : r.runs) {
        if (run.body != f.body) continue;
        const double p = std::clamp(g.probability(run.im), 1e-300, 1.0 - 1e-16);
        sum += run.overturned ? std::log(p) : std::log1p(-p);
      }
      return sum;
    };
    const double best = ll(f.fit.median, f.fit.beta);
    EXPECT_NEAR(best, f.fit.log_likelihood, 1e-9 * std::abs(best));
    for (double dm : {0.98, 1.02})
      for (double db : {0.98, 1.0, 1.02}) EXPECT_LT(ll(f.fit.median * dm, f.fit.beta * db), best);
    std::printf("[ measured ] %s: median PGV %.3f m/s (Ishiyama %.3f: ratio %.2f), beta %.2f, %zu non-monotone pairs\n",
                bodies()[f.body].name.c_str(), f.fit.median, f.thresholds.ishiyama.velocity,
                f.fit.median / f.thresholds.ishiyama.velocity, f.fit.beta, f.non_monotone);
  }
}

TEST(FragilityStudy, ThresholdsInTheIntensityMeasure) {
  ScreeningThresholds t;
  t.housner_pseudo_velocity = 0.4;
  t.ishiyama = {0.3, 2.0};
  EXPECT_EQ(thresholds_in(t, IntensityMeasure::Pgv).front().second, 0.3);
  EXPECT_EQ(thresholds_in(t, IntensityMeasure::Pga).front().second, 2.0);
  EXPECT_EQ(thresholds_in(t, IntensityMeasure::Psv).front().second, 0.4);
  EXPECT_THROW(parse_intensity_measure("sa"), StudyError);
}

}  // namespace
}  // namespace rocking_monitor::core::study
