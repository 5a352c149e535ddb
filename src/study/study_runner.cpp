#include "rocking_monitor/study/study_runner.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <functional>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include "rocking_monitor/model/batch_rocking.hpp"
#include "rocking_monitor/motion/response_spectrum.hpp"

namespace rocking_monitor::core::study {

std::vector<StudyInput> study_inputs(const std::vector<StudyRecord>& records,
                                     const StudyPlanOptions& options) {
  std::vector<StudyInput> inputs;
  for (std::size_t r = 0; r < records.size(); ++r) {
    for (int polarity : {1, -1}) {
      if (polarity < 0 && !options.both_polarities) continue;
      inputs.push_back({r, polarity, false});
      if (options.verticals && records[r].has_vertical()) inputs.push_back({r, polarity, true});
    }
  }
  return inputs;
}

std::size_t study_case_count(std::size_t bodies, const std::vector<StudyRecord>& records,
                             const StudyPlanOptions& plan) {
  return bodies * study_inputs(records, plan).size();
}

CaseRange shard_range(std::size_t total, int k, int n) {
  if (n < 1 || k < 1 || k > n)
    throw StudyError("invalid shard " + std::to_string(k) + "/" + std::to_string(n) +
                     " (need 1 <= k <= n)");
  const auto nn = static_cast<std::size_t>(n);
  const auto kk = static_cast<std::size_t>(k);
  // total * k may overflow only beyond 1e18 cases.
  return {total * (kk - 1) / nn, total * kk / nn};
}

std::pair<int, int> parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  int k = 0, n = 0;
  std::size_t used_k = 0, used_n = 0;
  try {
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    k = std::stoi(text.substr(0, slash), &used_k);
    n = std::stoi(text.substr(slash + 1), &used_n);
  } catch (const std::exception&) {
    throw StudyError("invalid shard '" + text + "' (expected k/n, e.g. 2/8)");
  }
  if (used_k != slash || used_n != text.size() - slash - 1)
    throw StudyError("invalid shard '" + text + "' (expected k/n, e.g. 2/8)");
  shard_range(1, k, n);  // range check
  return {k, n};
}

double pseudo_velocity_at(const std::vector<double>& accel, double dt, double period, double damping) {
  NigamJenningsOscillator osc(period, damping, dt);
  double peak = 0.0;
  for (std::size_t i = 1; i < accel.size(); ++i) {
    osc.step(accel[i - 1], accel[i]);
    peak = std::max(peak, std::abs(osc.displacement()));
  }
  return 2.0 * kPi / period * peak;
}

namespace {

// Everything of a case but the simulation.
CaseResult case_setup(const Body& body, const StudyRecord& rec, int polarity, bool vertical, double psv) {
  CaseResult c;
  c.polarity = polarity;
  c.vertical = vertical && rec.has_vertical();
  c.housner_period = housner_period(body);
  c.housner_psv = std::isnan(psv) ? pseudo_velocity_at(rec.corrected, rec.dt, c.housner_period) : psv;
  c.thresholds = screening_thresholds(body);
  c.prediction = screening_prediction(c.thresholds, rec.pga, rec.pgv, c.housner_psv);
  return c;
}

void finish_case(CaseResult& c, const Body& body, const RockingModel& model) {
  c.outcome = model.outcome();
  c.final_mode = model.mode();
  if (c.outcome.max_rotation_side != 0)
    c.max_theta = c.outcome.max_rotation_ratio * body.pivot(c.outcome.max_rotation_side).alpha;
}

}  // namespace

CaseResult run_case(const Body& body, const StudyRecord& rec, int polarity, bool vertical,
                    const SolverSettings& settings, double psv) {
  CaseResult c = case_setup(body, rec, polarity, vertical, psv);

  // Same loop as simulate() (rocking_sim), with the polarity applied to the horizontal only:
  // multiplying by +-1 is exact, so the samples are those of a record written with that sign.
  RockingModel model(body, settings);
  const double s = polarity < 0 ? -1.0 : 1.0;
  const std::vector<double>& ah = rec.horizontal;
  const bool use_v = c.vertical;
  const std::size_t n = ah.size();
  if (n > 0) {
    model.reset(rec.t0, s * ah[0], use_v ? rec.vertical[0] : 0.0);
    for (std::size_t i = 1; i < n; ++i) {
      const StepReport& r = model.step(s * ah[i], use_v ? rec.vertical[i] : 0.0, rec.dt);
      if (r.violation_onsets != 0 && c.violations == 0) c.first_violation_time = model.time();
      c.violations |= r.violation_onsets;
    }
  }
  finish_case(c, body, model);
  return c;
}

namespace {

// The study's cases laid out for the workers: what every unit of work reads, and where it writes.
struct StudyLayout {
  const std::vector<StudyBody>& bodies;
  const std::vector<StudyRecord>& records;
  const StudyOptions& options;
  std::vector<Body> rigid;
  std::vector<StudyInput> inputs;
  std::size_t per_body = 0;  // inputs per body
  CaseRange range;
  // A record's inputs: [first[r], first[r + 1]).
  std::vector<std::size_t> first;
};

// Scalar unit: one body on one record's inputs, as global case indices [begin, end).
struct ScalarUnit {
  std::size_t body, record, begin, end;
};

// Batched unit: one record with bodies [b0, b1) as lanes.
struct BatchUnit {
  std::size_t record, b0, b1;
};

std::vector<Body> rigid_bodies(const std::vector<StudyBody>& bodies) {
  std::vector<Body> rigid;
  rigid.reserve(bodies.size());
  for (const auto& b : bodies) {
    try {
      rigid.emplace_back(b.parameters);
    } catch (const std::exception& e) {
      throw StudyError("body '" + b.name + "': " + e.what());
    }
  }
  return rigid;
}

// The requested case range (end max: all), checked against the `total` cases.
CaseRange checked_range(CaseRange range, std::size_t total) {
  if (range.end == std::numeric_limits<std::size_t>::max()) range.end = total;
  if (range.begin > range.end || range.end > total)
    throw StudyError("case range [" + std::to_string(range.begin) + ", " + std::to_string(range.end) +
                     ") outside the " + std::to_string(total) + " cases");
  return range;
}

// Every record has at least its (polarity +1, vertical off) input, and a record's inputs are
// contiguous, in record order: first[r] is the index of its first.
std::vector<std::size_t> first_inputs(const std::vector<StudyInput>& inputs, std::size_t records, std::size_t per_body) {
  std::vector<std::size_t> first(records + 1, per_body);
  for (std::size_t i = 0; i < inputs.size(); ++i)
    if (i == 0 || inputs[i].record != inputs[i - 1].record) first[inputs[i].record] = i;
  return first;
}

// Work units: (body, record) -> its contiguous inputs within the range.
std::vector<ScalarUnit> scalar_units(const StudyLayout& s) {
  std::vector<ScalarUnit> units;
  if (s.per_body == 0) return units;
  for (std::size_t b = s.range.begin / s.per_body; b < s.bodies.size() && b * s.per_body < s.range.end; ++b) {
    for (std::size_t r = 0; r < s.records.size(); ++r) {
      const std::size_t lo = std::max(b * s.per_body + s.first[r], s.range.begin);
      const std::size_t hi = std::min(b * s.per_body + s.first[r + 1], s.range.end);
      if (lo < hi) units.push_back({b, r, lo, hi});
    }
  }
  return units;
}

// Batched: (record, bodies [b0, b1)); the bodies of a record input step together.
std::vector<BatchUnit> batch_units(const StudyLayout& s) {
  constexpr std::size_t kLanes = 64;
  std::vector<BatchUnit> units;
  if (s.per_body == 0 || s.range.begin >= s.range.end) return units;
  const std::size_t b_first = s.range.begin / s.per_body, b_last = (s.range.end - 1) / s.per_body + 1;
  for (std::size_t r = 0; r < s.records.size(); ++r)
    for (std::size_t b0 = b_first; b0 < b_last; b0 += kLanes) units.push_back({r, b0, std::min(b0 + kLanes, b_last)});
  return units;
}

// One scalar unit: PSV once, then run_case() per input. Returns the number of cases run.
std::size_t run_scalar_unit(const StudyLayout& s, const ScalarUnit& unit, std::vector<CaseResult>& results) {
  const Body& body = s.rigid[unit.body];
  const StudyRecord& rec = s.records[unit.record];
  const double psv = pseudo_velocity_at(rec.corrected, rec.dt, housner_period(body));
  for (std::size_t idx = unit.begin; idx < unit.end; ++idx) {
    const StudyInput& in = s.inputs[idx - unit.body * s.per_body];
    CaseResult c = run_case(body, rec, in.polarity, in.vertical, s.options.settings, psv);
    c.index = idx;
    c.body = unit.body;
    c.record = unit.record;
    results[idx - s.range.begin] = c;
  }
  return unit.end - unit.begin;
}

// One batched unit: PSV once per body, then each input of the record with the bodies whose case is
// in the range as lanes. Returns the number of cases run.
std::size_t run_batch_unit(const StudyLayout& s, const BatchUnit& unit, std::vector<CaseResult>& results) {
  const std::size_t r = unit.record, b0 = unit.b0, b1 = unit.b1;
  const StudyRecord& rec = s.records[r];
  std::vector<double> psv(b1 - b0);
  for (std::size_t b = b0; b < b1; ++b)
    psv[b - b0] = pseudo_velocity_at(rec.corrected, rec.dt, housner_period(s.rigid[b]));
  std::size_t count = 0;
  std::vector<std::size_t> lanes;
  std::vector<BodyParameters> params;
  for (std::size_t i = s.first[r]; i < s.first[r + 1]; ++i) {
    lanes.clear();
    params.clear();
    for (std::size_t b = b0; b < b1; ++b) {
      const std::size_t idx = b * s.per_body + i;
      if (idx >= s.range.begin && idx < s.range.end) {
        lanes.push_back(b);
        params.push_back(s.bodies[b].parameters);
      }
    }
    if (lanes.empty()) continue;
    const StudyInput& in = s.inputs[i];
    const double sign = in.polarity < 0 ? -1.0 : 1.0;
    const bool use_v = in.vertical && rec.has_vertical();
    const std::vector<double>& ah = rec.horizontal;
    BatchRocking batch(params, s.options.settings, s.options.trig);
    if (!ah.empty()) {
      batch.reset(rec.t0, sign * ah[0], use_v ? rec.vertical[0] : 0.0);
      for (std::size_t k = 1; k < ah.size(); ++k) batch.step_all(sign * ah[k], use_v ? rec.vertical[k] : 0.0, rec.dt);
    }
    for (std::size_t k = 0; k < lanes.size(); ++k) {
      const std::size_t b = lanes[k];
      CaseResult c = case_setup(s.rigid[b], rec, in.polarity, in.vertical, psv[b - b0]);
      c.violations = batch.violations_seen(k);
      c.first_violation_time = batch.first_violation_time(k);
      finish_case(c, s.rigid[b], batch.model(k));
      c.index = b * s.per_body + i;
      c.body = b;
      c.record = r;
      results[c.index - s.range.begin] = c;
      ++count;
    }
  }
  return count;
}

// Runs units [0, unit_count) on the options' threads, `run_unit(u)` returning the cases it ran; the
// calling thread reports progress of `cases` until the workers are done. The first exception stops
// the workers and is rethrown.
void run_units(std::size_t unit_count, std::size_t cases, const StudyOptions& options,
               const std::function<std::size_t(std::size_t)>& run_unit) {
  std::atomic<std::size_t> next{0}, done{0};
  std::atomic<bool> stop{false};
  std::exception_ptr error;
  std::mutex mutex;
  std::condition_variable finished_cv;
  int running = 0;
  auto worker = [&]() {
    try {
      for (;;) {
        if (stop.load(std::memory_order_relaxed)) break;
        const std::size_t u = next.fetch_add(1);
        if (u >= unit_count) break;
        done.fetch_add(run_unit(u));
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex);
      if (!error) error = std::current_exception();
      stop = true;
    }
    std::lock_guard<std::mutex> lock(mutex);
    --running;
    finished_cv.notify_all();
  };
  int threads = options.threads > 0 ? options.threads
                                    : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(threads),
                                                   std::max<std::size_t>(1, unit_count)));
  std::vector<std::thread> pool;
  running = threads;
  for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
  {
    std::unique_lock<std::mutex> lock(mutex);
    const auto interval = std::chrono::duration<double>(std::max(0.01, options.progress_interval_s));
    while (running > 0) {
      finished_cv.wait_for(lock, interval);
      if (options.progress && running > 0) {
        lock.unlock();
        options.progress(done.load(), cases);
        lock.lock();
      }
    }
  }
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  if (options.progress) options.progress(done.load(), cases);
}

}  // namespace

std::vector<CaseResult> run_study(const std::vector<StudyBody>& bodies,
                                  const std::vector<StudyRecord>& records, const StudyOptions& options) {
  if (const std::string e = validate(options.settings); !e.empty()) throw StudyError(e);
  StudyLayout s{bodies, records, options, rigid_bodies(bodies), study_inputs(records, options.plan), 0, {}, {}};
  s.per_body = s.inputs.size();
  s.range = checked_range(options.range, bodies.size() * s.per_body);
  s.first = first_inputs(s.inputs, records.size(), s.per_body);
  const std::vector<ScalarUnit> units = scalar_units(s);
  const std::vector<BatchUnit> batched = options.batch ? batch_units(s) : std::vector<BatchUnit>();
  std::vector<CaseResult> results(s.range.size());
  if (options.batch)
    run_units(batched.size(), s.range.size(), options, [&](std::size_t u) { return run_batch_unit(s, batched[u], results); });
  else
    run_units(units.size(), s.range.size(), options, [&](std::size_t u) { return run_scalar_unit(s, units[u], results); });
  return results;
}

}  // namespace rocking_monitor::core::study
