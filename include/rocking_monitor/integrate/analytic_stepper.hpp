#pragma once

#include "rocking_monitor/physics/dynamics.hpp"

namespace rocking_monitor::core {

/// Exact stepping of the LINEARIZED rocking equation. With u = theta - s*alpha it reads
///   u'' = k^2 u + (p^2/g) a_xg(t),   k^2 = p^2 (1 + a_yg/g),
/// which for a_xg linear in time has the closed-form solution
///   u(t) = u0 C(t) + u0' S(t) + f0 S1(t) + f1 S2(t),
/// C = cosh(kt), S = sinh(kt)/k, S1 = (C-1)/k^2, S2 = (S-t)/k^2 (series near k t = 0, and the
/// trigonometric forms when k^2 < 0, i.e. a_yg < -g). The solution is exact for a constant vertical
/// acceleration over the piece; a varying a_yg is represented by its mean over the piece.
class AnalyticStepper {
 public:
  /// Prepares the closed form for the piece [t, t_end] from (theta, omega); the state at t_end is
  /// then theta1()/omega1() and eval() gives the exact solution anywhere inside.
  void step(const RockingOde& ode, double t, double theta, double omega, double t_end);

  void eval(double t, double& theta, double& omega) const;
  double t0() const { return t0_; }
  double t1() const { return t1_; }
  double theta1() const { return th1_; }
  double omega1() const { return om1_; }

 private:
  double t0_ = 0.0, t1_ = 0.0;
  double k2_ = 0.0;            // k^2, 1/s^2
  double u0_ = 0.0, v0_ = 0.0; // u and u' at t0
  double f0_ = 0.0, f1_ = 0.0; // forcing (p^2/g) a_xg = f0 + f1 (t - t0), rad/s^2 and rad/s^3
  double offset_ = 0.0;        // s * alpha, so theta = u + offset
  double th1_ = 0.0, om1_ = 0.0;
};

}  // namespace rocking_monitor::core
