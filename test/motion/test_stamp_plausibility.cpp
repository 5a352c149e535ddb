// StampPlausibility (issue 19 part 1): a lone bad stamp is dropped and counted, never bridged nor a
// restart; a new time base needs rebase_samples consistent stamps; a stamp ahead of the clock is
// never used. Stamps at 100 Hz around an epoch-like 1.7e9 s, the clock following them.

#include <gtest/gtest.h>

#include "rocking_monitor/motion/sample_timing.hpp"
#include "rocking_monitor/motion/stamp_plausibility.hpp"

namespace rm = rocking_monitor::core;
using V = rm::StampPlausibility::Verdict;

namespace {

constexpr double kT0 = 1.7e9, kDt = 0.01;

// Feeds the guard as the monitor does: only plausible stamps reach SampleTiming.
struct Feed {
  rm::StampPlausibility guard;
  rm::SampleTiming timing;
  explicit Feed(int rebase = 20) : guard(config(rebase)) {}
  static rm::StampPlausibility::Config config(int rebase) {
    rm::StampPlausibility::Config c;
    c.rebase_samples = rebase;
    return c;
  }
  V push(double t, double now) {
    const V v = guard.check(t, now, timing.started(), timing.last_stamp());
    double dt = 0.0;
    if (v == V::Plausible) timing.classify(t, dt);
    return v;
  }
};

TEST(StampPlausibility, LoneFutureStampIsDroppedAndCountedAndTheNextStepIsTwoPeriods) {
  Feed f;
  for (int k = 0; k < 100; ++k) ASSERT_EQ(f.push(kT0 + k * kDt, kT0 + k * kDt), V::Plausible);
  EXPECT_EQ(f.push(kT0 + 100 * kDt + 1000.0, kT0 + 100 * kDt), V::Rejected);  // +1000 s glitch
  EXPECT_EQ(f.guard.counters().rejected, 1u);
  EXPECT_EQ(f.guard.counters().rejected_future, 1u);
  EXPECT_NEAR(f.guard.counters().last_rejected_jump, 1000.0 + kDt, 1e-6);
  double dt = 0.0;
  ASSERT_EQ(f.guard.check(kT0 + 101 * kDt, kT0 + 101 * kDt, true, f.timing.last_stamp()), V::Plausible);
  EXPECT_EQ(f.timing.classify(kT0 + 101 * kDt, dt), rm::SampleTiming::Verdict::Accept);
  EXPECT_NEAR(dt, 2 * kDt, 1e-6);  // the dropped sample's period, not 1000 s
  EXPECT_EQ(f.timing.counters().backward_jumps, 0u);
}

TEST(StampPlausibility, LoneFarStampIsHeldThenDroppedWhenTheGoodStampsComeBack) {
  // Without a clock (sim time before /clock): max_bridge alone catches it.
  Feed f;
  for (int k = 0; k < 10; ++k) ASSERT_EQ(f.push(kT0 + k * kDt, 0.0), V::Plausible);
  EXPECT_EQ(f.push(kT0 + 10 * kDt + 1000.0, 0.0), V::Held);
  EXPECT_EQ(f.guard.held(), 1);
  EXPECT_EQ(f.guard.counters().rejected, 0u);  // not yet known to be bad
  EXPECT_EQ(f.push(kT0 + 11 * kDt, 0.0), V::Plausible);
  EXPECT_EQ(f.guard.counters().rejected, 1u);
  EXPECT_EQ(f.guard.held(), 0);
}

TEST(StampPlausibility, LoneBackwardStampDoesNotRestart) {
  Feed f;
  for (int k = 0; k < 10; ++k) ASSERT_EQ(f.push(kT0 + k * kDt, kT0 + k * kDt), V::Plausible);
  EXPECT_EQ(f.push(kT0 + 10 * kDt - 1000.0, kT0 + 10 * kDt), V::Held);
  EXPECT_EQ(f.push(kT0 + 11 * kDt, kT0 + 11 * kDt), V::Plausible);
  EXPECT_EQ(f.guard.counters().rejected, 1u);
  EXPECT_NEAR(f.guard.counters().last_rejected_jump, -1000.0 + kDt, 1e-6);
  EXPECT_EQ(f.guard.counters().rebased_backward, 0u);
  EXPECT_EQ(f.timing.counters().backward_jumps, 0u);
}

TEST(StampPlausibility, BurstShorterThanRebaseSamplesIsDroppedWhole) {
  Feed f;
  for (int k = 0; k < 10; ++k) ASSERT_EQ(f.push(kT0 + k * kDt, kT0 + k * kDt), V::Plausible);
  // 19 consistent stamps 50 s late: one short of a new base.
  for (int k = 0; k < 19; ++k) ASSERT_EQ(f.push(kT0 - 50.0 + k * kDt, kT0 + (10 + k) * kDt), V::Held) << k;
  EXPECT_EQ(f.push(kT0 + 29 * kDt, kT0 + 29 * kDt), V::Plausible);
  EXPECT_EQ(f.guard.counters().rejected, 19u);
  EXPECT_EQ(f.guard.counters().rebased_backward + f.guard.counters().rebased_forward, 0u);
}

TEST(StampPlausibility, InconsistentCandidatesNeverConfirmABase) {
  Feed f(3);
  ASSERT_EQ(f.push(kT0, 0.0), V::Plausible);
  // Far stamps that disagree with each other (each more than max_step from the previous): each starts
  // a new run, the previous run is counted as rejected.
  for (int k = 0; k < 10; ++k) EXPECT_EQ(f.push(kT0 + 100.0 * (k + 1), 0.0), V::Held) << k;
  EXPECT_EQ(f.guard.counters().rejected, 9u);
  EXPECT_EQ(f.guard.held(), 1);
}

TEST(StampPlausibility, ConsistentForwardBaseIsAdoptedAfterRebaseSamplesAndItemsContinue) {
  Feed f;
  for (int k = 0; k < 10; ++k) ASSERT_EQ(f.push(kT0 + k * kDt, kT0 + k * kDt), V::Plausible);
  const double base = kT0 + 3600.0;  // the clock was stepped by an hour (sensor and node alike)
  for (int k = 0; k < 19; ++k) ASSERT_EQ(f.push(base + k * kDt, base + k * kDt), V::Held) << k;
  ASSERT_EQ(f.push(base + 19 * kDt, base + 19 * kDt), V::RebaseForward);
  EXPECT_EQ(f.guard.counters().rebased_forward, 1u);
  EXPECT_EQ(f.guard.counters().rejected, 0u);
  EXPECT_DOUBLE_EQ(f.guard.run_first(), base);
  // The caller absorbs the offset: the first held stamp follows the last accepted by one period.
  const double offset = f.guard.run_first() - (f.timing.last_stamp() + kDt);
  f.timing.shift(offset);
  double dt = 0.0;
  EXPECT_EQ(f.timing.classify(base, dt), rm::SampleTiming::Verdict::Accept);
  EXPECT_NEAR(dt, kDt, 1e-6);
  EXPECT_EQ(f.push(base + 20 * kDt, base + 20 * kDt), V::Plausible);  // the new base is the base now
}

TEST(StampPlausibility, ConfirmedBackwardBaseAsksForARestart) {
  Feed f(5);
  for (int k = 0; k < 10; ++k) ASSERT_EQ(f.push(kT0 + k * kDt, 0.0), V::Plausible);
  for (int k = 0; k < 4; ++k) ASSERT_EQ(f.push(kT0 - 7.0 + k * kDt, 0.0), V::Held);  // bag loop
  EXPECT_EQ(f.push(kT0 - 7.0 + 4 * kDt, 0.0), V::RebaseBackward);
  EXPECT_EQ(f.guard.counters().rebased_backward, 1u);
}

TEST(StampPlausibility, FutureCandidatesCanNeverConfirm) {
  Feed f(3);
  ASSERT_EQ(f.push(kT0, kT0), V::Plausible);
  for (int k = 1; k <= 10; ++k) EXPECT_EQ(f.push(kT0 + 3600.0 + k * kDt, kT0 + k * kDt), V::Rejected);
  EXPECT_EQ(f.guard.counters().rejected_future, 10u);
  EXPECT_EQ(f.guard.counters().rebased_forward, 0u);
  // Just inside max_future is fine.
  EXPECT_EQ(f.push(kT0 + 0.5, kT0 + 0.5 - 0.99), V::Plausible);
}

TEST(StampPlausibility, GapWithinMaxBridgeIsLeftToSampleTiming) {
  Feed f;
  ASSERT_EQ(f.push(kT0, 0.0), V::Plausible);
  EXPECT_EQ(f.push(kT0 + 0.5, 0.0), V::Plausible);  // a data gap for SampleTiming (max_gap), counted there
  EXPECT_EQ(f.timing.counters().gaps, 1u);
  EXPECT_EQ(f.push(kT0 + 0.5 + 1.0 + 1e-3, 0.0), V::Held);  // beyond max_bridge: never bridged
  EXPECT_EQ(f.timing.counters().gaps, 1u);
}

// A burst whose stamps were bad but which sat in sequence: the next good stamp is k + 1 periods after
// the last accepted one, so the k samples are re-stamped (still counted as rejected) rather than lost.
TEST(StampPlausibility, RejectedSamplesInSequenceAreRestampedOnlyWhenTheNextStampLeavesExactlyTheirRoom) {
  Feed f;
  for (int k = 0; k < 10; ++k) ASSERT_EQ(f.push(kT0 + k * kDt, kT0 + k * kDt), V::Plausible);
  const double last = f.timing.last_stamp();
  for (int k = 0; k < 5; ++k) ASSERT_EQ(f.push(kT0 - 1000.0 + k * kDt, kT0 + (10 + k) * kDt), V::Held);
  ASSERT_EQ(f.guard.check(kT0 + 15 * kDt, kT0 + 15 * kDt, true, last), V::Plausible);
  EXPECT_EQ(f.guard.counters().rejected, 5u);
  // One period more or fewer than the five (a sample also lost, or one too many): not in sequence.
  EXPECT_FALSE(f.guard.restamp(last, kT0 + 16 * kDt, 5, kDt));
  EXPECT_FALSE(f.guard.restamp(last, kT0 + 14 * kDt, 5, kDt));
  EXPECT_FALSE(f.guard.restamp(last, kT0 + 15.3 * kDt, 5, kDt));  // beyond a quarter period
  EXPECT_FALSE(f.guard.restamp(last, kT0 + 15 * kDt, 5, 0.0));    // no nominal period known
  EXPECT_FALSE(f.guard.restamp(last, kT0 + 11 * kDt, 0, kDt));    // nothing to re-stamp
  EXPECT_EQ(f.guard.counters().restamped, 0u);
  EXPECT_TRUE(f.guard.restamp(last, kT0 + 15.2 * kDt, 5, kDt));   // jitter within a quarter period
  EXPECT_EQ(f.guard.counters().restamped, 5u);
  EXPECT_EQ(f.guard.counters().rejected, 5u) << "re-stamped samples stay counted as rejected stamps";
}

}  // namespace
