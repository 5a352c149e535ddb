#pragma once

// Fragility curves from the study's engine: every body under every record component scaled to a set
// of intensities (incremental dynamic analysis), each run's overturning outcome, and a lognormal
// P(overturn | IM) fitted per body (fragility.hpp). Pure rocking, as the study.

#include <cstddef>
#include <string>
#include <vector>

#include "rocking_monitor/integrate/solver_settings.hpp"
#include "rocking_monitor/physics/criteria.hpp"
#include "rocking_monitor/study/fragility.hpp"
#include "rocking_monitor/study/study_bodies.hpp"
#include "rocking_monitor/study/study_records.hpp"

namespace rocking_monitor::core::study {

/// The intensity a fragility is expressed in.
enum class IntensityMeasure { Pgv, Pga, Psv };
const char* to_string(IntensityMeasure im);
const char* unit_of(IntensityMeasure im);  ///< "m/s" or "m/s^2"
/// "pgv", "pga" or "psv"; throws StudyError naming the text otherwise.
IntensityMeasure parse_intensity_measure(const std::string& text);

struct FragilityOptions {
  SolverSettings settings;
  IntensityMeasure im = IntensityMeasure::Pgv;
  /// Each record is scaled so that its PGV (baseline-corrected, the study's) takes `levels` values
  /// log-spaced over [pgv_min, pgv_max] (m/s): every record covers the same PGV range.
  int levels = 12;
  double pgv_min = 0.02, pgv_max = 2.0;
  bool both_polarities = true;  ///< also run each scaled record reversed (the vertical never is)
  bool vertical = true;         ///< with the station's vertical when it has one (scaled alike)
  int bootstrap = 200;          ///< bootstrap resamples of each fit
  std::uint64_t seed = 1;       ///< bootstrap seed
  /// Members per uncertain catalogue item (a body with distributions; its own ensemble_size wins),
  /// drawn as the live node draws them (draw_members(), seed member_seed = the node's ~ensemble_seed).
  int members = 32;
  std::uint64_t member_seed = 1;
  int threads = 0;              ///< 0 = hardware concurrency
};

/// One run: a body under one scaled record component.
struct FragilityRun {
  std::size_t body = 0, record = 0;
  int member = -1;      ///< the ensemble member of an uncertain body (0..), -1: an exact body
  int polarity = 1;
  double scale = 1.0;   ///< factor on the record (horizontal and vertical)
  double im = 0.0;      ///< the scaled record's intensity in options.im (PSV at the body's Housner period)
  bool overturned = false;
  bool beyond_tipping = false;
};

struct BodyFragility {
  std::size_t body = 0;
  std::size_t runs = 0, overturned = 0;
  int members = 0;            ///< ensemble members pooled in the fit (0: an exact body)
  bool fitted = false;        ///< false: no run overturned, or every run did (no curve); see note
  std::string note;
  LognormalFragility fit;
  FragilityBand band;         ///< at `band.im`, log-spaced over the runs' IM range
  ScreeningThresholds thresholds;  ///< the screening criteria's thresholds (vertical lines on the plot)
  double housner_period = 0.0;     ///< s
  /// Pairs (lower scale overturned, higher scale of the same record and polarity survived): rocking is
  /// not monotone in intensity; counted, not hidden.
  std::size_t non_monotone = 0;
};

struct FragilityResult {
  std::vector<FragilityRun> runs;       ///< body-major, then record, polarity, level
  std::vector<BodyFragility> bodies;
};

/// The scale factors of one record (levels values, ascending). Throws StudyError for a record with PGV 0.
std::vector<double> fragility_scales(const StudyRecord& record, const FragilityOptions& options);

/// Runs every body (every member of an uncertain one) under every record component at every level (threads share the work; results are
/// in a fixed order, identical for any thread count) and fits each body's fragility.
FragilityResult run_fragility(const std::vector<StudyBody>& bodies, const std::vector<StudyRecord>& records,
                              const FragilityOptions& options);

}  // namespace rocking_monitor::core::study
