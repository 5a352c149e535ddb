#pragma once
// The margin of a shaking-table test (issue 41): the smallest scale of the test's table motion at
// which the model overturns, the input of a lognormal fragility P(overturn) = Phi(-(ln s* + mu) / beta)
// (scripts/fragility_experiments.py, docs/validation.md section 0).
#include <functional>
#include <string>

namespace rocking_monitor::core {

struct MarginSearch {
  double lo = 0.25;    ///< smallest scale tried, dimensionless (> 0)
  double hi = 4.0;     ///< largest, > lo
  int grid = 9;        ///< scales lo (hi/lo)^(k/(grid-1)), k = 0..grid-1, all run (>= 2); 9: steps of sqrt 2, 1 among them
  int bisections = 5;  ///< halvings of ln s inside the first grid step that overturns (>= 0)
};

struct TestMargin {
  /// The smallest overturning scale: the geometric mean of the last bracket (interior), lo when the
  /// smallest grid scale already overturns (censored -1), hi when none does (censored +1).
  double scale = 0.0;
  int censored = 0;      ///< -1: s* <= lo; +1: s* > hi (stood at every grid scale); 0: bracketed
  /// The grid's outcomes are not monotone: the model stood at some scale above one where it
  /// overturned (chaotic rocking near the boundary); scale is still the first overturn's.
  bool chaotic = false;
  std::string pattern;   ///< one character per grid scale, smallest first: '1' overturned, '0' stood
  int runs = 0;          ///< model runs made
  double bracket_lo = 0.0, bracket_hi = 0.0;  ///< the final bracket (stood at lo, overturned at hi)
};

/// Throws std::invalid_argument for a bad search (naming the field).
void validate(const MarginSearch& search);

/// Runs `overturns(scale)` on the grid, then bisects ln s between the last grid scale that stood
/// before the first that overturned and that one. Deterministic: the same calls in the same order.
TestMargin table_test_margin(const std::function<bool(double)>& overturns, const MarginSearch& search = {});

}  // namespace rocking_monitor::core
