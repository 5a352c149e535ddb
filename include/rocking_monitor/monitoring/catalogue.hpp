#pragma once

// The monitor's catalogue (sensors and items), parsed and validated without ROS: the node reads it
// from the parameter server (ros/catalogue_param.hpp converts), the tools and the study from a YAML
// file (catalogue_file.hpp). One grammar, one set of error messages.

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "rocking_monitor/monitoring/item_monitor.hpp"
#include "rocking_monitor/monitoring/uncertain_item.hpp"

namespace rocking_monitor::core {

/// A ground-acceleration input of the monitor.
struct SensorSpec {
  enum class Type { Imu, Accel };
  std::string name;      ///< referenced by items
  std::string topic;     ///< sensor_msgs/Imu or geometry_msgs/AccelStamped topic
  Type type = Type::Imu; ///< imu: specific force incl. gravity (REP 145); accel: ground acceleration
  std::string frame_id;  ///< overrides the messages' header.frame_id when not empty
  double rate = 200.0;   ///< expected sample rate, Hz (diagnostics only; dt comes from the stamps)
};

/// Optional static pose of an item, published by the monitor as a static transform.
struct ItemPose {
  bool given = false;
  std::string parent_frame;            ///< e.g. the sensor's frame
  double x = 0.0, y = 0.0, z = 0.0;    ///< m
  double roll = 0.0, pitch = 0.0, yaw = 0.0;  ///< rad
};

struct CatalogueItem {
  ItemSpec spec;  ///< the nominal item (every uncertain field at its law's nominal)
  /// The item's uncertain parameters (issue 13): uncertain.nominal == spec; laws Fixed for every
  /// field given as a plain number. uncertain.uncertain(): some field was given as a distribution.
  UncertainItemSpec uncertain;
  ItemPose pose;
  /// Members of the item's ensemble (catalogue key `ensemble_size`, only for an uncertain item);
  /// 0: the node's ~ensemble_size / the tool's --samples.
  int ensemble_size = 0;
};

struct Catalogue {
  std::vector<SensorSpec> sensors;
  std::vector<CatalogueItem> items;
};

/// Thrown with one line naming the entry and the field: "items[2] 'server_rack': width: ...".
class CatalogueError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Which of n shards an item belongs to (1..n): FNV-1a hash of its id, modulo n. Stable across
/// machines, runs and catalogue order, so n monitors on n machines split one catalogue without
/// talking to each other.
int shard_of(const std::string& id, int n);

/// Parses "k/n" (1 <= k <= n); throws CatalogueError naming the text otherwise.
std::pair<int, int> parse_shard(const std::string& text);

/// The items of shard k of n (catalogue order kept; sensors all kept).
Catalogue select_shard(const Catalogue& catalogue, int k, int n);

/// Parses the `sensors` and `items` lists (JSON values as converted from the parameter server or a
/// YAML file: numbers, strings, booleans, lists, maps). Validates every field (types, units, ranges,
/// unique ids, known sensors). The numeric keys width, depth, cg_height, eccentricity,
/// eccentricity_y, radius_of_gyration, radius_of_gyration_y, mu_s, restitution and input_gain may be distribution
/// maps ({uniform: [lo, hi]}, {normal: [mean, sd]}, {lognormal: [median, beta]}, optionally nominal: x;
/// config/catalogue_uncertain_example.yaml), and an item with one may give `ensemble_size` (members,
/// 1..100000); errors name the item and the field: "items[2] 'cart': mu_s: uniform: lo 0.6 > hi 0.3".
Catalogue parse_catalogue(const nlohmann::json& sensors, const nlohmann::json& items);

/// The items alone (offline tools, the study: no sensors to check against). An item's `sensor`,
/// `frame`, `pose` and `description` are read and checked for type, the sensor name is not checked (default "offline").
std::vector<CatalogueItem> parse_catalogue_items(const nlohmann::json& items);

}  // namespace rocking_monitor::core
