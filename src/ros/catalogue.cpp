#include "rocking_monitor/ros/catalogue.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <set>
#include <sstream>

namespace rocking_monitor::live {
namespace {

using XmlRpc::XmlRpcValue;

const char* type_name(XmlRpcValue::Type t) {
  switch (t) {
    case XmlRpcValue::TypeBoolean: return "a boolean";
    case XmlRpcValue::TypeInt: return "an integer";
    case XmlRpcValue::TypeDouble: return "a number";
    case XmlRpcValue::TypeString: return "a string";
    case XmlRpcValue::TypeArray: return "a list";
    case XmlRpcValue::TypeStruct: return "a map";
    default: return "empty";
  }
}

// Reads fields of one list entry with messages that name the entry and the field.
class Entry {
 public:
  Entry(const XmlRpcValue& v, std::string where) : v_(const_cast<XmlRpcValue&>(v)), where_(std::move(where)) {
    if (v_.getType() != XmlRpcValue::TypeStruct) fail("", std::string("must be a map, found ") + type_name(v_.getType()));
  }
  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw CatalogueError(where_ + (field.empty() ? "" : ": " + field) + ": " + problem);
  }
  bool has(const std::string& f) const { return v_.hasMember(f); }
  std::string text(const std::string& f, bool required, const std::string& fallback = "") const {
    if (!has(f)) {
      if (required) fail(f, "missing");
      return fallback;
    }
    if (v_[f].getType() != XmlRpcValue::TypeString) fail(f, std::string("must be a string, found ") + type_name(v_[f].getType()));
    return static_cast<std::string>(v_[f]);
  }
  double number(const std::string& f, bool required, double fallback, const char* unit) const {
    if (!has(f)) {
      if (required) fail(f, std::string("missing (") + unit + ")");
      return fallback;
    }
    const XmlRpcValue& x = v_[f];
    double d;
    if (x.getType() == XmlRpcValue::TypeDouble) d = static_cast<double>(const_cast<XmlRpcValue&>(x));
    else if (x.getType() == XmlRpcValue::TypeInt) d = static_cast<int>(const_cast<XmlRpcValue&>(x));
    else fail(f, std::string("must be a number (") + unit + "), found " + type_name(x.getType()));
    if (!std::isfinite(d)) fail(f, "must be finite");
    return d;
  }
  const XmlRpcValue& member(const std::string& f) const { return v_[f]; }
  void only(const std::set<std::string>& known) const {
    for (auto it = v_.begin(); it != v_.end(); ++it)
      if (!known.count(it->first)) fail(it->first, "unknown key (a typo?)");
  }
  const std::string& where() const { return where_; }

 private:
  XmlRpcValue& v_;
  std::string where_;
};

std::string label(const char* list, int i, const std::string& name) {
  std::ostringstream os;
  os << list << "[" << i << "]";
  if (!name.empty()) os << " '" << name << "'";
  return os.str();
}

std::string name_of(const XmlRpcValue& v, const char* key) {
  auto& m = const_cast<XmlRpcValue&>(v);
  if (m.getType() == XmlRpcValue::TypeStruct && m.hasMember(key) && m[key].getType() == XmlRpcValue::TypeString)
    return static_cast<std::string>(m[key]);
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

Catalogue parse_catalogue(const XmlRpcValue& sensors, const XmlRpcValue& items) {
  Catalogue cat;
  if (sensors.getType() != XmlRpcValue::TypeArray || sensors.size() == 0)
    throw CatalogueError("sensors: must be a non-empty list of sensor entries");
  if (items.getType() != XmlRpcValue::TypeArray || items.size() == 0)
    throw CatalogueError("items: must be a non-empty list of catalogue items");

  std::set<std::string> sensor_names, topics;
  for (int i = 0; i < sensors.size(); ++i) {
    const XmlRpcValue& v = const_cast<XmlRpcValue&>(sensors)[i];
    const Entry e(v, label("sensors", i, name_of(v, "name")));
    e.only({"name", "topic", "type", "frame_id", "rate"});
    SensorSpec s;
    s.name = e.text("name", true);
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
  for (int i = 0; i < items.size(); ++i) {
    const XmlRpcValue& v = const_cast<XmlRpcValue&>(items)[i];
    const Entry e(v, label("items", i, name_of(v, "id")));
    e.only({"id", "description", "sensor", "frame", "shape", "width", "depth", "cg_height", "eccentricity",
            "eccentricity_y", "radius_of_gyration", "radius_of_gyration_y", "mu_s", "mu_k", "restitution",
            "overturn_angle", "pose"});
    CatalogueItem item;
    core::ItemSpec& s = item.spec;
    s.id = e.text("id", true);
    if (!ids.insert(s.id).second) e.fail("id", "duplicate id");
    s.description = e.text("description", false);
    s.sensor = e.text("sensor", true);
    if (!sensor_names.count(s.sensor)) e.fail("sensor", "'" + s.sensor + "' is not a sensor of this catalogue");
    s.frame = e.text("frame", false, s.id);
    core::BodyParameters& b = s.body;
    b.width = e.number("width", true, 0.0, "base width B, m");
    b.cg_height = e.number("cg_height", true, 0.0, "height h of the centre of mass, m");
    b.nu1 = e.number("eccentricity", false, 0.5, "nu1, dimensionless");
    const std::string shape = e.text("shape", false, "box");
    core::DepthParameters& d = s.depth;
    if (e.has("depth")) {
      d.depth = e.number("depth", true, 0.0, "base depth D along the item's y, m");
      d.eccentricity_y = e.number("eccentricity_y", false, 0.5, "nu1 of the y-z plane, dimensionless");
      if (e.has("radius_of_gyration_y")) d.radius_of_gyration_y = e.number("radius_of_gyration_y", false, 0.0, "m");
    } else {
      for (const char* key : {"eccentricity_y", "radius_of_gyration_y"})
        if (e.has(key)) e.fail(key, "needs depth (the base along the item's y): without it the item rocks in x only");
    }
    // Solid cylinder of diameter B and height 2h rocking about a horizontal diameter.
    auto cylinder = [&](double diameter) { return std::sqrt(diameter * diameter / 16.0 + b.cg_height * b.cg_height / 3.0); };
    if (e.has("radius_of_gyration")) {
      b.radius_of_gyration = e.number("radius_of_gyration", false, 0.0, "m");
    } else if (shape == "box") {
      // homogeneous block B x D x 2h: the core's default in both planes
    } else if (shape == "cylinder") {
      b.radius_of_gyration = cylinder(b.width);
      if (d.given() && !e.has("radius_of_gyration_y") && std::isfinite(d.depth)) d.radius_of_gyration_y = cylinder(d.depth);
    } else {
      e.fail("shape", "'" + shape + "' is not one of: box, cylinder (or give radius_of_gyration)");
    }
    b.mu_s = e.number("mu_s", false, b.mu_s, "static friction coefficient");
    if (e.has("mu_k")) b.mu_k = e.number("mu_k", false, 0.0, "kinetic friction coefficient");
    if (e.has("restitution")) b.restitution = e.number("restitution", false, 0.0, "angular-velocity ratio");
    if (e.has("overturn_angle")) b.overturn_angle = e.number("overturn_angle", false, 0.0, "rad");
    if (const std::string err = core::validate(s); !err.empty()) {
      // core messages read "item '<id>': <field> = <value> (...)"; keep the list position too.
      throw CatalogueError(e.where() + ": " + err.substr(err.find(": ") + 2));
    }
    if (e.has("pose")) {
      const Entry p(e.member("pose"), e.where() + ": pose");
      p.only({"parent_frame", "x", "y", "z", "roll", "pitch", "yaw"});
      item.pose.given = true;
      item.pose.parent_frame = p.text("parent_frame", true);
      item.pose.x = p.number("x", false, 0.0, "m");
      item.pose.y = p.number("y", false, 0.0, "m");
      item.pose.z = p.number("z", false, 0.0, "m");
      item.pose.roll = p.number("roll", false, 0.0, "rad");
      item.pose.pitch = p.number("pitch", false, 0.0, "rad");
      item.pose.yaw = p.number("yaw", false, 0.0, "rad");
    }
    cat.items.push_back(item);
  }
  return cat;
}

}  // namespace rocking_monitor::live
