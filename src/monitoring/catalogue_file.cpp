#include "rocking_monitor/monitoring/catalogue_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

namespace rocking_monitor::core {
namespace {

using nlohmann::json;

// A plain scalar the way YAML 1.2's core schema types it (rosparam reads these files with the same
// result for every value a catalogue holds).
json scalar_to_json(const YAML::Node& node) {
  const std::string& t = node.Scalar();
  if (node.Tag() == "!") return t;  // quoted: always a string
  if (t.empty() || t == "~" || t == "null" || t == "Null" || t == "NULL") return nullptr;
  if (t == "true" || t == "True" || t == "TRUE") return true;
  if (t == "false" || t == "False" || t == "FALSE") return false;
  if (t == ".nan" || t == ".NaN" || t == ".NAN") return std::numeric_limits<double>::quiet_NaN();
  for (const char* sign : {"", "+", "-"}) {
    for (const char* inf : {".inf", ".Inf", ".INF"}) {
      if (t == std::string(sign) + inf)
        return (sign[0] == '-' ? -1.0 : 1.0) * std::numeric_limits<double>::infinity();
    }
  }
  const char* begin = t.c_str();
  char* end = nullptr;
  errno = 0;
  const long long i = std::strtoll(begin, &end, 10);
  if (end != begin && *end == '\0' && errno == 0) return i;
  errno = 0;
  const double d = std::strtod(begin, &end);
  // Only decimal notation: strtod also reads "nan", "inf" and hex, which YAML does not.
  const bool decimal = t.find_first_not_of("0123456789+-.eE") == std::string::npos;
  if (decimal && end != begin && *end == '\0') return d;
  return t;
}

json to_json(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar: return scalar_to_json(node);
    case YAML::NodeType::Sequence: {
      json a = json::array();
      for (const YAML::Node& n : node) a.push_back(to_json(n));
      return a;
    }
    case YAML::NodeType::Map: {
      json o = json::object();
      for (const auto& kv : node) o[kv.first.as<std::string>()] = to_json(kv.second);
      return o;
    }
    default: return nullptr;
  }
}

template <class F>
auto with_path(const std::string& path, F&& parse) {
  try {
    return parse();
  } catch (const CatalogueError& e) {
    throw CatalogueError(path + ": " + e.what());
  }
}

}  // namespace

json load_yaml_as_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw CatalogueError(path + ": cannot read");
  try {
    return to_json(YAML::Load(in));
  } catch (const YAML::Exception& e) {
    throw CatalogueError(path + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) +
                         ": " + e.msg);
  }
}

Catalogue load_catalogue_file(const std::string& path) {
  const json root = load_yaml_as_json(path);
  return with_path(path, [&] {
    if (!root.is_object()) throw CatalogueError("expected a map with 'sensors:' and 'items:'");
    return parse_catalogue(root.value("sensors", json()), root.value("items", json()));
  });
}

std::vector<CatalogueItem> load_catalogue_items_file(const std::string& path) {
  const json root = load_yaml_as_json(path);
  return with_path(path, [&] {
    if (!root.is_object()) throw CatalogueError("expected a map with 'items:'");
    return parse_catalogue_items(root.value("items", json()));
  });
}

}  // namespace rocking_monitor::core
