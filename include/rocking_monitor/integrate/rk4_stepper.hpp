#pragma once

#include "rocking_monitor/physics/dynamics.hpp"

namespace rocking_monitor::core {

/// Classical fixed-step 4th-order Runge-Kutta. The model takes N equal sub-steps per input
/// sample; inside a step, theta and omega are interpolated by cubic Hermite polynomials
/// (theta from theta, omega; omega from omega, theta'') to locate events.
class Rk4Stepper {
 public:
  /// One step of size h from (t, theta, omega); afterwards eval() interpolates inside it.
  void step(const RockingOde& ode, double t, double theta, double omega, double h);
  /// Same step without touching the interpolant (to place the state at an event time).
  static void single_step(const RockingOde& ode, double t, double theta, double omega, double h,
                          double& theta_out, double& omega_out);

  void eval(double t, double& theta, double& omega) const;
  double t0() const { return t0_; }
  double t1() const { return t1_; }
  double theta1() const { return th1_; }
  double omega1() const { return om1_; }

 private:
  double t0_ = 0.0, t1_ = 0.0;
  double th0_ = 0.0, om0_ = 0.0, acc0_ = 0.0;
  double th1_ = 0.0, om1_ = 0.0, acc1_ = 0.0;
};

}  // namespace rocking_monitor::core
