// rostest: Northridge 1994, Rinaldi Receiving Station (228 deg + UP), converted to a bag with
// record_to_bag and streamed through the monitor; for every catalogue item the alarms (levels and
// overturn time) equal rocking_sim run offline on the original record files.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <nlohmann/json.hpp>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/Imu.h>

#include "rocking_monitor/OverturnAlarm.h"
#include "rocking_monitor/RockingStateArray.h"
#include "rocking_monitor/ros/catalogue.hpp"
#include "test_helpers.hpp"

namespace fs = std::filesystem;

namespace {

std::string num(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

std::string run(const std::string& cmd, int& status) {
  const rocking_monitor::core::testing::CommandResult r = rocking_monitor::core::testing::run_command(cmd);
  status = r.status;
  return r.out;
}

TEST(MonitorHistorical, AlarmsEqualRockingSimForEveryItem) {
  ros::NodeHandle pnh("~"), nh;
  std::string records, tools, horizontal, vertical;
  pnh.getParam("records", records);
  pnh.getParam("tools", tools);
  pnh.getParam("horizontal", horizontal);
  pnh.getParam("vertical", vertical);
  const fs::path h = fs::path(records) / horizontal, v = fs::path(records) / vertical;
  if (!fs::exists(h) || !fs::exists(v)) {
    std::printf("NOTICE: records not found (%s): historical replay test skipped\n", h.c_str());
    GTEST_SKIP() << "records directory not found: " << records;
  }

  // 1. The bag, as a user would make it.
  const fs::path bag_path = fs::temp_directory_path() / ("rocking_historical_" + std::to_string(getpid()) + ".bag");
  int status = 0;
  const std::string out = run(tools + "/record_to_bag --file " + h.string() + " --file " + v.string() + " -o " +
                                  bag_path.string() + " -q 2>&1",
                              status);
  ASSERT_EQ(status, 0) << out;

  // 2. Offline answers from rocking_sim for every item, with the monitor's solver settings.
  XmlRpc::XmlRpcValue sensors, items;
  ASSERT_TRUE(nh.getParam("/rocking_monitor/sensors", sensors));
  ASSERT_TRUE(nh.getParam("/rocking_monitor/items", items));
  const rocking_monitor::live::Catalogue cat = rocking_monitor::live::parse_catalogue(sensors, items);
  double tol = 1e-6;
  nh.getParam("/rocking_monitor/tol", tol);
  std::map<std::string, nlohmann::json> offline;
  for (const auto& item : cat.items) {
    const auto& b = item.spec.body;
    std::string cmd = tools + "/rocking_sim --record " + h.string() + " --vertical " + v.string() +
                      " --json --fidelity adaptive --scene unknown --tol " + num(tol) + " --width " + num(b.width) + " --cg-height " +
                      num(b.cg_height) + " --eccentricity " + num(b.nu1);
    if (!std::isnan(b.radius_of_gyration)) cmd += " --radius-of-gyration " + num(b.radius_of_gyration);
    if (!std::isnan(b.restitution)) cmd += " --restitution " + num(b.restitution);
    if (!std::isinf(b.mu_s)) cmd += " --mu-s " + num(b.mu_s);
    const std::string json = run(cmd + " 2>/dev/null", status);
    ASSERT_EQ(status, 0) << cmd;
    offline[item.spec.id] = nlohmann::json::parse(json);
  }

  // 3. Live: stream the bag in lock-step (the monitor publishes a state per sample).
  auto clock_pub = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  auto imu_pub = nh.advertise<sensor_msgs::Imu>("/ground/imu", 100);
  double acked = 0.0;
  std::map<std::string, std::map<int, double>> live;  // item -> level -> event time
  auto sub_s = nh.subscribe<rocking_monitor::RockingStateArray>(
      "/rocking_monitor/states", 100,
      [&](const rocking_monitor::RockingStateArray::ConstPtr& m) { acked = m->header.stamp.toSec(); });
  auto sub_a = nh.subscribe<rocking_monitor::OverturnAlarm>(
      "/rocking_monitor/alarms", 1000,
      [&](const rocking_monitor::OverturnAlarm::ConstPtr& m) { live[m->item_id][m->level] = m->event_time; });
  const ros::WallTime wait_until = ros::WallTime::now() + ros::WallDuration(20.0);
  while ((imu_pub.getNumSubscribers() == 0 || sub_s.getNumPublishers() == 0) && ros::WallTime::now() < wait_until)
    ros::WallDuration(0.05).sleep();
  ASSERT_GT(imu_pub.getNumSubscribers(), 0u);

  rosbag::Bag bag(bag_path.string());
  std::size_t n = 0;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/ground/imu"))) {
    const auto imu = m.instantiate<sensor_msgs::Imu>();
    rosgraph_msgs::Clock c;
    c.clock = imu->header.stamp;
    clock_pub.publish(c);
    imu_pub.publish(*imu);
    const double t = imu->header.stamp.toSec();
    const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(2.0);
    // The first sample only starts the models: no state for it.
    while (n > 0 && acked < t - 1e-7 && ros::WallTime::now() < give_up) {
      ros::spinOnce();
      ros::WallDuration(0.0002).sleep();
    }
    ASSERT_TRUE(n == 0 || acked >= t - 1e-7) << "monitor stopped acknowledging at sample " << n;
    ++n;
  }
  bag.close();
  fs::remove(bag_path);
  ros::WallDuration(0.3).sleep();
  ros::spinOnce();
  EXPECT_GT(n, 1900u);

  // 4. Same alarm set, same overturn time.
  using rocking_monitor::OverturnAlarm;
  int overturned = 0, survived = 0;
  for (const auto& [id, j] : offline) {
    const auto& got = live[id];
    EXPECT_EQ(got.count(OverturnAlarm::BEYOND_TIPPING) == 1, j["beyond_tipping"].get<bool>()) << id;
    EXPECT_EQ(got.count(OverturnAlarm::COMMITTED) == 1, j["committed"].get<bool>()) << id;
    EXPECT_EQ(got.count(OverturnAlarm::OVERTURNED) == 1, j["overturned"].get<bool>()) << id;
    if (j["overturned"].get<bool>()) {
      ++overturned;
      if (got.count(OverturnAlarm::OVERTURNED))
        EXPECT_NEAR(got.at(OverturnAlarm::OVERTURNED) - 1e9, j["overturn_time_s"].get<double>(), 1e-3) << id;
    } else {
      ++survived;
    }
  }
  // The scene must be a real test: some items fall, some stay.
  EXPECT_GT(overturned, 0);
  EXPECT_GT(survived, 0);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_monitor_historical");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
