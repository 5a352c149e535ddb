// PlaneMonitor (one rocking plane of the live node's per-item engine) against the models it wraps
// and an independent running intensity.
#include <gtest/gtest.h>

#include <cmath>

#include "rocking_monitor/monitoring/plane_monitor.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "rocking_monitor/monitoring/simulation.hpp"

namespace rocking_monitor::core {
namespace {

const std::string kPulse = std::string(ROCKING_SOURCE_DIR) + "/bags/one_sine_pulse.csv";

struct Spec {
  BodyParameters body;
};

Spec spec(double b, double h, double mu = std::numeric_limits<double>::infinity()) {
  Spec s;
  s.body.width = b;
  s.body.cg_height = h;
  s.body.mu_s = mu;
  return s;
}

TEST(PlaneMonitor, AlarmsEqualTheRockingModelAndScreeningFollowsTheRunningIntensity) {
  const Component c = read_record(kPulse).front();
  const Spec s = spec(0.15, 0.35);
  PlaneMonitor::Options rocking;
  rocking.fidelity = Fidelity::Rocking;
  PlaneMonitor im(s.body, rocking);
  im.start(0.0, c.accel[0], 0.0, c.dt);
  // Independent running PGA / PGV / PSV at the Housner period.
  StreamingIntensityConfig cfg;
  cfg.dt = c.dt;
  cfg.periods = {housner_period(Body(s.body))};
  cfg.velocity_highpass_hz = 0.05;
  StreamingIntensity ref(cfg);
  ref.push(c.accel[0]);
  const ScreeningThresholds th = screening_thresholds(Body(s.body));
  std::vector<AlarmEvent> alarms;
  bool ishiyama = false;
  for (std::size_t i = 1; i < c.accel.size(); ++i) {
    const PlaneEvents& ev = im.step(c.accel[i], 0.0, c.dt);
    ref.push(c.accel[i]);
    for (int k = 0; k < ev.alarm_count; ++k) alarms.push_back(ev.alarms[k]);
    for (int k = 0; k < ev.change_count; ++k) {
      if (ev.changes[k].id != CriterionId::Ishiyama) continue;
      EXPECT_FALSE(ishiyama) << "a running criterion is exceeded once";
      ishiyama = true;
      // It flips exactly at the first sample where both conditions of eq. 2 hold.
      EXPECT_GT(ref.pgv(), th.ishiyama.velocity);
      EXPECT_GE(ref.pga(), th.ishiyama.acceleration);
      EXPECT_DOUBLE_EQ(ev.changes[k].value, ref.pgv());
      EXPECT_DOUBLE_EQ(ev.changes[k].second_value, ref.pga());
    }
  }
  EXPECT_TRUE(ishiyama);
  const SimulationResult off = simulate(Body(s.body), SolverSettings{}, make_ground_motion(c, nullptr, 1.0));
  ASSERT_TRUE(off.outcome.overturned);
  ASSERT_EQ(alarms.size(), 3u);
  EXPECT_EQ(alarms.back().level, ItemMode::Overturned);
  EXPECT_DOUBLE_EQ(alarms.back().time, off.outcome.overturn_time);
  EXPECT_EQ(im.mode(), ItemMode::Overturned);
}

TEST(PlaneMonitor, AdaptiveIsTheDefaultFidelity) {
  EXPECT_EQ(PlaneMonitor::Options{}.fidelity, Fidelity::Adaptive);
  PlaneMonitor im(spec(0.5, 0.9, 0.6).body, PlaneMonitor::Options{});
  EXPECT_NE(im.adaptive(), nullptr);
  // Without mu_s the body is the paper's pure-rocking body, run as such (violations flagged).
  PlaneMonitor pure(spec(0.5, 0.9).body, PlaneMonitor::Options{});
  EXPECT_EQ(pure.adaptive(), nullptr);
}

TEST(PlaneMonitor, AdaptiveFidelityModelsSlidingAndMatchesTheAdaptiveModel) {
  const Component c = read_record(kPulse).front();
  const Spec s = spec(0.55, 0.75, 0.3);  // mu_s < tan(alpha) = 0.37: slides before it rocks
  PlaneMonitor::Options o;
  o.fidelity = Fidelity::Adaptive;
  PlaneMonitor im(s.body, o);
  AdaptiveModel direct(Body(s.body), AdaptiveSettings{});
  im.start(0.0, c.accel[0], 0.0, c.dt);
  direct.reset(0.0, c.accel[0], 0.0);
  bool slid = false;
  double max_slip = 0.0;
  int slide_changes = 0;
  bool slide_exceeded = false;
  for (std::size_t i = 1; i < c.accel.size(); ++i) {
    const PlaneEvents& ev = im.step(c.accel[i], 0.0, c.dt);
    direct.step(c.accel[i], 0.0, c.dt);
    ASSERT_EQ(im.theta(), direct.theta());
    ASSERT_EQ(im.slip(), direct.slip());
    slid |= im.contact_mode() == ContactMode::Slide;
    max_slip = std::max(max_slip, std::abs(im.slip()));
    EXPECT_EQ(im.violations(), 0) << "sliding is modelled, not flagged";
    for (int k = 0; k < ev.change_count; ++k) {
      if (ev.changes[k].id != CriterionId::SlideFromRest) continue;
      // Reported when the model switches: up to the contact model, and back down once at rest.
      EXPECT_NE(ev.changes[k].exceeded, slide_exceeded);
      slide_exceeded = ev.changes[k].exceeded;
      EXPECT_EQ(slide_exceeded, std::string(im.active_model()) == "contact");
      ++slide_changes;
    }
  }
  EXPECT_TRUE(slid);
  EXPECT_EQ(slide_changes, 2);  // slide from rest at 0.08 s, back to the rocking model at rest later
  EXPECT_GT(max_slip, 5e-3);  // about 12 mm out and back under the full sine
  EXPECT_EQ(im.impacts(), direct.outcome().impacts);
}

}  // namespace
}  // namespace rocking_monitor::core
