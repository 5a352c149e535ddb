#pragma once

// The catalogue as the node reads it from the parameter server: the parameters converted to JSON and
// parsed by the core (monitoring/catalogue.hpp), so the node, the tools and the study share one
// grammar and one set of messages.

#include <XmlRpcValue.h>
#include <nlohmann/json_fwd.hpp>

#include "rocking_monitor/monitoring/catalogue.hpp"

namespace rocking_monitor::live {

using core::Catalogue;
using core::CatalogueError;
using core::CatalogueItem;
using core::ItemPose;
using core::SensorSpec;
using core::parse_shard;
using core::select_shard;
using core::shard_of;

/// A parameter value as JSON (int, double, bool, string, list, map; others null).
nlohmann::json to_json(const XmlRpc::XmlRpcValue& value);

/// parse_catalogue() of the `sensors` and `items` parameters (as loaded by rosparam from
/// config/catalogue_example.yaml).
Catalogue parse_catalogue(const XmlRpc::XmlRpcValue& sensors, const XmlRpc::XmlRpcValue& items);

}  // namespace rocking_monitor::live
