#pragma once

// Dormand-Prince 5(4) for a fixed-size state (the 3-D model's pivoting on a vertex: orientation
// quaternion and angular velocity), with Hairer's dense output for event location. The same
// tableau and controller as the planar Dopri5Stepper; no allocation (Eigen fixed-size vectors).

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "rocking_monitor/integrate/dopri5_tableau.hpp"

namespace rocking_monitor::core {

template <int N>
class Dopri5Vector {
 public:
  using State = Eigen::Matrix<double, N, 1>;

  void invalidate() { fsal_valid_ = false; }
  void reset(double initial_step) {
    h_ = initial_step;
    fsal_valid_ = false;
  }

  /// One accepted step from (t, y) towards t_end (never beyond); f(t, y, dy). Error per component
  /// against atol(i) + tol |y_i|. Returns the number of attempts.
  template <class F>
  int step(const F& f, double t, const State& y, double t_end, double tol, const State& atol) {
    using namespace dopri5_tableau;
    if (!fsal_valid_) f(t, y, k_[0]);
    const double remaining = t_end - t;
    const double h_min = 1e-12 * std::max(1.0, std::abs(t_end));
    double h = std::min(h_, remaining);
    if (remaining - h < 0.01 * h) h = remaining;
    int attempts = 0;
    for (;;) {
      ++attempts;
      State yy;
      yy = y + h * a21 * k_[0];
      f(t + c2 * h, yy, k_[1]);
      yy = y + h * (a31 * k_[0] + a32 * k_[1]);
      f(t + c3 * h, yy, k_[2]);
      yy = y + h * (a41 * k_[0] + a42 * k_[1] + a43 * k_[2]);
      f(t + c4 * h, yy, k_[3]);
      yy = y + h * (a51 * k_[0] + a52 * k_[1] + a53 * k_[2] + a54 * k_[3]);
      f(t + c5 * h, yy, k_[4]);
      yy = y + h * (a61 * k_[0] + a62 * k_[1] + a63 * k_[2] + a64 * k_[3] + a65 * k_[4]);
      f(t + h, yy, k_[5]);
      const State y5 = y + h * (a71 * k_[0] + a73 * k_[2] + a74 * k_[3] + a75 * k_[4] + a76 * k_[5]);
      f(t + h, y5, k_[6]);
      const State err_v =
          h * (e1 * k_[0] + e3 * k_[2] + e4 * k_[3] + e5 * k_[4] + e6 * k_[5] + e7 * k_[6]);
      double err = 0.0;
      for (int i = 0; i < N; ++i) {
        const double sc = atol(i) + tol * std::max(std::abs(y(i)), std::abs(y5(i)));
        err += (err_v(i) / sc) * (err_v(i) / sc);
      }
      err = std::sqrt(err / N);
      const double factor = err == 0.0 ? 5.0 : std::min(5.0, std::max(0.2, 0.9 * std::pow(err, -0.2)));
      if (err <= 1.0 || h <= h_min || attempts >= 50) {
        constexpr double d1 = -12715105075.0 / 11282082432.0, d3 = 87487479700.0 / 32700410799.0,
                         d4 = -10690763975.0 / 1880347072.0, d5 = 701980252875.0 / 199316789632.0,
                         d6 = -1453857185.0 / 822651844.0, d7 = 69997945.0 / 29380423.0;
        t0_ = t;
        t1_ = (h == remaining) ? t_end : t + h;
        y1_ = y5;
        const State ydiff = y5 - y;
        const State bspl = h * k_[0] - ydiff;
        r_[0] = y;
        r_[1] = ydiff;
        r_[2] = bspl;
        r_[3] = ydiff - h * k_[6] - bspl;
        r_[4] = h * (d1 * k_[0] + d3 * k_[2] + d4 * k_[3] + d5 * k_[4] + d6 * k_[5] + d7 * k_[6]);
        k_[0] = k_[6];
        fsal_valid_ = true;
        const double h_next = h * factor;
        h_ = (h == remaining && h < h_) ? std::max(h_, h_next) : h_next;
        return attempts;
      }
      h = std::max(h * factor, h_min);
    }
  }

  /// The dense output inside the last step.
  /// What a step carries to the next (state snapshots, issue 29): the step size and the FSAL derivative.
  struct Saved {
    double h = 1e-3;
    bool fsal_valid = false;
    State k1 = State::Zero();
  };
  void save(Saved& out) const {
    out.h = h_;
    out.fsal_valid = fsal_valid_;
    out.k1 = k_[0];
  }
  void restore(const Saved& in) {
    h_ = in.h;
    fsal_valid_ = in.fsal_valid;
    k_[0] = in.k1;
  }

  State eval(double t) const {
    const double h = t1_ - t0_;
    const double s = h > 0.0 ? (t - t0_) / h : 1.0;
    const double s1 = 1.0 - s;
    return r_[0] + s * (r_[1] + s1 * (r_[2] + s * (r_[3] + s1 * r_[4])));
  }
  double t0() const { return t0_; }
  double t1() const { return t1_; }
  const State& y1() const { return y1_; }
  /// f(t1, y1), computed by the last step (first same as last): valid until the next step or invalidate().
  const State& derivative1() const { return k_[0]; }

 private:
  double h_ = 1e-3;
  bool fsal_valid_ = false;
  State k_[7];
  State r_[5];
  State y1_ = State::Zero();
  double t0_ = 0.0, t1_ = 0.0;
};

}  // namespace rocking_monitor::core
