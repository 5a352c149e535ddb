// The 3-D model sliding flat on its base (issue 51): against an exact 1-D sliding integrator under
// one component (piecewise-linear input: the slip velocity is piecewise quadratic, onset and stop the
// roots of linear and quadratic functions) over pulses and whole real records; free slides and spins
// that stop at their closed-form times; friction never adds energy; a snapshot mid-slide resumes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/motion/ground_motion.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "test_helpers.hpp"

namespace rocking_monitor::core {
namespace {

SolverSettings slide_settings() {
  SolverSettings s;
  s.method = Method::Dopri5;
  s.model = ModelKind::Nonlinear;
  s.tol = 1e-10;
  return s;
}

// A cabinet-like box (the issue's): base b x d centred on the origin, centre of mass h up.
BaseBodyParameters slide_box(double b, double d, double h, double mu_s, double mu_k) {
  return testing::uniform_box(b, d, h, mu_s, mu_k);
}

// The exact 1-D reference: a block on a floor with Coulomb friction under a(t) linear in each sample.
struct Slider1D {
  double mu_s, mu_k;
  double u = 0.0, x = 0.0;  // velocity and displacement relative to the floor
  int s = 0;                // 0 stuck, +-1 the sign of u
  long onsets = 0, sticks = 0;
  double first_onset = NAN;
  // One sample of length dt, a from a0 to a1 (horizontal), n = g + a_z from n0 to n1.
  void step(double t, double a0, double a1, double n0, double n1, double dt) {
    const double sa = (a1 - a0) / dt, sn = (n1 - n0) / dt;
    double tau = 0.0;
    for (int guard = 0; guard < 50 && tau < dt; ++guard) {
      if (s == 0) {
        // first tau' >= tau where +-a - mu_s n > 0 (linear): the ground pulls away
        double best = INFINITY;
        int dir = 0;
        for (int sg : {1, -1}) {
          const double f0 = sg * (a0 + sa * tau) - mu_s * (n0 + sn * tau), f1 = sg * (a0 + sa * dt) - mu_s * (n0 + sn * dt);
          double when = INFINITY;
          if (f0 > 0.0) when = tau;
          else if (f1 > 0.0) when = tau + (dt - tau) * (-f0) / (f1 - f0);
          if (when < best) { best = when; dir = -sg; }  // a > 0 pulls the floor ahead: the body slips back
        }
        if (!std::isfinite(best)) return;
        tau = best;
        s = dir;
        ++onsets;
        if (std::isnan(first_onset)) first_onset = t + tau;
      }
      // u' = -(a0 + sa t) - s mu_k (n0 + sn t) = c0 + c1 t on [tau, dt]
      const double c0 = -a0 - s * mu_k * n0, c1 = -sa - s * mu_k * sn;
      auto vel = [&](double q) { const double d = q - tau; return u + (c0 + c1 * tau) * d + 0.5 * c1 * d * d; };
      auto pos = [&](double q) { const double d = q - tau; return x + u * d + 0.5 * (c0 + c1 * tau) * d * d + c1 * d * d * d / 6.0; };
      // the first root of s u(q) = 0 in (tau, dt]
      const double A = 0.5 * c1, B = c0 + c1 * tau;  // u(tau + d) = u + B d + A d^2
      double stop = INFINITY;
      for (double d : {A == 0.0 ? -u / B : (-B - std::sqrt(std::max(0.0, B * B - 4 * A * u))) / (2 * A),
                       A == 0.0 ? INFINITY : (-B + std::sqrt(std::max(0.0, B * B - 4 * A * u))) / (2 * A)})
        if (d > 1e-15 && tau + d <= dt && B * B - 4 * A * u >= 0.0) stop = std::min(stop, tau + d);
      if (!std::isfinite(stop)) {
        x = pos(dt);
        u = vel(dt);
        return;
      }
      x = pos(stop);
      u = 0.0;
      tau = stop;
      const double a = a0 + sa * tau, n = n0 + sn * tau;
      if (std::abs(a) <= mu_s * n) { s = 0; ++sticks; }
      else s = a > 0.0 ? -1 : 1;
    }
  }
};

struct SlideCompare {
  double max_diff = 0.0, max_slip = 0.0;
  long onsets = 0, sticks = 0;
};

// The box under one horizontal along x (and optionally a vertical), the 3-D model against Slider1D
// at every sample end of the whole input.
// `direction`: the horizontal component acts along (cos, sin) of it (rad), the 1-D reference along it.
SlideCompare compare_1d(const BaseBodyParameters& p, const std::vector<double>& ax, const std::vector<double>& az,
                        double dt, const std::string& label, double direction = 0.0) {
  const Eigen::Vector2d e(std::cos(direction), std::sin(direction));
  Rocking3DModel m(BaseBody(p), slide_settings());
  Slider1D ref{p.mu_s, std::isnan(p.mu_k) ? p.mu_s : p.mu_k};
  m.reset(0.0, Eigen::Vector3d(ax[0] * e.x(), ax[0] * e.y(), az[0]));
  SlideCompare c;
  for (std::size_t i = 1; i < ax.size(); ++i) {
    ref.step(m.time(), ax[i - 1], ax[i], kGravity + az[i - 1], kGravity + az[i], dt);
    m.step(Eigen::Vector3d(ax[i] * e.x(), ax[i] * e.y(), az[i]), dt);
    const double diff = (m.slip() - ref.x * e).norm();
    if (std::getenv("SLIDE_DEBUG") && diff > 1e-9 && c.max_diff <= 1e-9)
      std::printf("%s: sample %zu t %.6f diff %.3g mode %s ref s %d u %.9f model u %.9f\n", label.c_str(), i, m.time(), diff,
                  to_string(m.mode()), ref.s, ref.u, m.slip_velocity().x());
    c.max_diff = std::max(c.max_diff, diff);
    c.max_slip = std::max(c.max_slip, std::abs(ref.x));
  }
  EXPECT_EQ(m.outcome().impacts, 0) << label;
  EXPECT_EQ(m.outcome_3d().slides, ref.onsets) << label;
  EXPECT_EQ(m.outcome_3d().sticks, ref.sticks) << label;
  EXPECT_LT(m.outcome_3d().max_twist, 1e-12) << label;
  if (ref.onsets > 0) EXPECT_NEAR(m.outcome_3d().first_slip_time, ref.first_onset, 1e-9) << label;
  EXPECT_LE(c.max_diff, 1e-6 * std::max(c.max_slip, 1e-3)) << label << ": slip differs by " << c.max_diff << " m of " << c.max_slip;
  c.onsets = ref.onsets;
  c.sticks = ref.sticks;
  return c;
}

std::vector<double> slide_pulse(double amp_g, double f_hz, double dt, double tail_s) {
  std::vector<double> a;
  for (double t = 0.0; t < 1.0 / f_hz; t += dt) a.push_back(amp_g * kGravity * std::sin(2.0 * kPi * f_hz * t));
  a.resize(a.size() + static_cast<std::size_t>(tail_s / dt), 0.0);
  return a;
}

TEST(Rocking3DSlide, ABoxUnderOneComponentSlidesAsTheExactOneDimensionalSolution) {
  // mu 0.3 < b / (2 h) = 0.857: it slides and never rocks (the centre of pressure stays mu h inside).
  int slid = 0;
  for (double mu_k : {0.3, 0.24})
    for (double f : {1.0, 2.0, 4.0})
      for (double amp : {0.25, 0.5, 0.7}) {
        const std::vector<double> ax = slide_pulse(amp, f, 0.005, 1.0);
        const std::vector<double> az(ax.size(), 0.0);
        const SlideCompare c = compare_1d(slide_box(0.6, 0.5, 0.35, 0.3, mu_k), ax, az, 0.005,
                                          "pulse " + std::to_string(f) + " Hz " + std::to_string(amp) + " g mu_k " + std::to_string(mu_k));
        slid += c.onsets > 0;
      }
  EXPECT_GE(slid, 12);
}

// One component along any horizontal direction: the cone's friction acts along the slip with its
// full mu N, so the slip is the 1-D solution along that direction (the per-axis pyramid of the planar
// pair would resist it with up to sqrt(2) mu N); the resultant passes through the centre of mass's
// vertical, so the box never twists.
TEST(Rocking3DSlide, ABoxUnderOneComponentAlongAnyDirectionSlidesAsTheOneDimensionalSolutionAlongIt) {
  int slid = 0;
  for (double deg_dir : {30.0, 45.0, 117.0, 250.0})
    for (double amp : {0.4, 0.7}) {
      const std::vector<double> ax = slide_pulse(amp, 2.0, 0.005, 1.0);
      const std::vector<double> az(ax.size(), 0.0);
      const SlideCompare c = compare_1d(slide_box(0.6, 0.5, 0.35, 0.3, 0.27), ax, az, 0.005,
                                        "pulse along " + std::to_string(deg_dir) + " deg " + std::to_string(amp) + " g",
                                        deg_dir * kPi / 180.0);
      slid += c.onsets > 0;
    }
  EXPECT_EQ(slid, 8);
  GroundMotion g;
  if (!testing::first_horizontal("kobe_1995/RSN1120_KOBE_TAK000.AT2", g)) GTEST_SKIP() << "records absent";
  const std::vector<double> az(g.horizontal.size(), 0.0);
  const SlideCompare k = compare_1d(slide_box(0.6, 0.5, 0.35, 0.3, 0.3), g.horizontal, az, g.dt, "Takatori along 40 deg",
                                    40.0 * kPi / 180.0);
  EXPECT_GT(k.max_slip, 0.2);
}

TEST(Rocking3DSlide, ABoxUnderARealRecordAndItsVerticalSlidesAsTheExactSolution) {
  // The case: Kobe Takatori (0.67 g) against a friction of 0.3, the whole record, with and
  // without the vertical component (which changes the normal force and so the friction).
  GroundMotion g;
  if (!testing::first_horizontal("kobe_1995/RSN1120_KOBE_TAK000.AT2", g)) GTEST_SKIP() << "records absent";
  std::vector<double> az(g.horizontal.size(), 0.0);
  const SlideCompare flat = compare_1d(slide_box(0.6, 0.5, 0.35, 0.3, 0.3), g.horizontal, az, g.dt, "Takatori");
  EXPECT_GT(flat.max_slip, 0.05);
  EXPECT_GT(flat.onsets, 10);
  for (std::size_t i = 0; i < az.size(); ++i) az[i] = 0.3 * kGravity * std::sin(2 * kPi * 3.0 * i * g.dt);
  const SlideCompare vert = compare_1d(slide_box(0.6, 0.5, 0.35, 0.3, 0.25), g.horizontal, az, g.dt, "Takatori + 0.3 g vertical");
  EXPECT_NE(vert.onsets, flat.onsets);
  RecordProperty("takatori_slip_m", std::to_string(flat.max_slip));
}

TEST(Rocking3DSlide, AFreeSlideStopsAtTheClosedFormTimeAndDistance) {
  // No shaking, initial slip u0 in an oblique direction: stops at u0 / (mu_k g) after u0^2 / (2 mu_k g).
  const BaseBodyParameters p = slide_box(0.6, 0.5, 0.35, 0.4, 0.3);
  Rocking3DModel m(BaseBody(p), slide_settings());
  m.reset(0.0);
  const Eigen::Vector2d u0(0.6, -0.8);  // 1 m/s
  m.set_slide_state(u0, 0.0);
  const double dt = 0.01;
  double t_stop = NAN;
  for (int i = 0; i < 100 && std::isnan(t_stop); ++i) {
    m.step(Eigen::Vector3d::Zero(), dt);
    if (m.mode() == Mode3D::Rest) t_stop = m.time();
  }
  const double mu_g = 0.3 * kGravity;
  EXPECT_EQ(m.outcome_3d().sticks, 1);
  EXPECT_NEAR(m.outcome_3d().slip_time, 1.0 / mu_g, 1e-9);
  EXPECT_NEAR((m.slip() - u0 / (2.0 * mu_g)).norm(), 0.0, 1e-9);
}

TEST(Rocking3DSlide, ASpinningSquareStopsAtTheClosedFormTimeAndAngle) {
  // A square box spinning on its base: torque mu g a (sqrt 2 + ln(1 + sqrt 2)) / 6 per unit mass
  // (uniform pressure: a box's gyroscopic moment vanishes), so the spin falls linearly.
  const double a = 0.5;
  const BaseBodyParameters p = slide_box(a, a, 0.4, 0.3, 0.3);
  Rocking3DModel m(BaseBody(p), slide_settings());
  m.reset(0.0);
  const double w0 = 6.0;
  m.set_slide_state(Eigen::Vector2d::Zero(), w0);
  const double torque = 0.3 * kGravity * a * (std::sqrt(2.0) + std::log(1.0 + std::sqrt(2.0))) / 6.0;
  const double jzz = a * a / 6.0, t_stop = w0 * jzz / torque;
  for (int i = 0; i < 200 && m.mode() == Mode3D::Slide; ++i) m.step(Eigen::Vector3d::Zero(), 0.01);
  EXPECT_EQ(m.mode(), Mode3D::Rest);
  EXPECT_NEAR(m.outcome_3d().slip_time, t_stop, 1e-9);
  EXPECT_NEAR(m.outcome_3d().max_twist, 0.5 * w0 * t_stop, 1e-8);
  EXPECT_NEAR(m.slip().norm(), 0.0, 1e-12);  // turning about its centre of mass
}

TEST(Rocking3DSlide, FrictionNeverAddsEnergyToRandomBasesSlidingAndTurning) {
  std::mt19937 rng(51);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int stopped = 0;
  for (int trial = 0; trial < 40; ++trial) {
    BaseBodyParameters p;
    const int n = 3 + trial % 6;
    for (int k = 0; k < n; ++k) {
      const double t = 2 * kPi * (k + 0.3 * u(rng)) / n;
      p.base.emplace_back(0.3 * std::cos(t), 0.2 * std::sin(t));
    }
    p.centre_of_mass = {0.02 * u(rng), 0.02 * u(rng), 0.3};
    const Eigen::Matrix3d q = Eigen::AngleAxisd(0.3 * u(rng), Eigen::Vector3d(u(rng), u(rng), 1).normalized()).toRotationMatrix();
    p.central_inertia = q * Eigen::Vector3d(0.04, 0.05, 0.03).asDiagonal() * q.transpose();
    p.mu_s = p.mu_k = 0.2 + 0.2 * std::abs(u(rng));
    Rocking3DModel m(BaseBody(p), slide_settings());
    m.reset(0.0);
    m.set_slide_state(Eigen::Vector2d(u(rng), u(rng)), 8.0 * u(rng));
    double e = m.kinetic_energy();
    for (int i = 0; i < 300 && m.mode() == Mode3D::Slide; ++i) {
      m.step(Eigen::Vector3d::Zero(), 0.005);
      ASSERT_LE(m.kinetic_energy(), e * (1 + 1e-12) + 1e-15) << "trial " << trial << " sample " << i;
      e = m.kinetic_energy();
    }
    // It stops, or an edge lifts (the centre of pressure reaching the edge: rocking takes over).
    stopped += m.mode() == Mode3D::Rest || m.outcome_3d().slide_to_rock > 0;
    if (std::getenv("SLIDE_DEBUG"))
      std::printf("trial %d mode %s steps %ld slip_time %.4f to_rock %ld impacts %ld\n", trial, to_string(m.mode()),
                  m.outcome().integrator_steps, m.outcome_3d().slip_time, m.outcome_3d().slide_to_rock, m.outcome().impacts);
  }
  EXPECT_EQ(stopped, 40);
}

TEST(Rocking3DSlide, BidirectionalShakingFromRestNeverTwists) {
  // From rest under ground translation alone the centre of pressure lies on the friction force's line
  // through the centre of mass: no torque, whatever the base (here irregular), so no twist.
  BaseBodyParameters p;
  p.base = {{0.0, 0.0}, {0.5, -0.05}, {0.6, 0.3}, {0.2, 0.45}, {-0.1, 0.2}};
  p.centre_of_mass = {0.22, 0.17, 0.3};
  p.central_inertia = Eigen::Vector3d(0.05, 0.04, 0.03).asDiagonal();
  p.mu_s = 0.25;
  Rocking3DModel m(BaseBody(p), slide_settings());
  m.reset(0.0);
  for (int i = 1; i < 800; ++i) {
    const double t = i * 0.005;
    m.step(Eigen::Vector3d(4.0 * std::sin(2 * kPi * 1.3 * t), 3.0 * std::cos(2 * kPi * 0.9 * t), 0.0), 0.005);
  }
  EXPECT_GT(m.outcome_3d().slides, 0);
  EXPECT_GT(m.outcome_3d().max_slip, 0.01);
  EXPECT_EQ(m.outcome_3d().max_twist, 0.0);
}

TEST(Rocking3DSlide, ASnapshotMidSlideResumesExactly) {
  const BaseBodyParameters p = slide_box(0.6, 0.5, 0.35, 0.3, 0.25);
  const std::vector<double> ax = slide_pulse(0.6, 1.5, 0.005, 1.0);
  Rocking3DModel a(BaseBody(p), slide_settings()), b(BaseBody(p), slide_settings());
  a.reset(0.0);
  Rocking3DModel::Saved saved;
  bool taken = false;
  for (std::size_t i = 1; i < ax.size(); ++i) {
    const Eigen::Vector3d in(ax[i], 0.5 * ax[i], 0.0);
    if (taken) b.step(in, 0.005);
    a.step(in, 0.005);
    if (!taken && a.mode() == Mode3D::Slide && a.slip().norm() > 0.01) {
      a.save(saved);
      b.restore(saved);
      taken = true;
    }
  }
  ASSERT_TRUE(taken);
  EXPECT_EQ(a.slip().x(), b.slip().x());
  EXPECT_EQ(a.slip().y(), b.slip().y());
  EXPECT_EQ(a.outcome_3d().sticks, b.outcome_3d().sticks);
}

}  // namespace
}  // namespace rocking_monitor::core
