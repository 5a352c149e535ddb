#pragma once
// What the batch engine tests (test_batch_rocking*.cpp) share: the inputs, one batch run compared
// lane by lane with the scalar RockingModel (Compare), its exact-match check, a spread of bodies.

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
#include "allocation_count.hpp"  // Compare counts the heap allocations inside batch.step()

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

inline Input pulse_csv() {
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

inline Input sine_pulse(double ap, double w, double dt, double t_end, double av = 0.0) {
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
inline Compare run_compare(const std::vector<BodyParameters>& bodies, const Input& in, BatchTrig trig,
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

inline void expect_exact(const Compare& c) {
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

}  // namespace
}  // namespace rocking_monitor::core
