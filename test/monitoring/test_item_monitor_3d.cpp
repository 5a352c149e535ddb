// ItemMonitor with a 3-D description (ItemSpec::solid): which model decides (SolidChoice), and the
// live monitor's 3-D answer equals the 3-D model run alone (live == offline).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/monitoring/item_monitor.hpp"

namespace rocking_monitor::core {
namespace {

ItemSpec box_item(double b, double d, double h) {
  ItemSpec s;
  s.id = "cabinet";
  s.sensor = "floor";
  s.frame = "cabinet";
  s.body.width = b;
  s.body.cg_height = h;
  s.depth.depth = d;
  s.solid = box_base_body(s.body, d, 0.5, std::nan(""));
  return s;
}

struct Input {
  std::vector<Eigen::Vector3d> a;
  double dt = 0.01;
};

// A 1 Hz sine pulse of amplitude amp (m/s^2) along direction (cx, cy), then 6 s at rest.
Input pulse(double amp, double cx, double cy) {
  Input in;
  for (double t = 0.0; t < 7.0; t += in.dt) {
    const double s = t < 1.0 ? std::sin(2.0 * kPi * t) : 0.0;
    in.a.emplace_back(amp * cx * s, amp * cy * s, 0.0);
  }
  return in;
}

std::vector<AlarmEvent> run(ItemMonitor& im, const Input& in) {
  std::vector<AlarmEvent> alarms;
  im.start(0.0, in.a[0].x(), in.a[0].y(), in.a[0].z(), in.dt);
  for (std::size_t i = 1; i < in.a.size(); ++i) {
    const ItemEvents& ev = im.step(in.a[i].x(), in.a[i].y(), in.a[i].z(), in.dt);
    for (int k = 0; k < ev.alarm_count; ++k) alarms.push_back(ev.alarms[k]);
  }
  return alarms;
}

TEST(ItemMonitor3D, AutoKeepsThePlanarPairForARectangleUnderOneComponent) {
  ItemMonitor im(box_item(0.4, 0.3, 0.6), ItemMonitor::Options{});
  ASSERT_NE(im.solid(), nullptr);
  run(im, pulse(0.45 * kGravity, 1.0, 0.0));
  EXPECT_FALSE(im.solid_active());
  EXPECT_GT(im.plane(Plane::X).impacts(), 0);  // it rocked, in the planar pair
}

// Bidirectional shaking: the 3-D model takes over, and the item's alarms are the 3-D model's own,
// sample for sample.
TEST(ItemMonitor3D, BidirectionalShakingHandsTheItemToThe3DModelWhichDecidesItsAlarms) {
  const ItemSpec spec = box_item(0.4, 0.3, 0.7);
  const Input in = pulse(0.6 * kGravity, std::sqrt(0.5), std::sqrt(0.5));
  ItemMonitor im(spec, ItemMonitor::Options{});
  const std::vector<AlarmEvent> alarms = run(im, in);
  ASSERT_TRUE(im.solid_active());
  SolverSettings s;
  Rocking3DModel alone(BaseBody(*spec.solid), s);
  alone.reset(0.0, in.a[0]);
  for (std::size_t i = 1; i < in.a.size(); ++i) alone.step(in.a[i], in.dt);
  const RockingOutcome& o = alone.outcome();
  ASSERT_TRUE(o.overturned);  // the case is one that reaches every level
  ASSERT_EQ(alarms.size(), 3u);
  // each level once, at the 3-D model's own time (on a corner COMMITTED may come before BEYOND_TIPPING)
  auto time_of = [&](ItemMode level) {
    double t = std::nan("");
    for (const AlarmEvent& a : alarms)
      if (a.level == level) t = a.time;
    return t;
  };
  EXPECT_NEAR(time_of(ItemMode::BeyondTipping), o.beyond_tipping_time, 1e-9);
  EXPECT_NEAR(time_of(ItemMode::Committed), o.committed_time, 1e-9);
  EXPECT_NEAR(time_of(ItemMode::Overturned), o.overturn_time, 1e-9);
  EXPECT_EQ(alarms[2].level, ItemMode::Overturned);
  EXPECT_LT(o.committed_time, o.overturn_time) << "the COMMITTED alarm gives lead time";
  EXPECT_EQ(im.mode(), ItemMode::Overturned);
  EXPECT_EQ(im.solid()->outcome().impacts, o.impacts);
}

TEST(ItemMonitor3D, AnIrregularBaseAlwaysRunsThe3DModelAndPlanarOnlyNever) {
  ItemSpec spec = box_item(0.4, 0.3, 0.6);
  spec.solid->base = {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.4, 0.05), Eigen::Vector2d(0.35, 0.3),
                      Eigen::Vector2d(0.02, 0.28)};
  ItemMonitor im(spec, ItemMonitor::Options{});
  im.start(0.0, 0.0, 0.0, 0.0, 0.01);
  EXPECT_TRUE(im.solid_active());
  ItemMonitor::Options planar;
  planar.solid = SolidChoice::Planar;
  ItemMonitor only_planar(spec, planar);
  EXPECT_EQ(only_planar.solid(), nullptr);
  ItemMonitor::Options solid;
  solid.solid = SolidChoice::Solid;
  ItemMonitor rect(box_item(0.4, 0.3, 0.6), solid);
  rect.start(0.0, 0.0, 0.0, 0.0, 0.01);
  EXPECT_TRUE(rect.solid_active());
}

// A cabinet (base 0.6 x 0.5 m, centre of mass 0.35 m high, mu_s 0.3: it slides rather than rocks) on
// a plinth 0.4 m beyond its centre of mass towards +x, 0.5 m towards -x (issue 51, docs/rocking_3d.md).
// The item's frame has its origin below the centre of mass (as Rocking3DSupport's box).
ItemSpec plinth_cabinet() {
  ItemSpec spec = box_item(0.6, 0.5, 0.35);
  spec.id = "cabinet_on_plinth";
  BaseBodyParameters& p = *spec.solid;
  p.centre_of_mass = {0.0, 0.0, 0.35};
  p.base = {{-0.3, -0.25}, {0.3, -0.25}, {0.3, 0.25}, {-0.3, 0.25}};
  p.central_inertia = Eigen::Vector3d((0.25 + 4 * 0.1225) / 12, (0.36 + 4 * 0.1225) / 12, (0.36 + 0.25) / 12).asDiagonal();
  p.mu_s = 0.3;
  p.support = {{-0.5, -0.4}, {0.4, -0.4}, {0.4, 0.4}, {-0.5, 0.4}};
  return spec;
}

// A 0.5 Hz sine pulse along x of amplitude amp (m/s^2), then 4 s at rest.
Input slow_pulse(double amp) {
  Input in;
  for (double t = 0.0; t < 6.0; t += in.dt) in.a.emplace_back(t < 2.0 ? -amp * std::sin(kPi * t) : 0.0, 0.0, 0.0);
  return in;
}

// It slides off the plinth: COMMITTED and OVERTURNED alarms whose cause says so, at the instant the 3-D model run
// alone locates the fall (that instant is checked against an exact 1-D slider in
// Rocking3DSupport.ABoxOnAPlinthFallsOffWhenItsSlipReachesTheEdge). A weaker pulse slides it less than
// the 0.4 m to the edge: no alarm, and its support margin says how far it stayed from the edge.
TEST(ItemMonitor3D, AnItemThatSlidesOffItsPlinthIsAlarmedOverturnedBecauseItFellOffItsSupport) {
  const ItemSpec spec = plinth_cabinet();
  ItemMonitor::Options solid;
  solid.solid = SolidChoice::Solid;
  const Input strong = slow_pulse(0.8 * kGravity);
  ItemMonitor im(spec, solid);
  const std::vector<AlarmEvent> alarms = run(im, strong);
  Rocking3DModel alone(BaseBody(*spec.solid), SolverSettings{});
  alone.reset(0.0, strong.a[0]);
  for (std::size_t i = 1; i < strong.a.size(); ++i) alone.step(strong.a[i], strong.dt);
  ASSERT_TRUE(alone.outcome_3d().fell_off_support) << "the case is one that slides off";
  // sliding is no tipping level: no BEYOND_TIPPING; COMMITTED and OVERTURNED at the fall
  ASSERT_EQ(alarms.size(), 2u);
  EXPECT_EQ(alarms[0].level, ItemMode::Committed);
  EXPECT_EQ(alarms[1].level, ItemMode::Overturned);
  for (const AlarmEvent& a : alarms) {
    EXPECT_EQ(a.cause, AlarmCause::FellOffSupport);
    EXPECT_NEAR(a.time, alone.outcome_3d().fell_off_time, 1e-9);
  }
  EXPECT_STREQ(to_string(alarms[1].cause), "fell_off_support");
  EXPECT_EQ(im.mode(), ItemMode::Overturned);
  EXPECT_NEAR(im.solid()->support_margin(), 0.0, 1e-9);  // on the edge when it went over

  ItemMonitor weak(spec, solid);
  EXPECT_TRUE(run(weak, slow_pulse(0.35 * kGravity)).empty());
  EXPECT_GT(weak.solid()->outcome_3d().max_slip, 0.0) << "it slid";
  EXPECT_LT(weak.solid()->outcome_3d().max_slip, 0.4) << "never as far as the edge";
  EXPECT_GT(weak.solid()->support_margin(), 0.0);
}

// Supports are known to the 3-D model only: the monitor runs it for an item on a support whatever the
// shaking (auto would keep the planar pair of a rectangle under one component, which knows no edge).
TEST(ItemMonitor3D, AutoRunsThe3DModelForAnItemOnASupport) {
  ItemMonitor im(plinth_cabinet(), ItemMonitor::Options{});
  const std::vector<AlarmEvent> alarms = run(im, slow_pulse(0.8 * kGravity));
  EXPECT_TRUE(im.solid_active());
  ASSERT_EQ(alarms.size(), 2u);
  EXPECT_EQ(alarms[1].level, ItemMode::Overturned);
  EXPECT_EQ(alarms[1].cause, AlarmCause::FellOffSupport);
}

// Without a support the same kind of item that overturns by rocking says so: cause rocking at every
// level (the bidirectional case above, the 3-D model deciding, and the planar pair).
TEST(ItemMonitor3D, AnItemThatOverturnsByRockingHasNoSupportCause) {
  for (SolidChoice choice : {SolidChoice::Solid, SolidChoice::Planar}) {
    ItemMonitor::Options o;
    o.solid = choice;
    ItemMonitor im(box_item(0.4, 0.3, 0.7), o);
    const std::vector<AlarmEvent> alarms = run(im, pulse(0.6 * kGravity, std::sqrt(0.5), std::sqrt(0.5)));
    ASSERT_EQ(im.mode(), ItemMode::Overturned) << to_string(choice);
    ASSERT_FALSE(alarms.empty());
    EXPECT_EQ(alarms.back().level, ItemMode::Overturned);
    for (const AlarmEvent& a : alarms) EXPECT_EQ(a.cause, AlarmCause::Rocking) << to_string(choice);
  }
}

}  // namespace
}  // namespace rocking_monitor::core
