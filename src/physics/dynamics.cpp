#include "rocking_monitor/physics/dynamics.hpp"

#include <stdexcept>
#include <string>

namespace rocking_monitor::core {

void require_valid_sample(double ax, double ay, double dt, const char* who) {
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw std::invalid_argument(std::string(who) + ": dt must be finite and > 0");
  if (!std::isfinite(ax) || !std::isfinite(ay))
    throw std::invalid_argument(std::string(who) + ": ground acceleration must be finite");
}

OverturnMargin overturn_margin(const Pivot& pv, int side, ModelKind model, double theta,
                               double omega) {
  const double phi = pv.alpha - side * theta;  // > 0: CoM still inside the pivot
  double deficit = 0.0;  // energy still missing to reach the barrier, normalised
  if (model == ModelKind::Linearized) {
    // theta'' = p^2 (s theta - alpha) without excitation: E = w^2/2 - p^2 phi^2/2, barrier E = 0.
    deficit = (pv.p2 * phi * phi - omega * omega) / (pv.p2 * pv.alpha * pv.alpha);
  } else {
    const double barrier = kGravity * pv.radius;  // per unit mass, above the pivot
    deficit = (barrier * (1.0 - std::cos(phi)) - 0.5 * pv.inertia * omega * omega) /
              (barrier * (1.0 - pv.cos_alpha));
  }
  const bool outward = side * omega > 0.0;
  const bool committed = phi > 0.0 ? (outward && deficit < 0.0) : (outward || deficit > 0.0);
  return {committed ? -std::abs(deficit) : std::abs(deficit), committed};
}

}  // namespace rocking_monitor::core
