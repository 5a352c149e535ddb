// Tests of the bridges' sample history (src/feeds/sample_history.cpp): what since() returns is
// checked sample by sample against the stream pushed, across wrap-around, with its completeness.
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "rocking_monitor/feeds/sample_history.hpp"

namespace fd = rocking_monitor::feeds;

namespace {

constexpr std::int64_t kT0 = 1'000'000'000LL * 1'000'000'000LL;  // 1e9 s, ns
constexpr std::int64_t kDt = 5'000'000;                            // 200 Hz

void push_range(fd::SampleHistory& h, int begin, int end) {
  for (int i = begin; i < end; ++i) ASSERT_TRUE(h.push(kT0 + i * kDt, i, -i, 9.81 + i));
}

}  // namespace

TEST(SampleHistory, CapacityForLengthAndRate) {
  EXPECT_EQ(fd::SampleHistory::capacity_for(300.0, 200.0), 60001u);
  EXPECT_EQ(fd::SampleHistory::capacity_for(0.01, 200.0), 3u);
  EXPECT_THROW(fd::SampleHistory::capacity_for(0.0, 200.0), std::invalid_argument);
  EXPECT_THROW(fd::SampleHistory::capacity_for(60.0, -1.0), std::invalid_argument);
  EXPECT_THROW(fd::SampleHistory::capacity_for(1e9, 1e3), std::invalid_argument);
  EXPECT_THROW(fd::SampleHistory(0), std::invalid_argument);
}

TEST(SampleHistory, ServesTheSamplesAfterAStampInOrder) {
  fd::SampleHistory h(100);
  push_range(h, 0, 50);
  std::vector<fd::HistorySample> out;
  const auto r = h.since(kT0 + 19 * kDt, out);  // strictly after sample 19
  ASSERT_EQ(r.count, 30u);
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(r.oldest_ns, kT0);
  EXPECT_EQ(r.newest_ns, kT0 + 49 * kDt);
  for (int k = 0; k < 30; ++k) {
    EXPECT_EQ(out[k].stamp_ns, kT0 + (20 + k) * kDt);
    EXPECT_EQ(out[k].x, 20.0 + k);
    EXPECT_EQ(out[k].y, -(20.0 + k));
    EXPECT_EQ(out[k].z, 9.81 + 20 + k);
  }
  // Between two stamps: from the next one on. After the newest: nothing, nothing missing.
  EXPECT_EQ(h.since(kT0 + 19 * kDt + 1, out).count, 30u);
  EXPECT_EQ(out.front().stamp_ns, kT0 + 20 * kDt);
  const auto none = h.since(kT0 + 49 * kDt, out);
  EXPECT_EQ(none.count, 0u);
  EXPECT_TRUE(none.complete);
  EXPECT_TRUE(out.empty());
}

TEST(SampleHistory, WrapsAroundKeepingTheNewestAndSaysWhenTheRequestReachesBeyond) {
  fd::SampleHistory h(64);
  push_range(h, 0, 1000);
  EXPECT_EQ(h.size(), 64u);
  EXPECT_EQ(h.pushed(), 1000u);
  EXPECT_EQ(h.overwritten(), 1000u - 64u);
  std::vector<fd::HistorySample> out;
  // Within the kept minutes: complete, exactly the samples after the stamp.
  auto r = h.since(kT0 + 950 * kDt, out);
  ASSERT_EQ(r.count, 49u);
  EXPECT_TRUE(r.complete);
  for (std::size_t k = 0; k < out.size(); ++k) EXPECT_EQ(out[k].stamp_ns, kT0 + (951 + static_cast<int>(k)) * kDt);
  // The oldest kept is 936: after 935 is still complete, after 934 is not (935 was overwritten).
  r = h.since(kT0 + 935 * kDt, out);
  EXPECT_EQ(r.count, 64u);
  EXPECT_TRUE(r.complete);
  r = h.since(kT0 + 934 * kDt, out);
  EXPECT_EQ(r.count, 64u);
  EXPECT_FALSE(r.complete);
  EXPECT_EQ(r.oldest_ns, kT0 + 936 * kDt);
  EXPECT_EQ(out.front().stamp_ns, kT0 + 936 * kDt);
  EXPECT_EQ(out.back().stamp_ns, kT0 + 999 * kDt);
}

TEST(SampleHistory, CompleteOnlyBackToItsFirstSample) {
  fd::SampleHistory h(64);
  push_range(h, 10, 20);
  std::vector<fd::HistorySample> out;
  // From its first sample on: all there, nothing thrown away.
  auto r = h.since(kT0 + 10 * kDt, out);
  EXPECT_EQ(r.count, 9u);
  EXPECT_TRUE(r.complete);
  // Before it: a source started later never had the samples in between (e.g. a restarted bridge).
  r = h.since(kT0 + 9 * kDt, out);
  EXPECT_EQ(r.count, 10u);
  EXPECT_FALSE(r.complete);
  EXPECT_FALSE(fd::SampleHistory(4).since(0, out).complete);  // empty: reaches back to nothing
}

TEST(SampleHistory, CapacityOneKeepsTheNewest) {
  fd::SampleHistory h(1);
  push_range(h, 0, 5);
  std::vector<fd::HistorySample> out;
  auto r = h.since(kT0 + 3 * kDt, out);
  ASSERT_EQ(r.count, 1u);
  EXPECT_EQ(out[0].stamp_ns, kT0 + 4 * kDt);
  EXPECT_TRUE(r.complete);
  EXPECT_FALSE(h.since(kT0 + 2 * kDt, out).complete);
}

TEST(SampleHistory, RepeatedStampRefusedEarlierStampRestarts) {
  fd::SampleHistory h(64);
  push_range(h, 0, 10);
  EXPECT_FALSE(h.push(kT0 + 9 * kDt, 1.0, 2.0, 3.0));
  EXPECT_EQ(h.refused(), 1u);
  EXPECT_EQ(h.size(), 10u);
  // The source went back (a new time base): the old samples are gone, requests before it incomplete.
  EXPECT_TRUE(h.push(kT0 + 2 * kDt, 7.0, 8.0, 9.0));
  EXPECT_EQ(h.restarts(), 1u);
  EXPECT_EQ(h.size(), 1u);
  std::vector<fd::HistorySample> out;
  auto r = h.since(kT0, out);
  ASSERT_EQ(r.count, 1u);
  EXPECT_EQ(out[0].x, 7.0);
  EXPECT_FALSE(r.complete);  // samples 1 (old base) were thrown away
  r = h.since(kT0 + 8 * kDt, out);  // a requester of the old base, beyond the new newest
  EXPECT_EQ(r.count, 0u);
  EXPECT_FALSE(r.complete);
}
