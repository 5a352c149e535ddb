#pragma once

#include <cmath>

#include "rocking_monitor/physics/body.hpp"
#include "rocking_monitor/constants.hpp"

namespace rocking_monitor::core {

/// Which equation of motion an item runs.
enum class ModelKind {
  Nonlinear,   ///< full equation (NOTES.md, "Sign convention")
  Linearized,  ///< slender-body variant: sin(x) -> x, cos(x) -> 1
};

/// Ground acceleration over one integration piece, linear in the local time tau
/// (first-order hold between input samples): a(tau) = a0 + slope * tau. SI units.
struct GroundInput {
  double ax0 = 0.0, ax_slope = 0.0;  ///< horizontal, m/s^2 and m/s^3
  double ay0 = 0.0, ay_slope = 0.0;  ///< vertical (positive up), m/s^2 and m/s^3

  double ax(double tau) const { return ax0 + ax_slope * tau; }
  double ay(double tau) const { return ay0 + ay_slope * tau; }

  /// The straight line from sample (ax0, ay0) to the next sample (ax1, ay1), dt seconds later.
  static GroundInput first_order_hold(double ax0, double ay0, double ax1, double ay1, double dt) {
    return {ax0, (ax1 - ax0) / dt, ay0, (ay1 - ay0) / dt};
  }
};

/// Throws std::invalid_argument ("<who>: ...") unless dt is finite and > 0 and ax, ay are finite:
/// the common precondition of the streaming models' step().
void require_valid_sample(double ax, double ay, double dt, const char* who);

/// Right-hand side of pure rocking about pivot `side` (+1: corner 1, theta > 0; -1: corner 2).
/// With phi = alpha_s - s*theta (angle of the pivot->CoM line from the vertical, > 0 inside):
///   theta'' = -s p_s^2 [ (1 + a_yg/g) sin(phi) - s (a_xg/g) cos(phi) ]        (nonlinear)
/// and sin(phi) -> phi, cos(phi) -> 1 for the linearized model.
struct RockingOde {
  const Pivot* pivot = nullptr;
  int side = 1;
  ModelKind model = ModelKind::Nonlinear;
  GroundInput input;

  double angular_acceleration(double tau, double theta) const {
    const double phi = pivot->alpha - side * theta;
    const double vertical = 1.0 + input.ay(tau) / kGravity;
    const double horizontal = input.ax(tau) / kGravity;
    if (model == ModelKind::Linearized) {
      return -side * pivot->p2 * (vertical * phi - side * horizontal);
    }
    return -side * pivot->p2 * (vertical * std::sin(phi) - side * horizontal * std::cos(phi));
  }
};

/// Ground reaction on the rocking body per unit mass (R_x, R_y of paper eqs. 8-9 extended to
/// the rocking phase, including the centripetal terms), m/s^2. R_y < 0 means the body would lift
/// off (free flight); |R_x| > mu_s R_y means the pivot would slip.
struct ContactReaction {
  double rx = 0.0;
  double ry = 0.0;
};

// Inline: its callers evaluate it right after RockingOde::angular_acceleration of the same angle
// (ContactModel::rock_friction_ok, RockingModel::reaction), whose sin/cos the compiler then shares.
inline ContactReaction rocking_reaction(const Pivot& pv, int side, double theta, double omega,
                                        double theta_ddot, double ax, double ay) {
  // CoM relative to the pivot: x = s R sin(phi), y = R cos(phi), phi = alpha - s theta.
  const double phi = pv.alpha - side * theta;
  const double c = std::cos(phi);
  const double s = std::sin(phi);
  const double w2 = omega * omega;
  const double x_ddot = -pv.radius * (c * theta_ddot + side * s * w2);
  const double y_ddot = -pv.radius * c * w2 + side * pv.radius * s * theta_ddot;
  return {ax + x_ddot, kGravity + ay + y_ddot};
}

/// Distance to overturning if the excitation stopped now (the "committed" test), in units of the
/// energy needed to lift the body from rest to its tipping point about the active pivot:
/// +1 at rest, 0 on the boundary, < 0 when the body will fall without further excitation.
struct OverturnMargin {
  double margin = 1.0;
  bool committed = false;
};

OverturnMargin overturn_margin(const Pivot& pivot, int side, ModelKind model, double theta,
                               double omega);

}  // namespace rocking_monitor::core
