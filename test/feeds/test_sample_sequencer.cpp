// Tests of the reorder window and loss accounting (src/feeds/sample_sequencer.cpp, time_grid.cpp):
// streams with known drops, swaps, duplicates, late samples and restarts; every count must equal
// what was injected, and the released samples must be exactly the delivered ones, in order.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <random>
#include <set>
#include <vector>

#include "rocking_monitor/feeds/sample_sequencer.hpp"
#include "rocking_monitor/feeds/time_grid.hpp"

namespace fd = rocking_monitor::feeds;

namespace {

fd::AccelSample sample(std::uint64_t seq) {
  fd::AccelSample s;
  s.has_sequence = true;
  s.sequence = seq;
  s.time_s = 0.005 * static_cast<double>(seq);
  s.accel[0] = static_cast<double>(seq);
  return s;
}

std::vector<std::uint64_t> run(fd::SampleSequencer& q, const std::vector<std::uint64_t>& order, bool flush = true) {
  std::vector<std::uint64_t> out;
  for (std::uint64_t s : order) {
    q.push(sample(s));
    for (std::size_t i = 0; i < q.ready_count(); ++i) out.push_back(q.ready()[i].sequence);
  }
  if (flush) {
    q.flush();
    for (std::size_t i = 0; i < q.ready_count(); ++i) out.push_back(q.ready()[i].sequence);
  }
  return out;
}

}  // namespace

TEST(SampleSequencer, InOrderStreamPassesStraightThrough) {
  fd::SampleSequencer q(4);
  std::vector<std::uint64_t> order;
  for (std::uint64_t s = 100; s < 200; ++s) order.push_back(s);
  EXPECT_EQ(run(q, order, false), order);  // released as they come, nothing held
  EXPECT_EQ(q.held(), 0u);
  EXPECT_EQ(q.counts().released, 100u);
  EXPECT_EQ(q.counts().lost + q.counts().reordered + q.counts().late + q.counts().duplicates, 0u);
}

TEST(SampleSequencer, SeededDropsAndSwapsAreCountedExactly) {
  // 1 % drops and 2 % adjacent swaps, seeded; never the first or last sample.
  std::mt19937_64 rng(18);
  const std::uint64_t n = 20000;
  std::set<std::uint64_t> dropped;
  std::vector<std::uint64_t> order;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uint64_t swaps = 0;
  for (std::uint64_t i = 0; i < n; ++i) order.push_back(i);
  for (std::uint64_t i = 1; i + 2 < n; ++i) {
    if (u(rng) < 0.02 && !dropped.count(i) && !dropped.count(i + 1)) {
      std::swap(order[i], order[i + 1]);
      ++swaps;
      ++i;  // swaps do not overlap
    } else if (u(rng) < 0.01) {
      dropped.insert(order[i]);
    }
  }
  std::vector<std::uint64_t> sent;
  for (std::uint64_t s : order)
    if (!dropped.count(s)) sent.push_back(s);
  fd::SampleSequencer q(4);
  const std::vector<std::uint64_t> out = run(q, sent);
  std::vector<std::uint64_t> want(sent);
  std::sort(want.begin(), want.end());
  EXPECT_EQ(out, want);  // every delivered sample, in order
  EXPECT_GT(dropped.size(), 100u);
  EXPECT_GT(swaps, 200u);
  EXPECT_EQ(q.counts().lost, dropped.size());
  EXPECT_EQ(q.counts().reordered, swaps);
  EXPECT_EQ(q.counts().late, 0u);
  EXPECT_EQ(q.counts().duplicates, 0u);
  EXPECT_EQ(q.counts().released, sent.size());
}

TEST(SampleSequencer, BeyondTheWindowIsLostThenLateDuplicatesDropped) {
  fd::SampleSequencer q(2);
  // 0 1 [2 missing] 3 4 5 -> 2 given up when 5 arrives (5 >= 2 + 3); 2 arrives later: late, not lost
  const std::vector<std::uint64_t> out = run(q, {0, 1, 3, 4, 5, 2, 5, 6}, false);
  EXPECT_EQ(out, (std::vector<std::uint64_t>{0, 1, 3, 4, 5, 6}));
  EXPECT_EQ(q.counts().lost, 0u);  // 2 did arrive
  EXPECT_EQ(q.counts().late, 1u);
  EXPECT_EQ(q.counts().duplicates, 1u);
  EXPECT_EQ(q.counts().reordered, 0u);  // 2 was not released in its place
  // Held samples wait for the window or a flush.
  fd::SampleSequencer h(8);
  EXPECT_EQ(run(h, {10, 12, 13}, false), (std::vector<std::uint64_t>{10}));
  EXPECT_EQ(h.held(), 2u);
  h.flush();
  ASSERT_EQ(h.ready_count(), 2u);
  EXPECT_EQ(h.ready()[0].sequence, 12u);
  EXPECT_EQ(h.counts().lost, 1u);
}

TEST(SampleSequencer, RestartOfTheCounterIsAResyncNotALoss) {
  fd::SampleSequencer q(4);
  const std::vector<std::uint64_t> out = run(q, {50000, 50001, 50002, 0, 1, 2}, false);
  EXPECT_EQ(out, (std::vector<std::uint64_t>{50000, 50001, 50002, 0, 1, 2}));
  EXPECT_EQ(q.counts().resyncs, 1u);
  EXPECT_EQ(q.counts().lost + q.counts().late, 0u);
}

TEST(TimeGrid, SequenceFromTimeAtTheNominalRate) {
  fd::TimeGrid g(200.0);
  const std::uint64_t o = fd::TimeGrid::kOrigin;
  EXPECT_EQ(g.sequence(1000.0), o);
  EXPECT_EQ(g.sequence(1000.005), o + 1);
  EXPECT_EQ(g.sequence(1000.0 + 0.005 * 37 + 0.001), o + 37);        // within a quarter sample
  EXPECT_EQ(g.sequence(1000.0 + 0.005 * 37 + 0.002), std::nullopt);  // 0.4 sample off: not this stream
  EXPECT_EQ(g.sequence(999.995), o - 1);                             // reordered before the first
  EXPECT_THROW(fd::TimeGrid(0.0), std::invalid_argument);
}

// The per-sample path allocates nothing. core_tests counts allocations with
// test/support/allocation_counter.hpp (included once, in test_batch_rocking.cpp); its counter is an
// inline variable, so this identical definition names the same object.
namespace rocking_monitor::testing {
inline std::atomic<long> g_allocation_count{0};
}  // namespace rocking_monitor::testing

TEST(SampleSequencer, PerSamplePathAllocatesNothing) {
  fd::SampleSequencer q(4);
  fd::TimeGrid grid(200.0);
  unsigned char bin[fd::kBinarySize];
  char text[64];
  const double a[3] = {0.1, -0.2, 0.3};
  const long before = rocking_monitor::testing::g_allocation_count.load();
  std::uint64_t released = 0;
  for (std::uint64_t i = 0; i < 10000; ++i) {
    const std::uint64_t s = (i % 50 == 7) ? i + 1 : (i % 50 == 8) ? i - 1 : i;  // swaps
    if (i % 97 == 13) continue;                                                 // drops
    fd::encode_binary(s, 0.005 * static_cast<double>(s), a, bin);
    fd::AccelSample sample;
    ASSERT_EQ(fd::parse_datagram(reinterpret_cast<const char*>(bin), sizeof bin, sample), fd::DatagramError::None);
    q.push(sample);
    released += q.ready_count();
    const int n = std::snprintf(text, sizeof text, "%.3f,0.1,-0.2,0.3\n", 0.005 * static_cast<double>(i));
    ASSERT_EQ(fd::parse_datagram(text, static_cast<std::size_t>(n), sample), fd::DatagramError::None);
    ASSERT_TRUE(grid.sequence(sample.time_s).has_value());
  }
  EXPECT_EQ(rocking_monitor::testing::g_allocation_count.load(), before);
  EXPECT_GT(released, 9800u);
  // the counter is live: a vector allocates
  std::vector<int> v(3);
  EXPECT_GT(rocking_monitor::testing::g_allocation_count.load(), before);
}

// Issue 52: the same sequence number with another payload is a conflict, not a duplicate; the
// first one is kept whether it was still held or already released.
TEST(SampleSequencer, ConflictingPayloadKeepsTheFirstAndIsCounted) {
  fd::SampleSequencer q(4);
  q.push(sample(10));  // released at once
  ASSERT_EQ(q.ready_count(), 1u);
  EXPECT_FALSE(q.ready()[0].conflict);
  fd::AccelSample other = sample(10);
  other.accel[0] = -3.5;
  q.push(other);  // after release: compared with the remembered payload
  EXPECT_EQ(q.ready_count(), 0u);
  q.push(sample(12));  // held: 11 is missing
  fd::AccelSample other12 = sample(12);
  other12.time_s += 1e-9;
  q.push(other12);  // held: compared with the held sample
  q.push(sample(12));  // the same bytes again: a duplicate
  q.push(sample(10));  // the released one again, same bytes: a duplicate
  EXPECT_EQ(q.counts().conflicts, 2u);
  EXPECT_EQ(q.counts().conflicts_marked, 1u);  // 12 was held; 10 had been released
  EXPECT_EQ(q.counts().last_conflict, 12u);
  EXPECT_EQ(q.counts().duplicates, 2u);
  q.flush();
  ASSERT_EQ(q.ready_count(), 1u);
  EXPECT_EQ(q.ready()[0].sequence, 12u);
  EXPECT_TRUE(q.ready()[0].conflict);  // released marked, with the first payload
  EXPECT_EQ(q.ready()[0].time_s, sample(12).time_s);
  EXPECT_EQ(q.ready()[0].accel[0], 12.0);
  EXPECT_EQ(q.counts().lost, 1u);
  EXPECT_EQ(q.counts().released, 2u);
}

// Issue 52: with a key, a replayed datagram far behind the stream has a valid tag; it must not be
// taken for a restart (which would publish it and drop the real stream after it as late).
TEST(SampleSequencer, WithoutBackwardResyncFarBehindIsStale) {
  fd::SampleSequencer q(4, /*resync_backward=*/false);
  const std::uint64_t far = fd::SampleSequencer::kResyncSpan + 1;
  // 10000..10004, then 10004 - far (a replay of an old datagram), then 10005; then a jump ahead.
  const auto out = run(q, {10000, 10001, 10002, 10003, 10004, 10004 - far, 10005, 10005 + far + 1});
  EXPECT_EQ(out, (std::vector<std::uint64_t>{10000, 10001, 10002, 10003, 10004, 10005, 10005 + far + 1}));
  EXPECT_EQ(q.counts().stale, 1u);
  EXPECT_EQ(q.counts().resyncs, 1u);  // forward: a sender's counter may jump ahead (it cannot be forged)
  EXPECT_EQ(q.counts().late, 0u);
  EXPECT_EQ(q.counts().accepted, 8u);
  // The same stream with backward resyncs on (no key): the old sample restarts the stream and is
  // published; the real one resyncs again after it.
  fd::SampleSequencer open(4);
  const auto out2 = run(open, {10000, 10001, 10002, 10003, 10004, 10004 - far, 10005});
  EXPECT_EQ(out2, (std::vector<std::uint64_t>{10000, 10001, 10002, 10003, 10004, 10004 - far, 10005}));
  EXPECT_EQ(open.counts().resyncs, 2u);
  EXPECT_EQ(open.counts().stale, 0u);
}
