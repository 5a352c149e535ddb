// rostest: a real record over SeedLink into the monitor (seedlink_monitor.test).
//  1. record_to_mseed writes the Rinaldi station (318, 228, UP) as steim2 miniSEED (channels HN1 at
//     318 deg, HN2, HNZ; 512-byte records of 74 to 151 samples, interleaved) and, with --table-out,
//     the dequantised samples in the station frame: the offline input of rocking_sim.
//  2. The test SeedLink server serves it at 4x real time, with a record of an unknown encoding in
//     the sequence, one malformed header and one repeated sequence number; it is killed with SIGKILL
//     in the middle and started again 1.5 s later on the same port.
//  3. Every sample time of the record is published exactly once, in order (nothing lost or
//     repeated across the restart); /diagnostics reports the outage, the malformed packet, the
//     repeated number and the unknown encoding; the monitor's alarms (level, plane, time to 1e-9 s)
//     and each plane's verdict equal rocking_sim's on the same quantised record (live == offline).
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <nlohmann/json.hpp>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/ros.h>
#include <sensor_msgs/Imu.h>

#include "rocking_monitor/OverturnAlarm.h"
#include "rocking_monitor/RockingStateArray.h"
#include "rocking_monitor/SampleHistory.h"
#include "rocking_monitor/ros/catalogue.hpp"
#include "test_helpers.hpp"

namespace fs = std::filesystem;

namespace {

std::string num(double v) { return rocking_monitor::core::testing::exact_number(v); }

pid_t start_server(const std::vector<std::string>& args) {
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

bool spin_until(const std::function<bool()>& done, double seconds) {
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(seconds);
  while (!done() && ros::WallTime::now() < until) {
    ros::spinOnce();
    ros::WallDuration(0.005).sleep();
  }
  ros::spinOnce();
  return done();
}

std::string value_of(const diagnostic_msgs::DiagnosticStatus& s, const std::string& key) {
  for (const auto& kv : s.values)
    if (kv.key == key) return kv.value;
  return "<no " + key + ">";
}

TEST(SeedLinkMonitor, LiveEqualsOfflineAcrossAServerRestart) {
  ros::NodeHandle pnh("~"), nh;
  std::string records, tools, script, horizontal, horizontal_y, vertical;
  int port = 0;
  double gain = 0.0;
  pnh.getParam("records", records);
  pnh.getParam("tools", tools);
  pnh.getParam("server_script", script);
  pnh.getParam("port", port);
  pnh.getParam("gain", gain);
  pnh.getParam("horizontal", horizontal);
  pnh.getParam("horizontal_y", horizontal_y);
  pnh.getParam("vertical", vertical);
  const fs::path h = fs::path(records) / horizontal, hy = fs::path(records) / horizontal_y, v = fs::path(records) / vertical;
  if (!fs::exists(h) || !fs::exists(hy) || !fs::exists(v)) {
    std::printf("NOTICE: records not found (%s): SeedLink test skipped\n", h.c_str());
    GTEST_SKIP() << "records directory not found: " << records;
  }
  const fs::path dir = fs::temp_directory_path() / ("rocking_seedlink_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string mseed = (dir / "rin.mseed").string(), table = (dir / "rin").string(), clock = (dir / "clock").string();

  // 1. miniSEED and the quantised record.
  auto r = rocking_monitor::core::testing::run_command(
      tools + "/record_to_mseed --file " + h.string() + " --file " + hy.string() + " --file " + v.string() + " -o " + mseed +
      " --gain " + num(gain) + " --network CI --station RIN --orientation 12 --table-out " + table + " 2>&1");
  ASSERT_EQ(r.status, 0) << r.out;
  ASSERT_NE(r.out.find("channel 1 at azimuth 318 deg"), std::string::npos) << r.out;

  // 2. Offline answers on the quantised record in the station frame.
  XmlRpc::XmlRpcValue sensors, items;
  ASSERT_TRUE(nh.getParam("/rocking_monitor/sensors", sensors));
  ASSERT_TRUE(nh.getParam("/rocking_monitor/items", items));
  const rocking_monitor::live::Catalogue cat = rocking_monitor::live::parse_catalogue(sensors, items);
  double tol = 1e-6;
  nh.getParam("/rocking_monitor/tol", tol);
  std::map<std::string, nlohmann::json> offline;
  for (const auto& item : cat.items) {
    const auto& b = item.spec.body;
    std::string cmd = tools + "/rocking_sim --record " + table + "_east.csv --vertical " + table +
                      "_up.csv --json --fidelity adaptive --scene unknown --tol " + num(tol) + " --width " + num(b.width) +
                      " --cg-height " + num(b.cg_height) + " --eccentricity " + num(b.nu1);
    if (!std::isnan(b.radius_of_gyration)) cmd += " --radius-of-gyration " + num(b.radius_of_gyration);
    if (!std::isnan(b.restitution)) cmd += " --restitution " + num(b.restitution);
    if (!std::isinf(b.mu_s)) cmd += " --mu-s " + num(b.mu_s);
    const auto& d = item.spec.depth;
    if (d.given()) {
      cmd += " --record-y " + table + "_north.csv --depth " + num(d.depth) + " --eccentricity-y " + num(d.eccentricity_y);
      if (!std::isnan(d.radius_of_gyration_y)) cmd += " --radius-of-gyration-y " + num(d.radius_of_gyration_y);
    }
    r = rocking_monitor::core::testing::run_command(cmd + " 2>/dev/null");
    ASSERT_EQ(r.status, 0) << cmd;
    offline[item.spec.id] = nlohmann::json::parse(r.out);
  }

  // 3. Live.
  std::vector<std::int64_t> stamps;
  std::vector<std::array<double, 3>> accels;  // as published, m/s^2 (the bridge's ~history is checked against them)
  auto sub_imu = nh.subscribe<sensor_msgs::Imu>("/seedlink_bridge/CI_RIN/imu", 100000, [&](const sensor_msgs::Imu::ConstPtr& m) {
    stamps.push_back(static_cast<std::int64_t>(m->header.stamp.toNSec()));
    accels.push_back({m->linear_acceleration.x, m->linear_acceleration.y, m->linear_acceleration.z});
  });
  rocking_monitor::RockingStateArray last;
  auto sub_s = nh.subscribe<rocking_monitor::RockingStateArray>(
      "/rocking_monitor/states", 100000, [&](const rocking_monitor::RockingStateArray::ConstPtr& m) { last = *m; });
  std::map<std::string, std::map<int, rocking_monitor::OverturnAlarm>> live;
  int repeated = 0;
  auto sub_a = nh.subscribe<rocking_monitor::OverturnAlarm>(
      "/rocking_monitor/alarms", 1000, [&](const rocking_monitor::OverturnAlarm::ConstPtr& m) {
        repeated += live[m->item_id].count(m->level);
        live[m->item_id][m->level] = *m;
      });
  std::map<std::string, diagnostic_msgs::DiagnosticStatus> diag;
  auto sub_d = nh.subscribe<diagnostic_msgs::DiagnosticArray>("/diagnostics", 100, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
    for (const auto& s : m->status) diag[s.name] = s;
  });
  ASSERT_TRUE(spin_until([&] { return sub_imu.getNumPublishers() > 0 && sub_s.getNumPublishers() > 0; }, 30.0));

  const std::vector<std::string> base = {"/usr/bin/python3", script, "--port", std::to_string(port), "--speed", "4",
                                         "--clock-file", clock, "--unknown-at", "5"};
  std::vector<std::string> first = base;
  for (const char* a : {"--inject-at", "10"}) first.push_back(a);
  first.push_back(mseed);
  std::vector<std::string> again = base;
  again.push_back(mseed);
  pid_t server = start_server(first);
  ASSERT_GT(server, 0);
  const bool halfway = spin_until([&] { return stamps.size() >= 800; }, 60.0);
  kill(server, SIGKILL);
  waitpid(server, nullptr, 0);
  ASSERT_TRUE(halfway) << "only " << stamps.size() << " samples before the restart";
  const std::size_t before_restart = stamps.size();
  spin_until([] { return false; }, 1.5);  // the server is down
  server = start_server(again);
  const bool all = spin_until([&] { return stamps.size() >= 1991; }, 90.0);
  spin_until([&] { return !last.items.empty() && last.header.stamp.toNSec() == static_cast<std::uint64_t>(stamps.back()); }, 10.0);
  spin_until([] { return false; }, 1.5);  // a diagnostics period after the end
  kill(server, SIGTERM);
  waitpid(server, nullptr, 0);
  fs::remove_all(dir);
  ASSERT_TRUE(all) << stamps.size() << " samples published";
  EXPECT_LT(before_restart, 1991u) << "the server was not restarted in the middle";

  // Every sample time of the record exactly once, in order: t0 + i * 10 ms.
  ASSERT_EQ(stamps.size(), 1991u);
  for (std::size_t i = 0; i < stamps.size(); ++i)
    ASSERT_EQ(stamps[i], 1000000000LL * 1000000000LL + static_cast<std::int64_t>(i) * 10000000LL) << "sample " << i;

  // The bridge's ~history (issue 29 part 2): exactly the samples it published after a stamp, complete
  // (its ring reaches back that far); before its first sample, not complete.
  rocking_monitor::SampleHistory hist;
  hist.request.topic = "/seedlink_bridge/CI_RIN/imu";
  hist.request.after.fromNSec(static_cast<std::uint64_t>(stamps[1000]));
  ASSERT_TRUE(ros::service::call("/seedlink_bridge/history", hist));
  EXPECT_TRUE(hist.response.ok && hist.response.complete) << hist.response.message;
  ASSERT_EQ(hist.response.stamps.size(), 990u) << hist.response.message;
  for (std::size_t i = 0; i < 990; ++i) {
    ASSERT_EQ(static_cast<std::int64_t>(hist.response.stamps[i].toNSec()), stamps[1001 + i]) << "history sample " << i;
    ASSERT_EQ((std::array<double, 3>{hist.response.x[i], hist.response.y[i], hist.response.z[i]}), accels[1001 + i])
        << "history sample " << i;
  }
  hist.request.after.fromNSec(static_cast<std::uint64_t>(stamps[0] - 1));
  ASSERT_TRUE(ros::service::call("/seedlink_bridge/history", hist));
  EXPECT_FALSE(hist.response.complete) << hist.response.message;
  EXPECT_EQ(hist.response.stamps.size(), 1991u);

  // /diagnostics: the outage and each fault, counted; the bridge still connected.
  const auto& conn = diag["seedlink_bridge: seedlink connection"];
  const auto& station = diag["seedlink_bridge: seedlink station CI_RIN"];
  EXPECT_EQ(value_of(conn, "connected"), "True");
  EXPECT_EQ(value_of(conn, "reconnects (connections lost)"), "1");
  EXPECT_GE(std::stod(value_of(conn, "last outage (s)")), 1.5);
  EXPECT_EQ(value_of(conn, "malformed packets"), "1");
  EXPECT_EQ(value_of(conn, "repeated sequence numbers (dropped)"), "1");
  EXPECT_EQ(value_of(station, "unknown-encoding records"), "1");
  EXPECT_EQ(value_of(station, "last unknown encoding"), "99");
  EXPECT_EQ(value_of(station, "samples published"), "1991");
  EXPECT_EQ(value_of(station, "gaps"), "0");
  EXPECT_EQ(value_of(station, "overlaps"), "0");
  EXPECT_EQ(value_of(station, "incomplete times dropped"), "0");
  EXPECT_GE(std::stod(value_of(station, "longest pause between records (s)")), 1.5);
  std::printf("[ measured ] outage %s s, longest pause between records %s s, %zu samples before the restart\n",
              value_of(conn, "last outage (s)").c_str(), value_of(station, "longest pause between records (s)").c_str(),
              before_restart);

  // The monitor: live == offline.
  EXPECT_EQ(repeated, 0);
  using rocking_monitor::OverturnAlarm;
  const std::array<std::pair<int, const char*>, 3> levels = {{{OverturnAlarm::BEYOND_TIPPING, "beyond_tipping"},
                                                             {OverturnAlarm::COMMITTED, "committed"},
                                                             {OverturnAlarm::OVERTURNED, "overturn"}}};
  int overturned = 0, survived = 0;
  ASSERT_EQ(last.items.size(), cat.items.size());
  for (std::size_t i = 0; i < cat.items.size(); ++i) {
    const std::string& id = cat.items[i].spec.id;
    const nlohmann::json& item = offline[id].at("item");
    const auto& got = live[id];
    for (const auto& [level, name] : levels) {
      const std::string flag = std::string(name) == "overturn" ? "overturned" : name;
      const bool reached = item.at(flag).get<bool>();
      ASSERT_EQ(got.count(level) == 1, reached) << id << " " << flag;
      if (!reached) continue;
      EXPECT_NEAR(got.at(level).time_since_first_sample, item.at(std::string(name) + "_time_s").get<double>(), 1e-9) << id << " " << flag;
      EXPECT_EQ(got.at(level).plane, item.at(std::string(name) + "_plane").get<std::string>()) << id << " " << flag;
    }
    const rocking_monitor::RockingState& s = last.items[i];
    for (const auto& [plane, state] : {std::pair<std::string, const rocking_monitor::PlaneState*>{"x", &s.x},
                                       std::pair<std::string, const rocking_monitor::PlaneState*>{"y", &s.y}}) {
      if (plane == "y" && s.plane_count == 1) continue;
      const nlohmann::json& p = offline[id].at("planes").at(plane);
      EXPECT_EQ(state->mode == rocking_monitor::RockingState::OVERTURNED, p.at("overturned").get<bool>()) << id << " " << plane;
      EXPECT_EQ(state->impacts, p.at("impacts").get<long>()) << id << " " << plane;
    }
    (item.at("overturned").get<bool>() ? overturned : survived) += 1;
  }
  EXPECT_GT(overturned, 0);
  EXPECT_GT(survived, 0);
  std::printf("[ measured ] %d items overturned, %d survived (live == offline)\n", overturned, survived);
}

}  // namespace

// main(): test/support/rostest_main.cpp
