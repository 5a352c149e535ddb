#include "rocking_monitor/physics/frictional_impact.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "rocking_monitor/constants.hpp"

namespace rocking_monitor::core {

namespace {

// Sweeps: a converged landing takes ~120 on average (test_frictional_impact.cpp); the bound keeps
// the worst landing's cost to a few milliseconds (rocking_benchmarks landing/frictional).
constexpr int kMaxSweeps = 2000;
constexpr int kPlainSweeps = 500;     // then under-relaxed (x 0.5, and x 0.25 after twice as many)
constexpr int kSlipAngles = 48;       // samples of the slip angle that bracket the local root
constexpr double kSweepTol = 1e-15;   // per unit of the landing's velocity scale
constexpr double kLawTol = 1e-14;     // the contact law's residual that ends the sweeps, per unit of the same scale
constexpr double kConvergedTol = 1e-10;  // the residual reported as converged (the rest of the sweep budget spent)
constexpr int kCheckEvery = 10;       // sweeps between residual checks

Eigen::Matrix3d skew_of(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

// One contact slipping in direction s = (cos phi, sin phi): the impulse r = r_n (-mu s, 1) that
// keeps it on the floor (u_n = 0), and its slip velocity u_t.
struct SlipTrial {
  Eigen::Vector3d r;
  Eigen::Vector2d ut, s;
  bool ok;
};

SlipTrial slip_trial(const Eigen::Matrix3d& w, const Eigen::Vector3d& q, double mu, double phi) {
  SlipTrial t;
  t.s = Eigen::Vector2d(std::cos(phi), std::sin(phi));
  const Eigen::Vector3d g(-mu * t.s.x(), -mu * t.s.y(), 1.0);
  const Eigen::Vector3d wg = w * g;
  t.ok = wg.z() > 0.0;
  const double rn = t.ok ? -q.z() / wg.z() : 0.0;
  t.r = rn * g;
  t.ut = rn * wg.head<2>() + q.head<2>();
  return t;
}

double slip_cross(const SlipTrial& t) { return t.ut.x() * t.s.y() - t.ut.y() * t.s.x(); }

// The slip trial's cross product u_t x s and its derivative in the slip angle (analytic: one sincos).
double slip_cross_and_slope(const Eigen::Matrix3d& w, const Eigen::Vector3d& q, double mu, double phi, double& slope) {
  const double c = std::cos(phi), sn = std::sin(phi);
  const Eigen::Vector3d g(-mu * c, -mu * sn, 1.0), dg(mu * sn, -mu * c, 0.0);
  const Eigen::Vector3d wg = w * g, dwg = w * dg;
  const double rn = -q.z() / wg.z(), drn = q.z() * dwg.z() / (wg.z() * wg.z());
  const Eigen::Vector2d ut = rn * wg.head<2>() + q.head<2>(), dut = drn * wg.head<2>() + rn * dwg.head<2>();
  slope = dut.x() * sn + ut.x() * c - dut.y() * c + ut.y() * sn;
  return ut.x() * sn - ut.y() * c;
}

// Newton's method on the slip angle from the previous root (a warm start: the sweeps change each
// contact's problem a little); false when it does not settle on an admissible root.
bool slip_newton(const Eigen::Matrix3d& w, const Eigen::Vector3d& q, double mu, double& phi, Eigen::Vector3d& r) {
  double x = phi;
  for (int it = 0;; ++it) {
    if (it == 12) return false;
    double df;
    const double f = slip_cross_and_slope(w, q, mu, x, df);
    if (!(std::abs(df) > 0.0)) return false;
    const double step = std::clamp(f / df, -0.5, 0.5);
    x -= step;
    if (std::abs(step) <= 1e-15 * (1.0 + std::abs(x))) break;
  }
  const SlipTrial t = slip_trial(w, q, mu, x);
  if (!t.ok || t.ut.dot(t.s) < 0.0) return false;
  phi = x;
  r = t.r;
  return true;
}

// The slip root: u_t parallel to s (cross product 0) with u_t . s >= 0: Newton from the previous
// root, else by bracketing the sampled slip angles and bisecting (the root nearest the previous one
// when several exist). `phi` is updated.
bool slip_root(const Eigen::Matrix3d& w, const Eigen::Vector3d& q, double mu, double& phi, Eigen::Vector3d& r) {
  if (slip_newton(w, q, mu, phi, r)) return true;
  bool found = false;
  double best_gap = 0.0;
  SlipTrial lo = slip_trial(w, q, mu, phi - kPi);
  for (int i = 1; i <= kSlipAngles; ++i) {
    const double b = phi - kPi + 2.0 * kPi * i / kSlipAngles;
    const SlipTrial hi = slip_trial(w, q, mu, b);
    const double f_lo = slip_cross(lo), f_hi = slip_cross(hi);
    if (lo.ok && hi.ok && (f_lo <= 0.0) != (f_hi <= 0.0)) {
      double a = b - 2.0 * kPi / kSlipAngles, c = b, fa = f_lo;
      for (int it = 0; it < 64 && c - a > 1e-15; ++it) {
        const double m = 0.5 * (a + c);
        const double fm = slip_cross(slip_trial(w, q, mu, m));
        if ((fm <= 0.0) == (fa <= 0.0)) a = m, fa = fm;
        else c = m;
      }
      const double root = 0.5 * (a + c);
      const SlipTrial t = slip_trial(w, q, mu, root);
      const double gap = std::abs(std::remainder(root - phi, 2.0 * kPi));
      if (t.ok && t.ut.dot(t.s) >= 0.0 && (!found || gap < best_gap)) {
        found = true;
        best_gap = gap;
        r = t.r;
        phi = root;
      }
    }
    lo = hi;
  }
  return found;
}

// One contact's problem u = W r + q under the contact law: separate, stick, or slip.
Eigen::Vector3d solve_contact(const Eigen::Matrix3d& w, const Eigen::Matrix3d& w_inv, const Eigen::Vector3d& q,
                              const ImpactFriction& f, double& phi) {
  if (q.z() >= 0.0) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d stick = -(w_inv * q);
  if (stick.z() > 0.0 && std::hypot(stick.x(), stick.y()) <= f.mu_s * stick.z()) return stick;
  if (f.mu_k == 0.0) return Eigen::Vector3d(0.0, 0.0, -q.z() / w(2, 2));
  Eigen::Vector3d r;
  if (slip_root(w, q, f.mu_k, phi, r)) return r;
  // No slip root (not met in the tests): the sticking impulse pulled back into the cone.
  const double rn = std::max(stick.z(), 0.0), rt = std::hypot(stick.x(), stick.y());
  const double k = rt > f.mu_k * rn ? f.mu_k * rn / rt : 1.0;
  return Eigen::Vector3d(k * stick.x(), k * stick.y(), rn);
}

// The largest violation of the contact law by the impulses r and the motion (v, omega) after, m/s;
// counts the contacts that stay on the floor and the ones of those that slip (into `out`).
double law_residual(const LandingContacts& c, const ImpactFriction& f, const Eigen::Vector3d* r,
                    const Eigen::Vector3d* arm, const Eigen::Vector3d& v, const Eigen::Vector3d& om, double scale,
                    FrictionalLanding& out) {
  const double v_tol = 1e-9 * scale;
  double worst = 0.0;
  out.stay = out.slipping = 0;
  for (int k = 0; k < c.count; ++k) {
    const Eigen::Vector3d u = v + om.cross(arm[k]);
    const double ut = std::hypot(u.x(), u.y()), rt = std::hypot(r[k].x(), r[k].y());
    double bad = std::max({0.0, -u.z(), -r[k].z()});
    if (r[k].z() > 0.0) bad = std::max(bad, std::abs(u.z()));
    if (ut > v_tol && r[k].z() > 0.0) bad = std::max(bad, (r[k].head<2>() + f.mu_k * r[k].z() * u.head<2>() / ut).norm());
    else bad = std::max(bad, rt - f.mu_s * std::max(r[k].z(), 0.0));
    worst = std::max(worst, bad);
    if (std::abs(u.z()) <= v_tol) {
      ++out.stay;
      if (ut > v_tol) ++out.slipping;
    }
  }
  return worst;
}

double kinetic(const LandingBody& b, const Eigen::Vector3d& omega, const Eigen::Vector3d& v) {
  return 0.5 * omega.dot(b.central_inertia * omega) + 0.5 * v.squaredNorm();
}

}  // namespace

namespace {

// The solver's state: per contact its lever from the centre of mass, Delassus block, impulse and last
// slip angle; one per thread (no allocation per landing).
struct Sweeper {
  Eigen::Vector3d r[LandingContacts::kMax], arm[LandingContacts::kMax];
  Eigen::Matrix3d w[LandingContacts::kMax], w_inv[LandingContacts::kMax];
  double phi[LandingContacts::kMax];
  Eigen::Matrix3d j_inv;
  double scale = 0.0;

  void start(const LandingBody& b, const LandingContacts& c) {
    j_inv = b.central_inertia.inverse();
    double size = 0.0;
    for (int k = 0; k < c.count; ++k) {
      arm[k] = c.point[k] - b.centre;
      const Eigen::Matrix3d s = skew_of(arm[k]);
      w[k] = Eigen::Matrix3d::Identity() - s * j_inv * s;  // the contact's own Delassus block
      w_inv[k] = w[k].inverse();                             // (symmetric positive definite: >= identity)
      r[k].setZero();
      const Eigen::Vector3d u = point_velocity(b.omega, b.velocity, b.centre, c.point[k]);
      phi[k] = std::atan2(u.y(), u.x());
      size = std::max(size, arm[k].norm());
    }
    scale = b.velocity.norm() + b.omega.norm() * size + 1e-300;
  }

  // Gauss-Seidel over the contacts `idx` (the others take no impulse); the law checked on all.
  FrictionalLanding sweep(const LandingBody& b, const LandingContacts& c, const ImpactFriction& f, const int* idx,
                          int m, int max_sweeps = kMaxSweeps, double sweep_tol = kSweepTol) {
    FrictionalLanding out;
    out.energy_before = kinetic(b, b.omega, b.velocity);
    Eigen::Vector3d v = b.velocity, om = b.omega;
    for (out.sweeps = 1; out.sweeps <= max_sweeps; ++out.sweeps) {
      double change = 0.0;
      // Where the sweeps cycle (a contact switching between stick and slip with its neighbours), an
      // under-relaxed update settles them.
      const double relax = out.sweeps < kPlainSweeps ? 1.0 : out.sweeps < 2 * kPlainSweeps ? 0.5 : 0.25;
      for (int i = 0; i < m; ++i) {
        const int k = idx[i];
        const Eigen::Vector3d q = v + om.cross(arm[k]) - w[k] * r[k];
        const Eigen::Vector3d d = relax * (solve_contact(w[k], w_inv[k], q, f, phi[k]) - r[k]);
        v += d;
        om += j_inv * arm[k].cross(d);
        r[k] += d;
        change = std::max(change, d.norm());
      }
      // Converged: the sweep moves nothing, or (checked every few sweeps: a face's redundant contacts
      // converge slowly in their impulses, not in the motion) the contact law holds to rounding.
      if (change <= sweep_tol * scale ||
          (out.sweeps % kCheckEvery == 0 && law_residual(c, f, r, arm, v, om, scale, out) <= kLawTol * scale))
        break;
    }
    out.sweeps = std::min(out.sweeps, max_sweeps);
    out.velocity = v;
    out.omega = om;
    out.impulse = v - b.velocity;
    out.energy_after = kinetic(b, om, v);
    out.residual = law_residual(c, f, r, arm, v, om, scale, out);
    out.converged = out.residual <= kConvergedTol * scale;
    return out;
  }
};

}  // namespace

FrictionalLanding frictional_landing(const LandingBody& b, const LandingContacts& c, const ImpactFriction& f,
                                     const int* first, int first_count) {
  static thread_local Sweeper s;
  static thread_local int all[LandingContacts::kMax];
  s.start(b, c);
  if (first_count > 0 && first_count < c.count) {
    // The contacts the sticking law loads, alone: where the others then leave the floor (or stay on
    // it) this is a solution of the whole set's law, at a fraction of the sweeps.
    const FrictionalLanding out = s.sweep(b, c, f, first, first_count);
    if (out.converged) return out;
    s.start(b, c);
  }
  for (int k = 0; k < c.count; ++k) all[k] = k;
  return s.sweep(b, c, f, all, c.count);
}

bool keeps_pivot(const LandingBody& b, const LandingContacts& c, const int* pivot, int pivot_count) {
  if (pivot_count <= 0 || pivot_count > 2 || pivot_count >= c.count) return false;
  // The frictionless impact on the pivot's contacts: normal impulses only, u_n = 0 at each (1 x 1 or
  // 2 x 2 in the normal rows of the Delassus operator).
  const Eigen::Matrix3d j_inv = b.central_inertia.inverse();
  Eigen::Vector3d arm[2], z_turn[2];
  double u_n[2];
  for (int i = 0; i < pivot_count; ++i) {
    arm[i] = c.point[pivot[i]] - b.centre;
    z_turn[i] = j_inv * arm[i].cross(Eigen::Vector3d::UnitZ());  // the turn of a unit normal impulse there
    u_n[i] = point_velocity(b.omega, b.velocity, b.centre, c.point[pivot[i]]).z();
  }
  auto w_nn = [&](int i, int k) { return 1.0 + z_turn[k].cross(arm[i]).z(); };
  double p[2] = {0.0, 0.0};
  if (pivot_count == 1) {
    p[0] = -u_n[0] / w_nn(0, 0);
  } else {
    const double a = w_nn(0, 0), bb = w_nn(0, 1), cc = w_nn(1, 0), d = w_nn(1, 1), det = a * d - bb * cc;
    if (!(std::abs(det) > 1e-12 * std::abs(a * d))) return false;
    p[0] = (-u_n[0] * d + u_n[1] * bb) / det;
    p[1] = (-u_n[1] * a + u_n[0] * cc) / det;
  }
  if (p[0] < 0.0 || p[1] < 0.0) return false;
  Eigen::Vector3d v = b.velocity, om = b.omega;
  for (int i = 0; i < pivot_count; ++i) {
    v.z() += p[i];
    om += p[i] * z_turn[i];
  }
  double size = 0.0;
  for (int k = 0; k < c.count; ++k) size = std::max(size, (c.point[k] - b.centre).norm());
  const double margin = 1e-6 * (b.velocity.norm() + b.omega.norm() * size);
  for (int k = 0; k < c.count; ++k) {
    const bool loaded = k == pivot[0] || (pivot_count == 2 && k == pivot[1]);
    if (!loaded && !(point_velocity(om, v, b.centre, c.point[k]).z() > margin)) return false;
  }
  return true;
}

}  // namespace rocking_monitor::core
