// rostest (issue 19 part 3; issue 42: deterministic). Under /use_sim_time this test owns /clock, so
// the node's lag (its clock minus a sample's stamp) is the test's to set, whatever the machine's
// speed: it holds the clock 3 s ahead of the samples it sends (~max_lag 1 s). The node must say so:
// ~overload (latched) true and the sensor's diagnostics ERROR at the same clock instant; markers and
// tf, then (after ~max_lag of wall time) ~states shed; no sample lost uncounted (stepped + lost in
// transport = sent); ~overload false again once the samples caught up with the clock, one episode.
//
// The node's clock is known, not guessed: after publishing a /clock the test waits for a diagnostics
// message stamped at or after it (the node publishes them from its clock's timer), and it sends
// samples only while the clock is held still.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/ros.h>
#include <rocking_monitor/RockingStateArray.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/Imu.h>
#include <std_msgs/Bool.h>

#include "diagnostics_connected.hpp"

namespace {

constexpr double kMaxLag = 1.0;                    // s, ~max_lag (monitor_overload.yaml)
constexpr std::int64_t kPeriodNs = 5'000'000;      // 200 Hz sensor, ns
const ros::Time kT0(100.0);                        // s, the clock while the node keeps up
const ros::Time kStart = kT0 - ros::Duration(0.5); // s, sample k is stamped kStart + k periods
const ros::WallDuration kGiveUp(60.0);             // s of wall time for any one condition (a hang, not a verdict)

ros::Time stamp_of(int k) { return kStart + ros::Duration().fromNSec(k * kPeriodNs); }

struct Observed {
  bool overload = false;
  int overload_msgs = 0;
  ros::WallTime overload_on_wall;  // when the test saw ~overload true (the node's own moment is earlier)
  ros::Time diag_stamp;            // newest diagnostics stamp: the node's clock when it published them
  ros::Time error_stamp;           // first sensor status ERROR "overload...": the node's clock then
  ros::Time states_stamp;          // newest ~states stamp: the newest input sample stepped
  std::map<std::string, std::string> sensor, catalogue;
};

bool wait_for(const std::function<bool()>& done, const std::function<void()>& meanwhile = {}) {
  const ros::WallTime until = ros::WallTime::now() + kGiveUp;
  while (!done()) {
    if (ros::WallTime::now() > until) return false;
    if (meanwhile) meanwhile();
    ros::WallDuration(0.005).sleep();
    ros::spinOnce();
  }
  return true;
}

TEST(Overload, IsVisibleShedsLoadCountsEverySampleAndRecovers) {
  ros::NodeHandle nh;
  Observed o;
  auto sub_o = nh.subscribe<std_msgs::Bool>("/rocking_monitor/overload", 10, [&](const std_msgs::Bool::ConstPtr& m) {
    if (m->data && !o.overload) o.overload_on_wall = ros::WallTime::now();
    o.overload = m->data;
    ++o.overload_msgs;
  });
  auto sub_d = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 1000, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        bool ours = false;
        for (const auto& st : m->status) {
          if (st.name == "rocking_monitor: sensor floor samples") {
            ours = true;
            for (const auto& kv : st.values) o.sensor[kv.key] = kv.value;
            if (st.level == diagnostic_msgs::DiagnosticStatus::ERROR && st.message.find("overload") == 0 &&
                o.error_stamp.isZero())
              o.error_stamp = m->header.stamp;
          }
          if (st.name == "rocking_monitor: catalogue")
            for (const auto& kv : st.values) o.catalogue[kv.key] = kv.value;
        }
        if (ours) o.diag_stamp = std::max(o.diag_stamp, m->header.stamp);
      });
  auto sub_s = nh.subscribe<rocking_monitor::RockingStateArray>(
      "/rocking_monitor/states", 1000,
      [&](const rocking_monitor::RockingStateArray::ConstPtr& m) { o.states_stamp = std::max(o.states_stamp, m->header.stamp); });
  auto clock_pub = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  auto imu_pub = nh.advertise<sensor_msgs::Imu>("/ground/imu", 2000);

  ros::Time clock;
  auto publish_clock = [&](const ros::Time& t) {
    clock = t;
    rosgraph_msgs::Clock c;
    c.clock = t;
    clock_pub.publish(c);
  };
  // The clock to t, returning once the node has it (a diagnostics message stamped at or after t).
  auto set_clock = [&](const ros::Time& t) {
    publish_clock(t);
    return wait_for([&] { return o.diag_stamp >= t; }, [&] { publish_clock(t); });
  };
  int sent = 0;
  auto send = [&](int k) {
    sensor_msgs::Imu m;
    m.header.stamp = stamp_of(k);
    m.header.frame_id = "accelerometer";
    const double t = (m.header.stamp - kStart).toSec();
    m.linear_acceleration.x = 3.0 * std::sin(2.0 * M_PI * 2.0 * t);  // a 2 Hz sine of 3 m/s^2: the items rock
    m.linear_acceleration.z = 9.80665;
    imu_pub.publish(m);
    ++sent;
    if (sent % 50 == 0) ros::spinOnce();
  };

  ASSERT_TRUE(wait_for([&] {
    return imu_pub.getNumSubscribers() > 0 && clock_pub.getNumSubscribers() > 0 && sub_o.getNumPublishers() > 0 &&
           sub_d.getNumPublishers() > 0 && sub_s.getNumPublishers() > 0;
  })) << "the monitor did not connect";
  // set_clock holds the clock and waits for the one publication a jump brings: proven receivable first,
  // on a clock that ends at most 67 s, before T0.
  ASSERT_TRUE(rocking_monitor::test::step_clock_until_diagnostics(
      publish_clock, [&] { return !o.diag_stamp.isZero(); }, ros::Time(1.0)))
      << "no /diagnostics from the monitor";
  ASSERT_TRUE(set_clock(kT0)) << "the monitor never published diagnostics on the test's /clock";
  ASSERT_TRUE(wait_for([&] { return o.overload_msgs > 0; })) << "~overload is not latched";
  EXPECT_FALSE(o.overload) << "~overload latched false at start";

  // 1. Keeping up: 100 samples up to the clock held at T0 (node clock - stamp from 0.495 s down to 0:
  //    its minimum 0, so lag 0). Stepped when ~states carries the last stamp.
  int k = 0;
  while (k < 100) send(++k);
  ASSERT_TRUE(wait_for([&] { return o.states_stamp >= stamp_of(k); })) << "samples not stepped while keeping up";
  ros::spinOnce();
  EXPECT_FALSE(o.overload) << "overload while the node kept up";

  // 2. Behind: the clock 3 s ahead (no sample meanwhile), then samples 2.9-3.0 s old: lag > ~max_lag
  //    at the first, with the node's clock exactly T1 (held).
  const ros::Time t1 = kT0 + ros::Duration(3.0);
  ASSERT_TRUE(set_clock(t1));
  while (k < 120) send(++k);
  ASSERT_TRUE(wait_for([&] { return o.overload && !o.error_stamp.isZero(); }))
      << "~overload " << o.overload << ", sensor ERROR (overload) seen " << !o.error_stamp.isZero() << "; lag max "
      << o.sensor["lag, max (s)"] << " s";
  // At once: stamped at the clock the overload began on (held, so no periodic update came between).
  EXPECT_EQ(o.error_stamp, t1) << "diagnostics ERROR (overload) at " << o.error_stamp << ", overload at " << t1;

  // 3. ~states are thinned once the overload has lasted ~max_lag of wall time (the node's rule: it
  //    must work when sim time stalls): wait that out, then more samples (still > 2.8 s behind), shed.
  ASSERT_TRUE(wait_for([&] { return (ros::WallTime::now() - o.overload_on_wall).toSec() > kMaxLag + 0.1; }));
  while (k < 140) send(++k);
  // Markers and tf are shed at the state timer's ticks: the clock on by 0.8 s (under ~max_lag since
  // the last sample, so not idle) in 0.02 s steps, until diagnostics from a tick at T1 + 0.5 s or
  // later (the period) show it came, with overload on.
  const ros::Time t2 = t1 + ros::Duration(0.8);
  for (int j = 1; j <= 40; ++j) {
    publish_clock(t1 + ros::Duration().fromNSec(j * 20'000'000LL));
    ros::WallDuration(0.002).sleep();
  }
  ASSERT_TRUE(wait_for([&] { return o.diag_stamp >= t1 + ros::Duration(0.5); }, [&] { publish_clock(t2); }));
  EXPECT_TRUE(o.overload);

  // 4. Catching up: the clock held at T2, samples up to it: the lag falls below ~max_lag / 2, the
  //    overload ends (at the latest with the last sample, stamped T2).
  while (stamp_of(k) < t2) send(++k);
  ASSERT_EQ(stamp_of(k), t2);
  ASSERT_TRUE(wait_for([&] { return !o.overload; })) << "~overload still true after the samples caught up";

  // 5. Drained: the clock on (no more input) until diagnostics count every sample stepped or lost.
  auto accounted = [&] {
    if (!o.sensor.count("accepted") || !o.sensor.count("lost in transport")) return -1L;
    return std::stol(o.sensor["accepted"]) + 1 + std::stol(o.sensor["lost in transport"]);  // + the first sample
  };
  ros::Time t = t2;
  const bool drained = wait_for([&] { return accounted() == sent && o.diag_stamp > t2; },
                                [&] { publish_clock(t += ros::Duration(0.05)); });
  std::string all;
  for (const auto& [key, v] : o.sensor) all += key + ": " + v + "\n";
  EXPECT_TRUE(drained) << "stepped + lost in transport must equal the samples sent (" << sent << ")\n" << all;
  EXPECT_FALSE(o.overload) << "~overload true again after the samples caught up";
  EXPECT_EQ(o.sensor["overload episodes"], "1") << all;
  EXPECT_GT(std::stol(o.catalogue["markers and tf publications shed (overload)"]), 0);
  EXPECT_GT(std::stol(o.catalogue["states publications shed (overload)"]), 0);
  EXPECT_GT(std::stod(o.sensor["lag, max (s)"]), 2.8);  // the first sample behind: 3 s - 1 period
  std::printf("[ measured ] %d samples at 200 Hz (sim time): overload at clock %.3f s, ERROR at %.3f s; max lag %s s; "
              "%s stepped, %s lost in transport; shed: %s marker/tf and %s states publications; %s overload "
              "episode(s); processing per sample mean %s s\n",
              sent, t1.toSec(), o.error_stamp.toSec(), o.sensor["lag, max (s)"].c_str(), o.sensor["accepted"].c_str(),
              o.sensor["lost in transport"].c_str(), o.catalogue["markers and tf publications shed (overload)"].c_str(),
              o.catalogue["states publications shed (overload)"].c_str(), o.sensor["overload episodes"].c_str(),
              o.sensor["processing per sample, mean (s)"].c_str());
}

}  // namespace

// main(): test/support/rostest_main.cpp
