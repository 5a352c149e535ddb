#pragma once

// The cases of the study (bodies x inputs), their shards, and running them on worker threads.
//
// Case numbering (stable, documented in docs/study.md): the inputs of one body are, for each record
// component r in load order, polarity +1 then -1, and for each polarity "vertical off" then
// (when the station has a vertical) "vertical on". case = body * inputs_per_body + input. Results
// are stored by case index, so the output does not depend on the number of threads, and a shard
// k/n is the contiguous index range [floor((k-1) N / n), floor(k N / n)).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "rocking_monitor/integrate/solver_settings.hpp"
#include "rocking_monitor/model/batch_rocking.hpp"
#include "rocking_monitor/model/rocking_model.hpp"
#include "rocking_monitor/physics/body.hpp"
#include "rocking_monitor/physics/criteria.hpp"
#include "rocking_monitor/study/study_bodies.hpp"
#include "rocking_monitor/study/study_error.hpp"
#include "rocking_monitor/study/study_records.hpp"

namespace rocking_monitor::core::study {

/// One excitation of a body: record component, polarity (+1 as recorded, -1 reversed; the vertical
/// is never reversed), vertical on or off.
struct StudyInput {
  std::size_t record = 0;
  int polarity = 1;
  bool vertical = false;
};

struct StudyPlanOptions {
  bool both_polarities = true;  ///< false: polarity +1 only
  bool verticals = true;        ///< false: never run the "vertical on" cases
};

/// The inputs of one body, in case order (see the file comment).
std::vector<StudyInput> study_inputs(const std::vector<StudyRecord>& records,
                                     const StudyPlanOptions& options = {});

/// Contiguous case range.
struct CaseRange {
  std::size_t begin = 0, end = 0;
  std::size_t size() const { return end - begin; }
};

/// Shard k of n (1 <= k <= n) of `total` cases: [floor((k-1) total / n), floor(k total / n)).
/// Throws StudyError for k or n out of range.
CaseRange shard_range(std::size_t total, int k, int n);
/// Parses "k/n" (e.g. "2/8"); throws StudyError naming the text.
std::pair<int, int> parse_shard(const std::string& text);

/// What one case produced.
struct CaseResult {
  std::size_t index = 0;   ///< global case index
  std::size_t body = 0;    ///< index into the bodies
  std::size_t record = 0;  ///< index into the records
  int polarity = 1;
  bool vertical = false;
  RockingOutcome outcome;
  Mode final_mode = Mode::Rest;
  double max_theta = 0.0;         ///< max |theta| reached, rad (= max_rotation_ratio * alpha of that pivot)
  std::uint8_t violations = 0;    ///< bit (1 << Criterion): the onset happened at least once
  double first_violation_time = std::numeric_limits<double>::quiet_NaN();  ///< s, first onset (NaN: none)
  double housner_period = 0.0;    ///< s, housner_period(body)
  double housner_psv = 0.0;       ///< 5 %-damped PSV of the corrected horizontal at that period, m/s
  ScreeningThresholds thresholds;
  ScreeningPrediction prediction;
};

/// 5 %-damped pseudo-velocity of `accel` at `period` (Nigam-Jennings, maxima over the samples), m/s.
double pseudo_velocity_at(const std::vector<double>& accel, double dt, double period,
                          double damping = 0.05);

/// Runs one case. `psv` is the record's PSV at housner_period(body) (pass NaN to compute it here).
CaseResult run_case(const Body& body, const StudyRecord& record, int polarity, bool vertical,
                    const SolverSettings& settings, double psv);

struct StudyOptions {
  SolverSettings settings;
  StudyPlanOptions plan;
  int threads = 0;  ///< 0 = std::thread::hardware_concurrency()
  /// Cases to run (global indices); the default (end = SIZE_MAX) means all.
  CaseRange range{0, std::numeric_limits<std::size_t>::max()};
  /// Called from the calling thread about every progress_interval_s seconds and once at the end,
  /// with (cases done, cases in range).
  std::function<void(std::size_t, std::size_t)> progress;
  double progress_interval_s = 0.5;
  /// Step the bodies that share a record input together in the batch engine (model/batch_rocking:
  /// SIMD across bodies; bit-identical to one RockingModel per case with trig Exact); false: one
  /// model per case.
  bool batch = true;
  /// The batch engine's sin/cos: Fast (Highway's vector Sin/Cos, a few ulp; meets the accuracy
  /// policy of docs/performance.md: decisions and event times as right as the scalar run's) or Exact
  /// (libm per lane: bit-identical to one RockingModel per case).
  BatchTrig trig = BatchTrig::Fast;
};

/// Total number of cases for these bodies and records.
std::size_t study_case_count(std::size_t bodies, const std::vector<StudyRecord>& records,
                             const StudyPlanOptions& plan = {});

/// Runs the cases of options.range on options.threads threads. Work is handed out per (record, up to
/// 64 bodies) with options.batch (each of the record's inputs steps those bodies together), else per
/// (body, record); either way the PSV is computed once per (body, record). Results are returned in
/// case order and are bit-identical for any thread count and either path. Throws the first error a
/// worker met.
std::vector<CaseResult> run_study(const std::vector<StudyBody>& bodies,
                                  const std::vector<StudyRecord>& records, const StudyOptions& options);

}  // namespace rocking_monitor::core::study
