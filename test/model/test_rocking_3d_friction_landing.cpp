// Friction at the 3-D model's landings (issue 51 part 3): where the sticking impact needs more than
// mu_s, the frictional plastic impact decides. Against the closed form of the simultaneous law where
// the base lands and slides on; over a whole bidirectional record, the energy law and the counts.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

#include "rocking_monitor/model/contact_model.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/motion/ground_motion.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "test_helpers.hpp"

namespace rocking_monitor::core {
namespace {

SolverSettings landing_settings() {
  SolverSettings s;
  s.method = Method::Dopri5;
  s.model = ModelKind::Nonlinear;
  s.tol = 1e-11;
  return s;
}

// A uniform box: base b x d centred on the origin, height 2h (centre of mass h up).
BaseBodyParameters friction_box(double b, double d, double h, double mu) { return testing::uniform_box(b, d, h, mu, mu); }

// A squat box rocking back onto its base, no shaking, friction 0.1: at the landing the new edge
// cannot take the tangential impulse that rocking on it would need, so the whole base lands and
// slides on, then stops. Closed form of the simultaneous law (both edges on the floor after, the
// rotation stopped by their normal impulses, every contact slipping the same way): the normal impulse
// stops the fall, P_n = |omega| b/2; friction takes mu_k P_n of the horizontal |omega| h; the slide
// then stops after (|omega| (h - mu b/2))^2 / (2 mu g).
// (The box starts a nanoradian above the floor: on the way down a pivot with friction 0.1 would
// slip, slide-rock that the 3-D model does not model.) The planar contact model treats this landing
// in two stages (the corner's impact, then flat without friction), which takes out more: measured
// below, a tenth of this slip.
TEST(FrictionLanding, ASquatBoxThatFrictionCannotTurnSlidesOnAsTheSimultaneousLawSays) {
  const double b = 0.6, d = 0.5, h = 0.3, mu = 0.1, dt = 0.005;
  for (double omega0 : {-0.2, -0.7, -2.0}) {
    Rocking3DModel solid(BaseBody(friction_box(b, d, h, mu)), landing_settings());
    solid.reset(0.0);
    solid.set_edge_state(1, 1e-9, omega0);  // on the edge x = +b/2, about to land
    BodyParameters x;
    x.width = b;
    x.cg_height = h;
    x.mu_s = mu;
    x.mu_k = mu;
    ContactModel planar(x);
    planar.reset(0.0);
    planar.set_state(0.0, 0.0, 0.0, 1, 1e-9, omega0);
    for (int i = 0; i < 600; ++i) {
      solid.step(Eigen::Vector3d::Zero(), dt);
      planar.step(0.0, 0.0, dt);
    }
    const Rocking3DOutcome& o = solid.outcome_3d();
    EXPECT_EQ(o.frictional_landings, 1) << omega0;
    EXPECT_EQ(o.landing_slides, 1) << omega0;
    EXPECT_EQ(o.pivot_slip_landings, 0) << omega0;
    EXPECT_EQ(o.sticks, 1) << omega0;
    EXPECT_EQ(solid.mode(), Mode3D::Rest) << omega0;
    const double v_after = std::abs(omega0) * (h - mu * b / 2);
    const double expected = v_after * v_after / (2 * mu * kGravity);
    std::printf("[ measure ] omega0 %.1f rad/s: slip %.12f m, closed form %.12f m, planar contact model %.6f m\n",
                omega0, solid.slip().x(), -expected, -planar.slip());
    EXPECT_NEAR(solid.slip().x(), -expected, 1e-6 * expected) << omega0;  // towards -x: the way it fell
    EXPECT_NEAR(solid.slip().y(), 0.0, 1e-12);
    EXPECT_LE(solid.outcome_3d().max_slip_speed, v_after) << omega0;  // (at step ends: after the first)
    EXPECT_LE(o.max_impact_energy_ratio, 1.0);
    // The transitions, located and named: the pivot slipping on the way down (rocking on it needs more
    // than mu), the landing (at once) and the stick, v / (mu g) later.
    ASSERT_EQ(solid.transition_records(), 3);
    EXPECT_EQ(solid.transition(0).reason, Transition3D::PivotSlips);
    EXPECT_EQ(o.pivot_slips, 1);
    const Transition3DRecord& land = solid.transition(1);
    const Transition3DRecord& stick = solid.transition(2);
    EXPECT_EQ(land.from, Mode3D::Edge);
    EXPECT_EQ(land.to, Mode3D::Slide);
    EXPECT_EQ(land.reason, Transition3D::LandingSlides);
    EXPECT_LT(land.time, 1e-8);
    EXPECT_EQ(stick.from, Mode3D::Slide);
    EXPECT_EQ(stick.to, Mode3D::Rest);
    EXPECT_EQ(stick.reason, Transition3D::Stick);
    EXPECT_NEAR(stick.time - land.time, v_after / (mu * kGravity), 1e-7) << omega0;  // (measured 2e-8 s)
  }
}

// Kobe Takatori, both horizontal components, on eccentric cabinets that rock and wobble on their
// corners with friction near their tipping slope: landings the sticking law cannot hold are decided
// by friction. Over the whole record every landing keeps the energy law, the frictional ones are
// counted by outcome.
TEST(FrictionLanding, BidirectionalTakatoriOnEccentricCabinets) {
  const std::string dir = std::string(ROCKING_RECORDS_DIR) + "/kobe_1995/";
  if (!std::ifstream(dir + "RSN1120_KOBE_TAK000.AT2").good()) GTEST_SKIP() << "records absent";
  const Component x = read_record(dir + "RSN1120_KOBE_TAK000.AT2").front();
  const Component y = read_record(dir + "RSN1120_KOBE_TAK090.AT2").front();
  const std::size_t n = std::min(x.accel.size(), y.accel.size());
  long frictional = 0, slides = 0, pivots = 0, unresolved = 0, landings = 0;
  for (double ecc : {0.0, 0.08}) {
    for (double mu : {0.3, 0.45, 0.6}) {
      BaseBodyParameters p = friction_box(0.5, 0.4, 0.7, mu);
      p.centre_of_mass = {ecc, 0.5 * ecc, 0.7};
      Rocking3DModel m(BaseBody(p), landing_settings());
      m.reset(0.0);
      for (std::size_t i = 0; i < n && m.mode() != Mode3D::Overturned; ++i)
        m.step(Eigen::Vector3d(x.accel[i], y.accel[i], 0.0), x.dt);
      const Rocking3DOutcome& o = m.outcome_3d();
      std::printf("[ measure ] ecc %.2f mu %.2f: %s, %ld impacts, demand up to %.3f, %ld frictional (%ld slid on, %ld "
                  "pivot slips, %ld unresolved), %ld slides, max slip %.3f m\n",
                  ecc, mu, m.outcome().overturned ? "OVERTURNED" : "survived", m.outcome().impacts,
                  o.max_friction_demand, o.frictional_landings, o.landing_slides, o.pivot_slip_landings,
                  o.unresolved_landings, o.slides, o.max_slip);
      EXPECT_LE(o.max_impact_energy_ratio, 1.0 + 1e-12);
      EXPECT_EQ(o.frictional_landings >= o.landing_slides + o.pivot_slip_landings, true);
      frictional += o.frictional_landings;
      slides += o.landing_slides;
      pivots += o.pivot_slip_landings;
      unresolved += o.unresolved_landings;
      landings += m.outcome().impacts;
    }
  }
  std::printf("[ measure ] %ld landings, %ld decided by friction: %ld slid on flat, %ld with a slipping pivot, %ld "
              "unresolved\n", landings, frictional, slides, pivots, unresolved);
  // Measured: 256 landings, 157 decided by friction (demand up to 31, on corners): 2 slid on flat, 155
  // with a slipping pivot (the sticking answer followed after the landing; a vertex then slide-rocks
  // where its reaction leaves the cone), 0 unresolved. (Before slide-rock on vertices: 192 landings, 96
  // by friction: a slipping corner lands more often, at lower speeds.)
  EXPECT_GT(frictional, 50);
  EXPECT_GT(slides, 0);
  EXPECT_LE(unresolved, frictional / 20);
}

// Every mode change of a 3-D run is recorded, in order, each from the mode the previous one went to,
// and the records add up to the outcome's counters: a centred and an eccentric cabinet with friction
// under a one-sine pulse along a diagonal (rocking, corner wobble, landings, slides, overturn).
TEST(FrictionLanding, EveryTransitionIsRecordedInOrderWithItsReason) {
  int runs_with_slip = 0, runs_with_wobble = 0, runs_with_pivot_slip = 0, complete = 0;
  for (double ecc : {0.0, 0.1}) {
    for (double ap : {0.35, 0.5, 0.8}) {
      BaseBodyParameters p = friction_box(0.5, 0.4, 0.7, 0.4);
      p.centre_of_mass = {ecc, 0.3 * ecc, 0.7};
      Rocking3DModel m(BaseBody(p), landing_settings());
      m.reset(0.0);
      const GroundMotion g = testing::one_sine_pulse(ap * kGravity, 2 * kPi * 2.0, 0.005, 3.0);
      for (double a : g.horizontal) {
        m.step(Eigen::Vector3d(a * 0.8, a * 0.6, 0.0), g.dt);
        if (m.mode() == Mode3D::Overturned) break;
      }
      const Rocking3DOutcome& o = m.outcome_3d();
      const bool all_kept = o.transitions <= Rocking3DModel::kMaxTransitionRecords;
      ASSERT_EQ(m.transition_records(), std::min<long>(o.transitions, Rocking3DModel::kMaxTransitionRecords));
      long counts[32] = {};  // (more than the reasons)
      Mode3D mode = Mode3D::Rest;
      double t = 0.0;
      for (int i = 0; i < m.transition_records(); ++i) {
        const Transition3DRecord& r = m.transition(i);
        EXPECT_EQ(r.from, mode) << i;
        EXPECT_GE(r.time, t) << i;
        mode = r.to;
        t = r.time;
        ++counts[static_cast<int>(r.reason)];
      }
      std::printf("[ measure ] ecc %.1f, %.2f g: %ld transitions, %s\n", ecc, ap, o.transitions,
                  m.outcome().overturned ? "overturned" : "survived");
      if (!all_kept) continue;  // (the first 64 kept: their order checked above)
      ++complete;
      EXPECT_EQ(mode, m.mode());
      auto n = [&](Transition3D r) { return counts[static_cast<int>(r)]; };
      EXPECT_EQ(n(Transition3D::SlipOnset), o.slides);
      EXPECT_EQ(n(Transition3D::Stick), o.sticks);
      EXPECT_EQ(n(Transition3D::EdgeToVertex), o.edge_to_vertex);
      EXPECT_EQ(n(Transition3D::LandingSlides), o.landing_slides);
      EXPECT_EQ(n(Transition3D::LandingPivotSlips), o.pivot_slip_landings);
      EXPECT_EQ(n(Transition3D::PivotSlips), o.pivot_slips);
      EXPECT_EQ(n(Transition3D::PivotLifts), o.pivot_lifts);
      EXPECT_EQ(n(Transition3D::LiftOff), o.flights);
      EXPECT_EQ(n(Transition3D::LandingCornerSlips), o.corner_slip_landings);
      EXPECT_EQ(n(Transition3D::Landing) + n(Transition3D::LandingSlides) + n(Transition3D::LandingPivotSlips) +
                    n(Transition3D::RestCapture) + n(Transition3D::LandingCornerSlips),
                m.outcome().impacts);
      EXPECT_EQ(n(Transition3D::Overturn) + n(Transition3D::FellOffSupport), m.outcome().overturned ? 1 : 0);
      if (m.outcome().overturned) EXPECT_EQ(t, m.outcome().overturn_time);
      runs_with_slip += o.slides > 0;
      runs_with_wobble += o.edge_to_vertex > 0;
      runs_with_pivot_slip += o.pivot_slips > 0;
    }
  }
  EXPECT_GE(complete, 4);
  EXPECT_GT(runs_with_slip, 0);
  EXPECT_GT(runs_with_wobble, 0);
  EXPECT_GT(runs_with_pivot_slip, 0);
}

}  // namespace
}  // namespace rocking_monitor::core
