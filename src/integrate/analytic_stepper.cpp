#include "rocking_monitor/integrate/analytic_stepper.hpp"

#include <cmath>

namespace rocking_monitor::core {
namespace {

struct Basis {
  double c, s, s1, s2;  // C, S, S1 = int S, S2 = int S1
};

// C(t), S(t), S1(t), S2(t) for u'' = k2 u; the power series avoids cancellation near k t = 0.
inline Basis basis(double k2, double t) {
  const double x = k2 * t * t;
  Basis b;
  if (std::abs(x) < 1e-2) {
    // Terms up to x^4 leave a relative error below 1e-15 for |x| < 1e-2.
    const double x2 = x * x, x3 = x2 * x, x4 = x3 * x;
    b.c = 1.0 + x / 2.0 + x2 / 24.0 + x3 / 720.0 + x4 / 40320.0;
    b.s = t * (1.0 + x / 6.0 + x2 / 120.0 + x3 / 5040.0 + x4 / 362880.0);
    b.s1 = t * t * (0.5 + x / 24.0 + x2 / 720.0 + x3 / 40320.0 + x4 / 3628800.0);
    b.s2 = t * t * t * (1.0 / 6.0 + x / 120.0 + x2 / 5040.0 + x3 / 362880.0 + x4 / 39916800.0);
    return b;
  }
  if (k2 > 0.0) {
    const double k = std::sqrt(k2);
    const double e = std::exp(k * t);
    const double ei = 1.0 / e;
    b.c = 0.5 * (e + ei);
    b.s = 0.5 * (e - ei) / k;
  } else {
    const double k = std::sqrt(-k2);
    b.c = std::cos(k * t);
    b.s = std::sin(k * t) / k;
  }
  b.s1 = (b.c - 1.0) / k2;
  b.s2 = (b.s - t) / k2;
  return b;
}

}  // namespace

void AnalyticStepper::step(const RockingOde& ode, double t, double theta, double omega,
                           double t_end) {
  const Pivot& pv = *ode.pivot;
  t0_ = t;
  t1_ = t_end;
  const double h = t_end - t;
  const double ay_mean = ode.input.ay(t + 0.5 * h);
  k2_ = pv.p2 * (1.0 + ay_mean / kGravity);
  offset_ = ode.side * pv.alpha;
  u0_ = theta - offset_;
  v0_ = omega;
  f0_ = pv.p2 / kGravity * ode.input.ax(t);
  f1_ = pv.p2 / kGravity * ode.input.ax_slope;
  eval(t_end, th1_, om1_);
}

void AnalyticStepper::eval(double t, double& theta, double& omega) const {
  const double tau = t - t0_;
  const Basis b = basis(k2_, tau);
  theta = offset_ + u0_ * b.c + v0_ * b.s + f0_ * b.s1 + f1_ * b.s2;
  omega = u0_ * k2_ * b.s + v0_ * b.c + f0_ * b.s + f1_ * b.s1;
}

}  // namespace rocking_monitor::core
