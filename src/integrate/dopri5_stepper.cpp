#include "rocking_monitor/integrate/dopri5_stepper.hpp"
#include "rocking_monitor/integrate/dopri5_tableau.hpp"

#include <algorithm>
#include <cmath>

namespace rocking_monitor::core {
namespace {

using namespace dopri5_tableau;  // the coefficients (integrate/dopri5_tableau.hpp)
constexpr double d1 = -12715105075.0 / 11282082432.0, d3 = 87487479700.0 / 32700410799.0,
                 d4 = -10690763975.0 / 1880347072.0, d5 = 701980252875.0 / 199316789632.0,
                 d6 = -1453857185.0 / 822651844.0, d7 = 69997945.0 / 29380423.0;

struct Stages {
  double k[8][2];  // k[1..7]
  double y[2];     // 5th-order solution
};

inline void rhs(const RockingOde& ode, double t, double th, double om, double* out) {
  out[0] = om;
  out[1] = ode.angular_acceleration(t, th);
}

// Computes stages 2..7 given k[1]; k[7] = f(t + h, y5) (FSAL).
inline void stages(const RockingOde& ode, double t, double th, double om, double h, Stages& s) {
  auto& k = s.k;
  double y0, y1;
  y0 = th + h * a21 * k[1][0];
  y1 = om + h * a21 * k[1][1];
  rhs(ode, t + c2 * h, y0, y1, k[2]);
  y0 = th + h * (a31 * k[1][0] + a32 * k[2][0]);
  y1 = om + h * (a31 * k[1][1] + a32 * k[2][1]);
  rhs(ode, t + c3 * h, y0, y1, k[3]);
  y0 = th + h * (a41 * k[1][0] + a42 * k[2][0] + a43 * k[3][0]);
  y1 = om + h * (a41 * k[1][1] + a42 * k[2][1] + a43 * k[3][1]);
  rhs(ode, t + c4 * h, y0, y1, k[4]);
  y0 = th + h * (a51 * k[1][0] + a52 * k[2][0] + a53 * k[3][0] + a54 * k[4][0]);
  y1 = om + h * (a51 * k[1][1] + a52 * k[2][1] + a53 * k[3][1] + a54 * k[4][1]);
  rhs(ode, t + c5 * h, y0, y1, k[5]);
  y0 = th + h * (a61 * k[1][0] + a62 * k[2][0] + a63 * k[3][0] + a64 * k[4][0] + a65 * k[5][0]);
  y1 = om + h * (a61 * k[1][1] + a62 * k[2][1] + a63 * k[3][1] + a64 * k[4][1] + a65 * k[5][1]);
  rhs(ode, t + h, y0, y1, k[6]);
  s.y[0] = th + h * (a71 * k[1][0] + a73 * k[3][0] + a74 * k[4][0] + a75 * k[5][0] + a76 * k[6][0]);
  s.y[1] = om + h * (a71 * k[1][1] + a73 * k[3][1] + a74 * k[4][1] + a75 * k[5][1] + a76 * k[6][1]);
  rhs(ode, t + h, s.y[0], s.y[1], k[7]);
}

}  // namespace

int Dopri5Stepper::step(const RockingOde& ode, double t, double theta, double omega, double t_end,
                        double tol, double atol_theta, double atol_omega) {
  Stages s;
  if (!fsal_valid_) rhs(ode, t, theta, omega, k1_);
  const double remaining = t_end - t;
  const double h_min = 1e-12 * std::max(1.0, std::abs(t_end));
  double h = std::min(h_, remaining);
  if (remaining - h < 0.01 * h) h = remaining;  // avoid a sliver step at the end of the piece
  int attempts = 0;
  for (;;) {
    ++attempts;
    s.k[1][0] = k1_[0];
    s.k[1][1] = k1_[1];
    stages(ode, t, theta, omega, h, s);
    const auto& k = s.k;
    double err = 0.0;
    const double y0[2] = {theta, omega};
    const double atol[2] = {atol_theta, atol_omega};
    for (int i = 0; i < 2; ++i) {
      const double ei = h * (e1 * k[1][i] + e3 * k[3][i] + e4 * k[4][i] + e5 * k[5][i] +
                             e6 * k[6][i] + e7 * k[7][i]);
      const double sc = atol[i] + tol * std::max(std::abs(y0[i]), std::abs(s.y[i]));
      err += (ei / sc) * (ei / sc);
    }
    err = std::sqrt(0.5 * err);
    // Standard controller: safety 0.9, growth limited to [0.2, 5].
    const double factor =
        err == 0.0 ? 5.0 : std::min(5.0, std::max(0.2, 0.9 * std::pow(err, -0.2)));
    if (err <= 1.0 || h <= h_min || attempts >= 50) {
      t0_ = t;
      t1_ = (h == remaining) ? t_end : t + h;
      y1_[0] = s.y[0];
      y1_[1] = s.y[1];
      for (int i = 0; i < 2; ++i) {
        const double ydiff = s.y[i] - y0[i];
        const double bspl = h * k[1][i] - ydiff;
        rcont_[0][i] = y0[i];
        rcont_[1][i] = ydiff;
        rcont_[2][i] = bspl;
        rcont_[3][i] = ydiff - h * k[7][i] - bspl;
        rcont_[4][i] = h * (d1 * k[1][i] + d3 * k[3][i] + d4 * k[4][i] + d5 * k[5][i] +
                            d6 * k[6][i] + d7 * k[7][i]);
      }
      k1_[0] = k[7][0];
      k1_[1] = k[7][1];
      fsal_valid_ = true;
      // A step cut short by the end of the piece must not shrink the next one.
      const double h_next = h * factor;
      h_ = (h == remaining && h < h_) ? std::max(h_, h_next) : h_next;
      return attempts;
    }
    h = std::max(h * factor, h_min);
  }
}

void Dopri5Stepper::single_step(const RockingOde& ode, double t, double theta, double omega,
                                double h, double& theta_out, double& omega_out) const {
  Stages s;
  rhs(ode, t, theta, omega, s.k[1]);
  stages(ode, t, theta, omega, h, s);
  theta_out = s.y[0];
  omega_out = s.y[1];
}

void Dopri5Stepper::eval(double t, double& theta, double& omega) const {
  const double h = t1_ - t0_;
  const double s = h > 0.0 ? (t - t0_) / h : 1.0;
  const double s1 = 1.0 - s;
  double out[2];
  for (int i = 0; i < 2; ++i) {
    out[i] = rcont_[0][i] +
             s * (rcont_[1][i] + s1 * (rcont_[2][i] + s * (rcont_[3][i] + s1 * rcont_[4][i])));
  }
  theta = out[0];
  omega = out[1];
}

}  // namespace rocking_monitor::core
