#pragma once

#include "rocking_monitor/physics/dynamics.hpp"

namespace rocking_monitor::core {

/// Adaptive Dormand-Prince 5(4) for the rocking ODE (theta, omega), with Hairer's 4th-order
/// dense output (Hairer, Norsett & Wanner, "Solving ODEs I", DOPRI5) used for event location.
/// Error per step is measured against atol_theta + tol*|theta| and atol_omega + tol*|omega|.
/// The step size is kept across input samples; first-same-as-last saves one RHS per step.
class Dopri5Stepper {
 public:
  /// Forget the FSAL derivative (after an event changes the state or the pivot).
  void invalidate() { fsal_valid_ = false; }
  void reset(double initial_step) {
    h_ = initial_step;
    fsal_valid_ = false;
  }

  /// Takes one accepted step from (t, theta, omega) towards t_end (never beyond it), retrying
  /// with smaller steps until the error test passes or the step reaches h_min (then accepted).
  /// Afterwards t0()/t1()/theta1()/omega1() describe the step and eval() interpolates inside it.
  /// Returns the number of RHS-evaluating attempts (for cost accounting).
  int step(const RockingOde& ode, double t, double theta, double omega, double t_end, double tol,
           double atol_theta, double atol_omega);

  /// One step of size h without error control (places the state exactly at an event time).
  void single_step(const RockingOde& ode, double t, double theta, double omega, double h,
                   double& theta_out, double& omega_out) const;

  void eval(double t, double& theta, double& omega) const;
  double t0() const { return t0_; }
  double t1() const { return t1_; }
  double theta1() const { return y1_[0]; }
  double omega1() const { return y1_[1]; }
  double step_size() const { return h_; }
  /// Controller state carried from one step to the next (the batch engine mirrors it): whether the
  /// first-same-as-last derivative is valid, and that derivative (theta', omega').
  bool fsal_valid() const { return fsal_valid_; }
  double fsal_k1(int i) const { return k1_[i]; }
  /// Sets the controller state after the same steps were taken elsewhere (BatchRocking's commit):
  /// next step size h and a valid FSAL derivative. No allocation.
  /// What a step carries to the next (state snapshots, issue 29): the step size and the FSAL
  /// derivative. The dense output belongs to the step just taken and is not kept.
  struct Saved {
    double h = 1e-3;
    bool fsal_valid = false;
    double k1_theta = 0.0, k1_omega = 0.0;
  };
  void save(Saved& out) const { out = {h_, fsal_valid_, k1_[0], k1_[1]}; }
  void restore(const Saved& in) {
    h_ = in.h;
    fsal_valid_ = in.fsal_valid;
    k1_[0] = in.k1_theta;
    k1_[1] = in.k1_omega;
  }
  void restore(double h, double k1_theta, double k1_omega) {
    h_ = h;
    k1_[0] = k1_theta;
    k1_[1] = k1_omega;
    fsal_valid_ = true;
  }

 private:
  double h_ = 1e-3;
  bool fsal_valid_ = false;
  double k1_[2] = {0.0, 0.0};
  double t0_ = 0.0, t1_ = 0.0;
  double y1_[2] = {0.0, 0.0};
  double rcont_[5][2] = {};
};

}  // namespace rocking_monitor::core
