// Three channels in records of different lengths, out of step -> one sample per time with all
// three; gaps and overlaps counted; 1/2 channels rotated by the station azimuth.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "rocking_monitor/feeds/station_merger.hpp"

namespace rocking_monitor::feeds {
namespace {

constexpr std::int64_t kStartUs = 1000000000LL * 1000000 + 2500;  // off the whole second: phase 2500 us
constexpr std::int64_t kPeriodUs = 10000;                         // 100 Hz

// The value channel `c` has at sample index i (distinct per channel and time).
double value(int c, std::int64_t i) { return 1000.0 * (c + 1) + static_cast<double>(i); }

DecodedRecord record(const std::string& channel, int c, std::int64_t first, std::size_t n) {
  DecodedRecord r;
  r.network = "CI";
  r.station = "RIN";
  r.channel = channel;
  r.sample_rate = 100.0;
  r.start_us = kStartUs + first * kPeriodUs;
  for (std::size_t k = 0; k < n; ++k) r.samples.push_back(value(c, first + static_cast<std::int64_t>(k)));
  return r;
}

struct Collect {
  std::vector<MergedSample> out;
  StationMerger::Emit emit() {
    return [this](const MergedSample& s) { out.push_back(s); };
  }
};

TEST(StationMerger, OutOfStepChannelsMergeOnTheirSampleTimes) {
  const double gain = 250.0;
  StationMerger m(gain, 0.0, false);
  Collect c;
  // Records of 5 (N), 11 (E) and 7 (Z) samples, arriving channel by channel, each ahead of the others.
  std::map<int, std::int64_t> next = {{0, 0}, {1, 0}, {2, 0}};
  const std::map<int, std::pair<std::string, std::size_t>> chans = {{0, {"HNN", 5}}, {1, {"HNE", 11}}, {2, {"HNZ", 7}}};
  for (int round = 0; round < 20; ++round) {
    for (int ch : {2, 0, 1}) {
      m.add(record(chans.at(ch).first, ch, next[ch], chans.at(ch).second), c.emit());
      next[ch] += static_cast<std::int64_t>(chans.at(ch).second);
    }
  }
  const std::int64_t complete = std::min({next[0], next[1], next[2]});  // 100: N ends first
  ASSERT_EQ(c.out.size(), static_cast<std::size_t>(complete));
  for (std::int64_t i = 0; i < complete; ++i) {
    const MergedSample& s = c.out[static_cast<std::size_t>(i)];
    EXPECT_EQ(s.time_ns, (kStartUs + i * kPeriodUs) * 1000) << i;
    EXPECT_EQ(s.enu[0], value(1, i) / gain) << "east = E channel";
    EXPECT_EQ(s.enu[1], value(0, i) / gain) << "north = N channel";
    EXPECT_EQ(s.enu[2], value(2, i) / gain);
  }
  const MergerCounters& k = m.counters();
  EXPECT_EQ(k.gaps + k.overlaps + k.incomplete + k.output_gaps + k.foreign_records + k.late_samples, 0u);
  EXPECT_EQ(m.channels()[0], "HNN");
  EXPECT_EQ(m.channels()[1], "HNE");
}

TEST(StationMerger, GapsDropTheTimesOneChannelMissesAndOverlapsAreNotRepeated) {
  StationMerger m(1.0, 0.0, false);
  Collect c;
  for (int ch = 0; ch < 3; ++ch) m.add(record(ch == 0 ? "HNN" : ch == 1 ? "HNE" : "HNZ", ch, 0, 10), c.emit());
  ASSERT_EQ(c.out.size(), 10u);
  // N skips samples 10..12 (a gap of 3); E repeats 6..9 before going on (an overlap of 4).
  m.add(record("HNN", 0, 13, 10), c.emit());
  m.add(record("HNE", 1, 6, 20), c.emit());
  m.add(record("HNZ", 2, 10, 13), c.emit());
  ASSERT_EQ(c.out.size(), 20u);  // 0..9, then 13..22
  for (std::size_t k = 0; k < c.out.size(); ++k) {
    const std::int64_t i = k < 10 ? static_cast<std::int64_t>(k) : static_cast<std::int64_t>(k) + 3;
    EXPECT_EQ(c.out[k].time_ns, (kStartUs + i * kPeriodUs) * 1000);
    EXPECT_EQ(c.out[k].enu[1], value(0, i));
  }
  const MergerCounters& k = m.counters();
  EXPECT_EQ(k.gaps, 1u);
  EXPECT_EQ(k.gap_samples, 3u);
  EXPECT_EQ(k.overlaps, 1u);
  EXPECT_EQ(k.overlap_samples, 4u);
  EXPECT_EQ(k.overlap_conflicts, 0u) << "the repeated samples carry the same values";
  EXPECT_EQ(k.incomplete, 3u);
  EXPECT_EQ(k.output_gaps, 1u);
  EXPECT_EQ(k.samples_out, 20u);
}

// Issue 52 item 3: a record that overlaps an earlier one with other samples is a conflict, not a
// repeat. The first values are kept; times still waiting for the other channels go out marked, times
// already out are counted only (they cannot be taken back).
TEST(StationMerger, AnOverlapWithOtherValuesIsAConflictTheFirstKept) {
  StationMerger m(1.0, 0.0, false);
  Collect c;
  for (int ch = 0; ch < 3; ++ch) m.add(record(ch == 0 ? "HNN" : ch == 1 ? "HNE" : "HNZ", ch, 0, 10), c.emit());
  ASSERT_EQ(c.out.size(), 10u);
  m.add(record("HNZ", 2, 10, 10), c.emit());  // Z runs ahead to 19: times 10..19 wait for N and E
  DecodedRecord other = record("HNZ", 2, 5, 10);  // Z again from 5 to 14 with other values at 8..11
  for (std::size_t k = 3; k < 7; ++k) other.samples[k] += 0.5;
  m.add(other, c.emit());
  m.add(record("HNN", 0, 10, 10), c.emit());
  m.add(record("HNE", 1, 10, 10), c.emit());
  ASSERT_EQ(c.out.size(), 20u);
  for (std::int64_t i = 0; i < 20; ++i) {
    const MergedSample& s = c.out[static_cast<std::size_t>(i)];
    EXPECT_EQ(s.enu[2], value(2, i)) << "time " << i << ": the first value is kept";
    EXPECT_EQ(s.conflict, i == 10 || i == 11) << "time " << i;
  }
  const MergerCounters& k = m.counters();
  EXPECT_EQ(k.overlaps, 1u);
  EXPECT_EQ(k.overlap_samples, 10u);
  EXPECT_EQ(k.overlap_conflicts, 4u) << "8 and 9 already out, 10 and 11 waiting";
  EXPECT_EQ(k.conflicts_marked, 2u);
}

// The ring's slot of a time given up long ago holds another time's value: an overlap reaching back
// that far cannot be compared and is no conflict (nor a false one).
TEST(StationMerger, AnOverlapBeyondTheRingIsNotCompared) {
  StationMerger m(1.0, 0.0, false, 16);
  Collect c;
  for (std::int64_t first = 0; first < 40; first += 8)  // records shorter than the ring, in step
    for (int ch = 0; ch < 3; ++ch) m.add(record(ch == 0 ? "HNN" : ch == 1 ? "HNE" : "HNZ", ch, first, 8), c.emit());
  ASSERT_EQ(c.out.size(), 40u);
  DecodedRecord old = record("HNZ", 2, 0, 40);
  for (double& v : old.samples) v += 1.0;  // every value differs, but 0..23 are no longer held
  m.add(old, c.emit());
  EXPECT_EQ(m.counters().overlap_samples, 40u);
  EXPECT_EQ(m.counters().overlap_conflicts, 16u) << "only the 16 times the ring still holds";
  EXPECT_EQ(m.counters().conflicts_marked, 0u);
}

TEST(StationMerger, NumberedHorizontalsTurnByTheAzimuth) {
  // Channel 1 points east (azimuth 90), so channel 2 (90 deg clockwise of it) points south.
  StationMerger m(2.0, 90.0, true);
  Collect c;
  m.add(record("HN1", 0, 0, 4), c.emit());
  m.add(record("HN2", 1, 0, 4), c.emit());
  m.add(record("HNZ", 2, 0, 4), c.emit());
  ASSERT_EQ(c.out.size(), 4u);
  for (std::int64_t i = 0; i < 4; ++i) {
    const MergedSample& s = c.out[static_cast<std::size_t>(i)];
    EXPECT_NEAR(s.enu[0], value(0, i) / 2.0, 1e-12);
    EXPECT_NEAR(s.enu[1], -value(1, i) / 2.0, 1e-9);
    EXPECT_EQ(s.enu[2], value(2, i) / 2.0);
  }
  // 1/2 channels with an unknown azimuth, and channels of no known direction, are refused.
  StationMerger blind(2.0, 0.0, false);
  blind.add(record("HN1", 0, 0, 4), c.emit());
  blind.add(record("HNU", 0, 0, 4), c.emit());
  EXPECT_EQ(blind.counters().foreign_records, 2u);
}

TEST(StationFrame, InverseAndErrors) {
  const StationFrame f(427000.0, 318.0);
  const auto counts = f.to_counts(0.3, -1.2, 2.5);
  const auto enu = f.to_enu(counts[0], counts[1], counts[2]);
  EXPECT_NEAR(enu[0], 0.3, 1e-12);
  EXPECT_NEAR(enu[1], -1.2, 1e-12);
  EXPECT_NEAR(enu[2], 2.5, 1e-12);
  EXPECT_THROW(StationFrame(0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(StationFrame(-1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(StationFrame(1.0, NAN), std::invalid_argument);
}

}  // namespace
}  // namespace rocking_monitor::feeds

namespace rocking_monitor::feeds {
namespace {

TEST(SeedChannels, RolesOfStrongMotionCodes) {
  for (const char* code : {"HNZ", "HLZ", "ENZ"}) EXPECT_EQ(channel_role(code)->slot, Slot::Z) << code;
  for (const char* code : {"HNN", "HLN", "ENN"}) {
    EXPECT_EQ(channel_role(code)->slot, Slot::H1) << code;
    EXPECT_FALSE(channel_role(code)->numbered) << code;
  }
  for (const char* code : {"HNE", "HLE", "ENE"}) EXPECT_EQ(channel_role(code)->slot, Slot::H2) << code;
  EXPECT_EQ(channel_role("HN1")->slot, Slot::H1);
  EXPECT_TRUE(channel_role("HN1")->numbered);
  EXPECT_EQ(channel_role("HN2")->slot, Slot::H2);
  EXPECT_TRUE(channel_role("EN2")->numbered);
  EXPECT_FALSE(channel_role("HNU"));   // Galperin axes: no single direction
  EXPECT_FALSE(channel_role("HN3"));
  EXPECT_FALSE(channel_role("LOG"));
  EXPECT_FALSE(channel_role("HN"));
}

}  // namespace
}  // namespace rocking_monitor::feeds

namespace rocking_monitor::feeds {
namespace {

TEST(StationMerger, AChannelThatNeverComesCostsOnlyTheRing) {
  // Ring of 16 samples: with Z silent, N and E are held until the ring is full, then the oldest
  // times are given up one by one (counted); nothing is emitted and nothing grows.
  StationMerger m(1.0, 0.0, false, 16);
  Collect c;
  m.add(record("HNN", 0, 0, 40), c.emit());
  m.add(record("HNE", 1, 0, 40), c.emit());
  EXPECT_TRUE(c.out.empty());
  EXPECT_EQ(m.counters().incomplete, 40u - 16u);  // N alone filled the ring: times 0..23 given up
  EXPECT_EQ(m.counters().late_samples, 24u);      // E's samples for those times came too late
  // Z arrives from time 25 on: 24 can never be complete, 25..39 go out.
  m.add(record("HNZ", 2, 25, 15), c.emit());
  ASSERT_EQ(c.out.size(), 15u);
  EXPECT_EQ(c.out.front().time_ns, (kStartUs + 25 * kPeriodUs) * 1000);
  EXPECT_EQ(m.counters().incomplete, 25u);
}

TEST(StationMerger, OtherRatesAndMixedOrientationsAreRefused) {
  StationMerger m(1.0, 30.0, true);
  Collect c;
  m.add(record("HNN", 0, 0, 10), c.emit());
  m.add(record("HN2", 1, 0, 10), c.emit());  // 1/2 after N/E: not one instrument
  DecodedRecord fast = record("HNE", 1, 0, 10);
  fast.sample_rate = 200.0;
  m.add(fast, c.emit());
  EXPECT_EQ(m.counters().foreign_records, 1u);
  EXPECT_EQ(m.counters().rate_mismatches, 1u);
  EXPECT_TRUE(c.out.empty());
}

}  // namespace
}  // namespace rocking_monitor::feeds
