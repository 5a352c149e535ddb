// The redundant pair's rule for "the same alarm" (core::AlarmDedup, as scripts/alarm_dedup.py): which
// copies from two monitors are one alarm, which are repeats, which are two alarms.
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "rocking_monitor/monitoring/alarm_dedup.hpp"

using rocking_monitor::core::AlarmDedup;
using rocking_monitor::core::AlarmIdentity;
using Outcome = AlarmDedup::Outcome;

namespace {
constexpr int kBeyond = 2, kCommitted = 3, kOverturned = 4;
constexpr std::int64_t kS = 1000000000;

AlarmIdentity alarm(const std::string& source, const std::string& item, int level, std::int64_t stamp_ns,
                    const std::string& event = "2026-11-26T03:00:00.000Z/1", std::uint64_t sequence = 1,
                    bool whole = true) {
  return {source, item, level, stamp_ns, event, sequence, whole};
}
}  // namespace

TEST(AlarmDedup, BothMonitorsTheSameAlarmIsOneRow) {
  AlarmDedup d;
  const auto first = d.add(alarm("/a", "vase", kOverturned, 100 * kS + kS / 4, "e/1", 3));
  EXPECT_EQ(first.outcome, Outcome::New);
  const auto second = d.add(alarm("/b", "vase", kOverturned, 100 * kS + kS / 4, "e/1", 3));
  EXPECT_EQ(second.outcome, Outcome::Merged);
  EXPECT_EQ(second.row, first.row);
  EXPECT_FALSE(second.replaces);
  EXPECT_EQ(d.merged(), 1u);
  EXPECT_EQ(d.repeats(), 0u);
}

TEST(AlarmDedup, OtherEventIdAndSequenceFromTheOtherMonitorIsStillOneAlarm) {
  // b started later (its own sensor run: another id prefix) and journaled a gap (sequence shifted by one)
  AlarmDedup d;
  d.add(alarm("/a", "rack", kCommitted, 101 * kS, "2026-11-26T03:00:00.000Z/1", 4));
  EXPECT_EQ(d.add(alarm("/b", "rack", kCommitted, 101 * kS, "2026-11-26T02:41:13.370Z/2", 5)).outcome, Outcome::Merged);
}

TEST(AlarmDedup, ResentFromTheSameMonitorIsARepeat) {
  AlarmDedup d;
  d.add(alarm("/a", "vase", kBeyond, 99 * kS, "e/1", 1));
  EXPECT_EQ(d.add(alarm("/a", "vase", kBeyond, 99 * kS, "e/1", 1)).outcome, Outcome::Repeat);
  EXPECT_EQ(d.repeats(), 1u);
  // without an event id (a monitor without journal): the same item, level and stamp
  d.add(alarm("/c", "vase", kBeyond, 50 * kS, "", 0));
  EXPECT_EQ(d.add(alarm("/c", "vase", kBeyond, 50 * kS, "", 0)).outcome, Outcome::Repeat);
  EXPECT_EQ(d.repeats(), 2u);
}

TEST(AlarmDedup, TheCopyFromEverySampleReplacesOneAfterAGap) {
  // a respawned on a plain topic: its copy 0.103 s earlier, received first, is replaced by b's
  AlarmDedup d;
  const auto gap = d.add(alarm("/a", "vase", kBeyond, 102671 * kS / 1000, "e/1", 4, false));
  const auto whole = d.add(alarm("/b", "vase", kBeyond, 102774 * kS / 1000, "e/1", 5, true));
  EXPECT_EQ(whole.outcome, Outcome::Merged);
  EXPECT_EQ(whole.row, gap.row);
  EXPECT_TRUE(whole.replaces);
  EXPECT_EQ(d.replaced(), 1u);
  // the other order: the whole copy stays
  AlarmDedup d2;
  d2.add(alarm("/b", "vase", kBeyond, 102774 * kS / 1000, "e/1", 5, true));
  EXPECT_FALSE(d2.add(alarm("/a", "vase", kBeyond, 102671 * kS / 1000, "e/1", 4, false)).replaces);
  EXPECT_EQ(d2.replaced(), 0u);
}

TEST(AlarmDedup, OfEqualCopiesTheEarlierIsShown) {
  AlarmDedup d;
  const auto late = d.add(alarm("/a", "shelf", kOverturned, 109 * kS + 3 * kS / 10, "e/1", 9));
  const auto early = d.add(alarm("/b", "shelf", kOverturned, 105 * kS, "e/1", 7));
  EXPECT_EQ(early.outcome, Outcome::Merged);
  EXPECT_EQ(early.row, late.row);
  EXPECT_TRUE(early.replaces);
  // the row is at 105 s now: a copy from c at 115.1 s is more than 10 s after it, another alarm
  EXPECT_EQ(d.add(alarm("/c", "shelf", kOverturned, 115 * kS + kS / 10, "x/1", 1)).outcome, Outcome::New);
}

TEST(AlarmDedup, OneMonitorNeverMergesItsOwnAlarms) {
  AlarmDedup d;  // after ~reset the same level 2 s later from the same monitor is a new alarm
  const auto r1 = d.add(alarm("/a", "vase", kBeyond, 100 * kS, "e/1", 1));
  const auto r2 = d.add(alarm("/a", "vase", kBeyond, 102 * kS, "e/2", 1));
  EXPECT_EQ(r2.outcome, Outcome::New);
  EXPECT_NE(r1.row, r2.row);
  EXPECT_EQ(d.add(alarm("/b", "vase", kBeyond, 100 * kS, "f/1", 1)).row, r1.row);
  EXPECT_EQ(d.add(alarm("/b", "vase", kBeyond, 102 * kS, "f/2", 1)).row, r2.row);
}

TEST(AlarmDedup, BeyondTheWindowOrAnotherLevelOrItemIsAnotherAlarm) {
  AlarmDedup d(10.0);
  const auto r = d.add(alarm("/a", "vase", kBeyond, 100 * kS, "e/1", 1));
  EXPECT_EQ(d.add(alarm("/b", "vase", kBeyond, 110 * kS + kS / 2, "e/1", 1)).outcome, Outcome::New);
  EXPECT_EQ(d.add(alarm("/b", "vase", kCommitted, 100 * kS, "e/1", 2)).outcome, Outcome::New);
  EXPECT_EQ(d.add(alarm("/b", "rack", kBeyond, 100 * kS, "e/1", 3)).outcome, Outcome::New);
  const auto within = d.add(alarm("/b", "vase", kBeyond, 109 * kS + 9 * kS / 10, "e/1", 4));
  EXPECT_EQ(within.outcome, Outcome::Merged);
  EXPECT_EQ(within.row, r.row);
}

TEST(AlarmDedup, AForgottenRowTakesNoMoreCopies) {
  AlarmDedup d;
  const auto r = d.add(alarm("/a", "vase", kBeyond, 100 * kS, "e/1", 1));
  d.forget(r.row);
  const auto again = d.add(alarm("/b", "vase", kBeyond, 100 * kS, "e/1", 1));
  EXPECT_EQ(again.outcome, Outcome::New);
  EXPECT_NE(again.row, r.row);
  EXPECT_EQ(d.add(alarm("/a", "vase", kBeyond, 100 * kS, "e/1", 1)).outcome, Outcome::Repeat);
}

TEST(AlarmDedup, ANegativeOrNanWindowIsRefused) {
  EXPECT_THROW(AlarmDedup(-1.0), std::invalid_argument);
  EXPECT_THROW(AlarmDedup(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  try {
    AlarmDedup bad(-1.0);
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "alarm dedup window must be >= 0 s, got -1.000000");
  }
}
