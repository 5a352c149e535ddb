#include "rocking_monitor/study/table_test_margin.hpp"

#include <cmath>
#include <stdexcept>

namespace rocking_monitor::core {

void validate(const MarginSearch& s) {
  if (!(std::isfinite(s.lo) && s.lo > 0.0)) throw std::invalid_argument("margin search: lo must be finite and > 0");
  if (!(std::isfinite(s.hi) && s.hi > s.lo)) throw std::invalid_argument("margin search: hi must be finite and > lo");
  if (s.grid < 2) throw std::invalid_argument("margin search: grid must be >= 2 scales");
  if (s.bisections < 0 || s.bisections > 60) throw std::invalid_argument("margin search: bisections must be in [0, 60]");
}

TestMargin table_test_margin(const std::function<bool(double)>& overturns, const MarginSearch& search) {
  validate(search);
  TestMargin m;
  const double ratio = search.hi / search.lo;
  auto scale_at = [&](int k) {
    if (k == search.grid - 1) return search.hi;  // exactly hi, not hi to rounding
    return search.lo * std::pow(ratio, static_cast<double>(k) / static_cast<double>(search.grid - 1));
  };
  int first = -1;
  for (int k = 0; k < search.grid; ++k) {
    const bool over = overturns(scale_at(k));
    ++m.runs;
    m.pattern += over ? '1' : '0';
    if (over && first < 0) first = k;
    if (!over && first >= 0) m.chaotic = true;  // stood above a scale that overturned
  }
  if (first < 0) {
    m.censored = 1;
    m.scale = m.bracket_lo = m.bracket_hi = search.hi;
    return m;
  }
  if (first == 0) {
    m.censored = -1;
    m.scale = m.bracket_lo = m.bracket_hi = search.lo;
    return m;
  }
  double lo = scale_at(first - 1), hi = scale_at(first);
  for (int i = 0; i < search.bisections; ++i) {
    const double mid = std::sqrt(lo * hi);  // halves ln s
    ++m.runs;
    (overturns(mid) ? hi : lo) = mid;
  }
  m.bracket_lo = lo;
  m.bracket_hi = hi;
  m.scale = std::sqrt(lo * hi);
  return m;
}

}  // namespace rocking_monitor::core
