// ground_motion_player under rostest (launch files next to this file):
//  * GroundMotionPlayerWall (player.test): the one-sine pulse at 4x real time: every sample arrives once,
//    in order, with the record's values (REP 145: z = g, covariances), AccelStamped without gravity,
//    stamps from ros::Time::now() spaced at the record's dt / 4 without drift, and ~finished = true.
//  * GroundMotionPlayerSimTime (player_sim_time.test): /use_sim_time with this test publishing /clock
//    at 8x wall speed: the player follows /clock (stamps exactly on the record's schedule with
//    ~stamp_source = schedule, never published before they are due) and signals the end.
//  * GroundMotionPlayerBadParam (player_bad_param.test): a bad parameter makes the node exit at once
//    without advertising anything.

#include <gtest/gtest.h>
#include <unistd.h>

#include <geometry_msgs/AccelStamped.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/Imu.h>
#include <std_msgs/Bool.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/motion/record_reader.hpp"

namespace {

using rocking_monitor::core::kGravity;

const std::string kPulseCsv = std::string(ROCKING_SOURCE_DIR) + "/bags/one_sine_pulse.csv";

struct Received {
  std::mutex mutex;
  std::vector<sensor_msgs::Imu> imu;
  std::vector<double> imu_arrival_wall;  ///< steady clock, s
  std::vector<ros::Time> imu_arrival_ros;
  std::vector<geometry_msgs::AccelStamped> accel;
  std::vector<bool> finished;
};

double steady_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Latest sim time published on /clock by the sim-time test (ns); 0 when not publishing. The player
/// cannot have seen a later time than this when it published.
std::atomic<std::int64_t> g_last_clock_ns{0};

struct Listener {
  Received r;
  ros::Subscriber imu_sub, accel_sub, finished_sub;
  explicit Listener(ros::NodeHandle& nh) {
    imu_sub = nh.subscribe<sensor_msgs::Imu>("/ground/imu", 20000, [this](const sensor_msgs::Imu::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(r.mutex);
      r.imu.push_back(*m);
      r.imu_arrival_wall.push_back(steady_s());
      const std::int64_t clock_ns = g_last_clock_ns.load();
      ros::Time arrival = ros::Time::now();
      if (clock_ns > 0) arrival.fromNSec(static_cast<std::uint64_t>(clock_ns));
      r.imu_arrival_ros.push_back(arrival);
    });
    accel_sub = nh.subscribe<geometry_msgs::AccelStamped>("/ground/accel", 20000, [this](const geometry_msgs::AccelStamped::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(r.mutex);
      r.accel.push_back(*m);
    });
    finished_sub = nh.subscribe<std_msgs::Bool>("/player/finished", 10, [this](const std_msgs::Bool::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(r.mutex);
      r.finished.push_back(m->data);
    });
  }
  /// Waits (wall time) until ~finished = true and `count` samples arrived, or the timeout.
  bool wait(std::size_t count, double timeout_s) {
    const double end = steady_s() + timeout_s;
    while (steady_s() < end && ros::ok()) {
      {
        std::lock_guard<std::mutex> lock(r.mutex);
        const bool done = !r.finished.empty() && r.finished.back();
        if (done && r.imu.size() >= count) return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }
};

/// Content checks shared by the wall and sim-time cases: every sample once, in order, exact values.
void expect_content(const Received& r, const rocking_monitor::core::Component& pulse, bool with_accel) {
  ASSERT_EQ(r.imu.size(), pulse.accel.size());
  if (with_accel) ASSERT_EQ(r.accel.size(), pulse.accel.size());
  for (std::size_t i = 0; i < r.imu.size(); ++i) {
    SCOPED_TRACE(i);
    const sensor_msgs::Imu& m = r.imu[i];
    ASSERT_EQ(m.linear_acceleration.x, pulse.accel[i]);
    ASSERT_EQ(m.linear_acceleration.y, 0.0);
    ASSERT_EQ(m.linear_acceleration.z, kGravity);
    ASSERT_EQ(m.header.frame_id, "accelerometer");
    ASSERT_EQ(m.orientation_covariance[0], -1.0);
    ASSERT_EQ(m.angular_velocity_covariance[0], -1.0);
    ASSERT_DOUBLE_EQ(m.linear_acceleration_covariance[0], 2.5e-4 * 2.5e-4 * 100.0);
    ASSERT_DOUBLE_EQ(m.linear_acceleration_covariance[8], 2.5e-4 * 2.5e-4 * 100.0);
    if (i > 0) ASSERT_GT(m.header.stamp, r.imu[i - 1].header.stamp);
    if (with_accel) {
      ASSERT_EQ(r.accel[i].accel.linear.x, pulse.accel[i]);
      ASSERT_EQ(r.accel[i].accel.linear.z, 0.0);
      ASSERT_EQ(r.accel[i].header.stamp, m.header.stamp);
    }
  }
  ASSERT_FALSE(r.finished.empty());
  EXPECT_TRUE(r.finished.back());
}

TEST(GroundMotionPlayerWall, PublishesEverySampleAtTheScaledRateAndSignalsTheEnd) {
  ros::NodeHandle nh;
  const double factor = 4.0;
  const rocking_monitor::core::Component pulse = rocking_monitor::core::read_record(kPulseCsv).at(0);
  Listener l(nh);
  ASSERT_TRUE(l.wait(pulse.accel.size(), 45.0)) << "received " << l.r.imu.size() << " samples, finished signals " << l.r.finished.size();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // AccelStamped may trail the end signal
  std::lock_guard<std::mutex> lock(l.r.mutex);
  expect_content(l.r, pulse, true);

  // Rate: 200 Hz x 4 = 800 Hz, from the stamps (ros::Time::now() at publish) and from the arrivals.
  const std::size_t n = l.r.imu.size();
  const double span = (l.r.imu.back().header.stamp - l.r.imu.front().header.stamp).toSec();
  const double expected_span = 8.0 / factor;
  EXPECT_NEAR(span, expected_span, 0.03) << "no drift: the last sample is due 2 s after the first";
  EXPECT_NEAR(static_cast<double>(n - 1) / span, 800.0, 800.0 * 0.015);
  const double arrival_span = l.r.imu_arrival_wall.back() - l.r.imu_arrival_wall.front();
  EXPECT_NEAR(arrival_span, expected_span, 0.1);
  // The stamps keep to the schedule (jitter, not accumulated error): the median departure. One late
  // wake of the publishing thread on a loaded machine (76 ms seen under ctest -j3 on 2 cores) is
  // the machine's, not the player's: the largest is reported, not judged.
  std::vector<double> departure(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double due = static_cast<double>(i) * pulse.dt / factor;
    departure[i] = std::fabs((l.r.imu[i].header.stamp - l.r.imu.front().header.stamp).toSec() - due);
  }
  std::sort(departure.begin(), departure.end());
  EXPECT_LT(departure[n / 2], 0.05) << "median departure of a stamp from the schedule, s";
  std::printf("[ measured ] departure of the stamps from the schedule: median %.4f s, largest %.4f s\n",
              departure[n / 2], departure.back());
  // ~finished is latched: false when the player starts, true at the end.
  EXPECT_TRUE(l.r.finished.back());
}

TEST(GroundMotionPlayerSimTime, FollowsClockAndStampsOnSchedule) {
  ros::NodeHandle nh;
  ASSERT_TRUE(ros::Time::isSimTime()) << "player_sim_time.test sets /use_sim_time";
  ros::Publisher clock_pub = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  const rocking_monitor::core::Component pulse = rocking_monitor::core::read_record(kPulseCsv).at(0);
  Listener l(nh);
  // Sim time starts at 100 s and runs at 8x wall speed on a 1 ms grid, from the steady clock (so at
  // 8x however late the thread wakes on a loaded machine).
  std::atomic<bool> stop{false};
  std::thread clock([&] {
    const auto start = std::chrono::steady_clock::now();
    std::int64_t last = -1;
    while (!stop && ros::ok()) {
      const std::int64_t elapsed =
          std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count();
      const std::int64_t ns = 100'000'000'000LL + (8 * elapsed) / 1'000'000 * 1'000'000;
      if (ns != last) {
        rosgraph_msgs::Clock c;
        c.clock.fromNSec(static_cast<std::uint64_t>(ns));
        g_last_clock_ns = ns;
        clock_pub.publish(c);
        last = ns;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
  });
  const double wall0 = steady_s();
  const bool done = l.wait(pulse.accel.size(), 45.0);
  const double wall = steady_s() - wall0;
  stop = true;
  clock.join();
  ASSERT_TRUE(done) << "received " << l.r.imu.size() << " samples";
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  std::lock_guard<std::mutex> lock(l.r.mutex);
  expect_content(l.r, pulse, false);
  const ros::Time first = l.r.imu.front().header.stamp;
  EXPECT_GE(first.toSec(), 100.0) << "stamps are sim time";
  for (std::size_t i = 0; i < l.r.imu.size(); ++i) {
    // ~stamp_source = schedule: exactly first + t_i (the record's 5 ms grid), to the nanosecond
    ASSERT_EQ(static_cast<std::int64_t>((l.r.imu[i].header.stamp - first).toNSec()), static_cast<std::int64_t>(i) * 5'000'000LL) << i;
    // not published before it was due on /clock (the latest /clock published when it arrived >= stamp)
    ASSERT_GE(l.r.imu_arrival_ros[i], l.r.imu[i].header.stamp) << i;
  }
  // 8 s of sim time at 8x: about 1 s of wall time. A player on the wall clock would need 8 s; the
  // 6 s bound (the one wall-time bound here) leaves 5 s for a loaded machine (issue 42).
  EXPECT_LT(wall, 6.0);
}

TEST(GroundMotionPlayerBadParam, ExitsWithoutAdvertising) {
  // The node (rate_factor -1) must exit at once: it never shows up as a publisher of /ground/imu, and
  // it is gone from the master. rostest starts the launch file's nodes before this test: waits for
  // the player's process to end (a condition, not a fixed time; the time limit catches a hang).
  // Only this rostest's player: a child of the roslaunch that started this test too.
  const auto player_running = [] {
    const std::string parent = std::to_string(getppid());
    for (const auto& e : std::filesystem::directory_iterator("/proc")) {
      std::ifstream f(e.path() / "cmdline");
      const std::string cmd((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
      if (cmd.find("__name:=player_bad") == std::string::npos) continue;
      std::ifstream st(e.path() / "stat");
      std::string stat((std::istreambuf_iterator<char>(st)), std::istreambuf_iterator<char>());
      std::istringstream fields(stat.substr(stat.rfind(')') + 1));  // state, ppid, ...
      std::string state, ppid;
      fields >> state >> ppid;
      if (ppid == parent && state != "Z") return true;
    }
    return false;
  };
  while (player_running()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ros::master::V_TopicInfo topics;
  ASSERT_TRUE(ros::master::getTopics(topics));
  for (const auto& t : topics) EXPECT_NE(t.name, "/ground/imu");
  std::vector<std::string> nodes;
  ASSERT_TRUE(ros::master::getNodes(nodes));
  for (const auto& n : nodes) EXPECT_NE(n, "/player_bad") << "the node should have exited";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ground_motion_player");
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  ros::shutdown();
  return result;
}
