#include "rocking_monitor/study/fragility_io.hpp"

#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "rocking_monitor/json_text.hpp"
#include "rocking_monitor/csv/csv_writer.hpp"

namespace rocking_monitor::core::study {
namespace {

using nlohmann::json;

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

}  // namespace

std::vector<std::pair<std::string, double>> thresholds_in(const ScreeningThresholds& t, IntensityMeasure im) {
  switch (im) {
    case IntensityMeasure::Pgv:
      return {{"ishiyama", t.ishiyama.velocity}, {"ishiyama_equivalent", t.ishiyama_equivalent.velocity},
              {"proposed", t.proposed.velocity}};
    case IntensityMeasure::Pga:
      return {{"ishiyama", t.ishiyama.acceleration}, {"ishiyama_equivalent", t.ishiyama_equivalent.acceleration},
              {"proposed", t.proposed.acceleration}};
    case IntensityMeasure::Psv: return {{"housner", t.housner_pseudo_velocity}};
  }
  return {};
}

void write_fragility_runs_csv(std::ostream& out, const FragilityResult& r, const std::vector<StudyBody>& bodies,
                              const std::vector<StudyRecord>& records, const FragilityOptions& o) {
  out << "body,member,record_file,event,station,component,polarity,scale,im_" << to_string(o.im)
      << ",overturned,beyond_tipping\n";
  csv::Writer w(out);
  for (const FragilityRun& run : r.runs) {
    const StudyRecord& rec = records[run.record];
    w.text(bodies[run.body].name).value(run.member < 0 ? "" : std::to_string(run.member)).text(rec.file).text(rec.event).text(rec.station).text(rec.component);
    w.value(std::to_string(run.polarity)).number("%.9g", run.scale).number("%.9g", run.im);
    w.value(run.overturned ? "1" : "0").value(run.beyond_tipping ? "1" : "0");
    w.end_row();
  }
}

void write_fragility_json(std::ostream& out, const FragilityResult& r, const std::vector<StudyBody>& bodies,
                          const FragilityOptions& o) {
  json list = json::array();
  for (const BodyFragility& f : r.bodies) {
    json thresholds = json::object();
    for (const auto& [name, v] : thresholds_in(f.thresholds, o.im)) thresholds[name] = v;
    json item = {{"body", bodies[f.body].name},
                 {"runs", f.runs},
                 {"members", f.members},
                 {"overturned", f.overturned},
                 {"non_monotone_pairs", f.non_monotone},
                 {"housner_period_s", f.housner_period},
                 {"thresholds", thresholds},
                 {"fitted", f.fitted},
                 {"note", f.note}};
    if (f.fitted) {
      item["median"] = f.fit.median;
      item["beta"] = f.fit.beta;
      item["converged"] = f.fit.converged;
      item["log_likelihood"] = f.fit.log_likelihood;
      item["median_95"] = {number_or_null(f.band.median_lower), number_or_null(f.band.median_upper)};
      item["beta_95"] = {number_or_null(f.band.beta_lower), number_or_null(f.band.beta_upper)};
      item["band"] = {{"im", f.band.im}, {"lower", f.band.lower}, {"upper", f.band.upper},
                      {"resamples", f.band.resamples}, {"skipped", f.band.skipped}, {"separable", f.band.separable}};
    }
    list.push_back(item);
  }
  const json doc = {{"intensity_measure", to_string(o.im)},
                    {"unit", unit_of(o.im)},
                    {"model", "pure rocking (paper), planar; two-plane items as two planar bodies"},
                    {"levels", o.levels},
                    {"pgv_range_mps", {o.pgv_min, o.pgv_max}},
                    {"both_polarities", o.both_polarities},
                    {"vertical", o.vertical},
                    {"bootstrap", o.bootstrap},
                    {"bodies", list}};
  out << json_text(doc, 2) << "\n";
}

std::string format_fragility(const FragilityResult& r, const std::vector<StudyBody>& bodies, const FragilityOptions& o) {
  std::ostringstream os;
  char line[512];
  std::snprintf(line, sizeof line, "%-28s %7s %7s %12s %14s %6s %14s %s\n", "body", "runs", "fell",
                ("median " + std::string(unit_of(o.im))).c_str(), "95 %", "beta", "95 %", "thresholds");
  os << line;
  for (const BodyFragility& f : r.bodies) {
    std::string th;
    for (const auto& [name, v] : thresholds_in(f.thresholds, o.im)) {
      char b[64];
      std::snprintf(b, sizeof b, "%s%s %.3g", th.empty() ? "" : ", ", name.c_str(), v);
      th += b;
    }
    if (f.fitted) {
      std::snprintf(line, sizeof line, "%-28s %7zu %7zu %12.4g %6.3g-%-7.3g %6.3f %6.3g-%-7.3g %s\n",
                    bodies[f.body].name.c_str(), f.runs, f.overturned, f.fit.median, f.band.median_lower,
                    f.band.median_upper, f.fit.beta, f.band.beta_lower, f.band.beta_upper, th.c_str());
    } else {
      std::snprintf(line, sizeof line, "%-28s %7zu %7zu   no fit: %s\n", bodies[f.body].name.c_str(), f.runs,
                    f.overturned, f.note.c_str());
    }
    os << line;
  }
  return os.str();
}

}  // namespace rocking_monitor::core::study
