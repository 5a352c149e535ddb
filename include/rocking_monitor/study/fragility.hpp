#pragma once

// Fragility curves: P(overturn | IM) = Phi(ln(IM / median) / beta), fitted by maximum likelihood to
// overturning outcomes (Baker 2015, "Efficient analytical fragility function fitting using dynamic
// structural analysis", Earthquake Spectra 31(1)), with a bootstrap confidence band.

#include <cstdint>
#include <string>
#include <vector>

#include "rocking_monitor/physics/parameter_distribution.hpp"

namespace rocking_monitor::core::study {

/// Outcomes at one intensity: `failures` of `trials` overturned (counts may be fractional weights).
struct FragilityPoint {
  double im = 0.0;        ///< intensity measure, > 0 (its unit: m/s for PGV, m/s^2 for PGA, ...)
  double failures = 0.0;  ///< overturned runs (or weight), 0 <= failures <= trials
  double trials = 1.0;    ///< runs (or weight), > 0
};

struct LognormalFragility {
  double median = 0.0;  ///< theta: the IM with P = 0.5, same unit as IM
  double beta = 0.0;    ///< logarithmic standard deviation, dimensionless
  double log_likelihood = 0.0;
  int iterations = 0;
  /// False when the outcomes are separable (every failure at a higher IM than every survival): the
  /// likelihood then grows as beta -> 0 without a maximum; median is the geometric midpoint of the
  /// separating gap and beta 0.
  bool converged = false;
  double probability(double im) const;  ///< P(overturn | im)
};

/// Maximum-likelihood fit (probit regression on ln IM, Newton-Raphson / IRLS). Throws StudyError
/// when the points cannot define a fragility (no point, an IM <= 0, no failure or no survival).
LognormalFragility fit_lognormal_fragility(const std::vector<FragilityPoint>& points);

struct FragilityBand {
  std::vector<double> im;       ///< the grid asked for
  std::vector<double> lower;    ///< 2.5 % of the bootstrap fits' P(im)
  std::vector<double> upper;    ///< 97.5 %
  double median_lower = 0.0, median_upper = 0.0;  ///< 95 % interval of the median (basic bootstrap, log scale)
  double beta_lower = 0.0, beta_upper = 0.0;      ///< 95 % interval of beta (basic bootstrap, log scale)
  int resamples = 0;            ///< bootstrap fits used
  int skipped = 0;              ///< resamples with no failure or no survival (no fit), counted
  int separable = 0;            ///< resamples fitted with beta = 0 (separable)
};

/// Nonparametric bootstrap over the individual runs (each point's trials resampled as 0/1 runs, so
/// points must hold whole counts), `resamples` fits with a fixed seed (the same band on every
/// machine), the band of P at the given IM grid (2.5 and 97.5 % of the resampled curves).
FragilityBand bootstrap_fragility(const std::vector<FragilityPoint>& points, const std::vector<double>& im_grid,
                                  int resamples, std::uint64_t seed);


}  // namespace rocking_monitor::core::study
