#include "rocking_monitor/physics/sliding_bound.hpp"

#include <algorithm>
#include <cmath>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/physics/impact.hpp"

namespace rocking_monitor::core {

namespace {

// Intervals of the rotation over which the rocking reactions are bounded (tightness vs cost;
// 64 bring the bound within a few per cent of the grid supremum, see the tests).
constexpr int kPhiIntervals = 64;

struct Range {
  double lo, hi;
};
Range operator+(Range a, Range b) { return {a.lo + b.lo, a.hi + b.hi}; }
// {lo, hi} times a scalar of either sign.
Range scale(Range r, double f) { return f >= 0.0 ? Range{r.lo * f, r.hi * f} : Range{r.hi * f, r.lo * f}; }
Range scale(double lo, double hi, double f) { return scale(Range{lo, hi}, f); }

}  // namespace

double impact_friction_demand(const Body& body, int new_side) {
  // Sticking impact from pure rocking about the old corner onto `new_side`: the impulse that
  // turns omega into e*omega about the new corner has |P_x| / P_y = h (1 - e) / (B (e nu_new +
  // nu_old)) (docs/contact_model.md, "Impact"); ContactModel's impact slips iff mu_s is below it.
  const double ig2 = body.radius_of_gyration() * body.radius_of_gyration();
  const double nu_new = body.pivot(new_side).nu, nu_old = body.pivot(-new_side).nu;
  const double e = impact_velocity_ratio(ig2, body.cg_height(), body.width(), nu_new);
  const double den = body.width() * (e * nu_new + nu_old);
  return den > 0.0 ? body.cg_height() * (1.0 - e) / den : std::numeric_limits<double>::infinity();
}

SlidingBound sliding_bound(const Body& body, const SceneEnvelope& scene) {
  SlidingBound b;
  const double H = scene.horizontal, V = scene.vertical, g = kGravity;
  const Pivot* pv[2] = {&body.pivot(1), &body.pivot(-1)};
  b.impact = std::max(impact_friction_demand(body, 1), impact_friction_demand(body, -1));
  if (!(V < g) || std::isnan(H)) return b;  // a_yg may reach -g: flight from rest (eq. 11)

  // Rest: |A| <= A_max (eq. 22) and, with a continuous input, |A| reaches tan(alpha_s) = 1/gamma
  // first and the body uplifts (eqs. 19, 26).
  const double a_max = H / (g - V);
  b.rest = std::min(a_max, std::max(pv[0]->tan_alpha, pv[1]->tan_alpha));
  b.can_rock = a_max >= std::min(pv[0]->tan_alpha, pv[1]->tan_alpha);
  b.flight_possible = false;
  if (!b.can_rock) return b;

  // Largest kinetic energy per unit mass, (I_O/m) omega^2 / 2, while |theta| < alpha. Between two
  // instants with omega = 0 (or an impact) theta is monotone, so the inertial forces do at most
  // (g + V) x (drop of the CoM) + H x (horizontal travel of the CoM) of work:
  //   falling towards theta = 0 from rest:  E_fall = (g + V) R (1 - cos alpha) + H R sin alpha;
  //   rising after an impact onto corner s: dE_s E_fall(other) + H R sin alpha (gravity only
  //   takes energy away while the CoM rises), dE_s = e_s^2 I_s / I_other (eq. 38).
  double e_fall[2];
  for (int i = 0; i < 2; ++i)
    e_fall[i] = (g + V) * pv[i]->radius * (1.0 - pv[i]->cos_alpha) + H * pv[i]->radius * pv[i]->sin_alpha;
  double w2s[2];
  for (int i = 0; i < 2; ++i) {
    const Pivot& p = *pv[i];
    const Pivot& o = *pv[1 - i];
    const double de = p.restitution * p.restitution * p.inertia / o.inertia;
    const double e_rise = de * e_fall[1 - i] + H * p.radius * p.sin_alpha;
    w2s[i] = 2.0 * std::max(e_fall[i], e_rise) / p.inertia;
    b.omega_max[i] = std::sqrt(w2s[i]);
  }
  for (int i = 0; i < 2; ++i) {
    const Pivot& p = *pv[i];
    const double w2 = w2s[i];

    // Reactions per unit mass about this corner, phi = alpha - theta in (0, alpha], k = R^2 m / I_O:
    //   R_x = a_x (1 - k cos^2 phi) + k (g + a_y) sin phi cos phi - R omega^2 sin phi
    //   R_y = (g + a_y)(1 - k sin^2 phi) + k a_x sin phi cos phi - R omega^2 cos phi
    // At fixed phi both are affine in (a_x, a_y, omega^2), so |R_x| / R_y (R_y > 0) is largest at
    // a corner of that box; over a short phi interval each term is bounded by its monotone range.
    const double k = p.radius * p.radius / p.inertia;
    for (int j = 0; j < kPhiIntervals; ++j) {
      const double lo = p.alpha * j / kPhiIntervals, hi = p.alpha * (j + 1) / kPhiIntervals;
      const Range c2{std::cos(hi) * std::cos(hi), std::cos(lo) * std::cos(lo)};
      const Range s2{std::sin(lo) * std::sin(lo), std::sin(hi) * std::sin(hi)};
      const Range sn{std::sin(lo), std::sin(hi)}, cs{std::cos(hi), std::cos(lo)};
      Range sc{0.5 * std::sin(2.0 * lo), 0.5 * std::sin(2.0 * hi)};
      if (sc.lo > sc.hi) std::swap(sc.lo, sc.hi);
      if (lo < 0.25 * kPi && hi > 0.25 * kPi) sc.hi = 0.5;
      for (double ax : {-H, H}) {
        for (double G : {g - V, g + V}) {
          for (double w : {0.0, w2}) {
            const Range rx = scale(1.0 - k * c2.hi, 1.0 - k * c2.lo, ax) + scale(sc, k * G) +
                             scale(sn, -p.radius * w);
            const Range ry = scale(1.0 - k * s2.hi, 1.0 - k * s2.lo, G) + scale(sc, k * ax) +
                             scale(cs, -p.radius * w);
            if (!(ry.lo > 0.0)) {
              b.flight_possible = true;
              b.rocking = std::numeric_limits<double>::infinity();
              return b;
            }
            b.rocking = std::max(b.rocking, std::max(std::abs(rx.lo), std::abs(rx.hi)) / ry.lo);
          }
        }
      }
    }
  }
  return b;
}

}  // namespace rocking_monitor::core
