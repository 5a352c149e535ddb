#pragma once

// Baseline correction and integration of a ground-acceleration record to velocity and displacement.
//
// Why: a recorded accelerogram carries a small offset / slow trend (instrument zero, tilt, digitising
// drift). Integrated twice, an offset of only 1e-3 m/s^2 becomes 0.05 m of spurious displacement after
// 10 s, so PGV/PGD and the rocking input are meaningless without removing it first.
//
// Units: acceleration m/s^2, velocity m/s, displacement m, time s.

#include <cstddef>
#include <vector>

#include "rocking_monitor/motion/component.hpp"

namespace rocking_monitor::core {

/// Baseline-correction settings.
struct BaselineOptions {
  /// Degree of the least-squares polynomial (in time) subtracted from the acceleration before integration:
  /// 0 = remove the mean, 1 = remove a straight line (default, the usual minimum correction), 2 = parabola, ...
  /// A negative value disables it. Limited to <= 10 (higher degrees only fit noise and are ill-conditioned).
  int accel_poly_order = 1;

  /// Displacement fit of Ancheta et al. (2013), PEER NGA-West2 database report (also gmprocess'
  /// "baseline_sixth_order"): after integrating, fit c2 t^2 + ... + cN t^N (N = this value; no constant
  /// or linear term, so displacement and velocity still start at zero) to the displacement by least
  /// squares, subtract its second derivative from the acceleration and integrate again. This removes
  /// the long-period drift a constant/linear correction leaves. 0 disables (default); otherwise
  /// 2 <= N <= 10, 6 is the value used in the NGA-West2 processing.
  int disp_poly_order = 0;
};

/// Acceleration (after baseline correction), velocity and displacement on the sample grid of the source.
struct GroundMotionHistories {
  double dt = 0.0;            ///< sample interval, s
  double t0 = 0.0;            ///< time of the first sample, s
  std::vector<double> accel;  ///< corrected ground acceleration, m/s^2
  std::vector<double> vel;    ///< ground velocity, m/s (0 at the first sample)
  std::vector<double> disp;   ///< ground displacement, m (0 at the first sample)

  std::size_t size() const { return accel.size(); }
  double time(std::size_t i) const { return t0 + dt * static_cast<double>(i); }
};

/// The least-squares polynomial of degree `order` through the uniformly sampled y, evaluated at the
/// samples (the sample index stands in for time; a polynomial in one is a polynomial in the other).
/// The degree is clamped to y.size() - 1. Fitted by column-pivoting Householder QR in a Legendre basis on
/// a time axis scaled to [-1, 1] (not via normal equations), so it stays accurate for long records.
/// Throws std::invalid_argument for order < 0 or > 10.
std::vector<double> polynomial_trend(const std::vector<double>& y, int order);

/// y -= polynomial_trend(y, order). A polynomial trend of degree <= order is removed exactly (to rounding).
void remove_polynomial_trend(std::vector<double>& y, int order);

/// Integrates the acceleration, taken as piecewise linear between samples, EXACTLY over each interval,
/// starting from rest (vel[0] = disp[0] = 0):
///   vel[i+1]  = vel[i] + dt (a[i] + a[i+1]) / 2                       (trapezoidal rule)
///   disp[i+1] = disp[i] + dt vel[i] + dt^2 (2 a[i] + a[i+1]) / 6     (velocity piecewise quadratic)
/// The same piecewise-linear assumption as the Nigam-Jennings oscillator recursion, so ground and
/// oscillator motions are consistent; a linear acceleration is integrated without error.
/// Throws std::invalid_argument unless dt is finite and > 0. vel and disp are resized to accel.size().
void integrate_acceleration(const std::vector<double>& accel, double dt, std::vector<double>& vel,
                            std::vector<double>& disp);

/// Second derivative (m/s^2, per sample) of the least-squares fit c2 t^2 + ... + cN t^N, N = order,
/// t = time since the first sample, to the displacement `disp` (m). Subtracting it from the acceleration
/// is the Ancheta et al. (2013) correction. Throws std::invalid_argument for order < 2 or > 10 or a bad dt.
/// Short records fit at most n - 1 terms (the t = 0 sample carries none); fewer than 2 samples give zeros.
std::vector<double> displacement_fit_acceleration(const std::vector<double>& disp, double dt, int order);

/// Baseline-corrects (options) and integrates a record: acceleration polynomial removal, integration,
/// then (if enabled) the displacement fit and a second integration.
GroundMotionHistories integrate_ground_motion(const std::vector<double>& accel, double dt,
                                              const BaselineOptions& options = {}, double t0 = 0.0);

/// Same for a Component (uses its dt and t0).
GroundMotionHistories integrate_ground_motion(const Component& component, const BaselineOptions& options = {});

}  // namespace rocking_monitor::core
