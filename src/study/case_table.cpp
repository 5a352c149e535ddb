#include "rocking_monitor/study/case_table.hpp"

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <ostream>
#include <string>

#include "rocking_monitor/csv/csv_writer.hpp"
#include "study_internal.hpp"

namespace rocking_monitor::core::study {

using detail::format_number;

const std::vector<std::string>& case_csv_columns() {
  static const std::vector<std::string> columns{
      "case", "body", "body_name", "width_m", "cg_height_m", "nu1", "eccentricity",
      "radius_of_gyration_m", "record", "event", "station", "component", "file", "polarity",
      "vertical", "vertical_component", "overturned", "committed", "beyond_tipping", "final_mode",
      "max_rotation_ratio", "max_theta_rad", "max_rotation_pivot", "impacts", "uplift_time_s",
      "beyond_tipping_time_s", "committed_time_s", "overturn_time_s", "rest_captures",
      "forced_rest_captures", "violations", "first_violation_time_s", "pga_mps2", "pgv_mps", "pga_vertical_mps2",
      "housner_period_s", "housner_psv_mps", "housner_threshold_mps", "ishiyama_v_mps",
      "ishiyama_a_mps2", "ishiyama_equivalent_v_mps", "ishiyama_equivalent_a_mps2",
      "proposed_v_mps", "proposed_a_mps2", "predicts_housner", "predicts_ishiyama",
      "predicts_ishiyama_equivalent", "predicts_proposed", "integrator_steps"};
  return columns;
}

void write_case_csv_header(std::ostream& out) {
  csv::Writer row(out);
  for (const std::string& column : case_csv_columns()) row.text(column);
  row.end_row();
}

namespace {

std::string num(double v) { return std::isnan(v) ? std::string() : format_number("%.9g", v); }

const char* flag(bool on) { return on ? "1" : "0"; }

void header(csv::Writer& row, std::initializer_list<const char*> columns) {
  for (const char* column : columns) row.text(column);
  row.end_row();
}

std::string violation_names(std::uint8_t mask) {
  std::string s;
  for (int c = 0; c < kCriterionCount; ++c) {
    if (mask & (1u << c)) {
      if (!s.empty()) s += '|';
      s += core::to_string(static_cast<Criterion>(c));
    }
  }
  return s;
}

}  // namespace

void write_case_csv_rows(std::ostream& out, const std::vector<CaseResult>& results,
                         const std::vector<StudyBody>& bodies, const std::vector<StudyRecord>& records) {
  csv::Writer row(out);
  for (const CaseResult& c : results) {
    const BodyParameters& b = bodies.at(c.body).parameters;
    const StudyRecord& r = records.at(c.record);
    const RockingOutcome& o = c.outcome;
    const ScreeningThresholds& t = c.thresholds;
    row.value(std::to_string(c.index)).value(std::to_string(c.body)).text(bodies[c.body].name);
    row.value(num(b.width)).value(num(b.cg_height)).value(num(b.nu1)).value(num(eccentricity_of(b)));
    row.value(num(b.radius_of_gyration));
    row.value(std::to_string(c.record)).text(r.event).text(r.station).text(r.component).text(r.file);
    row.value(std::to_string(c.polarity)).value(flag(c.vertical)).text(c.vertical ? r.vertical_component : "");
    row.value(flag(o.overturned)).value(flag(o.committed)).value(flag(o.beyond_tipping));
    row.value(core::to_string(c.final_mode));
    row.value(num(o.max_rotation_ratio)).value(num(c.max_theta)).value(std::to_string(o.max_rotation_side));
    row.value(std::to_string(o.impacts));
    row.value(num(o.uplift_time)).value(num(o.beyond_tipping_time)).value(num(o.committed_time));
    row.value(num(o.overturn_time));
    row.value(std::to_string(o.rest_captures)).value(std::to_string(o.forced_rest_captures));
    row.value(violation_names(c.violations)).value(num(c.first_violation_time));
    row.value(num(r.pga)).value(num(r.pgv)).value(c.vertical ? num(r.pga_vertical) : "");
    row.value(num(c.housner_period)).value(num(c.housner_psv)).value(num(t.housner_pseudo_velocity));
    row.value(num(t.ishiyama.velocity)).value(num(t.ishiyama.acceleration));
    row.value(num(t.ishiyama_equivalent.velocity)).value(num(t.ishiyama_equivalent.acceleration));
    row.value(num(t.proposed.velocity)).value(num(t.proposed.acceleration));
    row.value(flag(c.prediction.housner)).value(flag(c.prediction.ishiyama));
    row.value(flag(c.prediction.ishiyama_equivalent)).value(flag(c.prediction.proposed));
    row.value(std::to_string(o.integrator_steps));
    row.end_row();
  }
}

void write_bodies_csv(std::ostream& out, const std::vector<StudyBody>& bodies) {
  csv::Writer row(out);
  header(row, {"body", "body_name", "width_m", "cg_height_m", "nu1", "eccentricity", "radius_of_gyration_m",
               "alpha1_rad", "alpha2_rad", "p1_radps", "p2_radps", "restitution_to_1", "restitution_to_2",
               "housner_period_s", "housner_threshold_mps", "ishiyama_v_mps", "ishiyama_a_mps2",
               "ishiyama_equivalent_v_mps", "ishiyama_equivalent_a_mps2", "proposed_v_mps", "proposed_a_mps2"});
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body body(bodies[i].parameters);
    const ScreeningThresholds t = screening_thresholds(body);
    const Pivot& p1 = body.pivot(1);
    const Pivot& p2 = body.pivot(-1);
    row.value(std::to_string(i)).text(bodies[i].name);
    row.value(num(body.width())).value(num(body.cg_height())).value(num(body.nu1()));
    row.value(num(eccentricity_of(body.parameters()))).value(num(body.radius_of_gyration()));
    row.value(num(p1.alpha)).value(num(p2.alpha)).value(num(p1.p)).value(num(p2.p));
    row.value(num(p1.restitution)).value(num(p2.restitution));
    row.value(num(housner_period(body))).value(num(t.housner_pseudo_velocity));
    row.value(num(t.ishiyama.velocity)).value(num(t.ishiyama.acceleration));
    row.value(num(t.ishiyama_equivalent.velocity)).value(num(t.ishiyama_equivalent.acceleration));
    row.value(num(t.proposed.velocity)).value(num(t.proposed.acceleration));
    row.end_row();
  }
}

void write_records_csv(std::ostream& out, const std::vector<StudyRecord>& records) {
  csv::Writer row(out);
  header(row, {"record", "event", "station", "component", "file", "vertical_component", "vertical_file", "dt_s",
               "samples", "duration_s", "pga_mps2", "pgv_mps", "pga_vertical_mps2"});
  for (std::size_t i = 0; i < records.size(); ++i) {
    const StudyRecord& r = records[i];
    row.value(std::to_string(i)).text(r.event).text(r.station).text(r.component).text(r.file);
    row.text(r.vertical_component).text(r.vertical_file);
    row.value(num(r.dt)).value(std::to_string(r.horizontal.size()));
    row.value(num(r.dt * static_cast<double>(r.horizontal.size() - 1))).value(num(r.pga)).value(num(r.pgv));
    row.value(r.has_vertical() ? num(r.pga_vertical) : "");
    row.end_row();
  }
}

}  // namespace rocking_monitor::core::study
