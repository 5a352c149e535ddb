// rostest: a synthetic pulse bag replayed through the monitor (rosbag play --clock) gives, sample for
// sample, the same states and the same alarms (same input stamps) as the core library offline.
#include <gtest/gtest.h>

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <ros/ros.h>
#include <sensor_msgs/Imu.h>

#include "replay_support.hpp"
#include "rocking_monitor/CriterionExceedance.h"
#include "rocking_monitor/OverturnAlarm.h"
#include "rocking_monitor/ProbabilityAlarm.h"
#include "rocking_monitor/RockingStateArray.h"

namespace rocking_monitor::test {
namespace {

TEST(MonitorReplay, LiveEqualsOfflineSampleForSample) {
  ros::NodeHandle pnh("~");
  std::string bag_path, ns = "/rocking_monitor", must_overturn, must_survive, must_slide;
  ASSERT_TRUE(pnh.getParam("bag", bag_path));
  pnh.getParam("monitor", ns);
  pnh.getParam("must_overturn", must_overturn);
  pnh.getParam("must_survive", must_survive);
  pnh.getParam("must_slide", must_slide);
  std::string must_rule_out;  // adaptive with ~scene_envelope: this item never runs the contact model
  pnh.getParam("must_rule_out", must_rule_out);

  // Offline: the same samples through the core library.
  rosbag::Bag bag(bag_path);
  rosbag::View view(bag, rosbag::TopicQuery("/ground/imu"));
  std::string frame;
  std::vector<sensor_msgs::Imu> samples;
  for (const rosbag::MessageInstance& m : view) {
    const auto imu = m.instantiate<sensor_msgs::Imu>();
    ASSERT_TRUE(imu);
    samples.push_back(*imu);
    frame = imu->header.frame_id;
  }
  ASSERT_GT(samples.size(), 100u);
  OfflineMonitor offline(ns, frame);
  for (const auto& s : samples)
    offline.push(s.header.stamp,
                 Eigen::Vector3d(s.linear_acceleration.x, s.linear_acceleration.y, s.linear_acceleration.z));

  // Live: collect every state (state_rate 0 = one per input sample) and every alarm.
  ros::NodeHandle nh;
  std::map<long long, RockingStateArray> live;
  std::vector<OverturnAlarm> alarms;
  auto sub_s = nh.subscribe<RockingStateArray>(ns + "/states", 10000, [&](const RockingStateArray::ConstPtr& m) {
    live[OfflineMonitor::stamp_key(m->header.stamp.toSec())] = *m;
  });
  auto sub_a = nh.subscribe<OverturnAlarm>(ns + "/alarms", 1000, [&](const OverturnAlarm::ConstPtr& m) { alarms.push_back(*m); });
  std::vector<ProbabilityAlarm> crossings;
  auto sub_p = nh.subscribe<ProbabilityAlarm>(ns + "/probability_alarms", 1000,
                                              [&](const ProbabilityAlarm::ConstPtr& m) { crossings.push_back(*m); });
  std::vector<CriterionExceedance> criteria;
  auto sub_c = nh.subscribe<CriterionExceedance>(ns + "/criteria", 1000,
                                                 [&](const CriterionExceedance::ConstPtr& m) { criteria.push_back(*m); });
  const double last = samples.back().header.stamp.toSec();
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(45.0);
  while (ros::ok() && ros::WallTime::now() < deadline &&
         (live.empty() || live.rbegin()->first < OfflineMonitor::stamp_key(last))) {
    ros::spinOnce();
    ros::WallDuration(0.01).sleep();
  }
  ros::WallDuration(0.5).sleep();
  ros::spinOnce();
  ASSERT_FALSE(live.empty()) << "no states received";

  // Every input sample after the first produced one state; all equal the offline run.
  EXPECT_EQ(live.size(), offline.states().size());
  std::size_t compared = 0;
  for (const auto& [key, off] : offline.states()) {
    const auto it = live.find(key);
    ASSERT_NE(it, live.end()) << "no live state for input stamp " << key << " us";
    ASSERT_EQ(it->second.items.size(), off.size());
    for (std::size_t i = 0; i < off.size(); ++i) {
      const RockingState& s = it->second.items[i];
      ASSERT_EQ(s.mode, off[i].mode) << s.id << " at " << key;
      // Same code, same inputs: identical, in both planes.
      ASSERT_EQ(s.x.theta, off[i].theta[0]) << s.id << " at " << key;
      ASSERT_EQ(s.y.theta, off[i].theta[1]) << s.id << " at " << key;
      ASSERT_EQ(s.x.impacts, off[i].impacts[0]) << s.id << " at " << key;
      // Uncertain items: the ensemble's probabilities, the same members, the same shares.
      ASSERT_EQ(s.ensemble_size, off[i].ensemble_size) << s.id;
      ASSERT_EQ(s.p_beyond_tipping.probability, off[i].p[0]) << s.id << " at " << key;
      ASSERT_EQ(s.p_committed.probability, off[i].p[1]) << s.id << " at " << key;
      ASSERT_EQ(s.p_overturned.probability, off[i].p[2]) << s.id << " at " << key;
      ASSERT_LE(s.p_overturned.lower, s.p_overturned.probability);
      ASSERT_GE(s.p_overturned.upper, s.p_overturned.probability);
      ASSERT_EQ(s.y.impacts, off[i].impacts[1]) << s.id << " at " << key;
      // The item-level fields repeat the worse plane.
      const PlaneState& worse = s.plane == "y" ? s.y : s.x;
      ASSERT_EQ(s.theta, worse.theta) << s.id;
      ASSERT_TRUE(s.plane == "x" || (s.plane == "y" && s.plane_count == 2)) << s.id << " plane " << s.plane;
      ASSERT_EQ(OfflineMonitor::stamp_key(s.input_stamp.toSec()), key) << s.id;
    }
    ++compared;
  }
  EXPECT_GT(compared, 1000u);

  // Same alarms at the same input stamps.
  ASSERT_EQ(alarms.size(), offline.alarms().size());
  for (std::size_t i = 0; i < alarms.size(); ++i) {
    EXPECT_EQ(alarms[i].item_id, offline.alarms()[i].item);
    EXPECT_EQ(alarms[i].level, offline.alarms()[i].level);
    EXPECT_EQ(alarms[i].plane, offline.alarms()[i].plane);
    EXPECT_EQ(alarms[i].time_since_first_sample, offline.alarms()[i].time_since_first_sample);
    EXPECT_EQ(OfflineMonitor::stamp_key(alarms[i].header.stamp.toSec()),
              OfflineMonitor::stamp_key(offline.alarms()[i].stamp));
  }
  // Probability alarms: the same crossings, at the same times.
  ASSERT_EQ(crossings.size(), offline.crossings().size());
  for (std::size_t i = 0; i < crossings.size(); ++i) {
    EXPECT_EQ(crossings[i].item_id, offline.crossings()[i].item);
    EXPECT_EQ(crossings[i].level, offline.crossings()[i].level);
    EXPECT_EQ(crossings[i].time_since_first_sample, offline.crossings()[i].time_since_first_sample);
    EXPECT_EQ(crossings[i].value.probability, offline.crossings()[i].probability);
  }
  int must_cross = 0;
  pnh.getParam("must_cross", must_cross);
  EXPECT_GE(static_cast<int>(crossings.size()), must_cross) << "probability alarms expected in this scene";
  std::string must_be_uncertain;  // an item whose P(overturned) must end strictly between 0 and 1
  pnh.getParam("must_be_uncertain", must_be_uncertain);
  if (!must_be_uncertain.empty()) {
    const RockingStateArray& last = live.rbegin()->second;
    bool found = false;
    for (const RockingState& st : last.items) {
      if (st.id != must_be_uncertain) continue;
      found = true;
      EXPECT_GT(st.p_overturned.probability, 0.0) << must_be_uncertain;
      EXPECT_LT(st.p_overturned.probability, 1.0) << must_be_uncertain;
      std::printf("[ measured ] %s: P(overturned) %.3f [%.3f, %.3f] over %u members\n", st.id.c_str(),
                  st.p_overturned.probability, st.p_overturned.lower, st.p_overturned.upper, st.ensemble_size);
    }
    EXPECT_TRUE(found) << must_be_uncertain;
  }
  // A catalogue item's own ensemble_size wins over ~ensemble_size ("id:members").
  std::string item_ensemble;
  pnh.getParam("item_ensemble_size", item_ensemble);
  if (!item_ensemble.empty()) {
    const std::string id = item_ensemble.substr(0, item_ensemble.find(':'));
    const unsigned members = static_cast<unsigned>(std::stoul(item_ensemble.substr(item_ensemble.find(':') + 1)));
    bool found = false;
    for (const RockingState& st : live.rbegin()->second.items) {
      if (st.id != id) continue;
      found = true;
      EXPECT_EQ(st.ensemble_size, members) << id;
    }
    EXPECT_TRUE(found) << id;
  }
  // The physics oracle of this scene: which item falls and which stays (from the offline run).
  if (!must_overturn.empty()) {
    bool found = false;
    for (const auto& a : alarms) found |= a.item_id == must_overturn && a.level == OverturnAlarm::OVERTURNED;
    EXPECT_TRUE(found) << must_overturn << " must overturn";
  }
  if (!must_slide.empty()) {  // the contact model ran for it: sliding was modelled, not only flagged
    bool slid = false;
    for (const auto& [key, msg] : live)
      for (const RockingState& st : msg.items)
        slid |= st.id == must_slide && st.model == "contact" &&
                (st.contact_mode == RockingState::CONTACT_SLIDE || st.contact_mode == RockingState::CONTACT_SLIDE_ROCK);
    EXPECT_TRUE(slid) << must_slide << " must slide";
    // ... and does not rock: in neither plane does a corner lift (no rocking contact mode, no impact).
    for (const auto& [key, msg] : live)
      for (const RockingState& st : msg.items) {
        if (st.id != must_slide) continue;
        for (const PlaneState* p : {&st.x, &st.y}) {
          ASSERT_NE(p->contact_mode, RockingState::CONTACT_ROCK) << must_slide << " rocks at " << key;
          ASSERT_NE(p->contact_mode, RockingState::CONTACT_SLIDE_ROCK) << must_slide << " rocks at " << key;
          ASSERT_EQ(p->impacts, 0u) << must_slide << " at " << key;
        }
      }
    // ... and the node says why it switched to the contact model.
    bool why = false;
    for (const auto& c : criteria)
      why |= c.item_id == must_slide && c.criterion == CriterionExceedance::SLIDE_FROM_REST && c.exceeded;
    EXPECT_TRUE(why) << "no slide_from_rest event for " << must_slide;
  }
  if (!must_rule_out.empty()) {
    bool known = false;
    for (const auto& item : offline.items()) {
      if (item.spec().id != must_rule_out) continue;
      known = true;
      const core::AdaptiveModel* a = item.plane(core::Plane::X).adaptive();
      ASSERT_NE(a, nullptr);
      EXPECT_EQ(a->initial_reason(), core::SwitchReason::SceneRulesOutContact);
      EXPECT_EQ(a->outcome().samples_contact_model, 0);
      EXPECT_FALSE(std::isnan(a->outcome().uplift_time)) << must_rule_out << " must rock";
    }
    EXPECT_TRUE(known) << must_rule_out;
    for (const auto& [key, msg] : live)
      for (const RockingState& st : msg.items)
        if (st.id == must_rule_out) ASSERT_EQ(st.model, "rocking") << must_rule_out << " at " << key;
  }
  if (!must_survive.empty()) {
    for (const auto& a : alarms) EXPECT_NE(a.item_id, must_survive) << must_survive << " must raise no alarm";
  }
}

}  // namespace
}  // namespace rocking_monitor::test

// main(): test/support/rostest_main.cpp
