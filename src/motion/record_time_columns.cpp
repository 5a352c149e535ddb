// Time columns (BBP and CSV/whitespace records): the time step must be uniform within the printed
// rounding, and the time stamps must stay on the grid (no slow drift, no missing row).
#include "record_reader_internal.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rocking_monitor::core::record_io {

// ------------------------------------------------------------------ time columns

/// Checks that the time column is uniform and returns dt.
///
/// The README defines dt = t[1] - t[0]. Every step must equal it, and every time stamp must lie on
/// the grid t0 + i*dt (dt refined from the end points, the more accurate estimate; this catches
/// slow drifts that no single step reveals), within
///     1e-6*dt + the rounding of the printed digits involved (one unit in the last printed digit
///     of each time stamp, which also covers printers that truncate),
/// but the rounding part never exceeds 1 % of dt: when the time stamps are printed so coarsely
/// that their rounding is comparable to dt (e.g. dt = 0.01 s printed with 2 decimals), a missing
/// row would otherwise pass as rounding. Every step must also be positive.
double check_uniform_time(const std::string& path, const std::vector<TimeSample>& ts) {
  const std::size_t n = ts.size();
  if (n < 2) fail(path, ts.empty() ? 0 : ts[0].line, "need at least 2 samples to determine the time step");
  auto describe = [](const char* what, double t, double t_prev, double step, double expected) {
    char buf[240];
    std::snprintf(buf, sizeof buf, "%s: t=%.9g after t=%.9g (step %.9g, expected %.9g)", what, t, t_prev, step,
                  expected);
    return std::string(buf);
  };
  const double dt1 = ts[1].t - ts[0].t;
  if (!(dt1 > 0.0)) {
    fail(path, ts[1].line, describe("non-positive time step", ts[1].t, ts[0].t, dt1, dt1));
  }
  const double cap = 0.01 * dt1;
  const double base = ts[0].res + ts[1].res;
  for (std::size_t i = 1; i < n; ++i) {
    const double step = ts[i].t - ts[i - 1].t;
    const double tol = 1e-6 * dt1 + std::min(cap, base + ts[i].res + ts[i - 1].res);
    if (!(step > 0.0) || !(std::fabs(step - dt1) <= tol)) {
      fail(path, ts[i].line,
           describe(step > 0.0 ? "non-uniform time step" : "non-uniform time step (not increasing)", ts[i].t,
                    ts[i - 1].t, step, dt1));
    }
  }
  const double dt = (ts[n - 1].t - ts[0].t) / static_cast<double>(n - 1);
  // A drift is reported where it is largest (where the time stamps depart most from the grid
  // through the end points), which is near where it starts rather than where it first shows.
  const double ends = ts[0].res + ts[n - 1].res;
  std::size_t worst = n;
  double worst_excess = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double expected = ts[0].t + static_cast<double>(i) * dt;
    const double tol = 1e-6 * dt + std::min(0.01 * dt, ends + ts[i].res);
    const double excess = std::fabs(ts[i].t - expected) - tol;
    if (excess > worst_excess) {
      worst_excess = excess;
      worst = i;
    }
  }
  if (worst < n) {
    char buf[240];
    std::snprintf(buf, sizeof buf,
                  "non-uniform time step: t=%.9g is off the uniform grid t0 + i*dt (expected %.9g, dt %.9g)",
                  ts[worst].t, ts[0].t + static_cast<double>(worst) * dt, dt);
    fail(path, ts[worst].line, buf);
  }
  return dt;
}

}  // namespace rocking_monitor::core::record_io
