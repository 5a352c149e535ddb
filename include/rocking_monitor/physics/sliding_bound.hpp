#pragma once
// The static friction an item needs so that, for every ground motion inside a scene envelope,
// it can never slide, slip at an impact or lift off while it has not passed its tipping angle
// (issue 7: "an item whose friction makes sliding impossible for the whole scene never pays for
// the sliding model"). Derivation in docs/fidelity.md ("Static pre-check").

#include <limits>

#include "rocking_monitor/physics/body.hpp"

namespace rocking_monitor::core {

/// Limits of the ground acceleration in the item frame for a whole scene (m/s^2):
/// |a_xg| <= horizontal, |a_yg| <= vertical. +inf = unknown.
struct SceneEnvelope {
  double horizontal = std::numeric_limits<double>::infinity();
  double vertical = std::numeric_limits<double>::infinity();
  /// From configuration values where 0 means "unknown" (the node's ~scene_envelope/*).
  static SceneEnvelope from_parameters(double horizontal, double vertical) {
    constexpr double kUnknown = std::numeric_limits<double>::infinity();
    return {horizontal > 0.0 ? horizontal : kUnknown, vertical > 0.0 ? vertical : kUnknown};
  }
  bool contains(double ax, double ay) const {
    return !(ax > horizontal || -ax > horizontal || ay > vertical || -ay > vertical);
  }
};

/// What friction the scene can demand. Every ratio is |R_x| / R_y (dimensionless).
struct SlidingBound {
  /// At rest: |A| = |a_xg| / (a_yg + g) (eq. 21), which the input can raise only to the smaller of
  /// A_max = horizontal / (g - vertical) (eq. 22) and the uplift threshold tan(alpha_s) = 1/gamma
  /// of the larger side (eqs. 19, 26): the body rocks before it can slide from rest.
  double rest = std::numeric_limits<double>::infinity();
  bool can_rock = true;  ///< A_max reaches tan(alpha_s) of at least one corner
  /// While rocking with |theta| < alpha_s: an upper bound of |R_x| / R_y over every rotation in
  /// [0, alpha_s), input in the envelope and |omega| <= omega_max (0 when the body cannot rock).
  double rocking = 0.0;
  /// Tangential / normal impulse of a sticking impact from pure rocking, larger corner.
  double impact = 0.0;
  /// rad/s, per corner (index 0 corner 1, 1 corner 2): energy bound of |omega| while the body
  /// has not passed alpha_s, from the work the envelope can do between two instants of rest
  /// relative to the floor (omega = 0) and the energy ratio of an impact (eq. 38).
  double omega_max[2] = {0.0, 0.0};
  /// Free flight cannot be ruled out: vertical >= g at rest, or the rocking normal reaction
  /// bound reaches 0.
  bool flight_possible = true;
  /// The static friction that rules out slide, slide-rock, slip at impact and flight for the
  /// scene while |theta| < alpha_s: max(rest, rocking, impact), +inf when flight is possible.
  double required_mu() const {
    if (flight_possible) return std::numeric_limits<double>::infinity();
    double m = rest;
    if (can_rock) {
      if (rocking > m) m = rocking;
      if (impact > m) m = impact;
    }
    return m;
  }
};

/// |P_x| / P_y of a sticking impact from pure rocking that makes corner `new_side` the pivot
/// (geometry and eq. 34 only): ContactModel's impact slips when mu_s is below it.
double impact_friction_demand(const Body& body, int new_side);

/// Bound for one body and scene. Rigorous upper bound (the reactions are linear-fractional in the
/// input and omega^2, so their ratio peaks at a corner of the envelope; the rotation is covered
/// by 64 intervals with monotone term ranges). No allocation.
SlidingBound sliding_bound(const Body& body, const SceneEnvelope& scene);

}  // namespace rocking_monitor::core
