// Dashboard's setup and lifetime: parameters, the catalogue from the parameter server, subscriptions,
// timers, start and orderly stop. The state cache, the HTTP server and the SSE push have files of
// their own.
#include "rocking_monitor/ros/dashboard.hpp"

#include <cmath>

#include <httplib.h>

namespace rocking_monitor::live {

Dashboard::Dashboard(::ros::NodeHandle nh, ::ros::NodeHandle pnh) : nh_(nh), pnh_(pnh) {}

Dashboard::~Dashboard() {
  // Timers and subscribers first, so that no callback pushes into a stopping server.
  update_timer_.stop();
  catalogue_timer_.stop();
  states_sub_.shutdown();
  alarms_sub_.shutdown();
  pair_alarms_sub_.shutdown();
  criteria_sub_.shutdown();
  diagnostics_sub_.shutdown();
  input_sub_.shutdown();
  stop_server();
}

bool Dashboard::load_parameters() {
  auto wrong = [](const char* name, const char* expected) {
    ROS_FATAL("dashboard: parameter ~%s has the wrong type (expected %s)", name, expected);
    return false;
  };
  XmlRpc::XmlRpcValue v;
  if (pnh_.getParam("bind_address", v)) {
    if (v.getType() != XmlRpc::XmlRpcValue::TypeString) return wrong("bind_address", "string");
    bind_address_ = static_cast<std::string>(v);
  }
  if (pnh_.getParam("port", v)) {
    if (v.getType() != XmlRpc::XmlRpcValue::TypeInt) return wrong("port", "integer");
    port_ = static_cast<int>(v);
  }
  if (pnh_.getParam("monitor", v)) {
    if (v.getType() != XmlRpc::XmlRpcValue::TypeString) return wrong("monitor", "string");
    monitor_ = static_cast<std::string>(v);
  }
  if (pnh_.getParam("pair", v)) {
    if (v.getType() != XmlRpc::XmlRpcValue::TypeString) return wrong("pair", "string: the other monitor's namespace");
    pair_ = static_cast<std::string>(v);
  }
  if (pnh_.getParam("update_rate", v)) {
    if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) update_rate_ = static_cast<double>(v);
    else if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) update_rate_ = static_cast<int>(v);
    else return wrong("update_rate", "number, Hz");
  }
  if (pnh_.getParam("sensor_topic", v)) {
    if (v.getType() != XmlRpc::XmlRpcValue::TypeString) return wrong("sensor_topic", "string");
    sensor_topic_ = static_cast<std::string>(v);
  }
  if (pnh_.getParam("sensor_type", v)) {
    if (v.getType() != XmlRpc::XmlRpcValue::TypeString) return wrong("sensor_type", "string: imu or accel");
    sensor_type_ = static_cast<std::string>(v);
  }
  if (sensor_type_ != "imu" && sensor_type_ != "accel") {
    ROS_FATAL("dashboard: ~sensor_type = '%s' must be imu (sensor_msgs/Imu) or accel (geometry_msgs/AccelStamped)",
              sensor_type_.c_str());
    return false;
  }
  if (pnh_.getParam("max_clients", v)) {
    if (v.getType() != XmlRpc::XmlRpcValue::TypeInt) return wrong("max_clients", "integer");
    max_clients_ = static_cast<int>(v);
  }
  if (bind_address_.empty()) {
    ROS_FATAL("dashboard: ~bind_address is empty (use 127.0.0.1, or 0.0.0.0 for every interface)");
    return false;
  }
  if (port_ < 0 || port_ > 65535) {
    ROS_FATAL("dashboard: ~port = %d must be in [1, 65535] (0 = any free port)", port_);
    return false;
  }
  if (monitor_.empty() || monitor_[0] != '/') {
    ROS_FATAL("dashboard: ~monitor = '%s' must be the monitor's absolute namespace, e.g. /rocking_monitor",
              monitor_.c_str());
    return false;
  }
  while (monitor_.size() > 1 && monitor_.back() == '/') monitor_.pop_back();
  while (pair_.size() > 1 && pair_.back() == '/') pair_.pop_back();
  if (!pair_.empty() && (pair_[0] != '/' || pair_ == monitor_)) {
    ROS_FATAL("dashboard: ~pair = '%s' must be the absolute namespace of the other monitor of a redundant pair "
              "(not ~monitor '%s'), e.g. /rocking_monitor_b", pair_.c_str(), monitor_.c_str());
    return false;
  }
  // At most 10 Hz (issue 14): a person cannot follow faster, and 10,000 items must stay cheap.
  if (!std::isfinite(update_rate_) || update_rate_ <= 0.0 || update_rate_ > 10.0) {
    ROS_FATAL("dashboard: ~update_rate = %g Hz must be in (0, 10]", update_rate_);
    return false;
  }
  if (max_clients_ < 1 || max_clients_ > 64) {
    ROS_FATAL("dashboard: ~max_clients = %d must be in [1, 64]", max_clients_);
    return false;
  }
  return true;
}

void Dashboard::load_catalogue() {
  // The monitor's own catalogue (rosparam-loaded into its namespace): geometry and pose in one place,
  // without waiting for tf. The poses are the catalogue's static `pose` entries in their parent frame.
  XmlRpc::XmlRpcValue sensors, items;
  const ::ros::NodeHandle mon(monitor_);
  if (!mon.getParam("items", items)) {
    ROS_WARN_THROTTLE(30.0, "dashboard: no catalogue at %s/items yet: items appear as ~states names them",
                      monitor_.c_str());
    return;
  }
  Catalogue cat;
  const bool empty = items.getType() == XmlRpc::XmlRpcValue::TypeArray && items.size() == 0;
  try {
    // An empty list is a valid, empty view (parse_catalogue refuses it: a monitor needs items).
    if (!empty) {
      if (!mon.getParam("sensors", sensors)) throw CatalogueError("sensors: missing");
      cat = parse_catalogue(sensors, items);
    }
  } catch (const std::exception& e) {
    ROS_WARN("dashboard: catalogue at %s not usable (%s): items appear as ~states names them",
             monitor_.c_str(), e.what());
    std::lock_guard<std::mutex> lock(mutex_);
    catalogue_loaded_ = true;  // do not retry a bad catalogue every second; a new id in ~states does
    catalogue_dirty_ = false;
    return;
  }
  // The input chart follows the monitor's first sensor unless ~sensor_topic names one.
  if (sensor_topic_.empty() && !cat.sensors.empty())
    subscribe_input(cat.sensors.front().topic, cat.sensors.front().type == SensorSpec::Type::Imu);
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<ItemGeometry> next;
  next.reserve(cat.items.size());
  for (auto& e : cat.items) next.push_back({std::move(e), true});
  // Items the states named that this catalogue lacks stay (drawn without geometry) until ~states drops them.
  std::unordered_map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < next.size(); ++i) index.emplace(next[i].entry.spec.id, i);
  for (const auto& old : items_)
    if (!old.from_catalogue && index.count(old.entry.spec.id) == 0) {
      index.emplace(old.entry.spec.id, next.size());
      next.push_back(old);
    }
  items_ = std::move(next);
  index_of_ = std::move(index);
  sent_.assign(items_.size(), Sent{});
  history_.assign(items_.size(), {});
  state_to_item_.clear();
  // Map the newest states onto the new list now: after the event no new ~states may come.
  if (latest_) rebuild_index_locked(*latest_, false);
  latest_sent_ = false;
  catalogue_loaded_ = true;
  catalogue_dirty_ = false;
  ROS_INFO("dashboard: catalogue of %zu items from %s", items_.size(), monitor_.c_str());
}

bool Dashboard::init() {
  if (!load_parameters() || !load_server_limits()) return false;
  load_catalogue();
  read_journal();
  if (!start_server()) return false;
  pnh_.setParam("url", url_);
  ROS_INFO("dashboard: open %s in a browser (monitor %s%s%s)", url_.c_str(), monitor_.c_str(),
           pair_.empty() ? "" : ", its pair ", pair_.c_str());

  const auto hints = ::ros::TransportHints().tcpNoDelay();
  states_sub_ = nh_.subscribe(monitor_ + "/states", 10, &Dashboard::on_states, this, hints);
  alarms_sub_ = nh_.subscribe(monitor_ + "/alarms", 1000, &Dashboard::on_alarm, this, hints);
  // A redundant pair: the other monitor's alarms too (states, criteria and the journal are ~monitor's).
  if (!pair_.empty()) pair_alarms_sub_ = nh_.subscribe(pair_ + "/alarms", 1000, &Dashboard::on_pair_alarm, this, hints);
  criteria_sub_ = nh_.subscribe(monitor_ + "/criteria", 1000, &Dashboard::on_criterion, this, hints);
  diagnostics_sub_ = nh_.subscribe("/diagnostics", 50, &Dashboard::on_diagnostics, this);
  if (!sensor_topic_.empty()) subscribe_input(sensor_topic_, sensor_type_ == "imu");
  // Wall timers: under sim time the clock stops with the bag, and the page must still get the last state.
  update_timer_ = nh_.createWallTimer(::ros::WallDuration(1.0 / update_rate_), &Dashboard::on_update_timer, this);
  catalogue_timer_ = nh_.createWallTimer(::ros::WallDuration(1.0), &Dashboard::on_catalogue_timer, this);
  return true;
}

void Dashboard::on_catalogue_timer(const ::ros::WallTimerEvent&) {
  bool reload = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    reload = !catalogue_loaded_ || catalogue_dirty_;
  }
  if (!reload) return;
  load_catalogue();
  publish_event("catalogue", "{}");  // the page reloads the snapshot
}

}  // namespace rocking_monitor::live
