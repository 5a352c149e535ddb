#include "rocking_monitor/monitoring/catalogue.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "rocking_monitor/monitoring/catalogue_names.hpp"
#include "rocking_monitor/safe_text.hpp"

namespace rocking_monitor::core {
namespace {

using nlohmann::json;

const char* type_name(const json& v) {
  switch (v.type()) {
    case json::value_t::boolean: return "a boolean";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return "an integer";
    case json::value_t::number_float: return "a number";
    case json::value_t::string: return "a string";
    case json::value_t::array: return "a list";
    case json::value_t::object: return "a map";
    default: return "empty";
  }
}

// Reads fields of one list entry with messages that name the entry and the field.
class Entry {
 public:
  Entry(const json& v, std::string where) : v_(v), where_(std::move(where)) {
    if (!v_.is_object()) fail("", std::string("must be a map, found ") + type_name(v_));
  }
  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw CatalogueError(where_ + (field.empty() ? "" : ": " + field) + ": " + problem);
  }
  bool has(const std::string& f) const { return v_.contains(f); }
  std::string text(const std::string& f, bool required, const std::string& fallback = "") const {
    if (!has(f)) {
      if (required) fail(f, "missing");
      return fallback;
    }
    if (!v_[f].is_string()) fail(f, std::string("must be a string, found ") + type_name(v_[f]));
    return v_[f].get<std::string>();
  }
  double number(const std::string& f, bool required, double fallback, const char* unit) const {
    if (!has(f)) {
      if (required) fail(f, std::string("missing (") + unit + ")");
      return fallback;
    }
    const json& x = v_[f];
    if (!x.is_number()) fail(f, std::string("must be a number (") + unit + "), found " + type_name(x));
    const double d = x.get<double>();
    if (!std::isfinite(d)) fail(f, "must be finite");
    return d;
  }
  // A numeric key that may also be a distribution map ({uniform: [lo, hi]}, {normal: [mean, sd]},
  // {lognormal: [median, beta]}, optionally with nominal: x). Returns the nominal value; the law (if
  // any) goes into u.
  double quantity(const std::string& f, UncertainField field, bool required, double fallback, const char* unit,
                  UncertainItemSpec& u) const {
    if (!has(f) || !v_[f].is_object()) return number(f, required, fallback, unit);
    const Distribution d = distribution(f, field);
    u.law(field) = d;
    return d.nominal();
  }
  Distribution distribution(const std::string& f, UncertainField field) const {
    const json& m = v_[f];
    std::string law;
    const json* params = nullptr;
    bool nominal_given = false;
    double nominal = 0.0;
    for (auto it = m.begin(); it != m.end(); ++it) {
      const std::string& key = it.key();
      if (key == "nominal") {
        nominal = scalar(it.value(), f, "nominal");
        nominal_given = true;
      } else if (key == "uniform" || key == "normal" || key == "lognormal") {
        if (!law.empty()) fail(f, "two distributions (" + law + ", " + key + "): give one");
        law = key;
        params = &it.value();
      } else {
        fail(f, "'" + key + "' is not a distribution (uniform, normal, lognormal) nor nominal");
      }
    }
    if (law.empty())
      fail(f, "a map must give a distribution: {uniform: [lo, hi]}, {normal: [mean, sd]} or "
              "{lognormal: [median, beta]}, optionally with nominal: x");
    const char* first = law == "uniform" ? "lo" : law == "normal" ? "mean" : "median";
    const char* second = law == "uniform" ? "hi" : law == "normal" ? "sd" : "beta";
    const std::string shape = law + ": must be a list [" + first + ", " + second + "] of 2 numbers, found ";
    if (!params->is_array()) fail(f, shape + type_name(*params));
    if (params->size() != 2) fail(f, shape + std::to_string(params->size()) + (params->size() == 1 ? " entry" : " entries"));
    const double a = scalar((*params)[0], f, law + ": " + first), b = scalar((*params)[1], f, law + ": " + second);
    const ValueRange range = valid_range(field);
    Distribution d = law == "uniform"  ? Distribution::uniform(a, b, range)
                           : law == "normal" ? Distribution::normal(a, b, range)
                                             : Distribution::lognormal(a, b, range);
    if (nominal_given) d = d.with_nominal(nominal);
    if (const std::string error = validate(d, f); !error.empty()) throw CatalogueError(where_ + ": " + error);
    return d;
  }
  const json& member(const std::string& f) const { return v_[f]; }
  void only(const std::set<std::string>& known) const {
    for (auto it = v_.begin(); it != v_.end(); ++it)
      if (!known.count(it.key())) fail(it.key(), "unknown key (a typo?)");
  }
  const std::string& where() const { return where_; }
  // A number inside a distribution map ("<field>: <what>: must be a number, found ...").
  double scalar(const json& x, const std::string& f, const std::string& what) const {
    if (x.is_number()) return x.get<double>();
    fail(f, what + ": must be a number, found " + type_name(x));
  }

 private:
  const json& v_;
  std::string where_;
};

// A list of `n` numbers (n = 0: any length), each finite: "<field>: <what>".
std::vector<double> numbers(const Entry& e, const json& x, const std::string& f, std::size_t n, const std::string& what) {
  if (!x.is_array()) e.fail(f, what + ": must be a list, found " + type_name(x));
  if (n != 0 && x.size() != n)
    e.fail(f, what + ": must have " + std::to_string(n) + " numbers, found " + std::to_string(x.size()));
  std::vector<double> out;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double d = e.scalar(x[k], f, what + " entry " + std::to_string(k + 1));
    if (!std::isfinite(d)) e.fail(f, what + " entry " + std::to_string(k + 1) + ": must be finite");
    out.push_back(d);
  }
  return out;
}

// The 3-D description (model/rocking_3d_model.hpp): base_polygon, centre_of_mass, central_inertia
// and mass come together; restitution_factor is optional.
void parse_solid(const Entry& e, ItemSpec& s) {
  const char* keys[] = {"mass", "centre_of_mass", "central_inertia", "base_polygon"};
  bool any = false;
  for (const char* k : keys) any = any || e.has(k);
  if (!any) {
    if (e.has("restitution_factor")) e.fail("restitution_factor", "needs the 3-D description (base_polygon, ...)");
    if (e.has("hull")) e.fail("hull", "needs the 3-D description (base_polygon, ...)");
    if (e.has("support")) e.fail("support", "needs the 3-D description (base_polygon, ...)");
    if (e.has("support_lips")) e.fail("support_lips", "needs the 3-D description (base_polygon, ...) and a support");
    if (e.has("support_lip_height")) e.fail("support_lip_height", "needs the 3-D description (base_polygon, ...) and a support");
    return;
  }
  for (const char* k : keys)
    if (!e.has(k)) e.fail(k, "missing: the 3-D description needs mass, centre_of_mass, central_inertia and base_polygon");
  BaseBodyParameters b;
  b.mass = e.number("mass", true, 0.0, "kg");
  const auto c = numbers(e, e.member("centre_of_mass"), "centre_of_mass", 3, "[x, y, z] in m");
  b.centre_of_mass = Eigen::Vector3d(c[0], c[1], c[2]);
  const json& inertia = e.member("central_inertia");
  if (!inertia.is_array() || inertia.size() != 3)
    e.fail("central_inertia", "must be 3 rows of 3 numbers (kg m^2)");
  for (int r = 0; r < 3; ++r) {
    const auto row = numbers(e, inertia[static_cast<std::size_t>(r)], "central_inertia", 3, "row " + std::to_string(r + 1) + " (kg m^2)");
    for (int k = 0; k < 3; ++k) b.central_inertia(r, k) = row[static_cast<std::size_t>(k)];
  }
  const json& poly = e.member("base_polygon");
  if (!poly.is_array()) e.fail("base_polygon", "must be a list of [x, y] vertices (m)");
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const auto v = numbers(e, poly[k], "base_polygon", 2, "vertex " + std::to_string(k + 1) + " [x, y] (m)");
    b.base.emplace_back(v[0], v[1]);
  }
  if (e.has("hull")) {
    // The contact geometry beyond the base (issue 40 part 3): the body's convex hull points.
    const json& hull = e.member("hull");
    if (!hull.is_array()) e.fail("hull", "must be a list of [x, y, z] points (m)");
    for (std::size_t k = 0; k < hull.size(); ++k) {
      const auto v = numbers(e, hull[k], "hull", 3, "point " + std::to_string(k + 1) + " [x, y, z] (m)");
      b.hull.emplace_back(v[0], v[1], v[2]);
    }
  }
  if (e.has("support")) {
    // What it stands on (issue 51): a plinth's, shelf's or pedestal's top, in the item frame.
    const json& support = e.member("support");
    if (!support.is_array()) e.fail("support", "must be a list of [x, y] vertices (m): the top of the plinth, shelf or pedestal");
    for (std::size_t k = 0; k < support.size(); ++k) {
      const auto v = numbers(e, support[k], "support", 2, "vertex " + std::to_string(k + 1) + " [x, y] (m)");
      b.support.emplace_back(v[0], v[1]);
    }
  }
  if (e.has("support_lips")) {
    // The support's edges with a lip, numbered from 1 as its vertices (edge k: vertex k to k + 1).
    const json& lips = e.member("support_lips");
    if (!lips.is_array()) e.fail("support_lips", "must be a list of the support's edge numbers (edge k runs from vertex k to k + 1)");
    for (std::size_t k = 0; k < lips.size(); ++k) {
      if (!lips[k].is_number_integer())
        e.fail("support_lips", "entry " + std::to_string(k + 1) + " must be an edge number (an integer from 1)");
      b.support_lips.push_back(lips[k].get<int>() - 1);
    }
  }
  if (e.has("support_lip_height"))
    b.support_lip_height = e.number("support_lip_height", false, 0.0, "the lips' height above the support's top (m)");
  b.mu_s = s.body.mu_s;
  b.mu_k = s.body.mu_k;
  b.overturn_angle = s.body.overturn_angle;
  if (e.has("restitution_factor"))
    b.restitution_factor = e.number("restitution_factor", false, 1.0, "multiplies the 3-D impact law's angular velocity");
  if (const std::string err = validate(b); !err.empty()) e.fail("", err);
  if (!b.hull.empty()) {
    // The hull's own checks (its base face, the centre of mass inside) need the hull built.
    try {
      BaseBody check(b);
    } catch (const BodyError& err) {
      e.fail("", err.what());
    }
  }
  s.solid = b;
}

std::string label(const char* list, int i, const std::string& name) {
  std::ostringstream os;
  os << list << "[" << i << "]";
  if (!name.empty()) os << " '" << printable_text(name, 64) << "'";  // the id may be what is wrong
  return os.str();
}

std::string name_of(const json& v, const char* key) {
  if (v.is_object() && v.contains(key) && v[key].is_string()) return v[key].get<std::string>();
  return {};
}

}  // namespace

int shard_of(const std::string& id, int n) {
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a, 64 bit
  for (unsigned char c : id) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return static_cast<int>(h % static_cast<std::uint64_t>(n)) + 1;
}

std::pair<int, int> parse_shard(const std::string& text) {
  int k = 0, n = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%d/%d%c", &k, &n, &tail) != 2 || n < 1 || k < 1 || k > n)
    throw CatalogueError("shard: '" + text + "' is not k/n with 1 <= k <= n (e.g. 2/3)");
  return {k, n};
}

Catalogue select_shard(const Catalogue& catalogue, int k, int n) {
  Catalogue out;
  out.sensors = catalogue.sensors;
  for (const CatalogueItem& item : catalogue.items)
    if (shard_of(item.spec.id, n) == k) out.items.push_back(item);
  return out;
}

namespace {

// id, description, sensor and frame; `sensor_names` null: the sensor is not checked (offline use).
void parse_names(const Entry& e, ItemSpec& s, const std::set<std::string>* sensor_names, std::set<std::string>& ids) {
  s.id = e.text("id", true);
  // Live ids reach MQTT topics, mail and file names; offline catalogues may name ensemble members.
  const NameRule rule = sensor_names != nullptr ? NameRule::Strict : NameRule::MemberSuffix;
  if (const std::string why = name_problem(s.id, rule); !why.empty()) e.fail("id", why);
  if (!ids.insert(s.id).second) e.fail("id", "duplicate id");
  s.description = e.text("description", false);
  // Offline, an item may come without a sensor (the record is the input); validate() wants a name.
  s.sensor = e.text("sensor", sensor_names != nullptr, "offline");
  if (sensor_names != nullptr && !sensor_names->count(s.sensor))
    e.fail("sensor", "'" + s.sensor + "' is not a sensor of this catalogue");
  s.frame = e.text("frame", false, s.id);
}

// depth and the y-z plane's eccentricity and radius of gyration, which mean nothing without it.
void parse_depth(const Entry& e, DepthParameters& d, UncertainItemSpec& u) {
  using F = UncertainField;
  if (e.has("depth")) {
    d.depth = e.quantity("depth", F::Depth, true, 0.0, "base depth D along the item's y, m", u);
    d.eccentricity_y = e.quantity("eccentricity_y", F::EccentricityY, false, 0.5, "nu1 of the y-z plane, dimensionless", u);
    if (e.has("radius_of_gyration_y"))
      d.radius_of_gyration_y = e.quantity("radius_of_gyration_y", F::RadiusOfGyrationY, false, 0.0, "m", u);
  } else {
    for (const char* key : {"eccentricity_y", "radius_of_gyration_y"})
      if (e.has(key)) e.fail(key, "needs depth (the base along the item's y): without it the item rocks in x only");
  }
}

// The rocking planes' geometry: width, cg_height, eccentricity, depth and the radii of gyration
// (given, or from shape).
void parse_plane_geometry(const Entry& e, ItemSpec& s, UncertainItemSpec& u) {
  using F = UncertainField;
  BodyParameters& b = s.body;
  b.width = e.quantity("width", F::Width, true, 0.0, "base width B, m", u);
  b.cg_height = e.quantity("cg_height", F::CgHeight, true, 0.0, "height h of the centre of mass, m", u);
  b.nu1 = e.quantity("eccentricity", F::Eccentricity, false, 0.5, "nu1, dimensionless", u);
  const std::string shape = e.text("shape", false, "box");
  DepthParameters& d = s.depth;
  parse_depth(e, d, u);
  // Solid cylinder of diameter B and height 2h rocking about a horizontal diameter; an ensemble member
  // re-derives it from its own B (D) and h.
  if (e.has("radius_of_gyration")) {
    b.radius_of_gyration = e.quantity("radius_of_gyration", F::RadiusOfGyration, false, 0.0, "m", u);
  } else if (shape == "box") {
    // homogeneous block B x D x 2h: the core's default in both planes
  } else if (shape == "cylinder") {
    b.radius_of_gyration = cylinder_radius_of_gyration(b.width, b.cg_height);
    u.cylinder_radius_x = true;
    if (d.given() && !e.has("radius_of_gyration_y") && std::isfinite(d.depth)) {
      d.radius_of_gyration_y = cylinder_radius_of_gyration(d.depth, b.cg_height);
      u.cylinder_radius_y = true;
    }
  } else {
    e.fail("shape", "'" + shape + "' is not one of: box, cylinder (or give radius_of_gyration)");
  }
}

// Friction, restitution and the overturn angle: what happens at the contact.
void parse_contact(const Entry& e, BodyParameters& b, UncertainItemSpec& u) {
  using F = UncertainField;
  b.mu_s = e.quantity("mu_s", F::MuS, false, b.mu_s, "static friction coefficient", u);
  if (e.has("mu_k")) b.mu_k = e.number("mu_k", false, 0.0, "kinetic friction coefficient");
  if (e.has("restitution")) b.restitution = e.quantity("restitution", F::Restitution, false, 0.0, "angular-velocity ratio", u);
  if (e.has("restitution_shift"))
    b.restitution_shift = e.number("restitution_shift", false, 0.0, "added to each pivot's angular-velocity ratio");
  if (e.has("overturn_angle")) b.overturn_angle = e.number("overturn_angle", false, 0.0, "rad");
}

// ensemble_size, only for an item with a distribution.
void parse_ensemble_size(const Entry& e, const UncertainItemSpec& u, CatalogueItem& item) {
  if (!e.has("ensemble_size")) return;
  const double n = e.number("ensemble_size", false, 0.0, "members");
  if (!u.uncertain())
    e.fail("ensemble_size", "only for an item with a distribution (this item is deterministic: one run)");
  if (n != std::floor(n) || n < 1 || n > 100000) e.fail("ensemble_size", "must be an integer in [1, 100000]");
  item.ensemble_size = static_cast<int>(n);
}

// The optional static pose the monitor publishes as a transform.
void parse_pose(const Entry& e, ItemPose& pose) {
  if (!e.has("pose")) return;
  const Entry p(e.member("pose"), e.where() + ": pose");
  p.only({"parent_frame", "x", "y", "z", "roll", "pitch", "yaw"});
  pose.given = true;
  pose.parent_frame = p.text("parent_frame", true);
  pose.x = p.number("x", false, 0.0, "m");
  pose.y = p.number("y", false, 0.0, "m");
  pose.z = p.number("z", false, 0.0, "m");
  pose.roll = p.number("roll", false, 0.0, "rad");
  pose.pitch = p.number("pitch", false, 0.0, "rad");
  pose.yaw = p.number("yaw", false, 0.0, "rad");
}

// One `items:` entry; `sensor_names` null: the sensor is not checked (offline use).
CatalogueItem parse_item(const json& v, int i, const std::set<std::string>* sensor_names, std::set<std::string>& ids) {
  const Entry e(v, label("items", i, name_of(v, "id")));
  e.only({"id", "description", "sensor", "frame", "shape", "width", "depth", "cg_height", "eccentricity",
          "eccentricity_y", "radius_of_gyration", "radius_of_gyration_y", "mu_s", "mu_k", "restitution",
          "restitution_shift", "overturn_angle", "pose", "ensemble_size", "mass", "centre_of_mass",
          "central_inertia", "base_polygon", "restitution_factor", "hull", "support", "support_lips", "support_lip_height", "input_gain"});
  CatalogueItem item;
  ItemSpec& s = item.spec;
  UncertainItemSpec& u = item.uncertain;
  parse_names(e, s, sensor_names, ids);
  parse_plane_geometry(e, s, u);
  parse_contact(e, s.body, u);
  parse_solid(e, s);
  // A scale of the input (issue 41: the calibrated fragility of a shaking-table rock is a lognormal
  // input_gain): a number or a distribution, dimensionless, > 0 (validate(ItemSpec) says so).
  s.input_gain = e.quantity("input_gain", UncertainField::InputGain, false, 1.0,
                            "dimensionless scale of the ground acceleration", u);
  u.nominal = s;
  for (const std::string& err : {validate(s), validate(u)}) {
    // core messages read "item '<id>': <field> ..."; keep the list position too.
    if (!err.empty()) throw CatalogueError(e.where() + ": " + err.substr(err.find(": ") + 2));
  }
  parse_ensemble_size(e, u, item);
  parse_pose(e, item.pose);
  return item;
}

void check_items_list(const json& items) {
  if (!items.is_array() || items.empty()) throw CatalogueError("items: must be a non-empty list of catalogue items");
}

}  // namespace

Catalogue parse_catalogue(const json& sensors, const json& items) {
  Catalogue cat;
  if (!sensors.is_array() || sensors.empty())
    throw CatalogueError("sensors: must be a non-empty list of sensor entries");
  check_items_list(items);

  std::set<std::string> sensor_names, topics;
  for (int i = 0; i < static_cast<int>(sensors.size()); ++i) {
    const json& v = sensors[static_cast<std::size_t>(i)];
    const Entry e(v, label("sensors", i, name_of(v, "name")));
    e.only({"name", "topic", "type", "frame_id", "rate"});
    SensorSpec s;
    s.name = e.text("name", true);
    if (const std::string why = name_problem(s.name); !why.empty()) e.fail("name", why);
    s.topic = e.text("topic", true);
    const std::string type = e.text("type", false, "imu");
    if (type == "imu") s.type = SensorSpec::Type::Imu;
    else if (type == "accel") s.type = SensorSpec::Type::Accel;
    else e.fail("type", "'" + type + "' is not one of: imu, accel");
    s.frame_id = e.text("frame_id", false);
    s.rate = e.number("rate", false, 200.0, "Hz");
    if (s.rate <= 0.0) e.fail("rate", "must be > 0 Hz");
    if (!sensor_names.insert(s.name).second) e.fail("name", "duplicate sensor name '" + s.name + "'");
    if (!topics.insert(s.topic).second) e.fail("topic", "topic '" + s.topic + "' used by two sensors");
    cat.sensors.push_back(s);
  }

  std::set<std::string> ids;
  for (int i = 0; i < static_cast<int>(items.size()); ++i)
    cat.items.push_back(parse_item(items[static_cast<std::size_t>(i)], i, &sensor_names, ids));
  return cat;
}

std::vector<CatalogueItem> parse_catalogue_items(const json& items) {
  check_items_list(items);
  std::set<std::string> ids;
  std::vector<CatalogueItem> out;
  for (int i = 0; i < static_cast<int>(items.size()); ++i)
    out.push_back(parse_item(items[static_cast<std::size_t>(i)], i, nullptr, ids));
  return out;
}

}  // namespace rocking_monitor::core
