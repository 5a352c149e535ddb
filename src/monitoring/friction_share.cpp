#include "rocking_monitor/monitoring/friction_share.hpp"

#include <algorithm>
#include <cmath>

namespace rocking_monitor::core {
namespace {

// Each component's share of the vector's length; one component zero gives (1, 0) exactly.
void along(const double (&c)[2], FrictionShare& out) {
  const double n = std::hypot(c[0], c[1]);
  if (!(n > 0.0)) return;  // nothing demanded (mu_s = 0 at rest): nothing to share
  for (int i = 0; i < 2; ++i) out.share[i] = std::min(1.0, std::abs(c[i]) / n);
  out.engaged = true;
}

}  // namespace

FrictionShare friction_share(const double (&v)[2], const double (&w)[2], const double (&q0)[2],
                             const double (&q1)[2], double mu_s) {
  FrictionShare out;
  if (!std::isfinite(mu_s) || !std::isfinite(v[0]) || !std::isfinite(v[1])) return out;
  if (v[0] != 0.0 || v[1] != 0.0) {
    along(w, out);
    if (!out.engaged) along(v, out);  // (the ground's pull cancelling the slip exactly)
    return out;
  }
  // A plane without a normal force (lift-off, flight) is its own model's: no budget to share.
  if (!(std::isfinite(q0[0]) && std::isfinite(q0[1]) && std::isfinite(q1[0]) && std::isfinite(q1[1]))) return out;
  if (std::max(q0[0], q0[1]) < mu_s * kShareEngage) return out;
  out.engaged = true;
  // Sticking: inside the cone at the sample's end every plane keeps the whole budget (q_i <= |q| <=
  // mu_s: no plane's own check can fire); outside, the demand's direction there, so that each plane's
  // check q_i <= mu_s share_i is the cone's |q| <= mu_s, located inside the sample by the plane.
  if (std::hypot(q1[0], q1[1]) > mu_s) along(q1, out);
  return out;
}

FrictionShare friction_share(const AdaptiveModel& x, const AdaptiveModel& y, const double (&x0)[2],
                             const double (&y0)[2], const double (&x1)[2], const double (&y1)[2], double dt) {
  const double v[2] = {x.slip_velocity(), y.slip_velocity()};
  // (the base's slip accelerates against the ground's acceleration: -a_g)
  const double w[2] = {v[0] - 0.5 * (x0[0] + x1[0]) * dt, v[1] - 0.5 * (y0[0] + y1[0]) * dt};
  // (each plane's own last input: MonitorBatch asks with one plane's deferred samples not applied)
  const double q0[2] = {x.friction_demand(x0[0], x0[1]), y.friction_demand(y0[0], y0[1])};
  // At the end: the ground's demand on a plane at rest; a rocking plane's reaction as at the start.
  const double q1[2] = {x.friction_demand(x1[0], x1[1]), y.friction_demand(y1[0], y1[1])};
  return friction_share(v, w, q0, q1, x.body().mu_s());
}

bool friction_engaged(const AdaptiveModel& x, const AdaptiveModel& y, const double (&x0)[2], const double (&y0)[2]) {
  const double mu_s = x.body().mu_s();
  const double v[2] = {x.slip_velocity(), y.slip_velocity()};
  if (!std::isfinite(mu_s) || !std::isfinite(v[0]) || !std::isfinite(v[1])) return false;
  if (v[0] != 0.0 || v[1] != 0.0) return true;
  const double q0[2] = {x.friction_demand(x0[0], x0[1]), y.friction_demand(y0[0], y0[1])};
  return std::isfinite(q0[0]) && std::isfinite(q0[1]) && std::max(q0[0], q0[1]) >= mu_s * kShareEngage;
}

}  // namespace rocking_monitor::core
