// catalogue_check: loads a monitor catalogue with the node's own parser (monitoring/catalogue_file.hpp)
// and prints its error, or, with --json, what the monitor derives from each item in each rocking plane
// (physics/body.hpp, physics/criteria.hpp): the numbers scripts/rocking_catalogue.py check tabulates, so
// that they are the monitor's, not a second implementation's (issue 43).
//
//   catalogue_check CATALOGUE.yaml [--items-only] [--json]
// Exit status 0: the catalogue loads; 1: it does not (one line "<path>: items[k] 'id': field: ...").

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "rocking_monitor/json_text.hpp"

#include "command_line.hpp"
#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/monitoring/catalogue_file.hpp"
#include "rocking_monitor/physics/body.hpp"
#include "rocking_monitor/physics/criteria.hpp"
#include "rocking_monitor/physics/principal_planes.hpp"
#include "rocking_monitor/physics/support_polygon.hpp"

namespace {

using nlohmann::json;
using namespace rocking_monitor::core;
using rocking_monitor::json_text;

json finite_or_null(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

// One plane's derived quantities. Pivot 1 is the -x (-y) corner (theta > 0), pivot 2 the other.
json plane_json(const char* name, const BodyParameters& parameters) {
  const Body body(parameters);
  json plane = {{"plane", name},
                {"width", body.width()},                          // m
                {"cg_height", body.cg_height()},                  // m
                {"eccentricity", body.nu1()},
                {"radius_of_gyration", body.radius_of_gyration()},  // m
                {"mu_s", finite_or_null(body.mu_s())}};
  json pivots = json::array();
  for (int side : {1, -1}) {
    const Pivot& p = body.pivot(side);
    pivots.push_back({{"corner", side > 0 ? 1 : 2},
                      {"alpha", p.alpha},                          // rad
                      {"radius", p.radius},                        // m
                      {"p", p.p},                                  // rad/s
                      {"eta", p.restitution},                      // eq. 34 (or the measured ratio)
                      {"uplift_acceleration", kGravity * p.tan_alpha}});  // m/s^2, eq. 19 with a_yg = 0
  }
  plane["pivots"] = pivots;
  const Pivot& weak = body.pivot(1).alpha <= body.pivot(-1).alpha ? body.pivot(1) : body.pivot(-1);
  const ScreeningThresholds t = screening_thresholds(body);
  plane["housner_pseudo_velocity"] = t.housner_pseudo_velocity;  // m/s, eq. 1
  plane["housner_period"] = housner_period(body);                // s
  plane["ishiyama_velocity"] = t.ishiyama.velocity;              // m/s, eq. 2
  plane["ishiyama_acceleration"] = t.ishiyama.acceleration;      // m/s^2
  plane["ishiyama_equivalent_velocity"] = t.ishiyama_equivalent.velocity;
  plane["ishiyama_equivalent_acceleration"] = t.ishiyama_equivalent.acceleration;
  // Sliding precedes rocking when the friction is below what eq. 25 asks at the uplift threshold of
  // the weaker corner (eq. 26: 1/gamma = tan alpha).
  const double mu_needed = rock_without_slip_friction(body, weak, weak.tan_alpha);
  plane["mu_needed_to_rock"] = mu_needed;
  plane["slides_first"] = std::isfinite(body.mu_s()) ? json(body.mu_s() < mu_needed) : json(nullptr);
  return plane;
}

json item_json(const CatalogueItem& item) {
  const ItemSpec& s = item.spec;
  json j = {{"id", s.id}, {"description", s.description}, {"sensor", s.sensor},
            {"width", s.body.width}, {"eccentricity", s.body.nu1}, {"solid", s.solid.has_value()}};
  j["depth"] = s.two_planes() ? json(s.depth.depth) : json(nullptr);
  j["eccentricity_y"] = s.depth.eccentricity_y;
  if (item.pose.given) {
    j["pose"] = {{"parent_frame", item.pose.parent_frame}, {"x", item.pose.x}, {"y", item.pose.y},
                 {"yaw", item.pose.yaw}};
  }
  // What it stands on (issue 51): the support's top (m, item frame), the centre of mass's distance
  // inside its nearest edge at rest (m), and inside the contact (the base where it lies on the
  // support, m: over the centre of mass's height, the tangent of the smallest tipping angle there);
  // null on the open floor.
  j["support"] = nullptr;
  j["support_margin"] = nullptr;
  j["contact_margin"] = nullptr;
  j["support_lips"] = json::array();  // the lipped edges, numbered from 1 as in the catalogue
  if (s.solid)
    for (const int k : s.solid->support_lips) j["support_lips"].push_back(k + 1);
  if (s.solid && !s.solid->support.empty()) {
    const Eigen::Vector2d c = s.solid->centre_of_mass.head<2>();
    j["support"] = json::array();
    for (const auto& v : s.solid->support) j["support"].push_back({v.x(), v.y()});
    j["support_margin"] = inside_margin(s.solid->support, c);
    j["contact_margin"] = inside_margin(clip_convex(s.solid->base, s.solid->support), c);
  }
  json planes = json::array({plane_json("x", s.body)});
  if (s.two_planes()) planes.push_back(plane_json("y", y_plane_body(s.body, s.depth)));
  j["planes"] = planes;
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Loads a rocking_monitor catalogue with the node's parser; prints its first error, or "
               "(--json) what the monitor derives from each item."};
  std::string path;
  bool items_only = false, as_json = false;
  app.add_option("catalogue", path, "catalogue YAML (sensors: and items:)")->required();
  app.add_flag("--items-only", items_only, "only items: (their sensors are not checked against a list)");
  app.add_flag("--json", as_json, "print the derived quantities as JSON on stdout");
  if (auto status = rocking_monitor::tools::parse_command_line(app, argc, argv, "catalogue_check"))
    return *status;
  try {
    std::vector<CatalogueItem> items;
    std::size_t sensors = 0;
    if (items_only) {
      items = load_catalogue_items_file(path);
    } else {
      Catalogue c = load_catalogue_file(path);
      items = std::move(c.items);
      sensors = c.sensors.size();
    }
    if (as_json) {
      json out = json::array();
      for (const CatalogueItem& item : items) out.push_back(item_json(item));
      std::cout << json_text(json{{"catalogue", path}, {"sensors", sensors}, {"items", out}}, 1) << "\n";
    } else {
      std::cout << path << ": ok, " << items.size() << " items, " << sensors << " sensors\n";
    }
  } catch (const CatalogueError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {  // a body the parser accepted but the physics refuses
    std::cerr << path << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}
