#include "rocking_monitor/study/fragility_study.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>

#include "rocking_monitor/study/study_runner.hpp"

namespace rocking_monitor::core::study {
namespace {

// The record scaled by s: horizontal, vertical, corrected and their peaks (multiplying by s is
// linear, so the baseline-corrected PGV scales exactly).
StudyRecord scaled(const StudyRecord& r, double s) {
  StudyRecord out = r;
  for (double& a : out.horizontal) a *= s;
  for (double& a : out.vertical) a *= s;
  for (double& a : out.corrected) a *= s;
  out.pga *= s;
  out.pgv *= s;
  out.pga_vertical *= s;
  return out;
}

}  // namespace

const char* to_string(IntensityMeasure im) {
  switch (im) {
    case IntensityMeasure::Pgv: return "pgv";
    case IntensityMeasure::Pga: return "pga";
    case IntensityMeasure::Psv: return "psv";
  }
  return "?";
}

const char* unit_of(IntensityMeasure im) { return im == IntensityMeasure::Pga ? "m/s^2" : "m/s"; }

IntensityMeasure parse_intensity_measure(const std::string& text) {
  if (text == "pgv") return IntensityMeasure::Pgv;
  if (text == "pga") return IntensityMeasure::Pga;
  if (text == "psv") return IntensityMeasure::Psv;
  throw StudyError("--im '" + text + "' is not one of pgv, pga, psv");
}

std::vector<double> fragility_scales(const StudyRecord& record, const FragilityOptions& o) {
  if (!(record.pgv > 0.0)) throw StudyError(record.file + ": PGV 0: it cannot be scaled to a PGV range");
  std::vector<double> s;
  for (double pgv : geometric_spacing(o.pgv_min, o.pgv_max, o.levels)) s.push_back(pgv / record.pgv);
  return s;
}

namespace {

void check_fragility_options(const FragilityOptions& o) {
  if (o.levels < 2) throw StudyError("fragility: at least 2 intensity levels are needed");
  if (!(o.pgv_min > 0.0) || !(o.pgv_max > o.pgv_min)) throw StudyError("fragility: need 0 < pgv_min < pgv_max");
  if (o.members < 1) throw StudyError("fragility: --members must be >= 1");
  if (const std::string e = validate(o.settings); !e.empty()) throw StudyError(e);
}

// What every unit of work reads: the bodies' members, nominal bodies, the records and their scales.
struct FragilityPlan {
  const std::vector<StudyBody>& bodies;
  const std::vector<StudyRecord>& records;
  const FragilityOptions& o;
  // Each body's members: an uncertain catalogue item runs its Latin-hypercube members (the node's
  // draw with the same seed), an exact body runs once.
  std::vector<std::vector<Body>> rigid;
  std::vector<Body> nominal;
  std::vector<std::vector<double>> scales;  // per record, per level
  int polarities = 1;
};

std::vector<std::vector<Body>> member_rigid_bodies(const std::vector<StudyBody>& bodies, const FragilityOptions& o) {
  std::vector<std::vector<Body>> rigid(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (!bodies[b].uncertain) {
      rigid[b].emplace_back(bodies[b].parameters);
      continue;
    }
    const int n = bodies[b].ensemble_size > 0 ? bodies[b].ensemble_size : o.members;
    for (const BodyParameters& m : member_bodies(bodies[b], n, o.member_seed)) rigid[b].emplace_back(m);
  }
  return rigid;
}

// Work unit: one (body, member, record); its scaled copies are made once per level. Its runs are
// [first_run, first_run + polarities x levels), polarity-major.
struct FragilityUnit {
  std::size_t body, member, record, first_run;
};

std::vector<FragilityUnit> fragility_units(const FragilityPlan& plan) {
  const std::size_t per_record = static_cast<std::size_t>(plan.polarities * plan.o.levels);
  std::vector<FragilityUnit> units;
  for (std::size_t b = 0; b < plan.bodies.size(); ++b)
    for (std::size_t m = 0; m < plan.rigid[b].size(); ++m)
      for (std::size_t r = 0; r < plan.records.size(); ++r) units.push_back({b, m, r, units.size() * per_record});
  return units;
}

// One unit's runs: the member under the record at each level, each polarity.
void run_fragility_unit(const FragilityPlan& plan, const FragilityUnit& u, std::vector<FragilityRun>& runs) {
  const FragilityOptions& o = plan.o;
  // The IM is the record's (PSV at the nominal body's period): the same for every member.
  const double period = housner_period(plan.nominal[u.body]);
  for (int l = 0; l < o.levels; ++l) {
    const double s = plan.scales[u.record][static_cast<std::size_t>(l)];
    const StudyRecord rec = scaled(plan.records[u.record], s);
    const double psv = o.im == IntensityMeasure::Psv ? pseudo_velocity_at(rec.corrected, rec.dt, period)
                                                      : std::nan("");
    for (int p = 0; p < plan.polarities; ++p) {
      const int polarity = p == 0 ? 1 : -1;
      const CaseResult c = run_case(plan.rigid[u.body][u.member], rec, polarity, o.vertical, o.settings, psv);
      FragilityRun& run = runs[u.first_run + static_cast<std::size_t>(p * o.levels + l)];
      run.body = u.body;
      run.member = plan.bodies[u.body].uncertain ? static_cast<int>(u.member) : -1;
      run.record = u.record;
      run.polarity = polarity;
      run.scale = s;
      run.im = o.im == IntensityMeasure::Pgv ? rec.pgv : o.im == IntensityMeasure::Pga ? rec.pga : psv;
      run.overturned = c.outcome.overturned;
      run.beyond_tipping = c.outcome.beyond_tipping;
    }
  }
}

// Every unit on o.threads threads (the calling one among them); the first exception stops the
// others and is rethrown.
void run_fragility_units(const FragilityPlan& plan, const std::vector<FragilityUnit>& units,
                         std::vector<FragilityRun>& runs) {
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&] {
    for (;;) {
      const std::size_t w = next++;
      if (w >= units.size()) return;
      try {
        run_fragility_unit(plan, units[w], runs);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = units.size();
      }
    }
  };
  const int threads = plan.o.threads > 0 ? plan.o.threads : std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

// Body b's runs as fit points, with its counts (runs, overturned, non-monotone) into `f` and the IM
// range into lo, hi.
std::vector<FragilityPoint> fragility_points(const FragilityPlan& plan, const std::vector<FragilityUnit>& units,
                                             const std::vector<FragilityRun>& runs, std::size_t b,
                                             BodyFragility& f, double& lo, double& hi) {
  std::vector<FragilityPoint> points;
  lo = std::numeric_limits<double>::infinity();
  hi = 0.0;
  for (const FragilityUnit& u : units) {
    if (u.body != b) continue;
    for (int p = 0; p < plan.polarities; ++p) {
      bool fell_below = false;
      for (int l = 0; l < plan.o.levels; ++l) {
        const FragilityRun& run = runs[u.first_run + static_cast<std::size_t>(p * plan.o.levels + l)];
        ++f.runs;
        f.overturned += run.overturned;
        if (fell_below && !run.overturned) ++f.non_monotone;
        fell_below |= run.overturned;
        points.push_back({run.im, run.overturned ? 1.0 : 0.0, 1.0});
        lo = std::min(lo, run.im);
        hi = std::max(hi, run.im);
      }
    }
  }
  return points;
}

// Body b's fragility: its counts, the lognormal fit and its bootstrap band (or why not).
BodyFragility body_fragility(const FragilityPlan& plan, const std::vector<FragilityUnit>& units,
                             const std::vector<FragilityRun>& runs, std::size_t b) {
  BodyFragility f;
  f.body = b;
  f.members = plan.bodies[b].uncertain ? static_cast<int>(plan.rigid[b].size()) : 0;
  f.thresholds = screening_thresholds(plan.nominal[b]);
  f.housner_period = housner_period(plan.nominal[b]);
  double lo = 0.0, hi = 0.0;
  const std::vector<FragilityPoint> points = fragility_points(plan, units, runs, b, f, lo, hi);
  try {
    f.fit = fit_lognormal_fragility(points);
    std::vector<double> grid = geometric_spacing(lo, hi, 40);
    f.band = bootstrap_fragility(points, grid, plan.o.bootstrap, plan.o.seed + b);
    f.fitted = true;
    if (!f.fit.converged) f.note = "outcomes separable in IM: beta -> 0, median at the gap";
  } catch (const StudyError& e) {
    f.note = e.what();
  }
  return f;
}

}  // namespace

FragilityResult run_fragility(const std::vector<StudyBody>& bodies, const std::vector<StudyRecord>& records,
                              const FragilityOptions& o) {
  check_fragility_options(o);
  FragilityPlan plan{bodies, records, o, member_rigid_bodies(bodies, o), {}, {}, o.both_polarities ? 2 : 1};
  for (const StudyBody& b : bodies) plan.nominal.emplace_back(b.parameters);
  for (const StudyRecord& r : records) plan.scales.push_back(fragility_scales(r, o));
  const std::vector<FragilityUnit> units = fragility_units(plan);
  FragilityResult result;
  result.runs.resize(units.size() * static_cast<std::size_t>(plan.polarities * o.levels));
  run_fragility_units(plan, units, result.runs);
  for (std::size_t b = 0; b < bodies.size(); ++b) result.bodies.push_back(body_fragility(plan, units, result.runs, b));
  return result;
}

}  // namespace rocking_monitor::core::study
