#include "rocking_monitor/monitoring/item_spec.hpp"

#include <cmath>
#include <exception>
#include <string>

namespace rocking_monitor::core {
namespace {

// Body messages read "invalid body: <field> = <value> (...)"; the item's message names the item.
std::string without_prefix(std::string e) {
  const std::string prefix = "invalid body: ";
  if (e.rfind(prefix, 0) == 0) e = e.substr(prefix.size());
  return e;
}

}  // namespace

std::string validate(const ItemSpec& spec) {
  if (spec.id.empty()) return "item without an 'id'";
  const std::string who = "item '" + spec.id + "': ";
  if (spec.sensor.empty()) return who + "sensor: missing (name of the sensor that feeds the item)";
  if (spec.frame.empty()) return who + "frame: missing (tf frame of the item)";
  if (!(std::isfinite(spec.input_gain) && spec.input_gain > 0.0))
    return who + "input_gain: " + std::to_string(spec.input_gain) + " must be finite and > 0 (dimensionless scale of the ground acceleration)";
  if (const std::string e = validate(spec.body); !e.empty()) return who + without_prefix(e);
  if (const std::string e = validate(spec.depth); !e.empty()) return who + e;
  try {
    Body x(spec.body);
    if (spec.two_planes()) Body y(y_plane_body(spec.body, spec.depth));
  } catch (const std::exception& e) {
    return who + without_prefix(e.what());
  }
  return {};
}

}  // namespace rocking_monitor::core
