#pragma once

// The uncertainty of one item parameter (issue 13): a fixed value or a probability law, described and
// sampled by its inverse CDF. Pure description: no random engine here (monitoring/uncertain_item.hpp
// draws the members). std only.

#include <limits>
#include <string>

namespace rocking_monitor::core {

/// The values a parameter may take: [lo, hi] with either end open (e.g. eccentricity (0, 1),
/// friction [0, inf), a length (0, inf)). Every law is restricted to its field's range.
struct ValueRange {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = true;
  bool hi_open = true;

  bool contains(double x) const;
  /// The closest value to x inside the range (an open end: the next double inside it).
  double clamp(double x) const;
  /// "(0, 1)", "[0, inf)".
  std::string text() const;
};

/// The inverse of the standard normal CDF, Phi^-1(p), for p in (0, 1) (p = 0: -inf, p = 1: +inf).
/// P. J. Acklam's rational approximation (2003; "An algorithm for computing the inverse normal
/// cumulative distribution function", relative error 1.15e-9) refined by one step of Halley's method
/// on Phi(x) - p with std::erfc, which brings it to about 1e-15. The lower tail is always computed
/// (p > 0.5 as -Phi^-1(1 - p), 1 - p exact there), where erfc keeps full relative precision.
double inverse_normal_cdf(double p);
/// Phi(x) = erfc(-x / sqrt 2) / 2.
double normal_cdf(double x);

/// A fixed value | uniform[lo, hi] | normal[mean, sd] | lognormal[median, beta], each restricted
/// (truncated) to its field's ValueRange: the law of the member values is the law conditioned on the
/// range. A uniform must lie inside the range; a normal or lognormal is truncated. Zero spread (lo = hi,
/// sd = 0, beta = 0) is allowed: every quantile is then exactly that value.
class Distribution {
 public:
  enum class Kind { Fixed, Uniform, Normal, Lognormal };

  /// Fixed, value NaN: "the nominal item's value" (uncertain_item.hpp).
  Distribution() = default;
  static Distribution fixed(double value);
  static Distribution uniform(double lo, double hi, ValueRange range = {});
  static Distribution normal(double mean, double sd, ValueRange range = {});
  static Distribution lognormal(double median, double beta, ValueRange range = {});
  /// The same law with a given nominal value (else: the law's mean, see nominal()).
  Distribution with_nominal(double nominal) const;

  Kind kind() const { return kind_; }
  bool is_fixed() const { return kind_ == Kind::Fixed; }
  /// Fixed, or zero spread (lo = hi, sd = 0, beta = 0): every quantile is the same value.
  bool degenerate() const;
  double a() const { return a_; }  ///< value | lo | mean | median
  double b() const { return b_; }  ///< -    | hi | sd   | beta
  const ValueRange& range() const { return range_; }
  bool nominal_given() const { return nominal_given_; }

  /// The given `nominal:`, else the mean of the law as written (before truncation): the value for
  /// fixed, (lo + hi) / 2, the mean, median * exp(beta^2 / 2).
  double nominal() const;

  /// Inverse CDF of the (truncated) law for u in [0, 1]; u is first kept inside (0, 1) (u = 0 as the
  /// smallest positive double, u = 1 as 1 - 2^-53) and the result is clamped into the range as a last
  /// guard against rounding at an open end. Fixed: the value. Zero spread: lo, the mean, the median.
  double quantile(double u) const;
  /// CDF of the (truncated) law at x: 0 below the support, 1 above. Fixed / zero spread: a step.
  double cdf(double x) const;

  /// "uniform", "normal", "lognormal", "fixed".
  const char* name() const;

 private:
  Kind kind_ = Kind::Fixed;
  double a_ = std::numeric_limits<double>::quiet_NaN();
  double b_ = 0.0;
  ValueRange range_;
  bool nominal_given_ = false;
  double nominal_ = std::numeric_limits<double>::quiet_NaN();
};

/// Empty if valid, else "<field>: <law>: <problem>", e.g. "mu_s: uniform: lo 0.6 > hi 0.3",
/// "width: normal: sd -0.1 < 0", "cg_height: lognormal: median 0 <= 0",
/// "eccentricity: uniform: hi 1 outside (0, 1)", "mu_s: uniform: nominal 0.5 outside [0.25, 0.4]".
/// Checks: finite numbers; lo <= hi and both inside the range; sd >= 0 with the mean inside the range;
/// beta >= 0, median > 0 and inside the range; the nominal inside the law's support; a truncated law
/// with some probability inside the range.
std::string validate(const Distribution& d, const std::string& field);

}  // namespace rocking_monitor::core
