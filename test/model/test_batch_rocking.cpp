// BatchRocking (model/batch_rocking.hpp) against the scalar RockingModel, which is its oracle:
// every lane of a batch must give the decisions of a RockingModel stepped alone, with theta after
// every sample and the event times within 1e-9 (bit-identical with BatchTrig::Exact).
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "rocking_monitor/model/batch_rocking.hpp"
#include "rocking_monitor/motion/ground_motion.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "test_helpers.hpp"

#include "allocation_counter.hpp"  // counts heap allocations (replaces operator new)

namespace rocking_monitor::core {
namespace {

using testing::deg;
using testing::rectangle_with;

struct Input {
  std::string name;
  double dt = 0.005;
  std::vector<double> ax, ay;  // ay empty: no vertical
  double ay_at(std::size_t i) const { return ay.empty() ? 0.0 : ay[i]; }
};

Input pulse_csv() {
  Input in{"bags/one_sine_pulse.csv"};
  std::ifstream f(std::string(ROCKING_SOURCE_DIR) + "/bags/one_sine_pulse.csv");
  EXPECT_TRUE(f.good());
  std::string line;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    double t, a;
    if (std::sscanf(line.c_str(), "%lf,%lf", &t, &a) == 2) in.ax.push_back(a);
  }
  // 8 s of free rocking after the pulse (impacts, rest capture).
  in.ax.resize(in.ax.size() + 1600, 0.0);
  return in;
}

Input sine_pulse(double ap, double w, double dt, double t_end, double av = 0.0) {
  const GroundMotion g = testing::one_sine_pulse(ap, w, dt, t_end);
  Input in{"pulse"};
  in.dt = dt;
  in.ax = g.horizontal;
  if (av != 0.0)
    for (std::size_t i = 0; i < in.ax.size(); ++i) in.ay.push_back(av * std::sin(1.7 * w * i * dt));
  return in;
}

bool same_time(double a, double b) { return (std::isnan(a) && std::isnan(b)) || std::abs(a - b) <= 1e-9; }

/// Decisions of one lane vs its oracle; empty when equal.
std::string outcome_diff(const RockingModel& b, const RockingModel& s) {
  const RockingOutcome &x = b.outcome(), &y = s.outcome();
  std::string d;
  auto add = [&](const char* what) { d += std::string(d.empty() ? "" : ",") + what; };
  if (x.beyond_tipping != y.beyond_tipping) add("beyond_tipping");
  if (x.committed != y.committed) add("committed");
  if (x.overturned != y.overturned) add("overturned");
  if (x.impacts != y.impacts) add("impacts");
  if (x.rest_captures != y.rest_captures) add("rest_captures");
  if (b.mode() != s.mode()) add("final_mode");
  if (!same_time(x.uplift_time, y.uplift_time)) add("uplift_time");
  if (!same_time(x.beyond_tipping_time, y.beyond_tipping_time)) add("beyond_tipping_time");
  if (!same_time(x.committed_time, y.committed_time)) add("committed_time");
  if (!same_time(x.overturn_time, y.overturn_time)) add("overturn_time");
  return d;
}

struct Compare {
  long samples_theta_off = 0;   // lane-samples with |theta - oracle| > 1e-9
  long samples_not_bitwise = 0; // lane-samples with theta != oracle
  long report_off = 0;          // lane-samples whose StepReport decisions differ
  long lanes_off = 0;           // lanes whose outcome differs (flags, counts or times)
  long lanes_flags_off = 0;     // lanes whose beyond_tipping / committed / overturned / final mode differ
  long allocations = 0;         // inside batch.step()
  std::vector<std::size_t> lanes_decision_off;  // decisions differ or an event time by > 1e-6 s
  std::vector<std::string> notes;
  BatchStats totals;
};

/// Steps a batch and one RockingModel per lane on the same input, comparing after every sample.
/// theta0[k] != 0: lane k released from rest at that angle (rad) at t = 0.
/// stride > 1: the batch is looked at only every stride-th sample (and at the end), so lanes at
/// rest stay deferred for many samples between looks.
Compare run_compare(const std::vector<BodyParameters>& bodies, const Input& in, BatchTrig trig,
                    const std::vector<double>& theta0 = {}, const SolverSettings& s = {},
                    std::size_t stride = 1) {
  Compare c;
  BatchRocking batch(bodies, s, trig);
  std::vector<RockingModel> oracle;
  for (const BodyParameters& b : bodies) oracle.emplace_back(b, s);
  const std::size_t n = bodies.size();
  batch.reset(0.0, in.ax[0], in.ay_at(0));
  for (std::size_t k = 0; k < n; ++k) {
    oracle[k].reset(0.0, in.ax[0], in.ay_at(0));
    if (!theta0.empty() && theta0[k] != 0.0) {
      batch.model(k).set_state(theta0[k], 0.0);
      oracle[k].set_state(theta0[k], 0.0);
    }
  }
  std::vector<double> ax(n), ay(n);
  for (std::size_t i = 1; i < in.ax.size(); ++i) {
    for (std::size_t k = 0; k < n; ++k) {
      ax[k] = in.ax[i];
      ay[k] = in.ay_at(i);
    }
    const long a0 = rocking_monitor::testing::allocation_count();
    batch.step(ax.data(), ay.data(), in.dt);
    c.allocations += rocking_monitor::testing::allocation_count() - a0;
    const BatchStats& st = batch.stats();
    c.totals.rest_fast += st.rest_fast;
    c.totals.rocking_fast += st.rocking_fast;
    c.totals.scalar += st.scalar;
    c.totals.rocking_fallback += st.rocking_fallback;
    for (std::size_t k = 0; k < n; ++k) {
      const StepReport& r = oracle[k].step(ax[k], ay[k], in.dt);
      if (i % stride != 0 && i + 1 != in.ax.size()) continue;
      const RockingModel& b = batch.model(k);
      const StepReport& q = b.last_report();
      if (b.theta() != oracle[k].theta()) ++c.samples_not_bitwise;
      if (!(std::abs(b.theta() - oracle[k].theta()) <= 1e-9) || b.mode() != oracle[k].mode())
        ++c.samples_theta_off;
      if (q.uplift != r.uplift || q.impacts != r.impacts || q.rest_capture != r.rest_capture ||
          q.overturned != r.overturned || q.beyond_tipping_entered != r.beyond_tipping_entered ||
          q.committed_entered != r.committed_entered || q.violation_onsets != r.violation_onsets)
        ++c.report_off;
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    const RockingModel& bm = batch.model(k);
    if (bm.outcome().beyond_tipping != oracle[k].outcome().beyond_tipping ||
        bm.outcome().committed != oracle[k].outcome().committed ||
        bm.outcome().overturned != oracle[k].outcome().overturned || bm.mode() != oracle[k].mode())
      ++c.lanes_flags_off;
    {
      const RockingOutcome &x = bm.outcome(), &y = oracle[k].outcome();
      auto near = [](double a, double b) { return (std::isnan(a) && std::isnan(b)) || std::abs(a - b) <= 1e-6; };
      if (x.beyond_tipping != y.beyond_tipping || x.committed != y.committed || x.overturned != y.overturned ||
          bm.mode() != oracle[k].mode() || !near(x.uplift_time, y.uplift_time) ||
          !near(x.beyond_tipping_time, y.beyond_tipping_time) || !near(x.committed_time, y.committed_time) ||
          !near(x.overturn_time, y.overturn_time))
        c.lanes_decision_off.push_back(k);
    }
    const std::string d = outcome_diff(bm, oracle[k]);
    if (!d.empty()) {
      ++c.lanes_off;
      if (c.notes.size() < 20) {
        char buf[256];
        std::snprintf(buf, sizeof buf, "%s lane %zu (B=%.4f h=%.4f nu1=%.3f): %s", in.name.c_str(),
                      k, bodies[k].width, bodies[k].cg_height, bodies[k].nu1, d.c_str());
        c.notes.push_back(buf);
      }
    }
  }
  return c;
}

void expect_exact(const Compare& c) {
  for (const std::string& n : c.notes) ADD_FAILURE() << n;
  EXPECT_EQ(c.lanes_off, 0);
  EXPECT_EQ(c.report_off, 0);
  EXPECT_EQ(c.samples_theta_off, 0);
  EXPECT_EQ(c.samples_not_bitwise, 0);  // BatchTrig::Exact: the scalar model's bits
  EXPECT_EQ(c.allocations, 0);
}

// A spread of bodies around the pulse's overturning boundary, both eccentricities.
std::vector<BodyParameters> varied_bodies(std::size_t n, double nu1 = 0.5) {
  std::vector<BodyParameters> out;
  for (std::size_t k = 0; k < n; ++k) {
    BodyParameters b = rectangle_with(1.5 + 2.5 * k / std::max<std::size_t>(n - 1, 1),
                                      deg(6.0 + 14.0 * ((k * 7) % n) / std::max<std::size_t>(n, 1)));
    b.nu1 = nu1;
    out.push_back(b);
  }
  return out;
}

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

// ---------------------------------------------------------------- randomized property test
std::vector<BodyParameters> random_bodies(std::size_t n, std::uint64_t seed) {
  std::uint64_t s = seed;
  auto next = [&]() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  };
  auto uni = [&](double a, double b) { return a + (b - a) * (next() >> 11) * 0x1.0p-53; };
  std::vector<BodyParameters> out(n);
  for (BodyParameters& b : out) {
    b.width = uni(0.1, 1.0);
    b.cg_height = uni(0.2, 1.5);
    b.nu1 = uni(0.25, 0.75);
  }
  return out;
}

std::vector<Input> property_inputs() {
  std::vector<Input> out{pulse_csv()};
  for (const char* file : {"northridge_1994/Rinaldi228.AT2", "landers_1992/RSN879_LANDERS_LCN345.AT2"}) {
    GroundMotion g;
    if (!testing::first_horizontal(file, g)) continue;
    Input in{file};
    in.dt = g.dt;
    in.ax = g.horizontal;
    out.push_back(in);
  }
  return out;
}

// The property test: 10,000 random bodies x 3 inputs (about 20 s in Release); under the
// sanitizers 2,000 of the same bodies.
constexpr int kPropertyBodies = testing::kUnderSanitizers ? 2000 : 10000;

TEST(BatchRocking, RandomBodiesTimesThreeInputsSameDecisions) {
  const std::vector<BodyParameters> bodies = random_bodies(kPropertyBodies, 2024);
  const double n = kPropertyBodies;
  for (const Input& in : property_inputs()) {
    // Looked at every 37th sample: lanes at rest stay deferred in between.
    const Compare c = run_compare(bodies, in, BatchTrig::Exact, {}, SolverSettings{}, 37);
    std::printf("[ batch  ] %s: %d bodies, exact trig: %ld lanes differ, %ld lane-samples not bitwise; "
                "per lane-sample rest_fast %.3f rocking_fast %.3f scalar %.3f (rocking fallback %.4f)\n",
                in.name.c_str(), kPropertyBodies, c.lanes_off, c.samples_not_bitwise,
                double(c.totals.rest_fast) / (n * (in.ax.size() - 1)),
                double(c.totals.rocking_fast) / (n * (in.ax.size() - 1)),
                double(c.totals.scalar) / (n * (in.ax.size() - 1)),
                double(c.totals.rocking_fallback) / (n * (in.ax.size() - 1)));
    expect_exact(c);
  }
}

TEST(BatchRocking, OtherSettingsAreSteppedByTheScalarModel) {
  // rk4, analytic and the linearized model have no vector path for rocking lanes; their rest lanes
  // still use the (model-specific) uplift test and deferral.
  const Input in = pulse_csv();
  SolverSettings lin;
  lin.model = ModelKind::Linearized;
  SolverSettings rk4;
  rk4.method = Method::Rk4;
  SolverSettings ana;
  ana.method = Method::Analytic;
  ana.model = ModelKind::Linearized;
  for (const SolverSettings& s : {lin, rk4, ana}) {
    SCOPED_TRACE(to_string(s.method) + std::string(" ") + to_string(s.model));
    const Compare c = run_compare(varied_bodies(23), in, BatchTrig::Exact, {}, s, 7);
    expect_exact(c);
    EXPECT_GT(c.totals.rest_fast, 0u);
    EXPECT_EQ(c.totals.rocking_fast, 0u);
  }
}

TEST(BatchRocking, TenThousandLanesOnTheBundledPulse) {
  const Compare c = run_compare(random_bodies(10000, 99), pulse_csv(), BatchTrig::Exact, {},
                                SolverSettings{}, 61);
  expect_exact(c);
  EXPECT_GT(c.totals.rocking_fast, 0u);
}

// Every SIMD target compiled in (AVX-512, AVX2, SSE4, ..., and the emulated 128-bit / scalar
// fallback) gives the scalar model's bits with exact trig: the portable path answers the same.
TEST(BatchRocking, EverySimdTargetGivesTheSameBits) {
  const std::vector<BodyParameters> bodies = random_bodies(300, 77);
  std::vector<Input> inputs = property_inputs();
  inputs.resize(std::min<std::size_t>(inputs.size(), 2));
  int targets = 0;
  for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    std::printf("[ batch  ] SIMD target %s (batch reports %s)\n", hwy::TargetName(target),
                BatchRocking::simd_target());
    EXPECT_STREQ(BatchRocking::simd_target(), hwy::TargetName(target));
    for (const Input& in : inputs) {
      SCOPED_TRACE(std::string(hwy::TargetName(target)) + " " + in.name);
      expect_exact(run_compare(bodies, in, BatchTrig::Exact, {}, SolverSettings{}, 13));
    }
    ++targets;
  }
  hwy::SetSupportedTargetsForTest(0);  // back to the machine's own
  EXPECT_GE(targets, 2);
}

// The accuracy policy's judgement of one body (docs/performance.md, rocking_accuracy policy): its
// decisions and event times from a run over the input.
struct Judged {
  bool beyond = false, committed = false, overturned = false;
  Mode mode = Mode::Rest;
  double uplift = NAN, beyond_t = NAN, committed_t = NAN, overturn_t = NAN;  // s
  bool operator==(const Judged& o) const {
    auto near = [](double a, double b) { return (std::isnan(a) && std::isnan(b)) || std::abs(a - b) <= 1e-6; };
    return beyond == o.beyond && committed == o.committed && overturned == o.overturned && mode == o.mode &&
           near(uplift, o.uplift) && near(beyond_t, o.beyond_t) && near(committed_t, o.committed_t) &&
           near(overturn_t, o.overturn_t);
  }
};

Judged judge(const RockingModel& m) {
  const RockingOutcome& o = m.outcome();
  return {o.beyond_tipping, o.committed, o.overturned, m.mode(), o.uplift_time, o.beyond_tipping_time,
          o.committed_time, o.overturn_time};
}

// One body over the input made `fine` times finer (the same piecewise-linear signal).
Judged judge_run(const BodyParameters& body, const SolverSettings& s, const Input& in, int fine) {
  RockingModel m(body, s);
  m.reset(0.0, in.ax[0], in.ay_at(0));
  for (std::size_t i = 1; i < in.ax.size(); ++i)
    for (int j = 1; j <= fine; ++j) {
      const double f = static_cast<double>(j) / fine;
      m.step(in.ax[i - 1] + f * (in.ax[i] - in.ax[i - 1]), in.ay_at(i - 1) + f * (in.ay_at(i) - in.ay_at(i - 1)),
             in.dt / fine);
    }
  return judge(m);
}

// The fast trigonometry (Highway Sin/Cos, the batch's default) is not bit-identical. Under the
// accuracy policy a lane whose decisions or event times (1e-6 s) differ from the scalar tol-1e-8
// run's is judged against a converged reference (dopri5 1e-12 and rk4 x16, both on the input 8x
// finer, agreeing): it fails when the scalar run is right and the fast lane is not. Cases where
// the two references disagree are chaotic (counted, printed, not judged).
constexpr int kPolicyBodies = testing::kUnderSanitizers ? 400 : 2000;  // the first 400 of the same bodies

TEST(BatchRocking, FastTrigMeetsTheAccuracyPolicy) {
  const std::vector<BodyParameters> bodies = random_bodies(kPolicyBodies, 2024);
  SolverSettings ref, check;
  ref.tol = 1e-12;
  check.method = Method::Rk4;
  check.substeps = 16;
  long differing = 0, chaotic = 0, judged_right = 0;
  for (const Input& in : property_inputs()) {
    const Compare c = run_compare(bodies, in, BatchTrig::Fast);
    BatchRocking fast(bodies, SolverSettings{}, BatchTrig::Fast);
    fast.reset(0.0, in.ax[0], in.ay_at(0));
    for (std::size_t i = 1; i < in.ax.size(); ++i) fast.step_all(in.ax[i], in.ay_at(i), in.dt);
    for (std::size_t k : c.lanes_decision_off) {
      ++differing;
      const Judged r = judge_run(bodies[k], ref, in, 8);
      if (!(r == judge_run(bodies[k], check, in, 8))) {
        ++chaotic;
        continue;
      }
      const bool scalar_right = judge_run(bodies[k], SolverSettings{}, in, 1) == r;
      const bool fast_right = judge(fast.model(k)) == r;
      EXPECT_TRUE(fast_right || !scalar_right) << in.name << " lane " << k << ": the fast lane is wrong where the "
                                               << "scalar run is right";
      judged_right += fast_right;
    }
    std::printf("[ batch  ] %s: %d bodies, fast trig: %ld lanes differ in beyond_tipping / "
                "committed / overturned / final mode, %ld lanes in any outcome field (impacts, "
                "event times > 1e-9 s), %ld lane-samples with |theta diff| > 1e-9 or another "
                "mode, %ld step reports differ\n",
                in.name.c_str(), kPolicyBodies, c.lanes_flags_off, c.lanes_off, c.samples_theta_off, c.report_off);
    for (const std::string& n : c.notes) std::printf("[ batch  ]   %s\n", n.c_str());
    EXPECT_EQ(c.allocations, 0);
  }
  std::printf("[ batch  ] policy: %ld lanes decided differently from the scalar run: %ld chaotic, %ld with the fast "
              "lane right\n", differing, chaotic, judged_right);
}

}  // namespace
}  // namespace rocking_monitor::core
