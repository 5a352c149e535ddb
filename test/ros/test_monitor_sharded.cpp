// rostest: the catalogue split over two monitor shards (~shard 1/2 and 2/2, launch/sharded.launch)
// gives exactly the states and alarms of one monitor holding the whole catalogue.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <ros/ros.h>
#include <sensor_msgs/Imu.h>

#include "rocking_monitor/OverturnAlarm.h"
#include "rocking_monitor/RockingStateArray.h"

namespace {

using rocking_monitor::OverturnAlarm;
using rocking_monitor::RockingState;
using rocking_monitor::RockingStateArray;

struct Monitor {
  std::map<std::uint64_t, RockingStateArray> states;  // by input stamp, ns
  std::vector<OverturnAlarm> alarms;
  ros::Subscriber s, a;
  Monitor(ros::NodeHandle& nh, const std::string& ns) {
    s = nh.subscribe<RockingStateArray>(ns + "/states", 100000,
                                        [this](const RockingStateArray::ConstPtr& m) { states[m->header.stamp.toNSec()] = *m; });
    a = nh.subscribe<OverturnAlarm>(ns + "/alarms", 1000, [this](const OverturnAlarm::ConstPtr& m) { alarms.push_back(*m); });
  }
};

std::tuple<std::string, int, std::string, double> key(const OverturnAlarm& a) {
  return {a.item_id, a.level, a.plane, a.time_since_first_sample};
}

TEST(MonitorSharded, ShardsTogetherEqualTheWholeCatalogue) {
  ros::NodeHandle nh;
  Monitor whole(nh, "/rocking_monitor"), one(nh, "/rocking_monitor_1"), two(nh, "/rocking_monitor_2");
  // Done when each of the three has published its state for the bag's last sample, however slow the
  // machine: a few seconds without states once meant the end, and a starved player or shard at CI's
  // load made that come early ("a shard has no state for input stamp"). The player has ended when the
  // master lists no publisher of /ground/imu; the last stamp is the last one this test received.
  std::uint64_t last_input = 0;
  std::size_t inputs = 0;
  ros::Subscriber imu = nh.subscribe<sensor_msgs::Imu>("/ground/imu", 100000, [&](const sensor_msgs::Imu::ConstPtr& m) {
    last_input = std::max(last_input, m->header.stamp.toNSec());
    ++inputs;
  });
  const auto player_done = [] {
    ros::master::V_TopicInfo topics;
    ros::master::getTopics(topics);  // topics with a publisher
    return std::none_of(topics.begin(), topics.end(), [](const auto& t) { return t.name == "/ground/imu"; });
  };
  const auto has_last = [&](const Monitor& m) { return m.states.count(last_input) > 0; };
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(200.0);
  bool done = false;
  while (ros::ok() && ros::WallTime::now() < deadline && !done) {
    ros::spinOnce();
    ros::WallDuration(0.1).sleep();
    done = inputs > 0 && player_done() && has_last(whole) && has_last(one) && has_last(two);
  }
  ASSERT_TRUE(done) << "after 200 s of wall clock: " << inputs << " inputs seen, states "
                    << whole.states.size() << " / " << one.states.size() << " / " << two.states.size();
  // Alarms travel on their own topics: let those already sent arrive (as many from the shards as from
  // the whole, or 30 s), then one more second for any late extra one.
  const ros::WallTime alarms_deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  while (ros::ok() && ros::WallTime::now() < alarms_deadline &&
         whole.alarms.size() != one.alarms.size() + two.alarms.size()) {
    ros::spinOnce();
    ros::WallDuration(0.1).sleep();
  }
  for (int i = 0; i < 10; ++i) {
    ros::spinOnce();
    ros::WallDuration(0.1).sleep();
  }
  ASSERT_GT(whole.states.size(), 1000u);

  // Disjoint shards covering the catalogue, in catalogue order within each.
  const RockingStateArray& all = whole.states.rbegin()->second;
  ASSERT_FALSE(one.states.empty());
  ASSERT_FALSE(two.states.empty());
  std::set<std::string> ids, shard_ids;
  for (const RockingState& s : all.items) ids.insert(s.id);
  std::size_t in_shards = 0;
  for (const Monitor* m : {&one, &two}) {
    for (const RockingState& s : m->states.rbegin()->second.items) {
      EXPECT_TRUE(shard_ids.insert(s.id).second) << s.id << " is in both shards";
      ++in_shards;
    }
  }
  EXPECT_EQ(shard_ids, ids);
  EXPECT_EQ(in_shards, ids.size());
  EXPECT_GT(one.states.rbegin()->second.items.size(), 0u) << "a split that leaves a shard empty proves little";
  EXPECT_GT(two.states.rbegin()->second.items.size(), 0u);

  // Sample for sample, every item's state in its shard equals the whole monitor's.
  std::size_t compared = 0;
  for (const auto& [stamp, w] : whole.states) {
    std::map<std::string, const RockingState*> by_id;
    for (const Monitor* m : {&one, &two}) {
      const auto it = m->states.find(stamp);
      ASSERT_NE(it, m->states.end()) << "a shard has no state for input stamp " << stamp << " ns";
      for (const RockingState& s : it->second.items) by_id[s.id] = &s;
    }
    for (const RockingState& s : w.items) {
      const RockingState& t = *by_id.at(s.id);
      ASSERT_EQ(t.mode, s.mode) << s.id << " at " << stamp;
      ASSERT_EQ(t.x.theta, s.x.theta) << s.id << " at " << stamp;
      ASSERT_EQ(t.y.theta, s.y.theta) << s.id << " at " << stamp;
      ASSERT_EQ(t.x.slip, s.x.slip) << s.id << " at " << stamp;
      ASSERT_EQ(t.x.impacts + t.y.impacts, s.x.impacts + s.y.impacts) << s.id << " at " << stamp;
      ++compared;
    }
  }
  EXPECT_GT(compared, 6000u);

  // The alarms: the union of the shards' is the whole monitor's.
  std::multiset<std::tuple<std::string, int, std::string, double>> a, b;
  for (const auto& x : whole.alarms) a.insert(key(x));
  for (const Monitor* m : {&one, &two})
    for (const auto& x : m->alarms) b.insert(key(x));
  EXPECT_EQ(a, b);
  EXPECT_GE(a.size(), 3u) << "the scene must raise alarms, or this compares nothing";
}

}  // namespace

// main(): test/support/rostest_main.cpp
