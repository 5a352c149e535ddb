#pragma once
// An independent rocking simulator built on SUNDIALS CVODE (test dependency only), used to
// cross-check the package's own reference integrator (dopri5 at tight tolerance).
//
// It shares nothing with the package's integrators, event location or state machine: only the
// body geometry (Body: alpha, p^2, eq. 34 ratio per pivot) comes from the core. The model is
// restated here from ../shared/paper/NOTES.md:
//   * ground acceleration linear between input samples (first-order hold);
//   * rocking about corner s: theta'' = -s p_s^2 [(1 + a_y/g) sin(alpha_s - s theta)
//                                                 - s (a_x/g) cos(alpha_s - s theta)]
//     (sin x -> x, cos x -> 1 for the linearized model);
//   * uplift from rest when s a_x cos(alpha_s) > (a_y + g) sin(alpha_s) (linearized:
//     s a_x > (a_y + g) alpha_s); the uplift function is linear in time inside a sample, so its
//     zero is solved exactly, the earliest side wins, a tie goes to the side a_x tips to;
//   * impact when s theta returns to 0: the new pivot is -s, omega' = eta_new omega (eq. 34);
//   * rest capture: after an impact, REST when |omega'| < ratio p_new alpha_new;
//   * overturned when s theta reaches the overturn angle.
// Integration: CVODE (Adams-Moulton, Newton with a dense 2x2 solver), restarted at every input
// sample (the forcing has a kink there) and after every event; roots of s theta (impact,
// decreasing), s theta - overturn (increasing) and s omega (local maximum of s theta, decreasing).
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "rocking_monitor/physics/body.hpp"
#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/physics/dynamics.hpp"
#include "rocking_monitor/motion/ground_motion.hpp"

namespace rocking_monitor::reference {

using core::Body;
using core::GroundMotion;
using core::kGravity;
using core::ModelKind;
using core::Pivot;

/// What happened in one input sample (same meaning as core::StepReport's fields).
struct SampleSummary {
  int impacts = 0;
  double first_impact_time = std::numeric_limits<double>::quiet_NaN();
  double peak_ratio = 0.0;  ///< largest local maximum of |theta|/alpha inside the sample
  bool uplift = false;
  bool rest_capture = false;
};

struct CvodeResult {
  std::vector<SampleSummary> samples;     ///< one per step (input sample 1..n-1)
  std::vector<double> impact_times;       ///< every impact, s
  std::vector<double> peak_ratios;        ///< every local maximum of |theta|/alpha, in order
  double max_ratio = 0.0;
  bool overturned = false;
  double overturn_time = std::numeric_limits<double>::quiet_NaN();
  double uplift_time = std::numeric_limits<double>::quiet_NaN();
  long rest_captures = 0;
  long cvode_steps = 0;
};

class CvodeRocking {
 public:
  CvodeRocking(const Body& body, ModelKind model, double rtol, double atol_ratio,
               double rest_capture_ratio = 1e-3)
      : body_(body), model_(model), rtol_(rtol), atol_ratio_(atol_ratio),
        rest_ratio_(rest_capture_ratio) {
    if (SUNContext_Create(nullptr, &ctx_) != 0) throw std::runtime_error("SUNContext_Create");
    y_ = N_VNew_Serial(2, ctx_);
    atol_ = N_VNew_Serial(2, ctx_);
    mem_ = CVodeCreate(CV_ADAMS, ctx_);
    N_VConst(0.0, y_);
    check(CVodeInit(mem_, &CvodeRocking::rhs, 0.0, y_), "CVodeInit");
    check(CVodeSetUserData(mem_, this), "CVodeSetUserData");
    A_ = SUNDenseMatrix(2, 2, ctx_);
    ls_ = SUNLinSol_Dense(y_, A_, ctx_);
    check(CVodeSetLinearSolver(mem_, ls_, A_), "CVodeSetLinearSolver");
    check(CVodeRootInit(mem_, 3, &CvodeRocking::roots), "CVodeRootInit");
    int dir[3] = {-1, +1, -1};
    check(CVodeSetRootDirection(mem_, dir), "CVodeSetRootDirection");
    check(CVodeSetNoInactiveRootWarn(mem_), "CVodeSetNoInactiveRootWarn");
    check(CVodeSetMaxNumSteps(mem_, 1000000), "CVodeSetMaxNumSteps");
    check(CVodeSetMaxOrd(mem_, 12), "CVodeSetMaxOrd");
  }
  ~CvodeRocking() {
    CVodeFree(&mem_);
    SUNLinSolFree(ls_);
    SUNMatDestroy(A_);
    N_VDestroy(y_);
    N_VDestroy(atol_);
    SUNContext_Free(&ctx_);
  }
  CvodeRocking(const CvodeRocking&) = delete;
  CvodeRocking& operator=(const CvodeRocking&) = delete;

  /// Runs a whole record. theta0 != 0 starts rocking from rest at that angle (free rocking);
  /// otherwise the body starts at REST with the first sample.
  CvodeResult run(const GroundMotion& g, double theta0 = 0.0) {
    CvodeResult res;
    side_ = 0;
    theta_ = omega_ = 0.0;
    if (theta0 != 0.0) {
      side_ = theta0 > 0.0 ? 1 : -1;
      theta_ = theta0;
      res.max_ratio = std::abs(theta0) / pivot().alpha;
    }
    overturned_ = false;
    const std::size_t n = g.size();
    res.samples.reserve(n);
    for (std::size_t k = 1; k < n && !overturned_; ++k) {
      SampleSummary sum;
      t0_ = g.t0 + static_cast<double>(k - 1) * g.dt;
      const double t_end = t0_ + g.dt;
      ax0_ = g.horizontal[k - 1];
      ax1_ = (g.horizontal[k] - ax0_) / g.dt;
      ay0_ = g.ay(k - 1);
      ay1_ = (g.ay(k) - ay0_) / g.dt;
      double t = t0_;
      while (t < t_end && !overturned_) {
        if (side_ == 0) {
          const double tu = uplift_time(t, t_end);
          if (std::isinf(tu)) break;  // stays at rest for the rest of the sample
          side_ = uplift_side_;
          theta_ = omega_ = 0.0;
          t = tu;
          sum.uplift = true;
          if (std::isnan(res.uplift_time)) res.uplift_time = tu;
        }
        t = integrate(t, t_end, res, sum);
      }
      res.samples.push_back(sum);
    }
    return res;
  }

 private:
  static void check(int flag, const char* what) {
    if (flag < 0) throw std::runtime_error(std::string("CVODE: ") + what + " failed");
  }
  double ax(double t) const { return ax0_ + ax1_ * (t - t0_); }
  double ay(double t) const { return ay0_ + ay1_ * (t - t0_); }
  const Pivot& pivot() const { return body_.pivot(side_); }

  double acceleration(double t, double theta) const {
    const Pivot& pv = pivot();
    const double phi = pv.alpha - side_ * theta;
    const double v = 1.0 + ay(t) / kGravity, h = ax(t) / kGravity;
    if (model_ == ModelKind::Linearized) return -side_ * pv.p2 * (v * phi - side_ * h);
    return -side_ * pv.p2 * (v * std::sin(phi) - side_ * h * std::cos(phi));
  }

  double uplift_fn(int s, double t) const {
    const Pivot& pv = body_.pivot(s);
    if (model_ == ModelKind::Linearized) return s * ax(t) - (ay(t) + kGravity) * pv.alpha;
    return s * ax(t) * pv.cos_alpha - (ay(t) + kGravity) * pv.sin_alpha;
  }

  // Earliest time in [t, t_end] at which a corner lifts (+inf if none); sets uplift_side_.
  double uplift_time(double t, double t_end) {
    double best = std::numeric_limits<double>::infinity();
    uplift_side_ = 0;
    for (int s : {1, -1}) {
      const double u0 = uplift_fn(s, t), u1 = uplift_fn(s, t_end);
      double when;
      if (u0 > 0.0) when = t;
      else if (u1 > 0.0) when = std::clamp(t + (t_end - t) * (-u0) / (u1 - u0), t, t_end);
      else continue;
      const int tip = ax(when) >= 0.0 ? 1 : -1;
      if (when < best || (when == best && s == tip)) {
        best = when;
        uplift_side_ = s;
      }
    }
    return best;
  }

  void restart(double t) {
    NV_Ith_S(y_, 0) = theta_;
    NV_Ith_S(y_, 1) = omega_;
    const Pivot& pv = pivot();
    NV_Ith_S(atol_, 0) = atol_ratio_ * pv.alpha;
    NV_Ith_S(atol_, 1) = atol_ratio_ * pv.p * pv.alpha;
    check(CVodeReInit(mem_, t, y_), "CVodeReInit");
    check(CVodeSVtolerances(mem_, rtol_, atol_), "CVodeSVtolerances");
  }

  // Rocks from t towards t_end; returns the time reached (t_end, or an event time after which
  // the state machine continues: impact applied, rest capture, overturn).
  double integrate(double t, double t_end, CvodeResult& res, SampleSummary& sum) {
    restart(t);
    check(CVodeSetStopTime(mem_, t_end), "CVodeSetStopTime");
    for (;;) {
      double tret = t;
      const int flag = CVode(mem_, t_end, y_, &tret, CV_NORMAL);
      check(flag, "CVode");
      long nst = 0;
      CVodeGetNumSteps(mem_, &nst);
      theta_ = NV_Ith_S(y_, 0);
      omega_ = NV_Ith_S(y_, 1);
      if (flag != CV_ROOT_RETURN) {
        res.cvode_steps += nst;
        return t_end;
      }
      int info[3] = {0, 0, 0};
      CVodeGetRootInfo(mem_, info);
      if (info[2] != 0) {  // local maximum of s theta
        const double r = side_ * theta_ / pivot().alpha;
        res.peak_ratios.push_back(r);
        res.max_ratio = std::max(res.max_ratio, r);
        sum.peak_ratio = std::max(sum.peak_ratio, r);
      }
      if (info[1] != 0) {  // overturn
        overturned_ = true;
        res.overturned = true;
        res.overturn_time = tret;
        res.max_ratio = std::max(res.max_ratio, body_.overturn_angle() / pivot().alpha);
        res.cvode_steps += nst;
        return t_end;
      }
      if (info[0] != 0) {  // impact: switch pivot, eq. 34, rest capture
        res.impact_times.push_back(tret);
        if (sum.impacts++ == 0) sum.first_impact_time = tret;
        res.cvode_steps += nst;
        const int new_side = -side_;
        const Pivot& pv = body_.pivot(new_side);
        const double w = pv.restitution * omega_;
        if (pv.restitution <= 0.0 || std::abs(w) < rest_ratio_ * pv.p * pv.alpha) {
          side_ = 0;
          theta_ = omega_ = 0.0;
          sum.rest_capture = true;
          ++res.rest_captures;
        } else {
          side_ = new_side;
          theta_ = 0.0;
          omega_ = w;
        }
        return tret;
      }
      // Only a peak: CVODE continues from the root by itself.
    }
  }

  static int rhs(double t, N_Vector y, N_Vector ydot, void* user) {
    const auto* self = static_cast<const CvodeRocking*>(user);
    NV_Ith_S(ydot, 0) = NV_Ith_S(y, 1);
    NV_Ith_S(ydot, 1) = self->acceleration(t, NV_Ith_S(y, 0));
    return 0;
  }
  static int roots(double /*t*/, N_Vector y, double* g, void* user) {
    const auto* self = static_cast<const CvodeRocking*>(user);
    const int s = self->side_;
    g[0] = s * NV_Ith_S(y, 0);
    g[1] = s * NV_Ith_S(y, 0) - self->body_.overturn_angle();
    g[2] = s * NV_Ith_S(y, 1);
    return 0;
  }

  Body body_;
  ModelKind model_;
  double rtol_, atol_ratio_, rest_ratio_;
  SUNContext ctx_ = nullptr;
  N_Vector y_ = nullptr, atol_ = nullptr;
  SUNMatrix A_ = nullptr;
  SUNLinearSolver ls_ = nullptr;
  void* mem_ = nullptr;
  int side_ = 0, uplift_side_ = 0;
  double theta_ = 0.0, omega_ = 0.0;
  bool overturned_ = false;
  double t0_ = 0.0, ax0_ = 0.0, ax1_ = 0.0, ay0_ = 0.0, ay1_ = 0.0;
};

}  // namespace rocking_monitor::reference
