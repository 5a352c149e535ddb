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

#include "batch_rocking_wide-inl.h"  // the U-vector wrappers (namespace w), per target

// RockingSampleT's steps. Each is forced inline (HWY_INLINE): called out of line, GCC passes the U
// vectors through memory, and the kernel's speed is in keeping them in registers. The operations are
// the kernel's, in the same order: every lane keeps the scalar model's bits.

// A group of the lanes (indices ix, d.lanes() of them), read and written in place in the lanes' arrays.
template <std::size_t U>
struct Group {
  w::Tag<U> d;
  std::size_t L;
  const std::uint32_t* ix;
  HWY_INLINE w::Wide<U> gather(const std::vector<double>& a) const {
    alignas(64) double b[16];
    for (std::size_t k = 0; k < L; ++k) b[k] = a[ix[k]];
    return w::Load(d, b);
  }
  HWY_INLINE void scatter(w::Wide<U> v, std::vector<double>& a) const {
    alignas(64) double b[16];
    w::Store(v, d, b);
    for (std::size_t k = 0; k < L; ++k) a[ix[k]] = b[k];
  }
  HWY_INLINE void scatter_flags(w::WMask<U> m, std::vector<std::uint8_t>& a) const {  // 1: set
    alignas(64) double b[16];
    w::Store(w::IfThenElseZero(m, w::Set(d, 1.0)), d, b);
    for (std::size_t k = 0; k < L; ++k) a[ix[k]] = b[k] != 0.0 ? 1 : 0;
  }
};

// What a group's sample does not change: the bodies, tolerances, the sample's length, and its input.
template <std::size_t U>
struct Sample {
  w::Wide<U> side, alpha, atth, atom, ovt, dtv, tolv;
  w::WMask<U> not_beyond;                  // not yet beyond alpha: the first passage is an event
  w::Wide<U> ax0, ay0, axs, ays;           // GroundInput::first_order_hold: the line from the last input
  w::Wide<U> hx0, hxs, vy0, vys;           // the line in units of g (fast path: no division per stage)
  w::Wide<U> inv_alpha, negside_p2;        // 1 / alpha; -side * pivot->p2
};

template <std::size_t U>
HWY_INLINE Sample<U> LoadSample(const Group<U>& grp, const BatchRocking::Lanes& l, double dt, double tol) {
  const w::Tag<U> d = grp.d;
  const auto one = w::Set(d, 1.0), inv_g = w::Set(d, 1.0 / kGravity);
  Sample<U> s;
  s.dtv = w::Set(d, dt);
  s.tolv = w::Set(d, tol);
  s.side = grp.gather(l.side);
  s.alpha = grp.gather(l.alpha);
  s.atth = grp.gather(l.atol_th);
  s.atom = grp.gather(l.atol_om);
  s.ovt = grp.gather(l.overturn);
  s.not_beyond = w::Eq(grp.gather(l.beyond), w::Zero(d));
  s.ax0 = grp.gather(l.ax_prev);
  s.ay0 = grp.gather(l.ay_prev);
  s.axs = w::Div(w::Sub(grp.gather(l.ax_now), s.ax0), s.dtv);
  s.ays = w::Div(w::Sub(grp.gather(l.ay_now), s.ay0), s.dtv);
  s.hx0 = w::Mul(s.ax0, inv_g);
  s.hxs = w::Mul(s.axs, inv_g);
  s.vy0 = w::Add(one, w::Mul(s.ay0, inv_g));
  s.vys = w::Mul(s.ays, inv_g);
  s.inv_alpha = w::Div(one, s.alpha);
  s.negside_p2 = w::Mul(w::Neg(s.side), grp.gather(l.p2));
  return s;
}

// RockingOde::angular_acceleration at tau into the sample, same operations (exact path). sn, cs: sin
// and cos of the angle to the vertical (phi); the last stage's serve the sample-end screen.
template <bool kExact, std::size_t U>
HWY_INLINE w::Wide<U> AccelSC(w::Tag<U> d, const Sample<U>& s, w::Wide<U> tau, w::Wide<U> theta,
                              w::Wide<U>& sn, w::Wide<U>& cs) {
  const auto g = w::Set(d, kGravity), one = w::Set(d, 1.0);
  const auto phi = w::Sub(s.alpha, w::Mul(s.side, theta));
  w::Wide<U> vertical, horizontal;
  if constexpr (kExact) {
    vertical = w::Add(one, w::Div(w::Add(s.ay0, w::Mul(s.ays, tau)), g));
    horizontal = w::Div(w::Add(s.ax0, w::Mul(s.axs, tau)), g);
  } else {
    vertical = w::Add(s.vy0, w::Mul(s.vys, tau));
    horizontal = w::Add(s.hx0, w::Mul(s.hxs, tau));
  }
  w::SinCos<kExact>(d, phi, sn, cs);
  return w::Mul(s.negside_p2, w::Sub(w::Mul(vertical, sn), w::Mul(w::Mul(s.side, horizontal), cs)));
}
template <bool kExact, std::size_t U>
HWY_INLINE w::Wide<U> Accel(w::Tag<U> d, const Sample<U>& s, w::Wide<U> tau, w::Wide<U> theta) {
  w::Wide<U> sn, cs;
  return AccelSC<kExact>(d, s, tau, theta, sn, cs);
}

// A group's integration through its sample: where each lane stands and what the sample reports.
template <std::size_t U>
struct Walk {
  w::Wide<U> th, om, hc, k1a, k1b;   // theta, omega, the next step size, the first stage (FSAL)
  w::Wide<U> t, maxr, steps, attempts, h_try, sn_end, cs_end;
  w::WMask<U> active, clean, retry;  // still stepping; no event so far; the last trial was rejected
};

template <bool kExact, std::size_t U>
HWY_INLINE Walk<U> StartWalk(const Group<U>& grp, const BatchRocking::Lanes& l, const Sample<U>& s) {
  const w::Tag<U> d = grp.d;
  const auto zero = w::Zero(d);
  Walk<U> st;
  st.th = grp.gather(l.theta);
  st.om = grp.gather(l.omega);
  st.hc = grp.gather(l.h);
  st.k1a = grp.gather(l.k1a);
  st.k1b = grp.gather(l.k1b);
  const auto fsal = w::Ne(grp.gather(l.fsal), zero);
  if (!w::AllFalse(d, w::Not(fsal))) {  // a first step: no derivative kept from the last one
    const auto f = Accel<kExact>(d, s, zero, st.th);
    st.k1a = w::IfThenElse(fsal, st.k1a, st.om);
    st.k1b = w::IfThenElse(fsal, st.k1b, f);
  }
  st.t = st.maxr = st.steps = st.attempts = st.h_try = st.sn_end = st.cs_end = zero;
  st.active = w::Ne(grp.gather(l.vr), zero);  // the group's lanes with a sample to step
  st.clean = st.active;
  st.retry = w::Lt(w::Set(d, 1.0), zero);  // all false
  return st;
}

// One dopri5 trial of step h from the walk's state (dopri5_stepper.cpp: stages(), then
// Dopri5Stepper::step's error estimate).
template <std::size_t U>
struct Trial {
  w::Wide<U> y5a, y5b, k7a, k7b, sn7, cs7, err;
};

template <bool kExact, std::size_t U>
HWY_INLINE Trial<U> Dopri5Trial(w::Tag<U> d, const Sample<U>& s, const Walk<U>& st, w::Wide<U> h) {
  using V = w::Wide<U>;
  const V zero = w::Zero(d), t = st.t, th = st.th, om = st.om, k1a = st.k1a, k1b = st.k1b;
  auto lin2 = [&](double c1, V x1, double cc2, V x2) HWY_INLINE_LAMBDA {
    return w::Add(w::Mul(w::Set(d, c1), x1), w::Mul(w::Set(d, cc2), x2));
  };
  auto acc = [&](V sum, double c, V x) HWY_INLINE_LAMBDA { return w::Add(sum, w::Mul(w::Set(d, c), x)); };
  V y0 = w::Add(th, w::Mul(w::Mul(h, w::Set(d, a21)), k1a));
  V y1 = w::Add(om, w::Mul(w::Mul(h, w::Set(d, a21)), k1b));
  const V k2a = y1, k2b = Accel<kExact>(d, s, w::Add(t, w::Mul(w::Set(d, c2), h)), y0);
  y0 = w::Add(th, w::Mul(h, lin2(a31, k1a, a32, k2a)));
  y1 = w::Add(om, w::Mul(h, lin2(a31, k1b, a32, k2b)));
  const V k3a = y1, k3b = Accel<kExact>(d, s, w::Add(t, w::Mul(w::Set(d, c3), h)), y0);
  y0 = w::Add(th, w::Mul(h, acc(lin2(a41, k1a, a42, k2a), a43, k3a)));
  y1 = w::Add(om, w::Mul(h, acc(lin2(a41, k1b, a42, k2b), a43, k3b)));
  const V k4a = y1, k4b = Accel<kExact>(d, s, w::Add(t, w::Mul(w::Set(d, c4), h)), y0);
  y0 = w::Add(th, w::Mul(h, acc(acc(lin2(a51, k1a, a52, k2a), a53, k3a), a54, k4a)));
  y1 = w::Add(om, w::Mul(h, acc(acc(lin2(a51, k1b, a52, k2b), a53, k3b), a54, k4b)));
  const V k5a = y1, k5b = Accel<kExact>(d, s, w::Add(t, w::Mul(w::Set(d, c5), h)), y0);
  y0 = w::Add(th, w::Mul(h, acc(acc(acc(lin2(a61, k1a, a62, k2a), a63, k3a), a64, k4a), a65, k5a)));
  y1 = w::Add(om, w::Mul(h, acc(acc(acc(lin2(a61, k1b, a62, k2b), a63, k3b), a64, k4b), a65, k5b)));
  const V t_h = w::Add(t, h);
  const V k6a = y1, k6b = Accel<kExact>(d, s, t_h, y0);
  Trial<U> r;
  r.y5a = w::Add(th, w::Mul(h, acc(acc(acc(lin2(a71, k1a, a73, k3a), a74, k4a), a75, k5a), a76, k6a)));
  r.y5b = w::Add(om, w::Mul(h, acc(acc(acc(lin2(a71, k1b, a73, k3b), a74, k4b), a75, k5b), a76, k6b)));
  r.k7a = r.y5b;
  r.k7b = AccelSC<kExact>(d, s, t_h, r.y5a, r.sn7, r.cs7);
  const V ea = w::Mul(h, acc(acc(acc(acc(lin2(e1, k1a, e3, k3a), e4, k4a), e5, k5a), e6, k6a), e7, r.k7a));
  const V eb = w::Mul(h, acc(acc(acc(acc(lin2(e1, k1b, e3, k3b), e4, k4b), e5, k5b), e6, k6b), e7, r.k7b));
  const V sca = w::Add(s.atth, w::Mul(s.tolv, w::Max(w::Abs(th), w::Abs(r.y5a))));
  const V scb = w::Add(s.atom, w::Mul(s.tolv, w::Max(w::Abs(om), w::Abs(r.y5b))));
  const V qa = w::Div(ea, sca), qb = w::Div(eb, scb);
  r.err = w::Sqrt(w::Mul(w::Set(d, 0.5), w::Add(w::Add(zero, w::Mul(qa, qa)), w::Mul(qb, qb))));
  return r;
}

// The controller's factor min(5, max(0.2, 0.9 err^-0.2)), 5 at err 0: exact, the scalar std::pow lane
// by lane (the scalar model's step sizes); fast, exp(-0.2 log err) (not the bits of std::pow).
template <bool kExact, std::size_t U>
HWY_INLINE w::Wide<U> StepFactor(w::Tag<U> d, w::Wide<U> err) {
  if constexpr (kExact) {
    alignas(64) double errb[16], fac[16];
    w::Store(err, d, errb);
    for (std::size_t k = 0; k < d.lanes(); ++k) {
      const double e = errb[k];
      fac[k] = e == 0.0 ? 5.0 : std::min(5.0, std::max(0.2, 0.9 * std::pow(e, -0.2)));
    }
    return w::Load(d, fac);
  } else {
    const auto pw = w::Exp(d, w::Mul(w::Set(d, -0.2), w::Log(d, err)));
    const auto factor = w::Min(w::Set(d, 5.0), w::Max(w::Set(d, 0.2), w::Mul(w::Set(d, 0.9), pw)));
    return w::IfThenElse(w::Eq(err, w::Zero(d)), w::Set(d, 5.0), factor);
  }
}

// Events the scalar scan_step would act on in the trial: impact / degenerate (s*theta not > 0 at either
// end), a turning point (omega changes sign), overturn, the first passage beyond alpha, non-finite
// values. Such a lane goes back to the scalar model.
template <std::size_t U>
HWY_INLINE w::WMask<U> HasEvent(w::Tag<U> d, const Sample<U>& s, const Walk<U>& st, const Trial<U>& tr) {
  const auto zero = w::Zero(d);
  const auto g0 = w::Mul(s.side, st.th), g1 = w::Mul(s.side, tr.y5a);
  const auto w0 = w::Mul(s.side, st.om), w1 = w::Mul(s.side, tr.y5b);
  auto bad = w::Not(w::And(w::Gt(g0, zero), w::Gt(g1, zero)));
  bad = w::Or(bad, w::And(w::Gt(w0, zero), w::Lt(w1, zero)));
  bad = w::Or(bad, w::And(w::Lt(w0, zero), w::Gt(w1, zero)));
  bad = w::Or(bad, w::Ge(g1, s.ovt));
  bad = w::Or(bad, w::And(s.not_beyond, w::And(w::Le(g0, s.alpha), w::Gt(g1, s.alpha))));
  return w::Or(bad, w::Not(w::And(w::IsFinite(tr.y5a), w::IsFinite(tr.y5b))));
}

// One trial step for every active lane: accepted clean steps advance, rejected ones retry with
// h * factor (not below h_min), lanes with an event leave (not clean).
template <bool kExact, std::size_t U>
HWY_INLINE void Advance(w::Tag<U> d, const Sample<U>& s, w::Wide<U> h_min, Walk<U>& st) {
  using V = w::Wide<U>;
  const V one = w::Set(d, 1.0), remaining = w::Sub(s.dtv, st.t);
  V hn_ = w::Min(st.hc, remaining);
  hn_ = w::IfThenElse(w::Lt(w::Sub(remaining, hn_), w::Mul(w::Set(d, 0.01), hn_)), remaining, hn_);
  const V h = w::IfThenElse(st.retry, st.h_try, hn_);
  st.attempts = w::IfThenElse(st.retry, w::Add(st.attempts, one), one);
  const Trial<U> tr = Dopri5Trial<kExact>(d, s, st, h);
  const V factor = StepFactor<kExact>(d, tr.err);
  const auto accept = w::And(
      st.active, w::Or(w::Or(w::Le(tr.err, one), w::Le(h, h_min)), w::Ge(st.attempts, w::Set(d, 50.0))));
  const auto bad = HasEvent(d, s, st, tr);
  const auto dropped = w::And(accept, bad);
  const auto good = w::AndNot(bad, accept);
  st.clean = w::AndNot(dropped, st.clean);
  // Accepted clean steps.
  const V h_next = w::Mul(h, factor);
  const auto at_end = w::Eq(h, remaining);
  const V hc_new = w::IfThenElse(w::And(at_end, w::Lt(h, st.hc)), w::Max(st.hc, h_next), h_next);
  st.hc = w::IfThenElse(good, hc_new, st.hc);
  st.th = w::IfThenElse(good, tr.y5a, st.th);
  st.om = w::IfThenElse(good, tr.y5b, st.om);
  st.k1a = w::IfThenElse(good, tr.k7a, st.k1a);
  st.k1b = w::IfThenElse(good, tr.k7b, st.k1b);
  st.t = w::IfThenElse(good, w::IfThenElse(at_end, s.dtv, w::Add(st.t, h)), st.t);
  st.steps = w::IfThenElse(good, w::Add(st.steps, st.attempts), st.steps);
  const V ratio = kExact ? w::Div(w::Abs(st.th), s.alpha) : w::Mul(w::Abs(st.th), s.inv_alpha);
  st.maxr = w::IfThenElse(good, w::Max(st.maxr, ratio), st.maxr);
  st.sn_end = w::IfThenElse(good, tr.sn7, st.sn_end);  // the last accepted step ends at the sample end
  st.cs_end = w::IfThenElse(good, tr.cs7, st.cs_end);
  // Rejected steps retry with h * factor (not below h_min).
  const auto rejected = w::AndNot(accept, st.active);
  st.h_try = w::IfThenElse(rejected, w::Max(w::Mul(h, factor), h_min), st.h_try);
  st.retry = rejected;
  st.active = w::And(w::AndNot(dropped, st.active), w::Lt(st.t, s.dtv));
}

// Sample-end screen (a filter only, with margins far above the error of its sin/cos: those of the last
// stage, at the sample end's theta, exact or Highway's): no flight, no slide, not committed.
template <std::size_t U>
HWY_INLINE w::WMask<U> EndClear(const Group<U>& grp, const BatchRocking::Lanes& l, const Sample<U>& s,
                                const Walk<U>& st) {
  using V = w::Wide<U>;
  const w::Tag<U> d = grp.d;
  const V g = w::Set(d, kGravity), one = w::Set(d, 1.0), zero = w::Zero(d);
  const V side = s.side, th = st.th, om = st.om;
  const V ax1 = w::Add(s.ax0, w::Mul(s.axs, s.dtv)), ay1 = w::Add(s.ay0, w::Mul(s.ays, s.dtv));
  const V phi = w::Sub(s.alpha, w::Mul(side, th));
  const V sn = st.sn_end, cs = st.cs_end;
  const V thdd = w::Mul(s.negside_p2, w::Sub(w::Mul(w::Add(one, w::Div(ay1, g)), sn),
                                             w::Mul(w::Mul(side, w::Div(ax1, g)), cs)));
  const V R = grp.gather(l.radius);
  const V w2 = w::Mul(om, om);
  const V ry = w::Add(w::Add(g, ay1), w::Add(w::Neg(w::Mul(w::Mul(R, cs), w2)),
                                               w::Mul(w::Mul(side, w::Mul(R, sn)), thdd)));
  const V ry_scale = w::Add(w::Add(g, w::Abs(ay1)), w::Mul(R, w::Add(w2, w::Abs(thdd))));
  const auto no_flight = w::Gt(ry, w::Add(grp.gather(l.ry_min), w::Mul(w::Set(d, 1e-9), ry_scale)));
  // rocking_reaction(): R_x = a_x + x'' (x'' = -R (cos(phi) theta'' + s sin(phi) w^2)); sliding
  // surely not reached when |R_x| stays below mu_clear R_y by the margin (mu_clear 0: not screened).
  const V rx = w::Sub(ax1, w::Mul(R, w::Add(w::Mul(cs, thdd), w::Mul(side, w::Mul(sn, w2)))));
  const V rx_scale = w::Add(w::Abs(ax1), w::Mul(R, w::Add(w2, w::Abs(thdd))));
  const V mu_clear = grp.gather(l.mu_clear);
  const auto under_friction = w::Lt(w::Add(w::Abs(rx), w::Mul(w::Mul(w::Set(d, 1e-9), w::Add(one, mu_clear)),
                                                              w::Add(rx_scale, ry_scale))),
                                    w::Mul(mu_clear, ry));
  const auto no_slide = w::Or(w::Eq(grp.gather(l.slide_checked), zero), under_friction);
  // overturn_margin: deficit = (gR (1 - cos phi) - I w^2 / 2) / (gR (1 - cos alpha)).
  const V barrier = w::Mul(g, R);
  const V num = w::Sub(w::Mul(barrier, w::Sub(one, cs)), w::Mul(w::Mul(w::Set(d, 0.5), grp.gather(l.inertia)), w2));
  const V den = w::Mul(barrier, w::Sub(one, grp.gather(l.cos_al)));
  const V deficit = w::Div(num, den);
  const auto inward = w::Le(w::Mul(side, om), zero);
  const auto not_committed = w::And(w::Gt(phi, w::Set(d, 1e-6)), w::Or(inward, w::Gt(deficit, w::Set(d, 1e-6))));
  const auto latched = w::Ne(grp.gather(l.committed), zero);
  return w::And(w::And(no_flight, no_slide), w::Or(latched, not_committed));
}

// One dopri5 sample for m lanes (idx), L at a time, as the scalar model steps each: the lanes that
// stay clean (no event) get the scalar model's bits; the others go back to it.
template <bool kExact, std::size_t U>
void RockingSampleT(BatchRocking::Lanes& l, const std::uint32_t* idx, std::size_t m, double dt, double tol) {
  const w::Tag<U> d;
  const std::size_t L = d.lanes();
  const auto h_min = w::Set(d, 1e-12 * std::max(1.0, std::abs(dt)));
  for (std::size_t i = 0; i < m; i += L) {
    // The lanes' state stays in place (index = lane); this group's lanes are gathered from it.
    const Group<U> grp{d, L, idx + i};
    const Sample<U> s = LoadSample(grp, l, dt, tol);
    Walk<U> st = StartWalk<kExact>(grp, l, s);
    for (int iter = 0; !w::AllFalse(d, st.active); ++iter) {
      if (iter > 100000) {  // cannot happen with the scalar controller's bounds; stay safe
        st.clean = w::AndNot(st.active, st.clean);
        break;
      }
      Advance<kExact>(d, s, h_min, st);
    }
    grp.scatter_flags(EndClear(grp, l, s, st), l.end_clear);
    grp.scatter(st.th, l.theta_out);
    grp.scatter(st.om, l.omega_out);
    grp.scatter(st.hc, l.h_out);
    grp.scatter(st.k1a, l.k1a_out);
    grp.scatter(st.k1b, l.k1b_out);
    grp.scatter(st.steps, l.steps);
    grp.scatter(st.maxr, l.max_ratio);
    grp.scatter_flags(st.clean, l.clean);
  }
}

// Vectors per iteration: 2 (a block of 16 lanes holds 2 x 8 (AVX-512), 2 x 4 (AVX2), ...).
constexpr std::size_t kUnroll = 2;
static_assert(kBlock % (kUnroll * (HWY_MAX_BYTES / sizeof(double))) == 0, "a block of whole wide vectors");

void RockingSampleExact(BatchRocking::Lanes& l, const std::uint32_t* idx, std::size_t m, double dt, double tol) {
  RockingSampleT<true, kUnroll>(l, idx, m, dt, tol);
}
void RockingSampleFast(BatchRocking::Lanes& l, const std::uint32_t* idx, std::size_t m, double dt, double tol) {
  RockingSampleT<false, kUnroll>(l, idx, m, dt, tol);
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
  rocking_sample(l, l.idx.data(), m, dt, tol, exact_trig);
}
void rocking_sample(BatchRocking::Lanes& l, const std::uint32_t* idx, std::size_t m, double dt, double tol,
                    bool exact_trig) {
  if (exact_trig) HWY_DYNAMIC_DISPATCH(RockingSampleExact)(l, idx, m, dt, tol);
  else HWY_DYNAMIC_DISPATCH(RockingSampleFast)(l, idx, m, dt, tol);
}
const char* target_name() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }
}  // namespace rocking_monitor::core::batch_detail
#endif
