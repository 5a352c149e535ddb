// ItemMonitor: an item rocking in its two principal planes (planar decomposition). Oracles: a plane
// run alone (PlaneMonitor), symmetry of the planes, a 90 degree yaw of the item, and combine().
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/monitoring/item_monitor.hpp"
#include "rocking_monitor/physics/item_verdict.hpp"
#include "rocking_monitor/motion/record_reader.hpp"

namespace rocking_monitor::core {
namespace {

const std::string kPulseCsv = std::string(ROCKING_SOURCE_DIR) + "/bags/one_sine_pulse.csv";

ItemSpec item(double width, double depth, double h, double nu = 0.5, double nu_y = 0.5) {
  ItemSpec s;
  s.id = "item";
  s.sensor = "floor";
  s.frame = "item";
  s.body.width = width;
  s.body.cg_height = h;
  s.body.nu1 = nu;
  s.body.mu_s = 0.8;  // adaptive fidelity: friction high enough that these items rock
  if (depth > 0.0) {
    s.depth.depth = depth;
    s.depth.eccentricity_y = nu_y;
  }
  return s;
}

std::vector<double> pulse() { return read_record(kPulseCsv).front().accel; }
double pulse_dt() { return read_record(kPulseCsv).front().dt; }

struct Track {
  std::vector<double> theta[kPlaneCount];
  std::vector<AlarmEvent> alarms;
};

// Runs the item over (ax[i], ay[i], 0) and records each plane's theta after every sample.
Track run(ItemMonitor& im, const std::vector<double>& ax, const std::vector<double>& ay, double dt) {
  Track t;
  im.start(0.0, ax[0], ay[0], 0.0, dt);
  for (std::size_t i = 1; i < ax.size(); ++i) {
    const ItemEvents& ev = im.step(ax[i], ay[i], 0.0, dt);
    for (int k = 0; k < ev.alarm_count; ++k) t.alarms.push_back(ev.alarms[k]);
    for (int p = 0; p < im.plane_count(); ++p) t.theta[p].push_back(im.plane(static_cast<Plane>(p)).theta());
  }
  return t;
}

// One plane alone: theta after every sample and when each level was reached.
std::vector<double> run_plane(const BodyParameters& b, const std::vector<double>& a, double dt, LevelTimes* levels) {
  PlaneMonitor pm(b, PlaneMonitor::Options{});
  pm.start(0.0, a[0], 0.0, dt);
  std::vector<double> theta;
  for (std::size_t i = 1; i < a.size(); ++i) {
    const PlaneEvents& ev = pm.step(a[i], 0.0, dt);
    for (int k = 0; k < ev.alarm_count; ++k)
      levels->time[static_cast<int>(ev.alarms[k].level) - 2] = ev.alarms[k].time;
    theta.push_back(pm.theta());
  }
  return theta;
}

TEST(ItemMonitor, WithoutDepthItIsTheSinglePlaneMonitor) {
  const std::vector<double> a = pulse(), zero(a.size(), 0.0);
  ItemMonitor im(item(0.15, 0.0, 0.35), ItemMonitor::Options{});
  EXPECT_FALSE(im.two_planes());
  const Track t = run(im, a, zero, pulse_dt());
  LevelTimes alone;
  const std::vector<double> theta = run_plane(item(0.15, 0.0, 0.35).body, a, pulse_dt(), &alone);
  EXPECT_EQ(t.theta[0], theta);
  ASSERT_EQ(t.alarms.size(), 3u);
  for (const AlarmEvent& e : t.alarms) {
    EXPECT_EQ(e.plane, Plane::X);
    EXPECT_EQ(e.time, alone.at(static_cast<Level>(static_cast<int>(e.level) - 2)));
  }
}

TEST(ItemMonitor, MotionAlongYTipsOnlyTheYPlane) {
  const std::vector<double> a = pulse(), zero(a.size(), 0.0);
  const ItemSpec s = item(0.60, 0.15, 0.35);  // wide along x, slender along y
  ItemMonitor im(s, ItemMonitor::Options{});
  ASSERT_TRUE(im.two_planes());
  const Track t = run(im, zero, a, pulse_dt());
  for (double th : t.theta[0]) ASSERT_EQ(th, 0.0) << "no x motion: the x plane never uplifts";
  EXPECT_EQ(im.plane(Plane::X).mode(), ItemMode::Rest);
  EXPECT_EQ(im.plane(Plane::X).impacts(), 0);
  LevelTimes alone;
  EXPECT_EQ(t.theta[1], run_plane(y_plane_body(s.body, s.depth), a, pulse_dt(), &alone));
  ASSERT_TRUE(alone.reached(Level::Overturned));
  ASSERT_EQ(t.alarms.size(), 3u);
  for (const AlarmEvent& e : t.alarms) EXPECT_EQ(e.plane, Plane::Y);
  EXPECT_EQ(im.mode(), ItemMode::Overturned);
  EXPECT_EQ(im.worst_plane(), Plane::Y);
}

TEST(ItemMonitor, SquareSymmetricItemAt45DegreesRocksAlikeInBothPlanesAsASinglePlaneUnderAOverSqrt2) {
  const std::vector<double> a = pulse();
  const double az = 45.0 * kPi / 180.0;
  std::vector<double> ax(a.size()), ay(a.size()), reduced(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ax[i] = a[i] * std::cos(az);
    ay[i] = a[i] * std::sin(az);
    reduced[i] = a[i] / std::sqrt(2.0);
  }
  const ItemSpec s = item(0.20, 0.20, 0.45);
  ItemMonitor im(s, ItemMonitor::Options{});
  const Track t = run(im, ax, ay, pulse_dt());
  LevelTimes alone;
  const std::vector<double> single = run_plane(s.body, reduced, pulse_dt(), &alone);
  double max_theta = 0.0;
  for (std::size_t i = 0; i < single.size(); ++i) {
    ASSERT_NEAR(t.theta[0][i], t.theta[1][i], 1e-12) << "sample " << i;
    ASSERT_NEAR(t.theta[0][i], single[i], 1e-12) << "sample " << i;
    max_theta = std::max(max_theta, std::abs(single[i]));
  }
  EXPECT_GT(max_theta, 0.05) << "the case must rock, or the test proves nothing";
}

TEST(ItemMonitor, SwappingWidthAndDepthWithA90DegreeYawSwapsThePlanes) {
  const std::vector<double> a = pulse();
  // Ground motion at azimuth 30 deg in the frame of item A.
  std::vector<double> ax(a.size()), ay(a.size());
  const double az = 30.0 * kPi / 180.0;
  for (std::size_t i = 0; i < a.size(); ++i) { ax[i] = a[i] * std::cos(az); ay[i] = a[i] * std::sin(az); }
  const ItemSpec sa = item(0.20, 0.14, 0.40, 0.40, 0.35);
  // B is A yawed by +90 deg: x_B = y_A, y_B = -x_A. Its width lies along y_A, its depth along x_A,
  // and its -y corner is A's +x corner, so eccentricity_y_B = 1 - eccentricity_A.
  const ItemSpec sb = item(0.14, 0.20, 0.40, 0.35, 1.0 - 0.40);
  const Eigen::Matrix3d b_from_a = Eigen::AngleAxisd(kPi / 2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix().transpose();
  std::vector<double> bx(a.size()), by(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Eigen::Vector3d v = b_from_a * Eigen::Vector3d(ax[i], ay[i], 0.0);
    bx[i] = v.x();
    by[i] = v.y();
  }
  ItemMonitor ia(sa, ItemMonitor::Options{}), ib(sb, ItemMonitor::Options{});
  const Track ta = run(ia, ax, ay, pulse_dt()), tb = run(ib, bx, by, pulse_dt());
  double max_theta = 0.0;
  for (std::size_t i = 0; i < ta.theta[0].size(); ++i) {
    ASSERT_NEAR(tb.theta[0][i], ta.theta[1][i], 1e-12) << "sample " << i;
    ASSERT_NEAR(tb.theta[1][i], -ta.theta[0][i], 1e-12) << "mirrored: sample " << i;
    max_theta = std::max({max_theta, std::abs(ta.theta[0][i]), std::abs(ta.theta[1][i])});
  }
  EXPECT_GT(max_theta, 0.05);
  ASSERT_EQ(ta.alarms.size(), tb.alarms.size());
  for (std::size_t k = 0; k < ta.alarms.size(); ++k) {
    EXPECT_EQ(ta.alarms[k].level, tb.alarms[k].level);
    EXPECT_NE(ta.alarms[k].plane, tb.alarms[k].plane);
    EXPECT_NEAR(ta.alarms[k].time, tb.alarms[k].time, 1e-12);
  }
}

TEST(ItemMonitor, ItemAlarmsAreTheEarliestPlaneOfEachLevel) {
  // The same pulse along both axes: both planes overturn, the more slender y plane first.
  const std::vector<double> a = pulse();
  // Pure rocking (no friction given): with friction the pair shares one budget (friction_share.hpp)
  // and is no longer two independent planes.
  ItemSpec s = item(0.22, 0.17, 0.35);
  s.body.mu_s = std::numeric_limits<double>::infinity();
  ItemMonitor im(s, ItemMonitor::Options{});
  const Track t = run(im, a, a, pulse_dt());
  LevelTimes x, y;
  run_plane(s.body, a, pulse_dt(), &x);
  run_plane(y_plane_body(s.body, s.depth), a, pulse_dt(), &y);
  ASSERT_TRUE(x.reached(Level::Overturned) && y.reached(Level::Overturned));
  const ItemVerdict v = combine(x, &y);
  ASSERT_EQ(t.alarms.size(), 3u) << "each level once per item, not once per plane";
  for (const AlarmEvent& e : t.alarms) {
    const Level l = static_cast<Level>(static_cast<int>(e.level) - 2);
    EXPECT_EQ(e.time, v.levels.at(l));
    EXPECT_EQ(e.plane, v.plane[static_cast<int>(l)]);
  }
  EXPECT_EQ(t.alarms.back().plane, Plane::Y);
  EXPECT_LT(y.at(Level::Overturned), x.at(Level::Overturned));
}

TEST(ItemMonitor, BadDepthFieldsNameTheItemAndTheField) {
  struct Case { double depth, nu_y, ig_y; const char* field; };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Case& c : {Case{-0.4, 0.5, nan, "depth"}, Case{0.0, 0.5, nan, "depth"},
                        Case{std::numeric_limits<double>::infinity(), 0.5, nan, "depth"},
                        Case{0.4, 0.0, nan, "eccentricity_y"}, Case{0.4, 1.0, nan, "eccentricity_y"},
                        Case{0.4, nan, nan, "eccentricity_y"}, Case{0.4, 0.5, -1.0, "radius_of_gyration_y"}}) {
    ItemSpec s = item(0.5, 0.4, 0.9);
    s.id = "cabinet";
    s.depth.depth = c.depth;
    s.depth.eccentricity_y = c.nu_y;
    s.depth.radius_of_gyration_y = c.ig_y;
    const std::string e = validate(s);
    EXPECT_EQ(e.rfind("item 'cabinet': ", 0), 0u) << e;
    EXPECT_NE(e.find(std::string(c.field) + " = "), std::string::npos) << e;
    EXPECT_THROW(ItemMonitor(s, ItemMonitor::Options{}), std::invalid_argument);
  }
}

TEST(ItemMonitor, YPlaneRadiusOfGyrationFollowsThePlanUniformRule) {
  BodyParameters x;
  x.width = 0.6;
  x.cg_height = 0.95;
  DepthParameters d;
  d.depth = 1.0;
  // Homogeneous box: both planes homogeneous, the y plane with the depth.
  EXPECT_DOUBLE_EQ(Body(y_plane_body(x, d)).radius_of_gyration(), Body::homogeneous_radius_of_gyration(1.0, 0.95));
  // A given i_x keeps its height distribution: i_y^2 - i_x^2 = (D^2 - B^2) / 12 (exact for a box).
  x.radius_of_gyration = Body::homogeneous_radius_of_gyration(0.6, 0.95);
  EXPECT_NEAR(y_plane_body(x, d).radius_of_gyration, Body::homogeneous_radius_of_gyration(1.0, 0.95), 1e-15);
  x.radius_of_gyration = 0.6;
  EXPECT_NEAR(std::pow(y_plane_body(x, d).radius_of_gyration, 2) - 0.36, (1.0 - 0.36) / 12.0, 1e-15);
  d.radius_of_gyration_y = 0.7;
  EXPECT_EQ(y_plane_body(x, d).radius_of_gyration, 0.7);
}

// Issue 19: a level already alarmed before a restart (in the journal) is not alarmed again, also
// across start(); the other levels alarm at the same times as without the mark.
TEST(ItemMonitor, MarkedLevelIsNotAlarmedAgainButOthersAre) {
  const std::vector<double> a = pulse(), zero(a.size(), 0.0);
  ItemMonitor plain(item(0.15, 0.0, 0.35), ItemMonitor::Options{});
  const Track all = run(plain, a, zero, pulse_dt());
  ASSERT_EQ(all.alarms.size(), 3u);
  ItemMonitor marked(item(0.15, 0.0, 0.35), ItemMonitor::Options{});
  marked.mark_alarmed(ItemMode::Overturned);
  EXPECT_TRUE(marked.alarmed(ItemMode::Overturned));
  EXPECT_FALSE(marked.alarmed(ItemMode::Committed));
  const Track t = run(marked, a, zero, pulse_dt());  // run() calls start(): the mark survives it
  // The unmarked levels (COMMITTED may come before BEYOND_TIPPING), at the same times.
  std::vector<std::pair<ItemMode, double>> expected, got;
  for (const AlarmEvent& e : all.alarms)
    if (e.level != ItemMode::Overturned) expected.emplace_back(e.level, e.time);
  for (const AlarmEvent& e : t.alarms) got.emplace_back(e.level, e.time);
  ASSERT_EQ(expected.size(), 2u);
  EXPECT_EQ(got, expected);
  EXPECT_EQ(marked.mode(), ItemMode::Overturned);  // the state is not changed by the mark
  // A second run on the same monitor (a timing restart): the levels alarmed by the first run alarm
  // again (start re-arms them), the marked one never does.
  const Track again = run(marked, a, zero, pulse_dt());
  EXPECT_EQ(again.alarms.size(), 2u);
  EXPECT_THROW(marked.mark_alarmed(ItemMode::Rocking), std::invalid_argument);
}

// Contact fidelity without a friction coefficient (mu_s not given: no friction limit) must never slip:
// the no-slip constraint holds to rounding in every sample. Found by the MonitorBatch block test: a
// landing with a leftover horizontal velocity entered the Slide phase with mu_k = inf, and the slip
// ran to infinity (this body on Kobe Takatori at 0.5 g-scale with vertical input: at 2.42 s).
TEST(ItemMonitor, ContactModelWithoutAFrictionLimitNeverSlips) {
  const Component rec =
      read_record(std::string(ROCKING_RECORDS_DIR) + "/kobe_1995/RSN1120_KOBE_TAK090.AT2").front();
  const std::vector<double>& a = rec.accel;
  const std::size_t m = a.size();
  ItemSpec s = item(0.293848, 0.765748, 0.510499, 0.478914);
  s.body.mu_s = std::numeric_limits<double>::infinity();
  ItemMonitor::Options o;
  o.fidelity = Fidelity::Contact;
  for (double scale : {0.5, 0.8, 1.0}) {
    ItemMonitor it(s, o);
    it.start(0.0, scale * a[0], 0.7 * scale * a[m - 1], 0.3 * scale * a[0], rec.dt);
    std::size_t uplifted = 0;
    for (std::size_t i = 1; i < m; ++i) {
      it.step(scale * a[i], 0.7 * scale * a[m - 1 - i], 0.3 * scale * a[(i * 7) % m], rec.dt);
      for (int p = 0; p < it.plane_count(); ++p) {
        const PlaneMonitor& pm = it.plane(static_cast<Plane>(p));
        ASSERT_LT(std::abs(pm.slip()), 1e-9) << "scale " << scale << " plane " << p << " sample " << i;
        if (pm.theta() != 0.0) ++uplifted;
      }
    }
    EXPECT_GT(uplifted, 10u) << "scale " << scale << ": the body never rocked, nothing was tested";
  }
}

// Issue 29: after an event ends, an item at rest is re-armed (new_event): the same pulse again alarms
// the same levels at the same time after its start; without new_event the levels stay latched.
TEST(ItemMonitor, NewEventReArmsAnItemAtRest) {
  // The example catalogue's medicine cabinet under Rinaldi 228 (Northridge 1994): COMMITTED, it survives.
  ItemSpec spec;
  spec.id = "medicine_cabinet";
  spec.sensor = "floor";
  spec.frame = "medicine_cabinet";
  spec.body.width = 0.9;
  spec.body.cg_height = 0.9;
  spec.body.nu1 = 0.4;
  spec.body.mu_s = 0.6;
  spec.depth.depth = 0.4;
  const Component rec =
      read_record(std::string(ROCKING_RECORDS_DIR) + "/northridge_1994/Rinaldi228.AT2").front();
  const double dt = rec.dt;
  std::vector<double> pulse = rec.accel;
  pulse.resize(pulse.size() + static_cast<std::size_t>(8.0 / dt), 0.0);  // 8 s to come to rest
  auto play = [&](ItemMonitor& im, double& t) {
    std::vector<std::pair<ItemMode, double>> alarms;
    const double start = t;
    for (double a : pulse) {
      const ItemEvents& ev = im.step(a, 0.0, 0.0, dt);
      t += dt;
      for (int k = 0; k < ev.alarm_count; ++k) alarms.emplace_back(ev.alarms[k].level, ev.alarms[k].time - start);
    }
    return alarms;
  };
  ItemMonitor rearmed(spec, ItemMonitor::Options{}), latched(spec, ItemMonitor::Options{});
  double t1 = 0.0, t2 = 0.0;
  rearmed.start(0.0, 0.0, 0.0, 0.0, dt);
  latched.start(0.0, 0.0, 0.0, 0.0, dt);
  const auto first = play(rearmed, t1);
  play(latched, t2);
  ASSERT_FALSE(first.empty());
  ASSERT_EQ(rearmed.mode(), ItemMode::Rest);
  rearmed.new_event(t1);
  const auto second = play(rearmed, t1);
  ASSERT_EQ(second.size(), first.size());
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(second[i].first, first[i].first);
    EXPECT_NEAR(second[i].second, first[i].second, 1e-9);  // the same motion from rest
  }
  EXPECT_TRUE(play(latched, t2).empty());  // the control: latched levels do not alarm again
}

}  // namespace
}  // namespace rocking_monitor::core
