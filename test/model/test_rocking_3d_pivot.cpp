// The 3-D model's pivot against the friction cone while rocking (issue 51 part 2's onset): a box about
// a side under one component gives the planar contact model's SLIDE-ROCK onset (an independent code:
// the planar equations of motion in x, y, theta with RK4, its own event location); the reaction along
// the edge stays zero (symmetry); a vertical pull gives the FLIGHT onset; a snapshot carries the state.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "rocking_monitor/model/contact_model.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rhombus_on_corner.hpp"
#include "test_helpers.hpp"

namespace rocking_monitor::core {
namespace {

SolverSettings pivot_settings() {
  SolverSettings s;
  s.method = Method::Dopri5;
  s.model = ModelKind::Nonlinear;
  s.tol = 1e-11;
  return s;
}

// A uniform box (mu_k finite where mu_s is not given).
BaseBodyParameters pivot_box(double b, double d, double h, double mu) {
  return testing::uniform_box(b, d, h, mu, std::min(mu, 0.5));
}

struct Onsets {
  double uplift = NAN, slip = NAN, flight = NAN;
};

// One sine pulse a_x = A sin(2 pi t / T) for t < T (then still), vertical av(t), sampled at dt; run
// for `duration` or until the first slip or flight.
template <class Vertical>
Onsets planar_onsets(double b, double h, double mu, double A, double T, Vertical av, double dt, double duration) {
  BodyParameters x;
  x.width = b;
  x.cg_height = h;
  x.mu_s = mu;
  x.mu_k = std::min(mu, 0.5);  // (finite: without mu_s the slip is never checked)
  ContactSettings cs;
  cs.substeps = 256;
  ContactModel m(x, cs);
  m.reset(0.0, 0.0, av(0.0));
  for (int i = 1; i * dt <= duration + 1e-12; ++i) {
    const double t = i * dt;
    m.step(t < T ? A * std::sin(2 * kPi * t / T) : 0.0, av(t), dt);
    if (!std::isnan(m.outcome().first_slip_time) || !std::isnan(m.outcome().first_flight_time)) break;
  }
  return {m.outcome().first_uplift_time, m.outcome().first_slip_time, m.outcome().first_flight_time};
}

TEST(Rocking3DPivot, ABoxAboutASideLeavesTheConeWhenThePlanarContactModelSlideRocks) {
  const double b = 0.4, d = 0.5, h = 0.8, dt = 0.005;
  int compared = 0;
  double worst = 0.0;
  for (double mu : {0.26, 0.3, 0.35, 0.45})
    for (double A : {0.3, 0.45, 0.7})
      for (double T : {0.3, 0.6, 1.2}) {
        const Onsets ref = planar_onsets(b, h, mu, A * kGravity, T, [](double) { return 0.0; }, dt, 3.0);
        Rocking3DModel m(BaseBody(pivot_box(b, d, h, mu)), pivot_settings());
        m.reset(0.0);
        bool wobbled = false;
        for (int i = 1; i * dt <= 3.0 + 1e-12 && m.mode() != Mode3D::Overturned; ++i) {
          const double t = i * dt;
          m.step(Eigen::Vector3d(t < T ? A * kGravity * std::sin(2 * kPi * t / T) : 0.0, 0.0, 0.0), dt);
          if (m.mode() == Mode3D::Vertex) wobbled = true;  // a box about a side never lifts an end
          if (m.outcome_3d().pivot_slips + m.outcome_3d().pivot_lifts > 0) break;
        }
        const Rocking3DOutcome& o = m.outcome_3d();
        std::printf("[ measure ] mu %.2f A %.2f g T %.1f s: planar uplift %.6f slip %.9f flight %.6f | 3-D uplift %.6f "
                    "pivot slip %.9f (%ld slips, %ld lifts)\n", mu, A, T, ref.uplift, ref.slip, ref.flight,
                    m.outcome().uplift_time, o.first_pivot_slip_time, o.pivot_slips, o.pivot_lifts);
        EXPECT_FALSE(wobbled);
        if (std::isnan(ref.uplift) || !(ref.slip > ref.uplift)) {
          // Slides from rest or never rocks: the onset while rocking is not this test's.
          continue;
        }
        ++compared;
        EXPECT_NEAR(m.outcome().uplift_time, ref.uplift, 1e-6) << mu << " " << A << " " << T;
        ASSERT_EQ(o.pivot_slips, 1) << mu << " " << A << " " << T;
        EXPECT_NEAR(o.first_pivot_slip_time, ref.slip, 1e-6) << mu << " " << A << " " << T;
        worst = std::max(worst, std::abs(o.first_pivot_slip_time - ref.slip));
        // Named and located, no mode change: the last record (the run stops at it).
        ASSERT_GE(m.transition_records(), 2);
        const Transition3DRecord& r = m.transition(m.transition_records() - 1);
        EXPECT_EQ(r.reason, Transition3D::PivotSlips);
        EXPECT_EQ(r.from, Mode3D::Edge);
        EXPECT_EQ(r.to, Mode3D::Edge);
        EXPECT_DOUBLE_EQ(r.time, o.first_pivot_slip_time);
      }
  std::printf("[ measure ] %d slide-rock onsets compared with the planar contact model, largest difference %.2g s\n",
              compared, worst);
  EXPECT_GE(compared, 5);
}

// Rocking under a horizontal pulse, then the floor drops faster than gravity for 0.2 s: the pivot's
// normal reaction vanishes (FLIGHT in the planar contact model) with no friction limit to leave first.
TEST(Rocking3DPivot, AFloorFallingFasterThanGravityLiftsThePivotWhenThePlanarModelFlies) {
  const double b = 0.4, d = 0.5, h = 0.8, dt = 0.005, mu = INFINITY;
  int compared = 0;
  for (double drop : {1.2, 1.6, 2.5})
    for (double t_drop : {0.3, 0.45}) {
      auto av = [&](double t) { return t > t_drop && t < t_drop + 0.2 ? -drop * kGravity * std::sin(kPi * (t - t_drop) / 0.2) : 0.0; };
      const Onsets ref = planar_onsets(b, h, mu, 0.6 * kGravity, 0.6, av, dt, 1.5);
      Rocking3DModel m(BaseBody(pivot_box(b, d, h, mu)), pivot_settings());
      m.reset(0.0);
      for (int i = 1; i * dt <= 1.5 + 1e-12 && m.mode() != Mode3D::Overturned; ++i) {
        const double t = i * dt;
        m.step(Eigen::Vector3d(t < 0.6 ? 0.6 * kGravity * std::sin(2 * kPi * t / 0.6) : 0.0, 0.0, av(t)), dt);
        if (m.outcome_3d().pivot_slips + m.outcome_3d().pivot_lifts > 0) break;
      }
      const Rocking3DOutcome& o = m.outcome_3d();
      std::printf("[ measure ] drop %.1f g at %.2f s: planar uplift %.6f flight %.9f | 3-D pivot lift %.9f (%ld lifts, "
                  "mode %s)\n", drop, t_drop, ref.uplift, ref.flight, o.first_pivot_slip_time, o.pivot_lifts,
                  to_string(m.mode()));
      if (std::isnan(ref.flight) || !(ref.flight > ref.uplift)) continue;
      ++compared;
      EXPECT_EQ(o.pivot_slips, 0);
      ASSERT_EQ(o.pivot_lifts, 1);
      EXPECT_NEAR(o.first_pivot_slip_time, ref.flight, 1e-6) << drop << " " << t_drop;
      EXPECT_EQ(m.transition(m.transition_records() - 1).reason, Transition3D::PivotLifts);
    }
  EXPECT_GE(compared, 3);
}

// Slide-rock on a vertex against the planar contact model's SLIDE-ROCK: a rhombus base (a vertex at
// +x, symmetric about the x-z plane, diagonal inertia) pivoting on its +x vertex under shaking along
// x moves in the x-z plane as the planar body of width 2a with the same height and radius of gyration
// rocking on its corner. From a tilt, both sticking at first, the pivot's slip (onset, distance,
// reversal) and the tilt agree sample for sample until the first landing.
TEST(Rocking3DPivot, ARhombusSlideRocksOnItsVertexAsThePlanarContactModel) {
  const double a = 0.25, c = 0.3, h = 0.9, ig = 0.35, dt = 0.005;
  int compared = 0;
  double worst_theta = 0.0, worst_slip = 0.0, largest_slip = 0.0;
  for (double mu : {0.12, 0.2})
    for (double amp : {0.0, 0.3, -0.3})
      for (double omega0 : {0.8, -0.5}) {
        Rocking3DModel solid(BaseBody(testing::rhombus(a, c, h, ig, mu)), pivot_settings());
        ContactModel planar(testing::planar_rhombus(a, h, ig, mu), testing::fine_contact());
        testing::tilt_on_corner(solid, planar, 0.08, omega0);
        const Eigen::Vector3d start = solid.rotation() * solid.contact_point() + solid.translation();
        double slip = 0.0;
        for (int i = 1; i <= 400; ++i) {
          const double t = i * dt, ax = amp * kGravity * std::sin(2 * kPi * t / 0.8);
          solid.step(Eigen::Vector3d(ax, 0.0, 0.0), dt);
          // (the planar convention: a_xg > 0 tips about the -x corner; its x runs the other way about
          // corner 1, which the 3-D +x vertex is: the input and the slip are mirrored)
          const ContactReport& r = planar.step(-ax, 0.0, dt);
          if (solid.outcome().impacts > 0 || r.impacts > 0 || solid.mode() != Mode3D::Vertex) break;
          const Eigen::Vector3d pivot = solid.rotation() * solid.contact_point() + solid.translation();
          worst_theta = std::max(worst_theta, std::abs(solid.tilt() - std::abs(r.theta)));
          worst_slip = std::max(worst_slip, std::abs((pivot.x() - start.x()) + r.slip));
          largest_slip = std::max(largest_slip, std::abs(r.slip));
          slip = pivot.x() - start.x();
          EXPECT_NEAR(pivot.y(), start.y(), 1e-12);
          ++compared;
        }
        std::printf("[ measure ] mu %.2f amp %.1f g omega0 %.1f: %ld slip onsets, %ld sticks; the pivot's slip at the last "
                    "sample before the landing %.6f m\n", mu, amp, omega0, solid.outcome_3d().pivot_slips,
                    solid.outcome_3d().pivot_sticks, slip);
      }
  std::printf("[ measure ] %d samples compared: tilt within %.2g rad, slip within %.2g m (largest slip %.4f m)\n",
              compared, worst_theta, worst_slip, largest_slip);
  EXPECT_GT(largest_slip, 1e-3);
  EXPECT_LT(worst_theta, 1e-6);
  EXPECT_LT(worst_slip, 1e-6);
}

// Friction never adds energy: eccentric boxes thrown onto a corner with a spin, no shaking, low
// friction (the corner slips and sticks again): kinetic plus potential energy never grows while the
// body pivots on that vertex, sticking or slipping (landings are the impact law's, tested elsewhere).
TEST(Rocking3DPivot, ASlippingCornerNeverAddsEnergy) {
  int slipping_runs = 0;
  long checked = 0;
  for (double ecc : {0.0, 0.06})
    for (double mu : {0.1, 0.2})
      for (double spin : {-1.5, 0.7, 2.0}) {
        BaseBodyParameters p = pivot_box(0.5, 0.4, 0.8, mu);
        p.centre_of_mass = {ecc, -0.5 * ecc, 0.8};
        Rocking3DModel m(BaseBody(p), pivot_settings());
        m.reset(0.0);
        const Eigen::Quaterniond tilt(Eigen::AngleAxisd(0.12, Eigen::Vector3d(1.0, -1.0, 0.0).normalized()));
        m.set_vertex_state(0, tilt, Eigen::Vector3d(0.6, -0.6, spin));
        auto energy = [&] {
          return m.kinetic_energy() + kGravity * (m.rotation() * m.body().centre_of_mass() + m.translation()).z();
        };
        double before = energy();
        for (int i = 0; i < 300 && m.mode() == Mode3D::Vertex && m.outcome().impacts == 0; ++i) {
          m.step(Eigen::Vector3d::Zero(), 0.005);
          if (m.mode() != Mode3D::Vertex || m.outcome().impacts > 0) break;
          const double now = energy();
          EXPECT_LE(now, before + 1e-9 * std::abs(before)) << ecc << " " << mu << " " << spin << " sample " << i;
          before = now;
          ++checked;
        }
        slipping_runs += m.outcome_3d().pivot_slip_time > 0.0;
      }
  std::printf("[ measure ] %ld samples, %d of 12 runs slipped\n", checked, slipping_runs);
  EXPECT_GE(slipping_runs, 6);
  EXPECT_GT(checked, 100);
}

// A snapshot taken while the corner slips resumes exactly (save/restore carry the slip's state, its
// direction and its stepper): both copies go on identically, through sticks and landings.
TEST(Rocking3DPivot, ASnapshotMidSlideRockResumesExactly) {
  BaseBodyParameters p = pivot_box(0.5, 0.4, 0.8, 0.1);
  p.centre_of_mass = {0.06, -0.03, 0.8};
  Rocking3DModel a(BaseBody(p), pivot_settings()), b(BaseBody(p), pivot_settings());
  a.reset(0.0);
  b.reset(0.0);
  a.set_vertex_state(0, Eigen::Quaterniond(Eigen::AngleAxisd(0.12, Eigen::Vector3d(1.0, -1.0, 0.0).normalized())),
                     Eigen::Vector3d(0.6, -0.6, 0.7));
  auto input = [](int i) { return Eigen::Vector3d(2.0 * std::sin(0.05 * i), 1.5 * std::cos(0.07 * i), 0.0); };
  int i = 0;
  for (; i < 400 && a.pivot_slip_velocity().norm() == 0.0; ++i) a.step(input(i), 0.005);
  ASSERT_GT(a.pivot_slip_velocity().norm(), 0.0) << "the corner never slipped";
  Rocking3DModel::Saved saved;
  a.save(saved);
  b.restore(saved);
  for (int k = 0; k < 300; ++k, ++i) {
    a.step(input(i), 0.005);
    b.step(input(i), 0.005);
    ASSERT_EQ(a.mode(), b.mode()) << k;
    ASSERT_EQ((a.rotation() - b.rotation()).norm(), 0.0) << k;
    ASSERT_EQ((a.translation() - b.translation()).norm(), 0.0) << k;
    ASSERT_EQ((a.pivot_slip_velocity() - b.pivot_slip_velocity()).norm(), 0.0) << k;
  }
  EXPECT_EQ(a.outcome_3d().pivot_slip_distance, b.outcome_3d().pivot_slip_distance);
  EXPECT_EQ(a.outcome().impacts, b.outcome().impacts);
  std::printf("[ measure ] resumed at sample %d: %ld impacts, %ld sticks, %.4f m slipped after\n", i - 300,
              a.outcome().impacts, a.outcome_3d().pivot_sticks, a.outcome_3d().pivot_slip_distance);
}

}  // namespace
}  // namespace rocking_monitor::core
