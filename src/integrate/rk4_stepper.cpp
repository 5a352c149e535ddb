#include "rocking_monitor/integrate/rk4_stepper.hpp"

namespace rocking_monitor::core {

void Rk4Stepper::single_step(const RockingOde& ode, double t, double th, double om, double h,
                             double& theta_out, double& omega_out) {
  const double k1t = om, k1w = ode.angular_acceleration(t, th);
  const double k2t = om + 0.5 * h * k1w, k2w = ode.angular_acceleration(t + 0.5 * h, th + 0.5 * h * k1t);
  const double k3t = om + 0.5 * h * k2w, k3w = ode.angular_acceleration(t + 0.5 * h, th + 0.5 * h * k2t);
  const double k4t = om + h * k3w, k4w = ode.angular_acceleration(t + h, th + h * k3t);
  theta_out = th + h / 6.0 * (k1t + 2.0 * k2t + 2.0 * k3t + k4t);
  omega_out = om + h / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w);
}

void Rk4Stepper::step(const RockingOde& ode, double t, double theta, double omega, double h) {
  t0_ = t;
  t1_ = t + h;
  th0_ = theta;
  om0_ = omega;
  acc0_ = ode.angular_acceleration(t, theta);
  single_step(ode, t, theta, omega, h, th1_, om1_);
  acc1_ = ode.angular_acceleration(t1_, th1_);
}

void Rk4Stepper::eval(double t, double& theta, double& omega) const {
  const double h = t1_ - t0_;
  const double s = h > 0.0 ? (t - t0_) / h : 1.0;
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2,
               h11 = s3 - s2;
  theta = h00 * th0_ + h10 * h * om0_ + h01 * th1_ + h11 * h * om1_;
  omega = h00 * om0_ + h10 * h * acc0_ + h01 * om1_ + h11 * h * acc1_;
}

}  // namespace rocking_monitor::core
