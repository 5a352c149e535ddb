#pragma once

#include <cmath>

namespace rocking_monitor::core {

/// Root of a continuous f on [a, b] with f(a), f(b) of opposite signs (or f(b) == 0), by the
/// Illinois (modified regula falsi) method: superlinear, always bracketed, bounded work
/// (at most max_iter evaluations). Returns the abscissa of the sign change to within x_tol.
template <class F>
double bracketed_root(const F& f, double a, double b, double fa, double fb, double x_tol,
                      int max_iter = 60) {
  if (fb == 0.0) return b;
  if (fa == 0.0) return a;
  int side = 0;
  double c = b;
  for (int i = 0; i < max_iter && std::abs(b - a) > x_tol; ++i) {
    c = (fa * b - fb * a) / (fa - fb);
    if (!(c > a && c < b) && !(c < a && c > b)) c = 0.5 * (a + b);  // numerical safety
    const double fc = f(c);
    if (fc == 0.0) return c;
    if ((fc > 0.0) == (fb > 0.0)) {
      b = c;
      fb = fc;
      if (side == -1) fa *= 0.5;
      side = -1;
    } else {
      a = c;
      fa = fc;
      if (side == 1) fb *= 0.5;
      side = 1;
    }
  }
  // Return the end on the far side of the sign change so the located state has crossed.
  return b;
}

/// What an integration step over [t0, t1] of rocking about `side` crossed, found on the step's
/// continuous interpolant (dense output). Terminal events end the step early.
struct StepEvents {
  enum class Terminal { None, Impact, Overturn, Degenerate };
  Terminal terminal = Terminal::None;
  double t_event = 0.0;        ///< time of the terminal event
  bool has_peak = false;       ///< |theta| had a local maximum inside the step
  double peak_abs_theta = 0.0; ///< its value, rad
  bool tipping_crossed = false;  ///< s*theta rose above alpha inside [t0, t_end]
  double t_tipping = 0.0;
};

/// Scans one accepted step for impact (s*theta returns to 0, including a grazing touch that dips
/// below 0 and comes back inside the step), overturn (s*theta reaches overturn_angle), the peak
/// rotation and the first passage beyond alpha. `eval(t, theta, omega)` evaluates the interpolant.
template <class Eval>
StepEvents scan_step(const Eval& eval, int side, double alpha, double overturn_angle, double t0,
                     double t1, double theta0, double omega0, double theta1, double omega1,
                     double t_tol) {
  StepEvents ev;
  const double g0 = side * theta0, g1 = side * theta1;
  const double w0 = side * omega0, w1 = side * omega1;
  auto g_of = [&](double t) {
    double th, om;
    eval(t, th, om);
    return side * th;
  };
  auto w_of = [&](double t) {
    double th, om;
    eval(t, th, om);
    return side * om;
  };
  // Turning point of s*theta inside the step (omega changes sign).
  double t_turn = 0.0, g_turn = 0.0;
  const bool peak = w0 > 0.0 && w1 < 0.0;
  const bool trough = w0 < 0.0 && w1 > 0.0;
  if (peak || trough) {
    t_turn = bracketed_root(w_of, t0, t1, w0, w1, t_tol);
    g_turn = g_of(t_turn);
  }
  if (peak) {
    ev.has_peak = true;
    ev.peak_abs_theta = g_turn;
  }

  // Impact: find a bracket [ta, tb] with g(ta) > 0 >= g(tb), the first such crossing.
  double ta = t0, tb = t1, ga = g0, gb = g1;
  bool impact = false;
  if (g0 > 0.0) {
    if (trough && g_turn <= 0.0) {
      tb = t_turn; gb = g_turn; impact = true;
    } else if (g1 <= 0.0) {
      impact = true;
    }
  } else if (g1 <= 0.0) {
    // Started on the ground (launch after uplift or impact) and ended there.
    if (peak && g_turn > 0.0) {
      ta = t_turn; ga = g_turn; impact = true;
    } else {
      ev.terminal = StepEvents::Terminal::Degenerate;  // excursion below resolution
      ev.t_event = t0;
      return ev;
    }
  }
  double t_end = t1;
  if (impact) {
    ev.terminal = StepEvents::Terminal::Impact;
    ev.t_event = bracketed_root(g_of, ta, tb, ga, gb, t_tol);
    t_end = ev.t_event;
  } else if (g1 >= overturn_angle) {
    ev.terminal = StepEvents::Terminal::Overturn;
    ev.t_event = bracketed_root([&](double t) { return g_of(t) - overturn_angle; }, t0, t1,
                                g0 - overturn_angle, g1 - overturn_angle, t_tol);
    t_end = ev.t_event;
  }
  if (ev.has_peak && t_turn > t_end) ev.has_peak = false;
  // First passage beyond alpha inside [t0, t_end].
  if (g0 <= alpha) {
    double t_hi = -1.0, g_hi = 0.0;
    if (ev.has_peak && g_turn > alpha) { t_hi = t_turn; g_hi = g_turn; }
    else if (ev.terminal == StepEvents::Terminal::Overturn) { t_hi = t_end; g_hi = overturn_angle; }
    else if (ev.terminal == StepEvents::Terminal::None && g1 > alpha) { t_hi = t1; g_hi = g1; }
    if (t_hi >= t0) {
      ev.tipping_crossed = true;
      ev.t_tipping = bracketed_root([&](double t) { return g_of(t) - alpha; }, t0, t_hi,
                                    g0 - alpha, g_hi - alpha, t_tol);
    }
  }
  return ev;
}

}  // namespace rocking_monitor::core
