// ItemEnsemble: the probability of each overturning level over members with different parameters,
// against the members run one by one, and the Wilson interval against its closed form and a table.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "rocking_monitor/monitoring/item_ensemble.hpp"
#include "rocking_monitor/motion/record_reader.hpp"

namespace rocking_monitor::core {
namespace {

const std::string kEnsemblePulse = std::string(ROCKING_SOURCE_DIR) + "/bags/one_sine_pulse.csv";

ItemSpec item(double width, double depth) {
  ItemSpec s;
  s.id = "vase";
  s.sensor = "floor";
  s.frame = "vase";
  s.body.width = width;
  s.body.cg_height = 0.35;
  s.body.mu_s = 0.8;
  s.depth.depth = depth;
  return s;
}

TEST(Wilson, ClosedFormsAndATableValue) {
  const double z = 1.959963984540054, n = 32;
  EXPECT_DOUBLE_EQ(wilson_interval(0, 32).lower, 0.0);
  EXPECT_NEAR(wilson_interval(0, 32).upper, z * z / (n + z * z), 1e-15);
  EXPECT_NEAR(wilson_interval(32, 32).lower, n / (n + z * z), 1e-15);
  EXPECT_DOUBLE_EQ(wilson_interval(32, 32).upper, 1.0);
  // Newcombe (1998), Table I: 5 of 20 -> 0.1119 to 0.4687 (95 %).
  EXPECT_NEAR(wilson_interval(5, 20).lower, 0.1119, 5e-5);
  EXPECT_NEAR(wilson_interval(5, 20).upper, 0.4687, 5e-5);
  for (long k = 0; k <= 40; ++k) {
    EXPECT_NEAR(wilson_interval(k, 40).lower, 1.0 - wilson_interval(40 - k, 40).upper, 1e-14) << k;
  }
}

TEST(ItemEnsemble, IdenticalMembersGiveTheDeterministicAnswer) {
  const Component c = read_record(kEnsemblePulse).front();
  const ItemSpec s = item(0.15, 0.3);
  ItemEnsemble e(std::vector<ItemSpec>(8, s), ItemMonitor::Options{});
  ItemMonitor single(s, ItemMonitor::Options{});
  e.start(0.0, c.accel[0], 0.0, 0.0, c.dt);
  single.start(0.0, c.accel[0], 0.0, 0.0, c.dt);
  std::vector<ProbabilityCrossing> crossings;
  std::vector<AlarmEvent> alarms;
  for (std::size_t i = 1; i < c.accel.size(); ++i) {
    const EnsembleEvents& ev = e.step(c.accel[i], 0.0, 0.0, c.dt);
    for (int k = 0; k < ev.count; ++k) crossings.push_back(ev.crossings[k]);
    const ItemEvents& se = single.step(c.accel[i], 0.0, 0.0, c.dt);
    for (int k = 0; k < se.alarm_count; ++k) alarms.push_back(se.alarms[k]);
    for (int l = 0; l < kLevelCount; ++l) ASSERT_TRUE(e.probability(static_cast<Level>(l)) == 0.0 || e.probability(static_cast<Level>(l)) == 1.0);
  }
  ASSERT_EQ(alarms.size(), 3u) << "the vase must overturn, or the test proves little";
  ASSERT_EQ(crossings.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(static_cast<int>(crossings[k].level) + 2, static_cast<int>(alarms[k].level));
    EXPECT_EQ(crossings[k].time, alarms[k].time);
    EXPECT_EQ(crossings[k].probability, 1.0);
  }
}

TEST(ItemEnsemble, ProbabilitiesAreTheShareOfMembersRunAlone) {
  const Component c = read_record(kEnsemblePulse).front();
  std::vector<ItemSpec> members;
  for (int i = 0; i < 24; ++i) members.push_back(item(0.13 + 0.01 * i, 0.10 + 0.015 * i));  // B 0.13-0.36 m
  ItemEnsemble e(members, ItemMonitor::Options{}, 0.25);
  e.start(0.0, c.accel[0], 0.3 * c.accel[0], 0.0, c.dt);
  std::vector<ProbabilityCrossing> crossings;
  for (std::size_t i = 1; i < c.accel.size(); ++i) {
    const EnsembleEvents& ev = e.step(c.accel[i], 0.3 * c.accel[i], 0.0, c.dt);
    for (int k = 0; k < ev.count; ++k) crossings.push_back(ev.crossings[k]);
  }
  // Each member alone: which levels, when.
  std::array<std::vector<double>, kLevelCount> times;
  for (const ItemSpec& m : members) {
    ItemMonitor alone(m, ItemMonitor::Options{});
    alone.start(0.0, c.accel[0], 0.3 * c.accel[0], 0.0, c.dt);
    for (std::size_t i = 1; i < c.accel.size(); ++i) {
      const ItemEvents& ev = alone.step(c.accel[i], 0.3 * c.accel[i], 0.0, c.dt);
      for (int k = 0; k < ev.alarm_count; ++k) times[static_cast<int>(ev.alarms[k].level) - 2].push_back(ev.alarms[k].time);
    }
  }
  for (int l = 0; l < kLevelCount; ++l) EXPECT_EQ(e.reached(static_cast<Level>(l)), static_cast<long>(times[l].size()));
  const double p_over = e.probability(Level::Overturned);
  EXPECT_GT(p_over, 0.0);
  EXPECT_LT(p_over, 1.0) << "some members must stand, some fall";
  // A crossing happens at the 6th member's time (ceil(0.25 * 24)), once per level.
  ASSERT_FALSE(crossings.empty()) << "the threshold must be crossed, or the test proves little";
  for (const ProbabilityCrossing& x : crossings) {
    std::vector<double> t = times[static_cast<int>(x.level)];
    std::sort(t.begin(), t.end());
    ASSERT_GE(t.size(), 6u);
    EXPECT_EQ(x.time, t[5]);
  }
  for (int l = 0; l < kLevelCount; ++l) EXPECT_EQ(e.crossed(static_cast<Level>(l)), times[l].size() >= 6u);
  std::printf("[ measured ] P(beyond tipping) %.3f, P(committed) %.3f, P(overturned) %.3f [%.3f, %.3f] over 24 members\n",
              e.probability(Level::BeyondTipping), e.probability(Level::Committed), p_over,
              e.interval(Level::Overturned).lower, e.interval(Level::Overturned).upper);
}

TEST(ItemEnsemble, EachMemberFeelsTheInputTimesItsGain) {
  // issue 41: members that differ only by input_gain are one body under scaled records: each must
  // do what the same body run alone under its scaled input does, alarm for alarm.
  const Component c = read_record(kEnsemblePulse).front();
  std::vector<ItemSpec> members;
  for (int i = 0; i < 12; ++i) {
    members.push_back(item(0.2, 0.3));
    members.back().input_gain = 0.5 + 0.1 * i;  // 0.5 .. 1.6
  }
  ItemEnsemble e(members, ItemMonitor::Options{});
  e.start(0.0, c.accel[0], 0.2 * c.accel[0], 0.0, c.dt);
  for (std::size_t i = 1; i < c.accel.size(); ++i) e.step(c.accel[i], 0.2 * c.accel[i], 0.0, c.dt);
  long over = 0;
  for (const ItemSpec& m : members) {
    ItemSpec plain = m;
    plain.input_gain = 1.0;
    ItemMonitor alone(plain, ItemMonitor::Options{});
    const double g = m.input_gain;
    alone.start(0.0, g * c.accel[0], g * (0.2 * c.accel[0]), g * 0.0, c.dt);
    for (std::size_t i = 1; i < c.accel.size(); ++i) alone.step(g * c.accel[i], g * (0.2 * c.accel[i]), g * 0.0, c.dt);
    over += alone.mode() == ItemMode::Overturned;
  }
  EXPECT_EQ(e.reached(Level::Overturned), over);
  EXPECT_GT(over, 0) << "the strongest members must overturn, or the test proves little";
  EXPECT_LT(over, 12) << "the weakest must stand";
  // monotone here: the members that overturn are the strongest ones
  for (int i = 0; i < 12; ++i)
    EXPECT_EQ(e.member(i).mode() == ItemMode::Overturned, i >= 12 - over) << "gain " << members[i].input_gain;
  ItemSpec bad = item(0.2, 0.3);
  bad.input_gain = -1.0;
  EXPECT_THROW(ItemEnsemble({bad}, ItemMonitor::Options{}), std::invalid_argument);
}

TEST(ItemEnsemble, BadEnsemblesAreRefused) {
  EXPECT_THROW(ItemEnsemble({}, ItemMonitor::Options{}), std::invalid_argument);
  EXPECT_THROW(ItemEnsemble({item(0.15, 0.3)}, ItemMonitor::Options{}, 0.0), std::invalid_argument);
  ItemSpec bad = item(-0.1, 0.3);
  try {
    ItemEnsemble({item(0.15, 0.3), bad}, ItemMonitor::Options{});
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ensemble member 1: item 'vase': width"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rocking_monitor::core
