// BatchRocking (model/batch_rocking.hpp) against the scalar RockingModel, which is its oracle:
// every lane of a batch must give the decisions of a RockingModel stepped alone, with theta after
// every sample and the event times within 1e-9 (bit-identical with BatchTrig::Exact).
// Randomized bodies, the SIMD targets and the accuracy policy: test_batch_rocking_properties.cpp.
#include <gtest/gtest.h>

#include "allocation_counter.hpp"  // counts heap allocations (replaces operator new)

#include "batch_rocking_fixtures.hpp"

namespace rocking_monitor::core {
namespace {

using testing::deg;
using testing::rectangle_with;

TEST(BatchRocking, BundledPulseEveryLaneEqualsTheScalarModel) {
  const Input in = pulse_csv();
  const Compare c = run_compare(varied_bodies(40), in, BatchTrig::Exact);
  expect_exact(c);
  EXPECT_GT(c.totals.rocking_fast, 0u);  // the vector path did run
  EXPECT_GT(c.totals.rest_fast, 0u);
}

TEST(BatchRocking, PulsesNearTheOverturningBoundary) {
  // test_pulse_overturning's case: p = 2.5, alpha = 12 deg, w_p = 2p; amplitudes straddling the
  // closed-form minimum (2.350 alpha g) and above, where impacts come first.
  const double p = 2.5, alpha = deg(12), w = 2.0 * p, tp = 2.0 * kPi / w;
  std::vector<BodyParameters> bodies(1, rectangle_with(p, alpha));
  for (double ratio : {2.2, 2.34, 2.35, 2.36, 2.5, 3.0, 4.0}) {
    const Input in = sine_pulse(ratio * alpha * kGravity, w, 0.005, tp + 6.0);
    SCOPED_TRACE(ratio);
    expect_exact(run_compare(bodies, in, BatchTrig::Exact));
  }
}

TEST(BatchRocking, FreeRockingImpactsAndRestCapture) {
  std::vector<BodyParameters> bodies;
  std::vector<double> theta0;
  for (int k = 0; k < 9; ++k) {
    bodies.push_back(rectangle_with(2.0, deg(15)));
    theta0.push_back((k % 2 ? -1.0 : 1.0) * deg(15) * (0.1 + 0.1 * k));
  }
  Input in{"free"};
  in.ax.assign(2400, 0.0);  // 12 s: every lane comes to rest
  const Compare c = run_compare(bodies, in, BatchTrig::Exact, theta0);
  expect_exact(c);
}

// Where the tolerance binds (as in rocking_accuracy work-precision at 50 Hz; here 50 and 20 Hz
// inputs, tol 1e-3 ... 1e-12): several dopri5 steps per sample, which the 200 Hz inputs at the
// default tolerance above hardly need. Same bits as the scalar model.
TEST(BatchRocking, CoarseInputsAndBindingTolerancesGiveTheScalarBits) {
  std::vector<BodyParameters> bodies;
  std::vector<double> theta0;
  for (int k = 0; k < 11; ++k) {
    bodies.push_back(rectangle_with(2.0 + 0.6 * k, deg(10.0 + 0.5 * k)));  // p up to 8 rad/s
    theta0.push_back((k % 2 ? -1.0 : 1.0) * deg(10.0) * (0.2 + 0.07 * k));
  }
  for (double dt : {0.02, 0.05}) {
    Input free{"free"};
    free.dt = dt;
    free.ax.assign(static_cast<std::size_t>(6.0 / dt), 0.0);
    const double w = 5.0, tp = 2.0 * kPi / w;
    const Input pulse = sine_pulse(0.5 * kGravity, w, dt, tp + 5.0);
    for (double tol : {1e-3, 1e-6, 1e-10, 1e-12}) {
      SolverSettings s;
      s.tol = tol;
      SCOPED_TRACE(std::to_string(dt) + " s, tol " + std::to_string(tol));
      const Compare cf = run_compare(bodies, free, BatchTrig::Exact, theta0, s);
      expect_exact(cf);
      EXPECT_GT(cf.totals.rocking_fast, 0u);  // the vector kernel did step clean samples
      expect_exact(run_compare(bodies, pulse, BatchTrig::Exact, {}, s));
    }
  }
  // The tolerance does bind there: the stiffest body takes several steps per 50 ms sample.
  SolverSettings tight;
  tight.tol = 1e-10;
  RockingModel m(bodies.back(), tight);
  m.reset(0.0);
  m.set_state(theta0.back(), 0.0);
  for (int i = 0; i < 40; ++i) m.step(0.0, 0.0, 0.05);
  EXPECT_GT(static_cast<double>(m.outcome().integrator_steps) / 40.0, 2.0);
}

TEST(BatchRocking, EccentricBodiesAndVerticalAcceleration) {
  const double w = 5.0, tp = 2.0 * kPi / w;
  for (double av : {0.0, 0.3 * kGravity}) {
    const Input in = sine_pulse(0.45 * kGravity, w, 0.005, tp + 5.0, av);
    SCOPED_TRACE(av);
    expect_exact(run_compare(varied_bodies(17, 0.3), in, BatchTrig::Exact));
  }
}

// Ten lanes under one pulse: slender lanes overturn, squat lanes stay at rest, released lanes
// (theta0 != 0) rock from t = 0.
struct MixedLanes {
  Input in;
  std::vector<BodyParameters> all;
  std::vector<double> theta0;  // rad
};

MixedLanes mixed_lanes() {
  const double w = 5.0, tp = 2.0 * kPi / w;
  MixedLanes m{sine_pulse(0.5 * kGravity, w, 0.005, tp + 4.0), {}, {}};
  for (int k = 0; k < 10; ++k) {
    m.all.push_back(rectangle_with(2.0 + 0.2 * k, deg(k % 3 == 0 ? 40.0 : 8.0 + k)));
    m.theta0.push_back(k % 4 == 1 ? deg(3.0) : 0.0);
  }
  return m;
}

TEST(BatchRocking, BatchSizesAndMixedModesGiveTheSamePerLaneResults) {
  const MixedLanes m = mixed_lanes();
  const Input& in = m.in;
  const std::vector<BodyParameters>& all = m.all;
  const std::vector<double>& theta0 = m.theta0;
  for (std::size_t n : {1u, 7u, 8u, 9u, 10u}) {
    SCOPED_TRACE(n);
    std::vector<BodyParameters> b(all.begin(), all.begin() + n);
    std::vector<double> t0(theta0.begin(), theta0.begin() + n);
    const Compare c = run_compare(b, in, BatchTrig::Exact, t0);
    expect_exact(c);
  }
  // All three modes did occur in the 10-lane batch.
  BatchRocking batch(all, SolverSettings{});
  batch.reset(0.0, in.ax[0]);
  for (std::size_t k = 0; k < all.size(); ++k)
    if (theta0[k] != 0.0) batch.model(k).set_state(theta0[k], 0.0);
  bool seen_rest = false, seen_rocking = false, seen_over = false;
  for (std::size_t i = 1; i < in.ax.size(); ++i) {
    batch.step_all(in.ax[i], 0.0, in.dt);
    for (std::size_t k = 0; k < all.size(); ++k) {
      seen_rest |= batch.model(k).mode() == Mode::Rest;
      seen_rocking |= batch.model(k).mode() == Mode::Rocking;
    }
    if (seen_rocking && seen_rest) {
      for (std::size_t k = 0; k < all.size(); ++k) seen_over |= batch.model(k).mode() == Mode::Overturned;
    }
  }
  EXPECT_TRUE(seen_rest && seen_rocking && seen_over);
}

// With the default (fast) trig too, a lane's result does not depend on the other lanes: the same
// body gives the same bits alone (a batch of one) and in a 10-lane batch where other lanes rest,
// rock and overturn (vector positions, compaction and the scalar tail differ).
TEST(BatchRocking, FastTrigLanesOfEveryModeStayIndependent) {
  const MixedLanes m = mixed_lanes();
  const Input& in = m.in;
  const std::vector<BodyParameters>& all = m.all;
  const std::vector<double>& theta0 = m.theta0;
  auto run = [&](const std::vector<std::size_t>& lanes) {
    std::vector<BodyParameters> b;
    for (std::size_t k : lanes) b.push_back(all[k]);
    BatchRocking batch(b, SolverSettings{}, BatchTrig::Fast);
    batch.reset(0.0, in.ax[0]);
    for (std::size_t j = 0; j < lanes.size(); ++j)
      if (theta0[lanes[j]] != 0.0) batch.model(j).set_state(theta0[lanes[j]], 0.0);
    std::vector<std::vector<double>> theta(lanes.size());
    for (std::size_t i = 1; i < in.ax.size(); ++i) {
      batch.step_all(in.ax[i], 0.0, in.dt);
      for (std::size_t j = 0; j < lanes.size(); ++j) theta[j].push_back(batch.model(j).theta());
    }
    std::vector<Mode> modes;
    for (std::size_t j = 0; j < lanes.size(); ++j) modes.push_back(batch.model(j).mode());
    return std::make_pair(theta, modes);
  };
  const auto together = run({0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  int rest = 0, over = 0, rocked = 0;
  for (std::size_t k = 0; k < all.size(); ++k) {
    SCOPED_TRACE(k);
    const auto alone = run({k});
    ASSERT_EQ(alone.first[0].size(), together.first[k].size());
    for (std::size_t i = 0; i < alone.first[0].size(); ++i)
      ASSERT_TRUE(alone.first[0][i] == together.first[k][i]) << "sample " << i + 1;
    EXPECT_EQ(alone.second[0], together.second[k]);
    rest += together.second[k] == Mode::Rest;
    over += together.second[k] == Mode::Overturned;
    for (double t : together.first[k]) rocked += t != 0.0;
  }
  EXPECT_GT(rest, 0);  // the batch held every mode
  EXPECT_GT(over, 0);
  EXPECT_GT(rocked, 0);
}

TEST(BatchRocking, DeferredRestLanesCatchUpExactly) {
  // A weak input: no lane lifts; looked at only at the end, every lane must equal the oracle's
  // time, last inputs and sample count (the deferred samples applied at once).
  const Input in = sine_pulse(0.02 * kGravity, 4.0, 0.005, 20.0);
  const Compare c = run_compare(varied_bodies(9), in, BatchTrig::Exact, {}, SolverSettings{}, 1000000);
  expect_exact(c);
  BatchRocking batch(varied_bodies(9), SolverSettings{});
  RockingModel oracle(varied_bodies(9)[4], SolverSettings{});
  for (std::size_t i = 1; i < in.ax.size(); ++i) {
    batch.step_all(in.ax[i], 0.0, in.dt);
    oracle.step(in.ax[i], 0.0, in.dt);
  }
  EXPECT_EQ(batch.stats().rest_fast, 9u);
  EXPECT_EQ(batch.model(4).time(), oracle.time());
  EXPECT_EQ(batch.model(4).last_ax(), oracle.last_ax());
  EXPECT_EQ(batch.model(4).outcome().samples, oracle.outcome().samples);
}

TEST(BatchRocking, DeferredRockingLanesCatchUpExactlyWhenRead) {
  // Free rocking (released tilted, no input): most samples are clean and stay in the lanes. Lanes
  // read at irregular samples (const model(k): catch-up without re-reading every mirror) must equal
  // the oracle then, in state, controller, counters, maximum and the last sample's report.
  const std::vector<BodyParameters> bodies = varied_bodies(37);
  BatchRocking batch(bodies, SolverSettings{}, BatchTrig::Exact);
  std::vector<RockingModel> oracle;
  for (const BodyParameters& b : bodies) oracle.emplace_back(b, SolverSettings{});
  batch.reset(0.0);
  for (RockingModel& m : oracle) m.reset(0.0);
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const double th = 0.6 * oracle[k].body().pivot(1).alpha * (k % 2 == 0 ? 1.0 : -1.0);
    batch.model(k).set_state(th, 0.0);
    oracle[k].set_state(th, 0.0);
  }
  const BatchRocking& view = batch;
  long kept = 0, compared = 0;
  for (int i = 1; i <= 1500; ++i) {
    batch.step_all(0.0, 0.0, 0.005);
    for (RockingModel& m : oracle) m.step(0.0, 0.0, 0.005);
    kept += static_cast<long>(batch.stats().rocking_fast);
    for (std::size_t k = static_cast<std::size_t>(i) % 13; k < bodies.size(); k += 13) {
      if (i % 29 != 0) continue;
      SCOPED_TRACE(::testing::Message() << "lane " << k << " sample " << i);
      const RockingModel& b = view.model(k);
      ++compared;
      EXPECT_EQ(outcome_diff(b, oracle[k]), "");
      EXPECT_EQ(b.theta(), oracle[k].theta());
      EXPECT_EQ(b.omega(), oracle[k].omega());
      EXPECT_EQ(b.time(), oracle[k].time());
      EXPECT_EQ(b.dopri5().step_size(), oracle[k].dopri5().step_size());
      EXPECT_EQ(b.outcome().samples, oracle[k].outcome().samples);
      EXPECT_EQ(b.outcome().integrator_steps, oracle[k].outcome().integrator_steps);
      EXPECT_EQ(b.outcome().max_rotation_ratio, oracle[k].outcome().max_rotation_ratio);
      EXPECT_EQ(b.last_report().integrator_steps, oracle[k].last_report().integrator_steps);
    }
  }
  EXPECT_GT(kept, 10000);  // the vector path carried most rocking samples
  EXPECT_GT(compared, 50);
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(outcome_diff(batch.model(k), oracle[k]), "");
    EXPECT_EQ(batch.model(k).mode(), oracle[k].mode());
    EXPECT_EQ(batch.model(k).theta(), oracle[k].theta());
  }
}

TEST(BatchRocking, SettingUpOneLaneMidRunKeepsTheOthersDeferredSamples) {
  // Lanes at rest accumulate deferred samples; then one lane is taken for set-up (non-const
  // model(k): every mirror is re-read at the next step) and released again.
  const std::vector<BodyParameters> bodies = varied_bodies(50);
  const Input in = pulse_csv();
  BatchRocking batch(bodies, SolverSettings{}, BatchTrig::Exact);  // bit for bit: the exact path
  std::vector<RockingModel> oracle;
  for (const BodyParameters& b : bodies) oracle.emplace_back(b, SolverSettings{});
  batch.reset(0.0, in.ax[0]);
  for (RockingModel& m : oracle) m.reset(0.0, in.ax[0]);
  for (std::size_t i = 1; i < in.ax.size(); ++i) {
    if (i == 300) {
      batch.model(7).set_state(0.01, 0.0);
      oracle[7].set_state(0.01, 0.0);
    }
    batch.step_all(in.ax[i], 0.0, in.dt);
    for (RockingModel& m : oracle) m.step(in.ax[i], 0.0, in.dt);
  }
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(outcome_diff(batch.model(k), oracle[k]), "");
    EXPECT_EQ(batch.model(k).theta(), oracle[k].theta());
    EXPECT_EQ(batch.model(k).time(), oracle[k].time());
    EXPECT_EQ(batch.model(k).outcome().samples, oracle[k].outcome().samples);
    EXPECT_EQ(batch.model(k).outcome().integrator_steps, oracle[k].outcome().integrator_steps);
    EXPECT_EQ(batch.model(k).outcome().max_rotation_ratio, oracle[k].outcome().max_rotation_ratio);
  }
}

TEST(BatchRocking, InvalidSampleThrowsAndStepsNothing) {
  BatchRocking batch(varied_bodies(3), SolverSettings{});
  const double ax[3] = {0.0, NAN, 0.0}, ay[3] = {0.0, 0.0, 0.0};
  EXPECT_THROW(batch.step(ax, ay, 0.005), std::invalid_argument);
  EXPECT_EQ(batch.model(0).outcome().samples, 0);
}

}  // namespace
}  // namespace rocking_monitor::core
