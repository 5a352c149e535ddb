// Distribution (issue 13): quantiles against closed forms, the truncated normal, zero spread, and the
// validation messages that name the field.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "rocking_monitor/physics/parameter_distribution.hpp"

namespace rocking_monitor::core {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kZ975 = 1.959963984540054;  // Phi^-1(0.975)
const ValueRange kUnit{0.0, 1.0, true, true};
const ValueRange kPositive{0.0, kInf, true, true};

TEST(InverseNormalCdf, KnownPoints) {
  // Phi^-1 at tabulated points (to 16 digits; e.g. Wichura 1988, AS241's test values).
  EXPECT_NEAR(inverse_normal_cdf(0.975), kZ975, 1e-12);
  EXPECT_NEAR(inverse_normal_cdf(0.025), -kZ975, 1e-12);
  EXPECT_NEAR(inverse_normal_cdf(0.9), 1.2815515655446004, 1e-12);
  EXPECT_NEAR(inverse_normal_cdf(0.99), 2.3263478740408408, 1e-12);
  EXPECT_NEAR(inverse_normal_cdf(0.999), 3.090232306167813, 1e-12);
  EXPECT_NEAR(inverse_normal_cdf(0.8413447460685429), 1.0, 1e-12);  // Phi(1)
  EXPECT_EQ(inverse_normal_cdf(0.5), 0.0);
  EXPECT_EQ(inverse_normal_cdf(0.0), -kInf);
  EXPECT_EQ(inverse_normal_cdf(1.0), kInf);
  EXPECT_TRUE(std::isnan(inverse_normal_cdf(-0.1)));
  // Round trip over the whole lower tail, relative to p (erfc is accurate there): 1e-300 .. 0.5. The
  // bound is what x's own rounding allows: dp / p = |x| dx, |x| up to 37, dx half an ulp of x.
  for (double p = 1e-300; p < 0.5; p *= 1.7) EXPECT_NEAR(normal_cdf(inverse_normal_cdf(p)) / p, 1.0, 2e-12) << p;
  EXPECT_TRUE(std::isfinite(inverse_normal_cdf(0x1.0p-1074)));  // the smallest u a quantile is given
  // x -> Phi(x) -> x in the lower tail (above the mean Phi(x) rounds near 1: ill-conditioned there, so
  // the upper half is checked by the symmetry Phi^-1(1 - p) = -Phi^-1(p), 1 - p exact for p >= 1/4).
  for (double x = -8.0; x <= 0.0; x += 0.125) EXPECT_NEAR(inverse_normal_cdf(normal_cdf(x)), x, 1e-12) << x;
  for (double p = 0.25; p < 0.5; p += 0.01) EXPECT_EQ(inverse_normal_cdf(1.0 - p), -inverse_normal_cdf(p)) << p;
}

TEST(Distribution, UniformQuantileIsLinear) {
  const Distribution d = Distribution::uniform(0.25, 0.4, {0.0, kInf, false, true});
  for (double u : {0.1, 0.5, 0.75, 0.999}) EXPECT_NEAR(d.quantile(u), 0.25 + u * 0.15, 1e-16);
  EXPECT_DOUBLE_EQ(d.nominal(), 0.325);
  EXPECT_DOUBLE_EQ(d.with_nominal(0.3).nominal(), 0.3);
  EXPECT_EQ(d.quantile(0.0), 0.25);  // u kept inside (0, 1): 0.25 + 5e-324 * 0.15 rounds to 0.25
  EXPECT_NEAR(d.cdf(0.3), (0.3 - 0.25) / 0.15, 1e-15);
}

TEST(Distribution, LognormalMedianAndTail) {
  const Distribution d = Distribution::lognormal(0.9, 0.3, kPositive);
  EXPECT_NEAR(d.quantile(0.5), 0.9, 1e-15);
  EXPECT_NEAR(d.quantile(0.975) / (0.9 * std::exp(0.3 * kZ975)), 1.0, 1e-12);
  EXPECT_NEAR(d.quantile(0.025) / (0.9 * std::exp(-0.3 * kZ975)), 1.0, 1e-12);
  EXPECT_NEAR(d.nominal(), 0.9 * std::exp(0.045), 1e-15);  // the mean
  EXPECT_NEAR(d.cdf(0.9 * std::exp(0.3)), normal_cdf(1.0), 1e-15);
}

TEST(Distribution, NormalQuantile) {
  const Distribution d = Distribution::normal(1.0, 0.1, kPositive);  // truncation at 10 sd: negligible
  EXPECT_NEAR(d.quantile(0.975), 1.0 + 0.1 * kZ975, 1e-12);
  EXPECT_NEAR(d.quantile(0.5), 1.0, 1e-15);
  EXPECT_NEAR(d.quantile(0.9), 1.0 + 0.1 * 1.2815515655446004, 1e-12);
}

TEST(Distribution, TruncatedNormalStaysInItsRange) {
  // Symmetric truncation of N(0.5, 0.3^2) to (0, 1): the median stays 0.5.
  const Distribution d = Distribution::normal(0.5, 0.3, kUnit);
  EXPECT_NEAR(d.quantile(0.5), 0.5, 1e-15);
  for (double u = 0.0; u <= 1.0; u += 1.0 / 1024) {
    const double x = d.quantile(u);
    EXPECT_TRUE(x > 0.0 && x < 1.0) << u << " -> " << x;
  }
  EXPECT_GT(d.quantile(0.0), 0.0);
  EXPECT_LT(d.quantile(1.0), 1.0);
  // The CDF of the truncated law: (Phi(z) - Phi(a)) / (Phi(b) - Phi(a)).
  const double a = normal_cdf(-0.5 / 0.3), b = normal_cdf(0.5 / 0.3);
  EXPECT_NEAR(d.cdf(0.7), (normal_cdf(0.2 / 0.3) - a) / (b - a), 1e-15);
  for (double u = 0.01; u < 1.0; u += 0.01) EXPECT_NEAR(d.cdf(d.quantile(u)), u, 1e-12);
  // Asymmetric, deep in the upper tail (N(0, 1) on [5, 6]): the survival side keeps the precision.
  const Distribution tail = Distribution::normal(0.0, 1.0, {5.0, 6.0, false, false});
  for (double u = 0.01; u < 1.0; u += 0.01) {
    const double x = tail.quantile(u);
    EXPECT_TRUE(x >= 5.0 && x <= 6.0);
    EXPECT_NEAR(tail.cdf(x), u, 1e-10);
  }
  // Its median in closed form: Q(x) = (Q(5) + Q(6)) / 2 with Q the survival function.
  EXPECT_NEAR(tail.quantile(0.5), -inverse_normal_cdf(0.5 * (normal_cdf(-5.0) + normal_cdf(-6.0))), 1e-12);
  // Restitution near 1 with a lognormal: truncated to [0, 1].
  const Distribution e = Distribution::lognormal(0.95, 0.1, {0.0, 1.0, false, false});
  for (double u = 0.0; u <= 1.0; u += 1.0 / 256) EXPECT_LE(e.quantile(u), 1.0);
  EXPECT_NEAR(e.cdf(e.quantile(0.3)), 0.3, 1e-12);
}

TEST(Distribution, ZeroSpreadIsExactlyTheValue) {
  const Distribution n = Distribution::normal(0.3, 0.0, {0.0, kInf, false, true});
  const Distribution u = Distribution::uniform(0.7, 0.7, kPositive);
  const Distribution l = Distribution::lognormal(0.45, 0.0, kPositive);
  for (double p : {0.0, 1e-9, 0.5, 0.999, 1.0}) {
    EXPECT_EQ(n.quantile(p), 0.3);
    EXPECT_EQ(u.quantile(p), 0.7);
    EXPECT_EQ(l.quantile(p), 0.45);
  }
  EXPECT_EQ(n.nominal(), 0.3);
  EXPECT_EQ(u.nominal(), 0.7);
  EXPECT_EQ(l.nominal(), 0.45);
  EXPECT_TRUE(n.degenerate() && u.degenerate() && l.degenerate());
  EXPECT_EQ(validate(n, "mu_s"), "");
  EXPECT_EQ(validate(u, "width"), "");
  EXPECT_EQ(validate(l, "cg_height"), "");
}

TEST(Distribution, ValidationNamesTheField) {
  const ValueRange friction{0.0, kInf, false, true};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(validate(Distribution::uniform(0.6, 0.3, friction), "mu_s"), "mu_s: uniform: lo 0.6 > hi 0.3");
  EXPECT_EQ(validate(Distribution::uniform(0.0, 0.5, kUnit), "eccentricity"), "eccentricity: uniform: lo 0 outside (0, 1)");
  EXPECT_EQ(validate(Distribution::uniform(0.5, 1.0, kUnit), "eccentricity"), "eccentricity: uniform: hi 1 outside (0, 1)");
  EXPECT_EQ(validate(Distribution::uniform(nan, 1.0, friction), "mu_s"), "mu_s: uniform: lo nan is not a finite number");
  EXPECT_EQ(validate(Distribution::normal(0.9, -0.1, kPositive), "width"), "width: normal: sd -0.1 < 0");
  EXPECT_EQ(validate(Distribution::normal(kInf, 0.1, kPositive), "width"), "width: normal: mean inf is not a finite number");
  EXPECT_EQ(validate(Distribution::lognormal(0.0, 0.3, kPositive), "cg_height"), "cg_height: lognormal: median 0 <= 0");
  EXPECT_EQ(validate(Distribution::lognormal(0.9, -1.0, kPositive), "cg_height"), "cg_height: lognormal: beta -1 < 0");
  EXPECT_EQ(validate(Distribution::uniform(0.25, 0.4, friction).with_nominal(0.5), "mu_s"),
            "mu_s: uniform: nominal 0.5 outside [0.25, 0.4]");
  EXPECT_EQ(validate(Distribution::normal(-0.1, 0.2, friction), "mu_s"),
            "mu_s: normal: nominal -0.1 outside [0, inf) (the law's mean; give nominal: to choose another)");
  EXPECT_EQ(validate(Distribution::normal(-0.1, 0.2, friction).with_nominal(0.05), "mu_s"), "");  // half-normal-like
  EXPECT_EQ(validate(Distribution::normal(0.3, 0.0, friction).with_nominal(0.4), "mu_s"),
            "mu_s: normal: nominal 0.4 outside {0.3} (zero spread)");
  EXPECT_EQ(validate(Distribution::normal(-0.5, 0.0, friction), "mu_s"), "mu_s: normal: mean -0.5 outside [0, inf)");
  EXPECT_EQ(validate(Distribution::normal(-50.0, 1.0, friction).with_nominal(0.1), "mu_s"),
            "mu_s: normal: no probability left inside [0, inf) (the law is truncated to it)");
  EXPECT_EQ(validate(Distribution::lognormal(0.9, 1.0, kUnit), "eccentricity"),
            "eccentricity: lognormal: nominal 1.48384914363 outside (0, 1) (the law's mean; give nominal: to choose another)");
  EXPECT_EQ(validate(Distribution::lognormal(0.9, 1.0, kUnit).with_nominal(0.5), "eccentricity"), "");
  EXPECT_EQ(validate(Distribution::fixed(0.3), "mu_s"), "");
}

TEST(ValueRange, ClampKeepsOpenEndsOpen) {
  EXPECT_GT(kUnit.clamp(0.0), 0.0);
  EXPECT_LT(kUnit.clamp(1.0), 1.0);
  EXPECT_EQ(kUnit.clamp(0.5), 0.5);
  const ValueRange closed{0.0, 1.0, false, false};
  EXPECT_EQ(closed.clamp(-2.0), 0.0);
  EXPECT_EQ(closed.clamp(1.0), 1.0);
  EXPECT_EQ(closed.text(), "[0, 1]");
  EXPECT_EQ(kPositive.text(), "(0, inf)");
}

}  // namespace
}  // namespace rocking_monitor::core
