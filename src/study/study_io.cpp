#include "rocking_monitor/study/study_io.hpp"

#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "rocking_monitor/json_text.hpp"
#include "rocking_monitor/monitoring/catalogue_file.hpp"

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

namespace {

// A body file entry's name ("body<i>" when not given); `where` names the entry in errors.
std::string entry_name(const YAML::Node& item, std::size_t i, const std::string& where) {
  if (!item.IsMap()) throw StudyError(where + ": expected a map with width, cg_height, ...");
  std::string name = "body" + std::to_string(i);
  if (item["name"]) {
    if (!item["name"].IsScalar() || item["name"].Scalar().empty())
      throw StudyError(where + ": name: expected a non-empty string");
    name = item["name"].Scalar();
  }
  return name;
}

// Refuses a field the body file grammar does not know (a typo would otherwise be a silent default).
void check_entry_fields(const YAML::Node& item, const std::string& where) {
  static const std::set<std::string> known{"name", "width", "cg_height", "nu1", "radius_of_gyration",
                                               "restitution", "mu_s", "depth", "eccentricity_y",
                                               "radius_of_gyration_y", "restitution_shift"};
  for (const auto& kv : item) {
    const std::string key = kv.first.as<std::string>();
    if (!known.count(key)) {
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      throw StudyError(where + key + ": unknown field (known: " + list + ")");
    }
  }
}

// The x plane's parameters (nu1 left at its default) and the optional depth of a two-plane item.
void read_entry_parameters(const YAML::Node& item, const std::string& where, BodyParameters& p,
                           DepthParameters& depth) {
  for (const char* req : {"width", "cg_height"})
    if (!item[req]) throw StudyError(where + req + ": missing (required, m)");
  p.width = scalar(item["width"], where, "width");
  p.cg_height = scalar(item["cg_height"], where, "cg_height");
  if (item["radius_of_gyration"]) p.radius_of_gyration = scalar(item["radius_of_gyration"], where, "radius_of_gyration");
  if (item["restitution"]) p.restitution = scalar(item["restitution"], where, "restitution");
  if (item["mu_s"]) p.mu_s = scalar(item["mu_s"], where, "mu_s");
  if (item["restitution_shift"]) p.restitution_shift = scalar(item["restitution_shift"], where, "restitution_shift");
  if (item["depth"]) depth.depth = scalar(item["depth"], where, "depth");
  if (item["eccentricity_y"]) depth.eccentricity_y = scalar(item["eccentricity_y"], where, "eccentricity_y");
  if (item["radius_of_gyration_y"])
    depth.radius_of_gyration_y = scalar(item["radius_of_gyration_y"], where, "radius_of_gyration_y");
  if (!depth.given()) {
    for (const char* y : {"eccentricity_y", "radius_of_gyration_y"})
      if (item[y]) throw StudyError(where + y + ": given without depth (the y plane needs its depth)");
  }
}

// nu1: one value (default 0.5) or a list; `nu_list` true for a list (each value becomes a body
// named <name>_nu<value>).
std::vector<double> read_entry_nus(const YAML::Node& item, const std::string& where, bool& nu_list) {
  std::vector<double> nus{0.5};
  nu_list = false;
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
  return nus;
}

// One body (no depth) or two-plane item (with depth) per nu1 value, checked, into `out`.
void add_entry_bodies(const std::string& name, const std::string& where, const BodyParameters& p,
                      const DepthParameters& depth, const std::vector<double>& nus, bool nu_list, BodyFile& out,
                      std::set<std::string>& names) {
  for (double nu : nus) {
    BodyParameters b = p;
    b.nu1 = nu;
    const std::string body_name = nu_list ? name + "_nu" + format_value(nu) : name;
    const std::string nu_where =
        where + (nu_list ? "nu1 = " + format_value(nu) + ": " : std::string());
    if (const std::string e = validate(b); !e.empty()) throw StudyError(nu_where + e);
    if (!names.insert(body_name).second)
      throw StudyError(where + "name: '" + body_name + "' used twice");
    if (!depth.given()) {
      out.bodies.push_back({body_name, b, nullptr, Plane::X, 0});
      continue;
    }
    StudyItem it;
    it.name = body_name;
    it.x = b;
    it.depth = depth;
    try {
      it.y = y_plane_body(b, depth);  // radius of gyration derived from x's when not given
    } catch (const std::exception& e) {
      throw StudyError(nu_where + e.what());
    }
    if (const std::string e = validate(it.y); !e.empty()) throw StudyError(nu_where + "y plane: " + e);
    out.items.push_back(std::move(it));
  }
}

// One study body (name, nu1 list, ...) of a body file. (A monitor catalogue's items are read by the
// catalogue's own parser: load_catalogue_items().)
void load_entry(const YAML::Node& item, std::size_t i, const std::string& path, const std::string& prefix,
                BodyFile& out, std::set<std::string>& names) {
  std::string where = path + ": " + prefix + "[" + std::to_string(i) + "]";
  const std::string name = entry_name(item, i, where);
  where += " (" + name + "): ";
  check_entry_fields(item, where);
  BodyParameters p;
  DepthParameters depth;
  read_entry_parameters(item, where, p, depth);
  bool nu_list = false;
  const std::vector<double> nus = read_entry_nus(item, where, nu_list);
  // Validate the geometry before computing the default radius of gyration from it.
  {
    BodyParameters probe = p;
    probe.nu1 = 0.5;
    if (const std::string e = validate(probe); !e.empty()) throw StudyError(where + e);
    if (const std::string e = validate(depth); !e.empty()) throw StudyError(where + e);
  }
  if (std::isnan(p.radius_of_gyration)) p.radius_of_gyration = Body::homogeneous_radius_of_gyration(p.width, p.cg_height);
  add_entry_bodies(name, where, p, depth, nus, nu_list, out, names);
}

// A monitor catalogue (the node's grammar and messages, monitoring/catalogue.hpp): items without a
// depth are single-plane bodies, the others two-plane items; distributions are kept for the fragility.
BodyFile load_catalogue_items(const std::string& path) {
  std::vector<CatalogueItem> items;
  try {
    items = load_catalogue_items_file(path);
  } catch (const CatalogueError& e) {
    throw StudyError(e.what());
  }
  BodyFile out;
  for (const CatalogueItem& c : items) {
    const std::string where = path + ": item '" + c.spec.id + "': ";
    // The study scales its records itself (its intensity grid): a catalogue scale would be ignored.
    if (c.spec.input_gain != 1.0 || !c.uncertain.law(UncertainField::InputGain).is_fixed())
      throw StudyError(where + "input_gain: not used by the study (it scales the records itself); the monitor "
                               "and rocking_experiments apply it");
    auto laws = c.uncertain.uncertain() ? std::make_shared<const UncertainItemSpec>(c.uncertain) : nullptr;
    try {
      if (!c.spec.two_planes()) {
        if (c.spec.solid)
          out.notes.push_back(where + "its 3-D description runs on both horizontals, which needs a depth: "
                                      "only its x plane is run");
        StudyBody b{c.spec.id, plane_body(c.spec, Plane::X), laws, Plane::X, c.ensemble_size};
        out.bodies.push_back(std::move(b));
        continue;
      }
      StudyItem it;
      it.name = c.spec.id;
      it.uncertain = laws;
      it.ensemble_size = c.ensemble_size;
      it.x = plane_body(c.spec, Plane::X);
      it.depth = c.spec.depth;
      it.y = plane_body(c.spec, Plane::Y);
      if (const std::string e = validate(it.y); !e.empty()) throw StudyError("y plane: " + e);
      it.solid = c.spec.solid;
      out.items.push_back(std::move(it));
    } catch (const StudyError& e) {
      throw StudyError(where + e.what());
    }
  }
  return out;
}

}  // namespace

BodyFile load_body_file(const std::string& path) {
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
  bool catalogue = false;
  if (root.IsMap()) {
    catalogue = static_cast<bool>(root["items"]);
    if (catalogue && root["bodies"])
      throw StudyError(path + ": both 'bodies' and 'items' (give one list)");
    for (const auto& kv : root) {
      const std::string key = kv.first.as<std::string>();
      // A monitor catalogue's sensors feed the live node; the study brings its own records.
      if (key == "bodies" || key == "items" || (catalogue && key == "sensors")) continue;
      throw StudyError(path + ": unknown top-level key '" + key + "' (expected 'bodies' or 'items')");
    }
    prefix = catalogue ? "items" : "bodies";
    list = root[prefix];
  } else {
    prefix = "";
  }
  if (catalogue) return load_catalogue_items(path);
  if (!list || !list.IsSequence() || list.size() == 0)
    throw StudyError(path + ": expected a non-empty list of bodies (under 'bodies:' or 'items:')");
  BodyFile out;
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) load_entry(list[i], i, path, prefix, out, names);
  return out;
}

std::vector<StudyBody> load_bodies_yaml(const std::string& path) {
  BodyFile f = load_body_file(path);
  if (!f.items.empty())
    throw StudyError(path + ": '" + f.items.front().name +
                     "' has a depth (a two-plane item): read this file with load_body_file()");
  return std::move(f.bodies);
}

namespace {

json item_tally_json(const ItemTally& t) {
  json out = {{"cases", t.cases},
          {"overturned", t.overturned},
          {"overturned_percent", nullable(t.cases ? 100.0 * t.overturned / t.cases : NAN)},
          {"committed", t.committed},
          {"beyond_tipping", t.beyond_tipping},
          {"overturned_decided_by_y", t.overturned_decided_by_y},
          {"decided_by_y_percent_of_overturned",
           nullable(t.overturned ? 100.0 * t.overturned_decided_by_y / t.overturned : NAN)},
          {"overturned_x_plane_only", t.overturned_x_only},
          {"overturned_y_plane_only", t.overturned_y_only},
          {"overturned_both_planes", t.overturned_both}};
  if (t.solid_cases > 0)  // the 3-D model ran: its count beside the planar pair's
    out["solid"] = {{"cases", t.solid_cases},
                    {"overturned", t.solid_overturned},
                    {"overturned_percent", 100.0 * t.solid_overturned / t.solid_cases},
                    {"overturn_differs_from_planes", t.solid_differs}};
  return out;
}

json items_json(const ItemSummary& s) {
  json by_az = json::array();
  for (std::size_t a = 0; a < s.azimuths.size(); ++a) {
    json t = item_tally_json(s.by_azimuth[a]);
    t["azimuth_deg"] = s.azimuths[a];
    by_az.push_back(t);
  }
  json by_item = json::array();
  for (std::size_t i = 0; i < s.by_item.size(); ++i) {
    json t = item_tally_json(s.by_item[i]);
    t["item"] = s.item_names[i];
    by_item.push_back(t);
  }
  const StationPairs& k = s.skipped;
  return {{"description",
           "items with a depth: x plane (width) and y plane (depth) run separately with the station's two "
           "horizontals rotated to each azimuth (x along it, y 90 deg counter-clockwise), both polarities, "
           "the station's vertical when present; an item reaches a level when its first plane does"},
          {"model", "pure rocking (paper), the two planes uncoupled"},
          {"items", s.items},
          {"station_pairs", s.pairs},
          {"azimuths_deg", s.azimuths},
          {"all", item_tally_json(s.all)},
          {"by_azimuth", by_az},
          {"by_item", by_item},
          {"stations_not_run",
           {{"single_horizontal", k.single_horizontal},
            {"different_dt", k.different_dt},
            {"no_azimuth", k.no_azimuth},
            {"not_resolvable", k.not_resolvable}}},
          {"pairs_zero_padded", k.zero_padded},
          {"notes", k.notes}};
}

}  // namespace

std::string summary_json(const StudySummary& s, const StudyRunInfo& run, const ItemSummary* items) {
  json out;
  out["tool"] = "rocking_study";
  out["paper"] = "Boroschek & Romo, Overturning criteria for non-anchored non-symmetric rigid bodies";
  out["run"] = {{"records_dir", run.records_dir},
                {"from_manifest", run.from_manifest},
                {"bodies", run.bodies_source},
                {"method", run.method},
                {"model", run.model},
                {"rocking_model", kStudyRockingModel},
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
  if (items != nullptr) out["two_plane_items"] = items_json(*items);
  return json_text(out, 2) + "\n";
}

}  // namespace rocking_monitor::core::study
