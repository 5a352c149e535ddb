// BatchRocking's vector kernels (Highway, compiled once per SIMD target, dispatched at run time).
// The dopri5 kernel repeats Dopri5Stepper::step and RockingOde::angular_acceleration operation
// by operation, in the same order, so that each lane gives the scalar model's bits; this file is
// compiled with -ffp-contract=off (cmake/layers.cmake): no fused multiply-add may change them.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/model/batch_rocking_simd.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>
#include <hwy/contrib/math/math-inl.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/integrate/dopri5_tableau.hpp"
#include "rocking_monitor/model/batch_rocking.hpp"

HWY_BEFORE_NAMESPACE();
namespace rocking_monitor::core::batch_detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using namespace dopri5_tableau;  // the coefficients (integrate/dopri5_tableau.hpp)

void UpliftTest(BatchRocking::Lanes& l, std::size_t n, bool /*linearized*/) {
  const hn::ScalableTag<double> d;
  const std::size_t L = hn::Lanes(d);
  const auto g = hn::Set(d, kGravity);
  const auto zero = hn::Zero(d);
  const auto rel = hn::Set(d, 1e-12);
  for (std::size_t i = 0; i < n; i += L) {
    const auto axp = hn::LoadU(d, l.ax_prev.data() + i), ayp = hn::LoadU(d, l.ay_prev.data() + i);
    const auto axn = hn::LoadU(d, l.ax_now.data() + i), ayn = hn::LoadU(d, l.ay_now.data() + i);
    // Rounding room: the scalar code evaluates the end of the sample as ax0 + slope * dt.
    const auto scale = hn::Add(hn::Add(hn::Add(hn::Abs(axp), hn::Abs(axn)),
                                       hn::Add(hn::Abs(ayp), hn::Abs(ayn))), g);
    const auto margin = hn::Neg(hn::Mul(rel, scale));
    auto lift = hn::Lt(zero, zero);  // all false
    for (int j = 0; j < 2; ++j) {
      const auto sa = hn::LoadU(d, l.sin_a[j].data() + i), ca = hn::LoadU(d, l.cos_a[j].data() + i);
      const auto s = hn::Set(d, j == 0 ? 1.0 : -1.0);
      // uplift_function: s ax cos(alpha) - (ay + g) sin(alpha), at both ends (linear in between).
      const auto u0 = hn::Sub(hn::Mul(hn::Mul(s, axp), ca), hn::Mul(hn::Add(ayp, g), sa));
      const auto u1 = hn::Sub(hn::Mul(hn::Mul(s, axn), ca), hn::Mul(hn::Add(ayn, g), sa));
      lift = hn::Or(lift, hn::Or(hn::Gt(u0, margin), hn::Gt(u1, margin)));
      // NaN-safe: a non-finite value never reaches here (the batch validates the sample).
    }
    alignas(64) double flag[16];
    hn::Store(hn::IfThenElseZero(lift, hn::Set(d, 1.0)), d, flag);
    for (std::size_t k = 0; k < L; ++k) l.maybe_lift[i + k] = flag[k] != 0.0 ? 1 : 0;
  }
}

template <bool kExact>
HWY_INLINE void SinCos(hn::ScalableTag<double> d, hn::Vec<hn::ScalableTag<double>> phi,
                       hn::Vec<hn::ScalableTag<double>>& s, hn::Vec<hn::ScalableTag<double>>& c) {
  if constexpr (kExact) {
    alignas(64) double x[16], ys[16], yc[16];
    hn::Store(phi, d, x);
    const std::size_t L = hn::Lanes(d);
    for (std::size_t k = 0; k < L; ++k) {
      ys[k] = std::sin(x[k]);
      yc[k] = std::cos(x[k]);
    }
    s = hn::Load(d, ys);
    c = hn::Load(d, yc);
  } else {
    s = hn::Sin(d, phi);
    c = hn::Cos(d, phi);
  }
}

template <bool kExact>
void RockingSampleT(BatchRocking::Lanes& l, std::size_t m, double dt, double tol) {
  using D = hn::ScalableTag<double>;
  using V = hn::Vec<D>;
  const D d;
  const std::size_t L = hn::Lanes(d);
  const V g = hn::Set(d, kGravity), one = hn::Set(d, 1.0), zero = hn::Zero(d);
  const V dtv = hn::Set(d, dt), tolv = hn::Set(d, tol);
  const double h_min_s = 1e-12 * std::max(1.0, std::abs(dt));
  const V h_min = hn::Set(d, h_min_s);
  alignas(64) double errb[16], fac[16];

  for (std::size_t i = 0; i < m; i += L) {
    const V side = hn::LoadU(d, l.side.data() + i), alpha = hn::LoadU(d, l.alpha.data() + i);
    const V p2 = hn::LoadU(d, l.p2.data() + i);
    const V atth = hn::LoadU(d, l.atol_th.data() + i), atom = hn::LoadU(d, l.atol_om.data() + i);
    const V ovt = hn::LoadU(d, l.overturn.data() + i);
    const auto not_beyond = hn::Eq(hn::LoadU(d, l.beyond.data() + i), zero);
    const V ax0 = hn::LoadU(d, l.ax0.data() + i), axs = hn::LoadU(d, l.axs.data() + i);
    const V ay0 = hn::LoadU(d, l.ay0.data() + i), ays = hn::LoadU(d, l.ays.data() + i);
    const V negside_p2 = hn::Mul(hn::Neg(side), p2);  // -side * pivot->p2
    // RockingOde::angular_acceleration, same operations.
    auto accel = [&](V tau, V theta) -> V {
      const V phi = hn::Sub(alpha, hn::Mul(side, theta));
      const V vertical = hn::Add(one, hn::Div(hn::Add(ay0, hn::Mul(ays, tau)), g));
      const V horizontal = hn::Div(hn::Add(ax0, hn::Mul(axs, tau)), g);
      V sn, cs;
      SinCos<kExact>(d, phi, sn, cs);
      return hn::Mul(negside_p2,
                     hn::Sub(hn::Mul(vertical, sn), hn::Mul(hn::Mul(side, horizontal), cs)));
    };

    V th = hn::LoadU(d, l.theta.data() + i), om = hn::LoadU(d, l.omega.data() + i);
    V hc = hn::LoadU(d, l.h.data() + i);
    V k1a = hn::LoadU(d, l.k1a.data() + i), k1b = hn::LoadU(d, l.k1b.data() + i);
    {
      const auto fsal = hn::Ne(hn::LoadU(d, l.fsal.data() + i), zero);
      const V f = accel(zero, th);
      k1a = hn::IfThenElse(fsal, k1a, om);
      k1b = hn::IfThenElse(fsal, k1b, f);
    }
    V t = zero, maxr = zero, steps = zero, attempts = zero, h_try = zero;
    auto active = hn::Lt(t, dtv);
    auto clean = active;
    auto retry = hn::Lt(one, zero);  // all false
    for (int iter = 0; !hn::AllFalse(d, active); ++iter) {
      if (iter > 100000) {  // cannot happen with the scalar controller's bounds; stay safe
        clean = hn::AndNot(active, clean);
        break;
      }
      const V remaining = hn::Sub(dtv, t);
      V hn_ = hn::Min(hc, remaining);
      hn_ = hn::IfThenElse(hn::Lt(hn::Sub(remaining, hn_), hn::Mul(hn::Set(d, 0.01), hn_)),
                           remaining, hn_);
      const V h = hn::IfThenElse(retry, h_try, hn_);
      attempts = hn::IfThenElse(retry, hn::Add(attempts, one), one);
      // Stages (dopri5_stepper.cpp, stages()).
      V y0 = hn::Add(th, hn::Mul(hn::Mul(h, hn::Set(d, a21)), k1a));
      V y1 = hn::Add(om, hn::Mul(hn::Mul(h, hn::Set(d, a21)), k1b));
      const V k2a = y1, k2b = accel(hn::Add(t, hn::Mul(hn::Set(d, c2), h)), y0);
      auto lin2 = [&](double c1, V x1, double cc2, V x2) {
        return hn::Add(hn::Mul(hn::Set(d, c1), x1), hn::Mul(hn::Set(d, cc2), x2));
      };
      auto acc = [&](V sum, double c, V x) { return hn::Add(sum, hn::Mul(hn::Set(d, c), x)); };
      y0 = hn::Add(th, hn::Mul(h, lin2(a31, k1a, a32, k2a)));
      y1 = hn::Add(om, hn::Mul(h, lin2(a31, k1b, a32, k2b)));
      const V k3a = y1, k3b = accel(hn::Add(t, hn::Mul(hn::Set(d, c3), h)), y0);
      y0 = hn::Add(th, hn::Mul(h, acc(lin2(a41, k1a, a42, k2a), a43, k3a)));
      y1 = hn::Add(om, hn::Mul(h, acc(lin2(a41, k1b, a42, k2b), a43, k3b)));
      const V k4a = y1, k4b = accel(hn::Add(t, hn::Mul(hn::Set(d, c4), h)), y0);
      y0 = hn::Add(th, hn::Mul(h, acc(acc(lin2(a51, k1a, a52, k2a), a53, k3a), a54, k4a)));
      y1 = hn::Add(om, hn::Mul(h, acc(acc(lin2(a51, k1b, a52, k2b), a53, k3b), a54, k4b)));
      const V k5a = y1, k5b = accel(hn::Add(t, hn::Mul(hn::Set(d, c5), h)), y0);
      y0 = hn::Add(th, hn::Mul(h, acc(acc(acc(lin2(a61, k1a, a62, k2a), a63, k3a), a64, k4a), a65, k5a)));
      y1 = hn::Add(om, hn::Mul(h, acc(acc(acc(lin2(a61, k1b, a62, k2b), a63, k3b), a64, k4b), a65, k5b)));
      const V t_h = hn::Add(t, h);
      const V k6a = y1, k6b = accel(t_h, y0);
      const V y5a = hn::Add(th, hn::Mul(h, acc(acc(acc(lin2(a71, k1a, a73, k3a), a74, k4a), a75, k5a), a76, k6a)));
      const V y5b = hn::Add(om, hn::Mul(h, acc(acc(acc(lin2(a71, k1b, a73, k3b), a74, k4b), a75, k5b), a76, k6b)));
      const V k7a = y5b, k7b = accel(t_h, y5a);
      // Error estimate (Dopri5Stepper::step).
      const V ea = hn::Mul(h, acc(acc(acc(acc(lin2(e1, k1a, e3, k3a), e4, k4a), e5, k5a), e6, k6a), e7, k7a));
      const V eb = hn::Mul(h, acc(acc(acc(acc(lin2(e1, k1b, e3, k3b), e4, k4b), e5, k5b), e6, k6b), e7, k7b));
      const V sca = hn::Add(atth, hn::Mul(tolv, hn::Max(hn::Abs(th), hn::Abs(y5a))));
      const V scb = hn::Add(atom, hn::Mul(tolv, hn::Max(hn::Abs(om), hn::Abs(y5b))));
      const V qa = hn::Div(ea, sca), qb = hn::Div(eb, scb);
      const V err = hn::Sqrt(hn::Mul(hn::Set(d, 0.5), hn::Add(hn::Add(zero, hn::Mul(qa, qa)), hn::Mul(qb, qb))));
      // The controller's factor with the scalar std::pow, lane by lane (exact step sizes).
      V factor;
      if constexpr (kExact) {
        hn::Store(err, d, errb);
        for (std::size_t k = 0; k < L; ++k) {
          const double e = errb[k];
          fac[k] = e == 0.0 ? 5.0 : std::min(5.0, std::max(0.2, 0.9 * std::pow(e, -0.2)));
        }
        factor = hn::Load(d, fac);
      } else {  // err^-0.2 = exp(-0.2 log err): not the bits of std::pow
        const V pw = hn::Exp(d, hn::Mul(hn::Set(d, -0.2), hn::Log(d, err)));
        factor = hn::Min(hn::Set(d, 5.0), hn::Max(hn::Set(d, 0.2), hn::Mul(hn::Set(d, 0.9), pw)));
        factor = hn::IfThenElse(hn::Eq(err, zero), hn::Set(d, 5.0), factor);
      }
      const auto accept = hn::And(
          active, hn::Or(hn::Or(hn::Le(err, one), hn::Le(h, h_min)), hn::Ge(attempts, hn::Set(d, 50.0))));
      // Events the scalar scan_step would act on: impact / degenerate (s*theta not > 0 at either
      // end), a turning point (omega changes sign), overturn, the first passage beyond alpha,
      // non-finite values. Such a lane goes back to the scalar model.
      const V g0 = hn::Mul(side, th), g1 = hn::Mul(side, y5a);
      const V w0 = hn::Mul(side, om), w1 = hn::Mul(side, y5b);
      auto bad = hn::Not(hn::And(hn::Gt(g0, zero), hn::Gt(g1, zero)));
      bad = hn::Or(bad, hn::And(hn::Gt(w0, zero), hn::Lt(w1, zero)));
      bad = hn::Or(bad, hn::And(hn::Lt(w0, zero), hn::Gt(w1, zero)));
      bad = hn::Or(bad, hn::Ge(g1, ovt));
      bad = hn::Or(bad, hn::And(not_beyond, hn::And(hn::Le(g0, alpha), hn::Gt(g1, alpha))));
      bad = hn::Or(bad, hn::Not(hn::And(hn::IsFinite(y5a), hn::IsFinite(y5b))));
      const auto dropped = hn::And(accept, bad);
      const auto good = hn::AndNot(bad, accept);
      clean = hn::AndNot(dropped, clean);
      // Accepted clean steps.
      const V h_next = hn::Mul(h, factor);
      const auto at_end = hn::Eq(h, remaining);
      const V hc_new = hn::IfThenElse(hn::And(at_end, hn::Lt(h, hc)), hn::Max(hc, h_next), h_next);
      hc = hn::IfThenElse(good, hc_new, hc);
      th = hn::IfThenElse(good, y5a, th);
      om = hn::IfThenElse(good, y5b, om);
      k1a = hn::IfThenElse(good, k7a, k1a);
      k1b = hn::IfThenElse(good, k7b, k1b);
      t = hn::IfThenElse(good, hn::IfThenElse(at_end, dtv, t_h), t);
      steps = hn::IfThenElse(good, hn::Add(steps, attempts), steps);
      maxr = hn::IfThenElse(good, hn::Max(maxr, hn::Div(hn::Abs(th), alpha)), maxr);
      // Rejected steps retry with h * factor (not below h_min).
      const auto rejected = hn::AndNot(accept, active);
      h_try = hn::IfThenElse(rejected, hn::Max(hn::Mul(h, factor), h_min), h_try);
      retry = rejected;
      active = hn::And(hn::AndNot(dropped, active), hn::Lt(t, dtv));
    }
    // Sample-end screen (Highway Sin/Cos; a filter only, with margins far above its error).
    {
      const V ax1 = hn::Add(ax0, hn::Mul(axs, dtv)), ay1 = hn::Add(ay0, hn::Mul(ays, dtv));
      const V phi = hn::Sub(alpha, hn::Mul(side, th));
      const V sn = hn::Sin(d, phi), cs = hn::Cos(d, phi);
      const V thdd = hn::Mul(negside_p2, hn::Sub(hn::Mul(hn::Add(one, hn::Div(ay1, g)), sn),
                                                 hn::Mul(hn::Mul(side, hn::Div(ax1, g)), cs)));
      const V R = hn::LoadU(d, l.radius.data() + i);
      const V w2 = hn::Mul(om, om);
      const V ry = hn::Add(hn::Add(g, ay1), hn::Add(hn::Neg(hn::Mul(hn::Mul(R, cs), w2)),
                                                   hn::Mul(hn::Mul(side, hn::Mul(R, sn)), thdd)));
      const V ry_scale = hn::Add(hn::Add(g, hn::Abs(ay1)), hn::Mul(R, hn::Add(w2, hn::Abs(thdd))));
      const auto no_flight = hn::Gt(ry, hn::Mul(hn::Set(d, 1e-9), ry_scale));
      const auto no_slide = hn::Eq(hn::LoadU(d, l.slide_checked.data() + i), zero);
      // overturn_margin: deficit = (gR (1 - cos phi) - I w^2 / 2) / (gR (1 - cos alpha)).
      const V barrier = hn::Mul(g, R);
      const V num = hn::Sub(hn::Mul(barrier, hn::Sub(one, cs)),
                            hn::Mul(hn::Mul(hn::Set(d, 0.5), hn::LoadU(d, l.inertia.data() + i)), w2));
      const V den = hn::Mul(barrier, hn::Sub(one, hn::LoadU(d, l.cos_al.data() + i)));
      const V deficit = hn::Div(num, den);
      const auto inward = hn::Le(hn::Mul(side, om), zero);
      const auto not_committed = hn::And(hn::Gt(phi, hn::Set(d, 1e-6)),
                                         hn::Or(inward, hn::Gt(deficit, hn::Set(d, 1e-6))));
      const auto latched = hn::Ne(hn::LoadU(d, l.committed.data() + i), zero);
      const auto clear = hn::And(hn::And(no_flight, no_slide), hn::Or(latched, not_committed));
      alignas(64) double eb[16];
      hn::Store(hn::IfThenElseZero(clear, one), d, eb);
      for (std::size_t k = 0; k < L; ++k) l.end_clear[i + k] = eb[k] != 0.0 ? 1 : 0;
    }
    hn::StoreU(th, d, l.theta.data() + i);
    hn::StoreU(om, d, l.omega.data() + i);
    hn::StoreU(hc, d, l.h.data() + i);
    hn::StoreU(k1a, d, l.k1a.data() + i);
    hn::StoreU(k1b, d, l.k1b.data() + i);
    hn::StoreU(steps, d, l.steps.data() + i);
    hn::StoreU(maxr, d, l.max_ratio.data() + i);
    alignas(64) double cb[16];
    hn::Store(hn::IfThenElseZero(clean, one), d, cb);
    for (std::size_t k = 0; k < L; ++k) l.clean[i + k] = cb[k] != 0.0 ? 1 : 0;
  }
}

void RockingSampleExact(BatchRocking::Lanes& l, std::size_t m, double dt, double tol) {
  RockingSampleT<true>(l, m, dt, tol);
}
void RockingSampleFast(BatchRocking::Lanes& l, std::size_t m, double dt, double tol) {
  RockingSampleT<false>(l, m, dt, tol);
}
const char* TargetName() { return hwy::TargetName(HWY_TARGET); }

// sin and cos of n values (n a multiple of 16), as the dopri5 kernel evaluates them per stage
// (for the benchmark of their cost).
template <bool kExact>
void SinCosT(const double* x, double* s, double* c, std::size_t n) {
  const hn::ScalableTag<double> d;
  for (std::size_t i = 0; i < n; i += hn::Lanes(d)) {
    hn::Vec<hn::ScalableTag<double>> vs, vc;
    SinCos<kExact>(d, hn::LoadU(d, x + i), vs, vc);
    hn::StoreU(vs, d, s + i);
    hn::StoreU(vc, d, c + i);
  }
}
void SinCosExact(const double* x, double* s, double* c, std::size_t n) { SinCosT<true>(x, s, c, n); }
void SinCosFast(const double* x, double* s, double* c, std::size_t n) { SinCosT<false>(x, s, c, n); }

}  // namespace HWY_NAMESPACE
}  // namespace rocking_monitor::core::batch_detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace rocking_monitor::core::batch_detail {
HWY_EXPORT(UpliftTest);
HWY_EXPORT(RockingSampleExact);
HWY_EXPORT(RockingSampleFast);
HWY_EXPORT(TargetName);
HWY_EXPORT(SinCosExact);
HWY_EXPORT(SinCosFast);

void sincos_lanes(const double* x, double* s, double* c, std::size_t n, bool exact_trig) {
  if (exact_trig) HWY_DYNAMIC_DISPATCH(SinCosExact)(x, s, c, n);
  else HWY_DYNAMIC_DISPATCH(SinCosFast)(x, s, c, n);
}

void uplift_test(BatchRocking::Lanes& l, std::size_t n, bool linearized) {
  HWY_DYNAMIC_DISPATCH(UpliftTest)(l, n, linearized);
}
void rocking_sample(BatchRocking::Lanes& l, std::size_t m, double dt, double tol, bool exact_trig) {
  if (exact_trig) HWY_DYNAMIC_DISPATCH(RockingSampleExact)(l, m, dt, tol);
  else HWY_DYNAMIC_DISPATCH(RockingSampleFast)(l, m, dt, tol);
}
const char* target_name() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }
}  // namespace rocking_monitor::core::batch_detail
#endif
