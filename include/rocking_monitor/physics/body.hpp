#pragma once

#include <limits>
#include <stdexcept>
#include <string>

namespace rocking_monitor::core {

/// Thrown for an invalid body; what() names the field and the offending value.
class BodyError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// What the user describes (paper, "Model Geometry", Figure 1). SI units.
/// Corner 1 is at x = 0, corner 2 at x = B, the centre of mass at (nu1 B, h).
struct BodyParameters {
  double width = 0.0;        ///< B, base width, m
  double cg_height = 0.0;    ///< h, height of the centre of mass, m
  double nu1 = 0.5;          ///< horizontal eccentricity: CoM at nu1*B from corner 1, in (0, 1)
  /// i_g, central radius of gyration, m. NaN = homogeneous rectangle of width B and height 2h,
  /// i_g^2 = (B^2 + (2h)^2) / 12.
  double radius_of_gyration = std::numeric_limits<double>::quiet_NaN();
  /// mu_s, static friction coefficient. +inf = friction not given: sliding criteria not evaluated.
  double mu_s = std::numeric_limits<double>::infinity();
  /// mu_k, kinetic friction (not used by the pure-rocking model; kept for the sliding model). NaN = mu_s.
  double mu_k = std::numeric_limits<double>::quiet_NaN();
  /// Measured angular-velocity ratio at impact, in [0, 1]. NaN = theory (paper eq. 34).
  double restitution = std::numeric_limits<double>::quiet_NaN();
  /// Added to each pivot's ratio (eq. 34's, or `restitution` when given), the sum clipped to
  /// [0, 1]: an ensemble's spread around the theory that keeps the per-pivot dependence on alpha.
  /// In [-1, 1]; 0 = none (the ratio unchanged, bit for bit).
  double restitution_shift = 0.0;
  /// |theta| at which the body lies on its side and is counted OVERTURNED, rad (pi/2 for a box).
  double overturn_angle = 1.5707963267948966;
};

/// Quantities of rocking about one base corner (pivot). Derived once, used every step.
struct Pivot {
  double nu = 0.0;           ///< nu_s: horizontal distance pivot->CoM as a fraction of B
  double alpha = 0.0;        ///< tipping angle, atan(nu B / h) (eqs. 4, 5), rad
  double radius = 0.0;       ///< R, pivot->CoM distance, m
  double inertia = 0.0;      ///< I_O / m = i_g^2 + R^2, m^2 (eqs. 28, 29)
  double p2 = 0.0;           ///< p^2 = g R / (I_O/m), frequency parameter squared, rad^2/s^2
  double p = 0.0;            ///< p, rad/s
  double sin_alpha = 0.0;
  double cos_alpha = 0.0;
  double tan_alpha = 0.0;    ///< = nu B / h = 1/gamma (eq. 17): uplift threshold of |A| (eq. 19)
  double gamma = 0.0;        ///< h / (nu B) (eq. 17)
  /// Angular-velocity ratio for an impact that makes THIS corner the new pivot (eq. 34 with
  /// nu_s = this pivot's nu), or the user's restitution when given.
  double restitution = 0.0;
};

/// A validated body with both pivots derived. pivot(+1) is corner 1 (theta > 0),
/// pivot(-1) corner 2 (theta < 0).
class Body {
 public:
  /// Throws BodyError naming the field and value (B<=0, h<=0, nu1 outside (0,1), i_g<=0,
  /// mu<0, restitution outside [0,1], NaN anywhere it is not a documented default).
  explicit Body(const BodyParameters& parameters);

  const BodyParameters& parameters() const { return params_; }
  const Pivot& pivot(int side) const { return side > 0 ? pivot1_ : pivot2_; }
  double width() const { return params_.width; }
  double cg_height() const { return params_.cg_height; }
  double nu1() const { return params_.nu1; }
  double nu2() const { return 1.0 - params_.nu1; }
  double radius_of_gyration() const { return ig_; }
  double mu_s() const { return params_.mu_s; }
  double overturn_angle() const { return params_.overturn_angle; }
  bool uses_theoretical_restitution() const;

  /// Rectangle's central radius of gyration, m.
  static double homogeneous_radius_of_gyration(double width, double cg_height);

 private:
  Pivot make_pivot(double nu, double nu_other) const;

  BodyParameters params_;
  double ig_ = 0.0;
  Pivot pivot1_;
  Pivot pivot2_;
};

/// Validates without constructing; returns an empty string when valid, else the message.
std::string validate(const BodyParameters& parameters);

}  // namespace rocking_monitor::core
