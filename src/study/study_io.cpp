#include "rocking_monitor/study/study_io.hpp"

#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

namespace rocking_monitor::core::study {
namespace {

using nlohmann::json;

std::string format_value(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// A YAML scalar as a finite double, or a StudyError naming the item and field.
double scalar(const YAML::Node& node, const std::string& where, const std::string& field) {
  if (!node.IsScalar()) throw StudyError(where + field + ": expected a number");
  const std::string text = node.Scalar();
  double v = 0.0;
  std::size_t used = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v))
    throw StudyError(where + field + ": expected a finite number, got '" + text + "'");
  return v;
}

json nullable(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json tally_json(const Tally& t) {
  json criteria = json::object();
  for (int k = 0; k < kScreeningCount; ++k) {
    const auto c = static_cast<Screening>(k);
    criteria[to_string(c)] = {{"predicted", t.predicted[k]},
                              {"missed", t.missed[k]},
                              {"false_alarms", t.false_alarms[k]},
                              {"consistent_percent", nullable(t.cases ? t.consistent_percent(c) : NAN)}};
  }
  return {{"cases", t.cases},
          {"overturned", t.overturned},
          {"overturned_percent", nullable(t.cases ? t.overturned_percent() : NAN)},
          {"committed", t.committed},
          {"beyond_tipping", t.beyond_tipping},
          {"criteria", criteria}};
}

json set_json(const SetSummary& s) {
  json by_e = json::array(), by_eh = json::array();
  for (std::size_t e = 0; e < s.eccentricities.size(); ++e) {
    json t = tally_json(s.by_eccentricity[e]);
    t["eccentricity"] = s.eccentricities[e];
    t["ratio_to_symmetric"] = nullable(s.overturn_ratio(e));
    by_e.push_back(t);
    for (std::size_t h = 0; h < s.heights.size(); ++h) {
      json th = tally_json(s.by_eccentricity_height[e][h]);
      th["eccentricity"] = s.eccentricities[e];
      th["cg_height_m"] = s.heights[h];
      th["ratio_to_symmetric"] = nullable(s.overturn_ratio(e, static_cast<int>(h)));
      by_eh.push_back(th);
    }
  }
  json by_pgv = json::array();
  const auto& edges = pgv_band_edges();
  for (std::size_t e = 0; e < s.eccentricities.size(); ++e) {
    for (std::size_t b = 0; b <= edges.size(); ++b) {
      json t = tally_json(s.by_eccentricity_pgv[e][b]);
      t["eccentricity"] = s.eccentricities[e];
      t["pgv_min_mps"] = b == 0 ? 0.0 : edges[b - 1];
      t["pgv_max_mps"] = b == edges.size() ? json(nullptr) : json(edges[b]);
      t["ratio_to_symmetric"] = nullable(s.overturn_ratio_pgv(e, b));
      by_pgv.push_back(t);
    }
  }
  return {{"eccentricities", s.eccentricities},
          {"by_eccentricity_pgv", by_pgv},
          {"cg_heights_m", s.heights},
          {"all", tally_json(s.all)},
          {"by_eccentricity", by_e},
          {"by_eccentricity_height", by_eh}};
}

}  // namespace

std::vector<StudyBody> load_bodies_yaml(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw StudyError(path + ": cannot open");
  } catch (const YAML::Exception& e) {
    throw StudyError(path + ":" + std::to_string(e.mark.line + 1) + ":" +
                     std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
  YAML::Node list = root;
  std::string prefix = "bodies";
  if (root.IsMap()) {
    for (const auto& kv : root) {
      const std::string key = kv.first.as<std::string>();
      if (key != "bodies") throw StudyError(path + ": unknown top-level key '" + key + "' (expected 'bodies')");
    }
    list = root["bodies"];
  } else {
    prefix = "";
  }
  if (!list || !list.IsSequence() || list.size() == 0)
    throw StudyError(path + ": expected a non-empty list of bodies (under 'bodies:')");

  static const std::set<std::string> known{"name", "width", "cg_height", "nu1",
                                           "radius_of_gyration", "restitution", "mu_s"};
  std::vector<StudyBody> bodies;
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node item = list[i];
    std::string where = path + ": " + prefix + "[" + std::to_string(i) + "]";
    if (!item.IsMap()) throw StudyError(where + ": expected a map with width, cg_height, ...");
    std::string name = "body" + std::to_string(i);
    if (item["name"]) {
      if (!item["name"].IsScalar() || item["name"].Scalar().empty())
        throw StudyError(where + ": name: expected a non-empty string");
      name = item["name"].Scalar();
    }
    where += " (" + name + "): ";
    for (const auto& kv : item) {
      const std::string key = kv.first.as<std::string>();
      if (!known.count(key))
        throw StudyError(where + key + ": unknown field (known: name, width, cg_height, nu1, "
                                       "radius_of_gyration, restitution, mu_s)");
    }
    BodyParameters p;
    for (const char* req : {"width", "cg_height"})
      if (!item[req]) throw StudyError(where + req + ": missing (required, m)");
    p.width = scalar(item["width"], where, "width");
    p.cg_height = scalar(item["cg_height"], where, "cg_height");
    if (item["radius_of_gyration"]) p.radius_of_gyration = scalar(item["radius_of_gyration"], where, "radius_of_gyration");
    if (item["restitution"]) p.restitution = scalar(item["restitution"], where, "restitution");
    if (item["mu_s"]) p.mu_s = scalar(item["mu_s"], where, "mu_s");
    std::vector<double> nus{0.5};
    bool nu_list = false;
    if (const YAML::Node nu = item["nu1"]) {
      nus.clear();
      if (nu.IsSequence()) {
        nu_list = true;
        if (nu.size() == 0) throw StudyError(where + "nu1: empty list");
        for (std::size_t k = 0; k < nu.size(); ++k)
          nus.push_back(scalar(nu[k], where, "nu1[" + std::to_string(k) + "]"));
      } else {
        nus.push_back(scalar(nu, where, "nu1"));
      }
    }
    // Validate the geometry before computing the default radius of gyration from it.
    {
      BodyParameters probe = p;
      probe.nu1 = 0.5;
      if (const std::string e = validate(probe); !e.empty()) throw StudyError(where + e);
    }
    if (std::isnan(p.radius_of_gyration))
      p.radius_of_gyration = Body::homogeneous_radius_of_gyration(p.width, p.cg_height);
    for (double nu : nus) {
      StudyBody b;
      b.parameters = p;
      b.parameters.nu1 = nu;
      b.name = nu_list ? name + "_nu" + format_value(nu) : name;
      if (const std::string e = validate(b.parameters); !e.empty())
        throw StudyError(where + (nu_list ? "nu1 = " + format_value(nu) + ": " : std::string()) + e);
      if (!names.insert(b.name).second) throw StudyError(where + "name: '" + b.name + "' used twice");
      bodies.push_back(std::move(b));
    }
  }
  return bodies;
}

std::string summary_json(const StudySummary& s, const StudyRunInfo& run) {
  json out;
  out["tool"] = "rocking_study";
  out["paper"] = "Boroschek & Romo, Overturning criteria for non-anchored non-symmetric rigid bodies";
  out["run"] = {{"records_dir", run.records_dir},
                {"from_manifest", run.from_manifest},
                {"bodies", run.bodies_source},
                {"method", run.method},
                {"model", run.model},
                {"tol", run.tol},
                {"substeps", run.substeps},
                {"threads", run.threads},
                {"shard", run.shard},
                {"case_begin", run.case_begin},
                {"case_end", run.case_end},
                {"total_cases", run.total_cases},
                {"wall_time_s", run.wall_time_s >= 0.0 ? json(run.wall_time_s) : json(nullptr)},
                {"notes", run.notes}};
  out["cases"] = s.cases;
  out["bodies"] = s.bodies;
  out["records"] = s.records;
  out["records_with_vertical"] = s.records_with_vertical;
  const int sym = s.horizontal.symmetric_index();
  if (sym >= 0) {
    const Tally& t = s.horizontal.by_eccentricity[static_cast<std::size_t>(sym)];
    out["headline"] = {
        {"description",
         "symmetric bodies (nu = 0.5), every record, both polarities, no vertical: share of cases "
         "where Ishiyama's criterion (eq. 2) is satisfied, i.e. no overturn where it predicts safety"},
        {"cases", t.cases},
        {"overturned", t.overturned},
        {"missed_by_ishiyama", t.missed[static_cast<int>(Screening::Ishiyama)]},
        {"ishiyama_consistent_percent", nullable(t.cases ? t.consistent_percent(Screening::Ishiyama) : NAN)},
        {"paper_percent", 99.4}};
  } else {
    out["headline"] = nullptr;
  }
  out["sets"] = {{s.horizontal.name, set_json(s.horizontal)},
                 {s.subset_without_vertical.name, set_json(s.subset_without_vertical)},
                 {s.with_vertical.name, set_json(s.with_vertical)}};
  json ve = json::array();
  const VerticalEffect& v = s.vertical_effect;
  for (std::size_t e = 0; e < v.eccentricities.size(); ++e) {
    ve.push_back({{"eccentricity", v.eccentricities[e]},
                  {"pairs", v.pairs[e]},
                  {"overturned_without_vertical", v.overturned_without[e]},
                  {"overturned_with_vertical", v.overturned_with[e]},
                  {"overturn_only_with_vertical", v.only_with[e]},
                  {"overturn_only_without_vertical", v.only_without[e]}});
  }
  out["vertical_effect"] = ve;
  return out.dump(2) + "\n";
}

}  // namespace rocking_monitor::core::study
