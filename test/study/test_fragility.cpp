// Lognormal fragility fitting: closed forms (normal quantiles), exact recovery from exact
// probabilities, and the coverage of the bootstrap band on synthetic outcomes of a known fragility.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "rocking_monitor/study/fragility.hpp"
#include "rocking_monitor/study/study_error.hpp"

namespace rocking_monitor::core::study {
namespace {

double unit(std::mt19937_64& e) { return static_cast<double>(e() >> 11) * 0x1.0p-53; }

TEST(Fragility, ExactProbabilitiesGiveTheParametersBack) {
  // Fractional outcomes equal to a lognormal's probabilities: the MLE is that lognormal.
  for (auto [median, beta] : {std::pair{0.35, 0.4}, std::pair{1.2, 0.25}, std::pair{0.08, 0.8}}) {
    std::vector<FragilityPoint> pts;
    for (int i = 0; i < 15; ++i) {
      const double im = median * std::exp((i - 7) * 0.25 * beta);
      pts.push_back({im, 10.0 * normal_cdf(std::log(im / median) / beta), 10.0});
    }
    const LognormalFragility f = fit_lognormal_fragility(pts);
    EXPECT_TRUE(f.converged);
    EXPECT_NEAR(f.median / median, 1.0, 1e-9);
    EXPECT_NEAR(f.beta / beta, 1.0, 1e-9);
    EXPECT_NEAR(f.probability(median), 0.5, 1e-9);
  }
}

TEST(Fragility, BootstrapBandCoversTheTrueMedianAndBeta) {
  const double median = 0.3, beta = 0.4;  // e.g. PGV in m/s
  int covered_median = 0, covered_beta = 0, trials = 0;
  std::mt19937_64 e(20261123);
  for (int t = 0; t < 100; ++t) {
    std::vector<FragilityPoint> pts;
    for (int i = 0; i < 250; ++i) {
      const double im = 0.05 * std::pow(2.0 / 0.05, unit(e));  // log-uniform 0.05-2 m/s
      pts.push_back({im, unit(e) < normal_cdf(std::log(im / median) / beta) ? 1.0 : 0.0, 1.0});
    }
    const FragilityBand band = bootstrap_fragility(pts, {0.1, 0.3, 1.0}, 150, 1000 + t);
    ASSERT_GE(band.resamples, 145);
    covered_median += band.median_lower <= median && median <= band.median_upper;
    covered_beta += band.beta_lower <= beta && beta <= band.beta_upper;
    ++trials;
    for (std::size_t g = 0; g < band.im.size(); ++g) EXPECT_LE(band.lower[g], band.upper[g]);
  }
  std::printf("[ measured ] 95 %% bootstrap band holds the true median in %d/%d trials, beta in %d/%d\n",
              covered_median, trials, covered_beta, trials);
  EXPECT_GE(covered_median, 90);
  EXPECT_GE(covered_beta, 90);
}

TEST(Fragility, SameSeedSameBand) {
  std::vector<FragilityPoint> pts;
  for (int i = 0; i < 30; ++i) pts.push_back({0.05 * (i + 1), i % 3 == 0 || i > 20 ? 1.0 : 0.0, 1.0});
  const FragilityBand a = bootstrap_fragility(pts, {0.5}, 100, 7), b = bootstrap_fragility(pts, {0.5}, 100, 7);
  EXPECT_EQ(a.median_lower, b.median_lower);
  EXPECT_EQ(a.upper, b.upper);
}

TEST(Fragility, SeparableOutcomesHaveNoMaximumAndSaySo) {
  const std::vector<FragilityPoint> pts = {{0.1, 0, 1}, {0.2, 0, 1}, {0.4, 1, 1}, {0.8, 1, 1}};
  const LognormalFragility f = fit_lognormal_fragility(pts);
  EXPECT_FALSE(f.converged);
  EXPECT_EQ(f.beta, 0.0);
  EXPECT_NEAR(f.median, std::sqrt(0.2 * 0.4), 1e-15);
  EXPECT_EQ(f.probability(0.3), 1.0);
  EXPECT_EQ(f.probability(0.25), 0.0);
}

TEST(Fragility, PointsThatDefineNoFragilityAreErrors) {
  EXPECT_THROW(fit_lognormal_fragility({}), StudyError);
  EXPECT_THROW(fit_lognormal_fragility({{0.1, 1, 1}, {0.2, 1, 1}}), StudyError);  // all overturned
  EXPECT_THROW(fit_lognormal_fragility({{0.1, 0, 1}, {0.2, 0, 1}}), StudyError);  // none
  EXPECT_THROW(fit_lognormal_fragility({{0.0, 1, 1}, {0.2, 0, 1}}), StudyError);  // IM 0
  EXPECT_THROW(fit_lognormal_fragility({{0.1, 2, 1}, {0.2, 0, 1}}), StudyError);  // failures > trials
  EXPECT_THROW(bootstrap_fragility({{0.1, 0.5, 1}, {0.2, 0, 1}}, {0.1}, 10, 1), StudyError);  // not whole runs
}

}  // namespace
}  // namespace rocking_monitor::core::study
