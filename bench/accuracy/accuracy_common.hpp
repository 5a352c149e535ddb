#pragma once
// What the parts of rocking_accuracy share: one run of a body summarised (Run), timed runs, the
// reference run, the error measures, CSV number format, a thread pool loop and the study bodies.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "bench_common.hpp"
#include "command_line.hpp"
#include "progress_meter.hpp"
#include "rocking_monitor/model/batch_rocking.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/physics/principal_planes.hpp"

namespace rocking_monitor::bench::accuracy {

namespace rb = rocking_monitor::bench;
using namespace rocking_monitor::core;  // NOLINT(google-build-using-namespace): as in every bench file

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kRefUpsample = 8;
constexpr double kRefTol = 1e-12;
constexpr std::size_t kImpactsCompared = 10;

// ------------------------------------------------------------------ one run, summarised
struct Run {
  std::vector<int> impacts;        // per input sample
  std::vector<double> first_impact;  // per input sample (NaN if none)
  std::vector<double> peak;          // per input sample: largest located peak of |theta|/alpha
  RockingOutcome outcome;
  double rest_time = kNaN;  // end of the first sample after which a rocking body was at rest
  double seconds = 0.0;     // wall time of one run
  int max_steps = 0;        // most integrator steps in one sample
  int max_impacts = 0;      // most impacts in one sample
  double duration = 0.0;    // simulated seconds
  std::size_t stepped = 0;  // input samples stepped (fewer than the input's after an overturn)
  double final_theta = 0.0;
};

inline GroundMotion upsample(const GroundMotion& g, int factor) {
  GroundMotion r = rb::resample(g, g.dt / factor);
  // resample() floors the sample count; make sure the last original sample is there.
  const std::size_t want = (g.size() - 1) * static_cast<std::size_t>(factor) + 1;
  r.horizontal.resize(want, g.horizontal.back());
  r.horizontal.back() = g.horizontal.back();
  if (!g.vertical.empty()) {
    r.vertical.resize(want, g.vertical.back());
    r.vertical.back() = g.vertical.back();
  }
  return r;
}

/// Summarises stepping one lane over `g` (already reset to g.t0 and released), every `group`
/// samples as one (so a run on an upsampled input reports on the original sample grid). `lane`
/// has step(ax, ay, dt) -> const StepReport&, mode(), outcome() and theta(): a RockingModel, or
/// one lane of a BatchRocking.
template <class Lane>
inline Run summarise(Lane& lane, const GroundMotion& g, int group) {
  Run r;
  const std::size_t n = g.size();
  const std::size_t groups = (n - 1) / static_cast<std::size_t>(group);
  r.impacts.assign(groups, 0);
  r.first_impact.assign(groups, kNaN);
  r.peak.assign(groups, 0.0);
  bool was_rocking = lane.mode() == Mode::Rocking;
  std::vector<int> steps(groups, 0);
  for (std::size_t i = 1; i < n; ++i) {
    const StepReport& rep = lane.step(g.horizontal[i], g.ay(i), g.dt);
    r.stepped = i;
    const std::size_t k = std::min((i - 1) / static_cast<std::size_t>(group), groups - 1);
    if (rep.impacts > 0 && std::isnan(r.first_impact[k])) r.first_impact[k] = rep.first_impact_time;
    r.impacts[k] += rep.impacts;
    r.peak[k] = std::max(r.peak[k], rep.peak_ratio);
    steps[k] += rep.integrator_steps;
    if (lane.mode() == Mode::Rocking) was_rocking = true;
    if (was_rocking && lane.mode() == Mode::Rest && std::isnan(r.rest_time)) {
      r.rest_time = g.t0 + static_cast<double>(k + 1) * g.dt * group;
    }
    if (lane.mode() == Mode::Overturned) break;
  }
  r.outcome = lane.outcome();
  r.final_theta = lane.theta();
  r.max_steps = *std::max_element(steps.begin(), steps.end());
  r.max_impacts = *std::max_element(r.impacts.begin(), r.impacts.end());
  r.duration = g.dt * static_cast<double>(n - 1);
  return r;
}

/// Runs one item over `g` (optionally released at theta0); see summarise() for `group`.
inline Run run_once(const BodyParameters& body, const SolverSettings& s, const GroundMotion& g,
             double theta0, int group = 1) {
  RockingModel m(body, s);
  m.reset(g.t0, g.horizontal[0], g.ay(0));
  if (theta0 != 0.0) m.set_state(theta0, 0.0);
  return summarise(m, g, group);
}

/// Thread CPU time of stepping one item over `g` (nothing else in the loop), s.
inline double time_once(const BodyParameters& body, const SolverSettings& s, const GroundMotion& g,
                 double theta0) {
  RockingModel m(body, s);
  const double t0 = rb::thread_cpu_seconds();
  m.reset(g.t0, g.horizontal[0], g.ay(0));
  if (theta0 != 0.0) m.set_state(theta0, 0.0);
  for (std::size_t i = 1; i < g.size() && m.mode() != Mode::Overturned; ++i)
    m.step(g.horizontal[i], g.ay(i), g.dt);
  return rb::thread_cpu_seconds() - t0;
}

/// The best of 5 batches of `once()` (seconds), each repeated until it takes at least
/// min_seconds (the minimum filters out interference from other processes).
template <class Once>
inline double best_time(Once once, double min_seconds = 0.01) {
  double best = std::numeric_limits<double>::infinity();
  for (int batch = 0; batch < 5; ++batch) {
    int reps = 0;
    double total = 0.0;
    do {
      total += once();
      ++reps;
    } while (total < min_seconds && reps < 1000);
    best = std::min(best, total / reps);
  }
  return best;
}

/// run_once() plus its cost (best_time of pure stepping).
inline Run run_timed(const BodyParameters& body, const SolverSettings& s, const GroundMotion& g,
              double theta0) {
  Run r = run_once(body, s, g, theta0);  // also warms the caches
  r.seconds = best_time([&] { return time_once(body, s, g, theta0); });
  return r;
}

inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Field by field (the struct has padding bytes), doubles bit for bit.
inline bool same_outcome(const RockingOutcome& a, const RockingOutcome& b) {
  return a.beyond_tipping == b.beyond_tipping && a.committed == b.committed &&
         a.overturned == b.overturned && same_bits(a.max_rotation_ratio, b.max_rotation_ratio) &&
         a.max_rotation_side == b.max_rotation_side && a.impacts == b.impacts &&
         a.rest_captures == b.rest_captures && a.forced_rest_captures == b.forced_rest_captures &&
         a.integrator_steps == b.integrator_steps && a.samples == b.samples &&
         same_bits(a.uplift_time, b.uplift_time) &&
         same_bits(a.beyond_tipping_time, b.beyond_tipping_time) &&
         same_bits(a.committed_time, b.committed_time) && same_bits(a.overturn_time, b.overturn_time);
}

/// Lane 0 of a batch whose lanes all share the input, seen as one model (summarise()). Reading
/// lane 0 after each sample brings only that lane up to date; the other lanes run as in a
/// catalogue (deferred rest included).
struct BatchLane {
  BatchRocking& batch;
  const StepReport& step(double ax, double ay, double dt) {
    batch.step_all(ax, ay, dt);
    return batch.report(0);
  }
  Mode mode() const { return std::as_const(batch).model(0).mode(); }
  const RockingOutcome& outcome() const { return std::as_const(batch).model(0).outcome(); }
  double theta() const { return std::as_const(batch).model(0).theta(); }
};

inline void release(BatchRocking& batch, const GroundMotion& g, double theta0) {
  batch.reset(g.t0, g.horizontal[0], g.ay(0));
  if (theta0 != 0.0)
    for (std::size_t k = 0; k < batch.size(); ++k) batch.model(k).set_state(theta0, 0.0);
}

/// The same case through BatchRocking with `lanes` identical lanes: lane 0's run and the cost
/// per lane (the batch's time / lanes, so that the cost is the amortized one of a full batch).
/// The timed loop steps as many samples as the summarised run did (it stops at an overturn).
/// `lanes_differing`: lanes whose final outcome or theta is not lane 0's, bit for bit.
inline Run run_batch_timed(const BodyParameters& body, const SolverSettings& s, const GroundMotion& g,
                    double theta0, BatchTrig trig, std::size_t lanes, long& lanes_differing) {
  BatchRocking batch(std::vector<BodyParameters>(lanes, body), s, trig);
  release(batch, g, theta0);
  BatchLane lane{batch};
  Run r = summarise(lane, g, 1);
  lanes_differing = 0;
  for (std::size_t k = 1; k < lanes; ++k) {
    const RockingModel& m = std::as_const(batch).model(k);
    lanes_differing += !same_outcome(m.outcome(), r.outcome) || !same_bits(m.theta(), r.final_theta);
  }
  r.seconds = best_time([&] {
                const double t0 = rb::thread_cpu_seconds();
                release(batch, g, theta0);
                for (std::size_t i = 1; i <= r.stepped; ++i)
                  batch.step_all(g.horizontal[i], g.ay(i), g.dt);
                return rb::thread_cpu_seconds() - t0;
              }) /
              static_cast<double>(lanes);
  return r;
}

/// What differs, bit for bit, between two summarised runs of the same case (empty: nothing):
/// every per-sample impact count, first impact time and peak, the outcome and the final theta.
inline std::string bitwise_difference(const Run& a, const Run& b) {
  auto same = [](const auto& x, const auto& y) {
    return x.size() == y.size() &&
           (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof x[0]) == 0);
  };
  std::string d;
  auto add = [&](const char* what) { d += std::string(d.empty() ? "" : ", ") + what; };
  if (!same(a.impacts, b.impacts)) add("impacts per sample");
  if (!same(a.first_impact, b.first_impact)) add("impact times");
  if (!same(a.peak, b.peak)) add("peaks");
  if (!same_outcome(a.outcome, b.outcome)) add("outcome");
  if (!same_bits(a.final_theta, b.final_theta)) add("final theta");
  if (a.stepped != b.stepped) add("samples stepped");
  return d;
}

inline Run reference_run(const BodyParameters& body, ModelKind model, const GroundMotion& g, double theta0) {
  SolverSettings s;
  s.method = Method::Dopri5;
  s.model = model;
  s.tol = kRefTol;
  return run_once(body, s, upsample(g, kRefUpsample), theta0, kRefUpsample);
}

inline std::vector<double> impact_list(const Run& r, std::size_t max_count) {
  std::vector<double> out;
  for (double t : r.first_impact) {
    if (std::isnan(t)) continue;
    out.push_back(t);
    if (out.size() == max_count) break;
  }
  return out;
}

/// Worst distance between the first impacts of the two runs (each impact to the nearest of the
/// other run, both ways), over the reference's first kImpactsCompared impact samples. NaN when
/// neither run has an impact; +inf when only one does.
inline double impact_time_error(const Run& r, const Run& ref) {
  const std::vector<double> a = impact_list(ref, kImpactsCompared);
  std::vector<double> b = impact_list(r, kImpactsCompared + 5);
  if (a.empty() && b.empty()) return kNaN;
  if (a.empty() || b.empty()) return std::numeric_limits<double>::infinity();
  const double horizon = a.back() + 1e-9;
  b.erase(std::remove_if(b.begin(), b.end(), [&](double t) { return t > horizon + 0.05; }), b.end());
  auto nearest = [](const std::vector<double>& v, double t) {
    double d = std::numeric_limits<double>::infinity();
    for (double x : v) d = std::min(d, std::abs(x - t));
    return d;
  };
  double e = 0.0;
  for (double t : a) e = std::max(e, nearest(b, t));
  for (double t : b)
    if (t <= horizon) e = std::max(e, nearest(a, t));
  return e;
}

/// Worst error of the rotation peaks: max |theta|/alpha of the run, and the first
/// kImpactsCompared located local maxima of |theta|/alpha above 1e-3 (in order), in units of alpha.
inline double peak_error(const Run& r, const Run& ref) {
  auto peaks = [](const Run& x) {
    std::vector<double> out;
    for (double p : x.peak)
      if (p >= 1e-3 && out.size() < kImpactsCompared) out.push_back(p);
    return out;
  };
  const std::vector<double> a = peaks(r), b = peaks(ref);
  double e = std::abs(r.outcome.max_rotation_ratio - ref.outcome.max_rotation_ratio);
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) e = std::max(e, std::abs(a[i] - b[i]));
  return e;
}

/// Largest rise of a located peak over the previous one, relative (free rocking must lose energy
/// at every impact, so successive peaks must fall). 0 when they never rise.
inline double energy_gain(const Run& r) {
  double prev = -1.0, worst = 0.0;
  for (double p : r.peak) {
    if (p <= 0.0) continue;
    if (prev > 0.0) worst = std::max(worst, (p - prev) / prev);
    prev = p;
  }
  return worst;
}

inline std::string fmt(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

// ------------------------------------------------------------------ parallel map
// f(0) .. f(n-1) on `jobs` threads; progress (if any) counts the finished ones.
inline void parallel_for(std::size_t n, int jobs, const std::function<void(std::size_t)>& f,
                         rocking_monitor::tools::ProgressMeter* progress = nullptr) {
  std::atomic<std::size_t> next{0}, done{0};
  if (progress) progress->update(0, n);
  auto worker = [&] {
    for (std::size_t i = next++; i < n; i = next++) {
      f(i);
      const std::size_t d = ++done;
      if (progress) progress->update(d, n);
    }
  };
  std::vector<std::thread> pool;
  for (int j = 1; j < jobs; ++j) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
}

// ------------------------------------------------------------------ overturn decisions
struct NamedBody {
  std::string name;
  BodyParameters body;
};

inline std::vector<NamedBody> study_bodies() {
  std::vector<NamedBody> out;
  auto make = [](double b, double h, double nu1) {
    BodyParameters p;
    p.width = b;
    p.cg_height = h;
    p.nu1 = nu1;
    return p;
  };
  out.push_back({"small_slender_0.1x0.5", make(0.1, 0.25, 0.5)});  // alpha 11 deg, p 5.5
  out.push_back({"cabinet_0.4x1.6", make(0.4, 0.8, 0.5)});         // alpha 14 deg, p 2.7
  out.push_back({"eccentric_0.5x1.2_nu0.3", make(0.5, 0.6, 0.3)}); // alpha 14/30 deg
  out.push_back({"squat_0.6x0.8", make(0.6, 0.4, 0.5)});           // alpha 37 deg, p 3.4
  return out;
}

}  // namespace rocking_monitor::bench::accuracy
