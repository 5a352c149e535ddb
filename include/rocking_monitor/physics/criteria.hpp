#pragma once

#include <cstdint>

#include "rocking_monitor/physics/body.hpp"
#include "rocking_monitor/physics/dynamics.hpp"

namespace rocking_monitor::core {

// ------------------------------------------------------------------ contact (paper eqs. 11-26)

/// Conditions under which the pure-rocking model no longer holds ("Limiting condition").
enum class Criterion : std::uint8_t {
  FreeFlight = 0,         ///< a_yg + g < 0 at rest (eq. 11) or R_y < 0 while rocking
  SlideFromRest = 1,      ///< |A| > mu_s at rest (eq. 22 violated)
  SlideAtUplift = 2,      ///< rocking starts but mu_s is below eq. 25 (eq. 26 at the threshold)
  SlideWhileRocking = 3,  ///< |R_x| / R_y > mu_s during rocking
};
inline constexpr int kCriterionCount = 4;
const char* to_string(Criterion criterion);

/// A = a_xg / (a_yg + g) (eq. 18).
double acceleration_ratio(double ax, double ay);

/// Pivot the body would tip about from rest: +1 (corner 1) for a_xg >= 0, else -1 (eqs. 12-13).
inline int tipping_side(double ax) { return ax >= 0.0 ? 1 : -1; }

/// Eq. 11 violated: the ground pulls away faster than gravity, the body leaves the ground.
inline bool free_flight(double ay) { return ay + kGravity < 0.0; }

/// Uplift from rest (eq. 19): |A| >= 1/gamma with nu_s by the sign of a_xg. Written as
/// s a_xg cos(alpha_s) > (a_yg + g) sin(alpha_s), which is eq. 19 when a_yg + g > 0 and is exactly
/// the sign of theta'' at theta = 0 (so the model and the criterion agree). The linearized model
/// has its own threshold |A| > alpha_s (tan alpha -> alpha); pass its kind to get that one.
/// Returns the side that lifts (+1/-1) or 0 for none.
int uplift_side(const Body& body, double ax, double ay, ModelKind model = ModelKind::Nonlinear);

/// Uplift function of one side, > 0 when that corner lifts; linear in a_xg and a_yg.
double uplift_function(const Pivot& pivot, int side, ModelKind model, double ax, double ay);

/// Eq. 22 violated: the static friction cannot hold the body at rest.
bool slides_from_rest(const Body& body, double ax, double ay);

/// Right-hand side of eq. 25: the smallest mu_s for which the body starts to rock without slip
/// under ratio |A| about the pivot with coefficient nu_s. At |A| = 1/gamma it equals 1/gamma (eq. 26).
double rock_without_slip_friction(const Body& body, const Pivot& pivot, double abs_a);

/// |R_x| > mu_s R_y while rocking ("Limit to avoid sliding from rocking").
bool slides_while_rocking(const ContactReaction& reaction, double mu_s);

// ------------------------------------------------------------------ overturning screening (eqs. 1-2)

/// Housner's pseudo-velocity for a 50 % chance of overturning (eq. 1), m/s.
/// alpha: corner->CoM angle from the vertical (rad); r: corner->CoM distance (m).
double housner_pseudo_velocity(double alpha, double r);

/// Thresholds of Ishiyama's criterion (eq. 2): overturning needs v_max > velocity AND
/// a_max >= acceleration.
struct IshiyamaThreshold {
  double velocity = 0.0;      ///< m/s
  double acceleration = 0.0;  ///< m/s^2
};

/// Eq. 2 for a symmetric block of base `base` and centre-of-mass height h (H = 2h):
/// velocity = coefficient * S_v(eq. 1) with alpha = atan(base / 2h), r = sqrt(base^2 + 4h^2)/2;
/// acceleration = (base / 2h) g.
IshiyamaThreshold ishiyama_threshold(double base, double cg_height, double coefficient = 0.4);

/// Period at which the record's pseudo-velocity spectrum is read for Housner's criterion:
/// T = 2 pi / p of the weaker corner (smaller alpha), s. Housner compared the rocking block with a
/// pendulum of frequency p; the 5 %-damped PSV at that period is the demand compared with eq. 1.
double housner_period(const Body& body);

/// The four screening criteria the paper compares, for one body.
struct ScreeningThresholds {
  double housner_pseudo_velocity = 0.0;  ///< eq. 1 with the body's smaller alpha and its R, m/s
  IshiyamaThreshold ishiyama;            ///< eq. 2, body taken as symmetric (nu = 0.5)
  IshiyamaThreshold ishiyama_equivalent; ///< eq. 2 with B' = 2 nu_min B (paper, result 1)
  IshiyamaThreshold proposed;            ///< eq. 2 with 0.2 instead of 0.4, symmetric geometry (result 2)
};
ScreeningThresholds screening_thresholds(const Body& body);

/// Which criteria predict overturning for a record with the given peaks.
struct ScreeningPrediction {
  bool housner = false;              ///< S_v(record) >= eq. 1 threshold
  bool ishiyama = false;
  bool ishiyama_equivalent = false;
  bool proposed = false;
};
/// pgv in m/s, pga in m/s^2, spectral_pseudo_velocity (the record's S_v for Housner) in m/s.
ScreeningPrediction screening_prediction(const ScreeningThresholds& thresholds, double pga,
                                         double pgv, double spectral_pseudo_velocity);

}  // namespace rocking_monitor::core
