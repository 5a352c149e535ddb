#pragma once

// A monitor catalogue read from a YAML file (the file `rosparam load` gives the node), for the
// offline tools and the study: the same grammar and messages as the live node (catalogue.hpp).

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "rocking_monitor/monitoring/catalogue.hpp"

namespace rocking_monitor::core {

/// The YAML document of `path` as JSON: plain scalars become integers, numbers (also .nan, .inf),
/// booleans (true/false) or null (~, null, empty) when they read as one in full, else strings; quoted
/// scalars stay strings. Throws CatalogueError "<path>: cannot read" or "<path>:<line>:<col>: <problem>".
nlohmann::json load_yaml_as_json(const std::string& path);

/// The whole catalogue (top-level `sensors:` and `items:`). Errors read "<path>: items[2] 'cart': ...".
Catalogue load_catalogue_file(const std::string& path);

/// The items only (`items:`; a `sensors:` list is allowed and ignored; the items' sensors are not
/// checked). Errors read "<path>: items[2] 'cart': ...".
std::vector<CatalogueItem> load_catalogue_items_file(const std::string& path);

}  // namespace rocking_monitor::core
