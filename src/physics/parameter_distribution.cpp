#include "rocking_monitor/physics/parameter_distribution.hpp"

#include <cmath>
#include <cstdio>

namespace rocking_monitor::core {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string num(double x) {
  if (x == kInf) return "inf";
  if (x == -kInf) return "-inf";
  char text[32];
  std::snprintf(text, sizeof text, "%.12g", x);
  return text;
}

// A standard normal restricted to [alpha, beta] (standardised bounds, +-inf allowed).
// The probabilities are taken on the side of the mean where the interval lies, so that a truncation
// deep in the upper tail keeps its precision (the survival function there, via the symmetry).
struct Truncated {
  double alpha, beta;
  bool upper() const { return alpha >= 0.0; }
  double mass() const { return upper() ? normal_cdf(-alpha) - normal_cdf(-beta) : normal_cdf(beta) - normal_cdf(alpha); }
  double quantile(double u) const {
    if (upper()) {
      const double sa = normal_cdf(-alpha), sb = normal_cdf(-beta);
      return -inverse_normal_cdf(sa - u * (sa - sb));
    }
    const double pa = normal_cdf(alpha), pb = normal_cdf(beta);
    return inverse_normal_cdf(pa + u * (pb - pa));
  }
  double cdf(double z) const {
    if (!(z > alpha)) return 0.0;
    if (!(z < beta)) return 1.0;
    if (upper()) {
      const double sa = normal_cdf(-alpha), sb = normal_cdf(-beta);
      return (sa - normal_cdf(-z)) / (sa - sb);
    }
    const double pa = normal_cdf(alpha), pb = normal_cdf(beta);
    return (normal_cdf(z) - pa) / (pb - pa);
  }
};

// Acklam's coefficients (see the header).
constexpr double kA[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                         1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
constexpr double kB[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                         6.680131188771972e+01,  -1.328068155288572e+01};
constexpr double kC[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                         -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
constexpr double kD[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                         3.754408661907416e+00};

// p in (0, 0.5].
double acklam_lower(double p) {
  constexpr double p_low = 0.02425;
  if (p < p_low) {
    const double q = std::sqrt(-2.0 * std::log(p));
    return (((((kC[0] * q + kC[1]) * q + kC[2]) * q + kC[3]) * q + kC[4]) * q + kC[5]) /
           ((((kD[0] * q + kD[1]) * q + kD[2]) * q + kD[3]) * q + 1.0);
  }
  const double q = p - 0.5, r = q * q;
  return (((((kA[0] * r + kA[1]) * r + kA[2]) * r + kA[3]) * r + kA[4]) * r + kA[5]) * q /
         (((((kB[0] * r + kB[1]) * r + kB[2]) * r + kB[3]) * r + kB[4]) * r + 1.0);
}

}  // namespace

bool ValueRange::contains(double x) const {
  if (!(x == x)) return false;
  const bool above = lo_open ? x > lo : x >= lo;
  const bool below = hi_open ? x < hi : x <= hi;
  return above && below;
}

double ValueRange::clamp(double x) const {
  if (x < lo || (lo_open && x == lo)) x = lo_open ? std::nextafter(lo, kInf) : lo;
  if (x > hi || (hi_open && x == hi)) x = hi_open ? std::nextafter(hi, -kInf) : hi;
  return x;
}

std::string ValueRange::text() const {
  return std::string(lo_open ? "(" : "[") + num(lo) + ", " + num(hi) + (hi_open ? ")" : "]");
}

double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

double inverse_normal_cdf(double p) {
  if (!(p > 0.0)) return p == 0.0 ? -kInf : std::numeric_limits<double>::quiet_NaN();
  if (!(p < 1.0)) return p == 1.0 ? kInf : std::numeric_limits<double>::quiet_NaN();
  if (p > 0.5) return -inverse_normal_cdf(1.0 - p);  // 1 - p exact for p >= 0.5 (Sterbenz)
  double x = acklam_lower(p);
  // One Halley step on f(x) = Phi(x) - p (Acklam's refinement): f' = phi(x), f'' = -x phi(x).
  // Skipped where exp(x^2 / 2) overflows (p below about 1e-300; Acklam's 1.15e-9 then stands).
  const double e = normal_cdf(x) - p;
  if (e != 0.0) {
    const double u = e * std::sqrt(2.0 * 3.14159265358979323846) * std::exp(x * x / 2.0);
    const double refined = x - u / (1.0 + x * u / 2.0);
    if (std::isfinite(refined)) x = refined;
  }
  return x;
}

Distribution Distribution::fixed(double value) {
  Distribution d;
  d.a_ = value;
  return d;
}

Distribution Distribution::uniform(double lo, double hi, ValueRange range) {
  Distribution d;
  d.kind_ = Kind::Uniform;
  d.a_ = lo;
  d.b_ = hi;
  d.range_ = range;
  return d;
}

Distribution Distribution::normal(double mean, double sd, ValueRange range) {
  Distribution d = uniform(mean, sd, range);
  d.kind_ = Kind::Normal;
  return d;
}

Distribution Distribution::lognormal(double median, double beta, ValueRange range) {
  Distribution d = uniform(median, beta, range);
  d.kind_ = Kind::Lognormal;
  return d;
}

Distribution Distribution::with_nominal(double nominal) const {
  Distribution d = *this;
  d.nominal_given_ = true;
  d.nominal_ = nominal;
  return d;
}

bool Distribution::degenerate() const {
  switch (kind_) {
    case Kind::Fixed: return true;
    case Kind::Uniform: return a_ == b_;
    default: return b_ == 0.0;
  }
}

double Distribution::nominal() const {
  if (nominal_given_) return nominal_;
  switch (kind_) {
    case Kind::Uniform: return a_ == b_ ? a_ : 0.5 * (a_ + b_);
    case Kind::Lognormal: return b_ == 0.0 ? a_ : a_ * std::exp(0.5 * b_ * b_);
    default: return a_;  // fixed value, normal mean
  }
}

const char* Distribution::name() const {
  switch (kind_) {
    case Kind::Uniform: return "uniform";
    case Kind::Normal: return "normal";
    case Kind::Lognormal: return "lognormal";
    default: return "fixed";
  }
}

namespace {

// The standardised truncation of a normal (z = (x - mean) / sd) or lognormal (z = ln(x / median) / beta).
Truncated standardised(Distribution::Kind kind, double a, double b, const ValueRange& r) {
  if (kind == Distribution::Kind::Normal) return {(r.lo - a) / b, (r.hi - a) / b};
  const double lo = r.lo > 0.0 ? std::log(r.lo / a) / b : -kInf;
  const double hi = r.hi == kInf ? kInf : (r.hi > 0.0 ? std::log(r.hi / a) / b : -kInf);
  return {lo, hi};
}

}  // namespace

double Distribution::quantile(double u) const {
  if (degenerate()) return a_;
  constexpr double kTiny = 0x1.0p-1074, kBelowOne = 1.0 - 0x1.0p-53;
  u = u > kTiny ? u : kTiny;
  u = u < kBelowOne ? u : kBelowOne;
  double x;
  switch (kind_) {
    case Kind::Uniform: x = a_ + u * (b_ - a_); break;
    case Kind::Normal: x = a_ + b_ * standardised(kind_, a_, b_, range_).quantile(u); break;
    default: x = a_ * std::exp(b_ * standardised(kind_, a_, b_, range_).quantile(u)); break;
  }
  return range_.clamp(x);
}

double Distribution::cdf(double x) const {
  if (degenerate()) return x < a_ ? 0.0 : 1.0;
  switch (kind_) {
    case Kind::Uniform: return x <= a_ ? 0.0 : (x >= b_ ? 1.0 : (x - a_) / (b_ - a_));
    case Kind::Normal: return standardised(kind_, a_, b_, range_).cdf((x - a_) / b_);
    default: return x <= 0.0 ? 0.0 : standardised(kind_, a_, b_, range_).cdf(std::log(x / a_) / b_);
  }
}

std::string validate(const Distribution& d, const std::string& field) {
  const std::string who = field + ": " + d.name() + ": ";
  const ValueRange& r = d.range();
  switch (d.kind()) {
    case Distribution::Kind::Fixed:
      if (!std::isfinite(d.a())) return field + ": " + num(d.a()) + " is not a finite number";
      return {};
    case Distribution::Kind::Uniform:
      if (!std::isfinite(d.a())) return who + "lo " + num(d.a()) + " is not a finite number";
      if (!std::isfinite(d.b())) return who + "hi " + num(d.b()) + " is not a finite number";
      if (d.a() > d.b()) return who + "lo " + num(d.a()) + " > hi " + num(d.b());
      if (!r.contains(d.a())) return who + "lo " + num(d.a()) + " outside " + r.text();
      if (!r.contains(d.b())) return who + "hi " + num(d.b()) + " outside " + r.text();
      break;
    case Distribution::Kind::Normal:
      if (!std::isfinite(d.a())) return who + "mean " + num(d.a()) + " is not a finite number";
      if (!std::isfinite(d.b())) return who + "sd " + num(d.b()) + " is not a finite number";
      if (d.b() < 0.0) return who + "sd " + num(d.b()) + " < 0";
      break;
    case Distribution::Kind::Lognormal:
      if (!std::isfinite(d.a())) return who + "median " + num(d.a()) + " is not a finite number";
      if (!std::isfinite(d.b())) return who + "beta " + num(d.b()) + " is not a finite number";
      if (d.a() <= 0.0) return who + "median " + num(d.a()) + " <= 0";
      if (d.b() < 0.0) return who + "beta " + num(d.b()) + " < 0";
      break;
  }
  const double nominal = d.nominal();
  if (!std::isfinite(nominal)) return who + "nominal " + num(nominal) + " is not a finite number";
  if (d.degenerate()) {
    if (!r.contains(d.a()))
      return who + (d.kind() == Distribution::Kind::Normal ? "mean " : "median ") + num(d.a()) + " outside " + r.text();
    if (nominal != d.a()) return who + "nominal " + num(nominal) + " outside {" + num(d.a()) + "} (zero spread)";
    return {};
  }
  if (d.kind() == Distribution::Kind::Uniform) {
    if (nominal < d.a() || nominal > d.b())
      return who + "nominal " + num(nominal) + " outside [" + num(d.a()) + ", " + num(d.b()) + "]";
    return {};
  }
  if (!r.contains(nominal) || (d.kind() == Distribution::Kind::Lognormal && !(nominal > 0.0)))
    return who + "nominal " + num(nominal) + " outside " + r.text() +
           (d.nominal_given() ? "" : " (the law's mean; give nominal: to choose another)");
  if (!(standardised(d.kind(), d.a(), d.b(), r).mass() > 0.0))
    return who + "no probability left inside " + r.text() + " (the law is truncated to it)";
  return {};
}

}  // namespace rocking_monitor::core
