// RockingMonitor's setup and lifetime: parameters, init() (catalogue, topics, diagnostics,
// subscriptions, timers), the log of each item's initial model, the startup timer's warning and
// the ~reset service. The per-sample path, publication and diagnostics have files of their own.
#include "rocking_monitor/ros/monitor.hpp"

#include <cmath>
#include <cstdlib>
#include <map>
#include <thread>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/MarkerArray.h>

#include "rocking_monitor/integrate/solver_settings.hpp"

namespace rocking_monitor::live {
namespace {

// Reads ~name if present; false (after a ROS_FATAL naming it) on a wrong type. Integers are
// accepted for numbers, and numeric strings too (YAML reads "1e-6" as a string).
template <class T>
bool param(const ::ros::NodeHandle& nh, const std::string& name, T& value, const char* unit) {
  if (!nh.hasParam(name)) return true;
  if constexpr (std::is_same_v<T, double>) {
    XmlRpc::XmlRpcValue v;
    nh.getParam(name, v);
    if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) { value = static_cast<double>(v); return true; }
    if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) { value = static_cast<int>(v); return true; }
    if (v.getType() == XmlRpc::XmlRpcValue::TypeString) {
      const std::string text = static_cast<std::string>(v);
      char* end = nullptr;
      const double d = std::strtod(text.c_str(), &end);
      if (!text.empty() && end == text.c_str() + text.size()) { value = d; return true; }
    }
  } else if (nh.getParam(name, value)) {
    return true;
  }
  ROS_FATAL("rocking_monitor: parameter ~%s has the wrong type (expected %s)", name.c_str(), unit);
  return false;
}

}  // namespace

RockingMonitor::RockingMonitor(::ros::NodeHandle nh, ::ros::NodeHandle pnh) : nh_(nh), pnh_(pnh) {}

RockingMonitor::~RockingMonitor() {
  journal_.drain();  // the last alarms published while the publishers are still there
}

bool RockingMonitor::load_parameters() {
  std::string method = "dopri5", model = "nonlinear", baseline = "tracked", fidelity = "adaptive", solid = "auto";
  int substeps = options_.solver.substeps;
  bool ok = param(pnh_, "method", method, "string") && param(pnh_, "model", model, "string") &&
            param(pnh_, "tol", options_.solver.tol, "number") && param(pnh_, "substeps", substeps, "integer") &&
            param(pnh_, "rest_capture_ratio", options_.solver.rest_capture_ratio, "number") &&
            param(pnh_, "velocity_highpass_hz", options_.velocity_highpass_hz, "number") &&
            param(pnh_, "gravity_baseline/mode", baseline, "string") &&
            param(pnh_, "gravity_baseline/time_constant", baseline_config_.time_constant, "number") &&
            param(pnh_, "gravity_baseline/quiet_threshold", baseline_config_.quiet_threshold, "number") &&
            param(pnh_, "max_gap", timing_config_.max_gap, "number") &&
            param(pnh_, "backward_jump", timing_config_.backward_jump, "number") &&
            param(pnh_, "max_future", plausibility_config_.max_future, "number") &&
            param(pnh_, "max_bridge", plausibility_config_.max_bridge, "number") &&
            param(pnh_, "rebase_samples", plausibility_config_.rebase_samples, "integer") &&
            param(pnh_, "restamp_in_sequence", restamp_in_sequence_, "bool") &&
            param(pnh_, "max_lag", max_lag_, "number") &&
            param(pnh_, "max_abs_acceleration", max_abs_acceleration_, "number") &&
            param(pnh_, "state_rate", state_rate_, "number") &&
            param(pnh_, "state_queue_size", state_queue_size_, "integer") &&
            param(pnh_, "state_items_per_s", state_items_per_s_, "number") &&
            param(pnh_, "publish_markers", publish_markers_, "bool") &&
            param(pnh_, "publish_tf", publish_tf_, "bool") && param(pnh_, "threads", threads_, "integer") &&
            param(pnh_, "marker_rate", marker_rate_, "number") &&
            param(pnh_, "fidelity", fidelity, "string") && param(pnh_, "shard", shard_, "string (k/n)") &&
            param(pnh_, "solid_model", solid, "string") &&
            param(pnh_, "bidirectional_ratio", options_.bidirectional_ratio, "number") &&
            param(pnh_, "ensemble_size", ensemble_size_, "integer") && param(pnh_, "ensemble_seed", ensemble_seed_, "integer") &&
            param(pnh_, "alarm_probability", alarm_probability_, "number") &&
            param(pnh_, "snapshot_period", snapshot_period_, "number") &&
            param(pnh_, "snapshot_max_load", snapshot_max_load_, "number") &&
            param(pnh_, "event_quiet_time", event_quiet_time_, "number") &&
            param(pnh_, "event_quiet_threshold", event_quiet_threshold_, "number");
  double scene_h = 0.0, scene_v = 0.0;
  ok = ok && param(pnh_, "linearized_max_alpha", options_.linearized_max_alpha, "number") &&
       param(pnh_, "scene_envelope/horizontal", scene_h, "number") &&
       param(pnh_, "scene_envelope/vertical", scene_v, "number");
  if (!ok || !load_journal_parameters() || !load_snapshot_parameters() || !load_catch_up_parameters()) return false;
  return check_scene_and_ensemble(scene_h, scene_v, substeps) && resolve_threads() &&
         parse_solver_choices(method, model, fidelity, solid) && parse_baseline_mode(baseline) &&
         check_positive_parameters();
}

// ~linearized_max_alpha, ~scene_envelope, ~ensemble_size and ~alarm_probability in range; the scene
// and ~substeps into the options.
bool RockingMonitor::check_scene_and_ensemble(double scene_h, double scene_v, int substeps) {
  if (!(options_.linearized_max_alpha >= 0.0) || !(options_.linearized_max_alpha < 1.0)) {
    ROS_FATAL("rocking_monitor: ~linearized_max_alpha = %g rad must be in [0, 1) (0 = off)",
              options_.linearized_max_alpha);
    return false;
  }
  if (!(scene_h >= 0.0) || !(scene_v >= 0.0)) {
    ROS_FATAL("rocking_monitor: ~scene_envelope/horizontal = %g and ~scene_envelope/vertical = %g must be "
              ">= 0 m/s^2 (0 = unknown)", scene_h, scene_v);
    return false;
  }
  options_.scene = core::SceneEnvelope::from_parameters(scene_h, scene_v);
  options_.solver.substeps = substeps;
  if (ensemble_size_ < 1 || ensemble_size_ > 100000) {
    ROS_FATAL("rocking_monitor: ~ensemble_size = %d must be in [1, 100000] (members per uncertain item)", ensemble_size_);
    return false;
  }
  if (!(alarm_probability_ > 0.0 && alarm_probability_ <= 1.0)) {
    ROS_FATAL("rocking_monitor: ~alarm_probability = %g must be in (0, 1]", alarm_probability_);
    return false;
  }
  return true;
}

// ~threads: 0 is every core; more than one steps the items on a task arena.
bool RockingMonitor::resolve_threads() {
  if (threads_ < 0) {
    ROS_FATAL("rocking_monitor: ~threads = %d must be >= 1, or 0 for every core of this machine", threads_);
    return false;
  }
  if (threads_ == 0) {  // every core (issue 28): catalogues of >= 64 items step in parallel
    threads_ = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    ROS_INFO("rocking_monitor: ~threads 0: %d worker threads (every core)", threads_);
  }
  if (threads_ > 1) arena_ = std::make_unique<tbb::task_arena>(threads_);
  return true;
}

// ~method, ~fidelity, ~solid_model, ~bidirectional_ratio and ~model into the options, then the
// solver settings checked as a whole.
bool RockingMonitor::parse_solver_choices(const std::string& method, const std::string& model,
                                          const std::string& fidelity, const std::string& solid) {
  if (!core::parse_method(method, options_.solver.method)) {
    ROS_FATAL("rocking_monitor: ~method '%s' is not one of dopri5, rk4, analytic", method.c_str());
    return false;
  }
  if (!core::parse_fidelity(fidelity.c_str(), options_.fidelity)) {
    ROS_FATAL("rocking_monitor: ~fidelity '%s' is not one of rocking, adaptive, contact", fidelity.c_str());
    return false;
  }
  if (!core::parse_solid_choice(solid, options_.solid)) {
    ROS_FATAL("rocking_monitor: ~solid_model '%s' is not one of auto, 3d, planar (items with a base_polygon)",
              solid.c_str());
    return false;
  }
  if (!(options_.bidirectional_ratio >= 0.0 && options_.bidirectional_ratio <= 1.0)) {
    ROS_FATAL("rocking_monitor: ~bidirectional_ratio = %g must be in [0, 1]", options_.bidirectional_ratio);
    return false;
  }
  if (!core::parse_model(model, options_.solver.model)) {
    ROS_FATAL("rocking_monitor: ~model '%s' is not one of nonlinear, linearized", model.c_str());
    return false;
  }
  if (const std::string e = core::validate(options_.solver); !e.empty()) {
    ROS_FATAL("rocking_monitor: %s", e.c_str());
    return false;
  }
  return true;
}

bool RockingMonitor::parse_baseline_mode(const std::string& baseline) {
  using Mode = core::GravityBaseline::Mode;
  if (baseline == "tracked") baseline_config_.mode = Mode::Tracked;
  else if (baseline == "initial") baseline_config_.mode = Mode::Initial;
  else if (baseline == "fixed") baseline_config_.mode = Mode::Fixed;
  else {
    ROS_FATAL("rocking_monitor: ~gravity_baseline/mode '%s' is not one of tracked, initial, fixed", baseline.c_str());
    return false;
  }
  return true;
}

// The times, thresholds and rates that must be > 0 (~state_rate, ~state_items_per_s: or 0; the
// queue size: >= 1).
bool RockingMonitor::check_positive_parameters() const {
  auto positive = [](double v, const char* name, const char* unit) {
    if (std::isfinite(v) && v > 0.0) return true;
    ROS_FATAL("rocking_monitor: ~%s = %g must be > 0 %s", name, v, unit);
    return false;
  };
  return positive(baseline_config_.time_constant, "gravity_baseline/time_constant", "s") &&
         positive(baseline_config_.quiet_threshold, "gravity_baseline/quiet_threshold", "m/s^2") &&
         positive(timing_config_.max_gap, "max_gap", "s") &&
         positive(timing_config_.backward_jump, "backward_jump", "s") &&
         positive(plausibility_config_.max_future, "max_future", "s") &&
         positive(plausibility_config_.max_bridge, "max_bridge", "s") &&
         positive(plausibility_config_.rebase_samples, "rebase_samples", "samples") &&
         positive(max_lag_, "max_lag", "s") &&
         positive(max_abs_acceleration_, "max_abs_acceleration", "m/s^2") &&
         positive(options_.velocity_highpass_hz, "velocity_highpass_hz", "Hz") &&
         positive(marker_rate_, "marker_rate", "Hz") &&
         (state_rate_ >= 0.0 || positive(state_rate_, "state_rate", "Hz (0 = every input sample)")) &&
         (state_items_per_s_ == 0.0 ||
          positive(state_items_per_s_, "state_items_per_s", "item-states per second in full ~states (0 = no limit)")) &&
         (state_queue_size_ >= 1 || positive(state_queue_size_, "state_queue_size", "messages"));
}

bool RockingMonitor::init() {
  if (!load_parameters()) return false;
  XmlRpc::XmlRpcValue sensors, items;
  Catalogue cat;
  if (!load_catalogue(sensors, items, cat)) return false;
  add_sensors(cat);
  add_items(cat);
  advertise_outputs(sensors, items);
  add_diagnostics();
  subscribe_sensors();
  start_timers();
  log_startup();
  log_initial_models();
  return true;
}

// ~sensors and ~items parsed, then this node's ~shard of the items. False after a ROS_FATAL.
bool RockingMonitor::load_catalogue(XmlRpc::XmlRpcValue& sensors, XmlRpc::XmlRpcValue& items, Catalogue& cat) {
  if (!pnh_.getParam("sensors", sensors) || !pnh_.getParam("items", items)) {
    ROS_FATAL("rocking_monitor: no catalogue: parameters ~sensors and ~items are required "
              "(load one, e.g. rosparam load config/catalogue_example.yaml into the node's namespace)");
    return false;
  }
  try {
    cat = parse_catalogue(sensors, items);
  } catch (const CatalogueError& e) {
    ROS_FATAL("rocking_monitor: bad catalogue: %s", e.what());
    return false;
  }
  try {
    const auto [k, n] = parse_shard(shard_);
    if (n > 1) {
      const std::size_t all = cat.items.size();
      cat = select_shard(cat, k, n);
      ROS_INFO("rocking_monitor: shard %d/%d: %zu of the catalogue's %zu items (by a stable hash of the id)", k, n,
               cat.items.size(), all);
      if (cat.items.empty()) ROS_WARN("rocking_monitor: shard %d/%d holds no item of this catalogue", k, n);
    }
  } catch (const CatalogueError& e) {
    ROS_FATAL("rocking_monitor: ~%s", e.what());
    return false;
  }
  return true;
}

// Each sensor's input conditioning: gravity baseline, sample timing, stamp plausibility.
void RockingMonitor::add_sensors(const Catalogue& cat) {
  for (const SensorSpec& spec : cat.sensors) {
    Sensor s;
    s.spec = spec;
    s.baseline = core::GravityBaseline(baseline_config_);
    if (spec.type == SensorSpec::Type::Accel && baseline_config_.mode == core::GravityBaseline::Mode::Fixed) {
      core::GravityBaseline::Config c = baseline_config_;
      c.fixed = Eigen::Vector3d::Zero();  // AccelStamped carries ground acceleration without gravity
      s.baseline = core::GravityBaseline(c);
    }
    s.timing = core::SampleTiming(timing_config_);
    core::StampPlausibility::Config pc = plausibility_config_;
    pc.backward_jump = timing_config_.backward_jump;
    pc.max_step = timing_config_.max_gap;
    s.plausibility = core::StampPlausibility(pc);
    s.held.resize(static_cast<std::size_t>(pc.rebase_samples));
    s.suspects.resize(static_cast<std::size_t>(pc.rebase_samples));
    sensors_.push_back(std::move(s));
  }
}

// Each item: its ensemble members (uncertain items), models and sensor; the given poses go out on
// /tf_static.
void RockingMonitor::add_items(const Catalogue& cat) {
  tf2_msgs::TFMessage statics;
  for (const CatalogueItem& entry : cat.items) {
    Item it;
    it.entry = entry;
    if (entry.uncertain.uncertain()) {
      std::vector<int> pulled;
      const int n = entry.ensemble_size > 0 ? entry.ensemble_size : ensemble_size_;  // the item's own, if given
      it.members = core::draw_members(entry.uncertain, n, static_cast<std::uint64_t>(ensemble_seed_), &pulled);
      if (!pulled.empty())
        ROS_WARN("rocking_monitor: item '%s': %zu of %d members drawn outside the valid geometry were pulled toward "
                 "the nominal item", entry.spec.id.c_str(), pulled.size(), n);
    }
    make_models(it);
    for (std::size_t i = 0; i < sensors_.size(); ++i)
      if (sensors_[i].spec.name == entry.spec.sensor) it.sensor = i;
    it.slot = sensors_[it.sensor].items.size();
    sensors_[it.sensor].items.push_back(items_.size());
    if (entry.pose.given) statics.transforms.push_back(pose_transform(entry));
    items_.push_back(std::move(it));
  }
  if (!statics.transforms.empty()) publish_static_poses(statics);
}

// An item's ~pose as the transform parent frame -> item frame.
geometry_msgs::TransformStamped RockingMonitor::pose_transform(const CatalogueItem& entry) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = ::ros::Time::now();
  t.header.frame_id = entry.pose.parent_frame;
  t.child_frame_id = entry.spec.frame;
  t.transform.translation.x = entry.pose.x;
  t.transform.translation.y = entry.pose.y;
  t.transform.translation.z = entry.pose.z;
  const Eigen::Quaterniond q = Eigen::AngleAxisd(entry.pose.yaw, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(entry.pose.pitch, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(entry.pose.roll, Eigen::Vector3d::UnitX());
  t.transform.rotation = tf2::toMsg(q);
  return t;
}

void RockingMonitor::publish_static_poses(tf2_msgs::TFMessage& statics) {
  // A frame given twice (two items in one frame) once, as tf2_ros's broadcaster keeps it: the last pose.
  std::unordered_map<std::string, std::size_t> at;
  std::vector<geometry_msgs::TransformStamped> unique;
  for (geometry_msgs::TransformStamped& t : statics.transforms) {
    const auto [it, fresh] = at.emplace(t.child_frame_id, unique.size());
    if (fresh) unique.push_back(std::move(t));
    else unique[it->second] = std::move(t);
  }
  statics.transforms = std::move(unique);
  tf_static_pub_ = nh_.advertise<tf2_msgs::TFMessage>("/tf_static", 100, true);
  tf_static_pub_.publish(statics);
}

// tf, the published topics (the alarm journal and the state snapshot opened on the way) and the
// services.
void RockingMonitor::advertise_outputs(const XmlRpc::XmlRpcValue& sensors, const XmlRpc::XmlRpcValue& items) {
  tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
  tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_, nh_);
  items_without_rotation_ = items_.size();
  tf_pub_ = nh_.advertise<tf2_msgs::TFMessage>("/tf", 100);  // as tf2_ros::TransformBroadcaster

  states_pub_ = pnh_.advertise<RockingStateArray>("states", static_cast<std::uint32_t>(state_queue_size_));
  // The items whose state changed since its previous message (docs/monitor.md: large catalogues).
  state_changes_pub_ = pnh_.advertise<RockingStateArray>("state_changes", static_cast<std::uint32_t>(state_queue_size_));
  criteria_pub_ = pnh_.advertise<CriterionExceedance>("criteria", 100);
  // Not latched (a latched topic keeps only its last message): every new subscriber is sent all the
  // alarms of the open event instead, in journal order, then the live ones (docs/journal.md).
  open_journal();
  open_snapshot(sensors, items);  // after the journal: levels it marked alarmed stay so when restored
  alarms_pub_ = pnh_.advertise<OverturnAlarm>(
      "alarms", 1000, [this](const ::ros::SingleSubscriberPublisher& p) {
        journal_.drain();  // the last sample's alarms on disk (and published) before they are resent
        for (const OverturnAlarm& m : event_alarms_) p.publish(m);
      });
  probability_alarms_pub_ = pnh_.advertise<ProbabilityAlarm>(
      "probability_alarms", 1000, [this](const ::ros::SingleSubscriberPublisher& p) {
        journal_.drain();
        for (const ProbabilityAlarm& m : event_probability_alarms_) p.publish(m);
      });
  if (publish_markers_) markers_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 2);
  overload_pub_ = pnh_.advertise<std_msgs::Bool>("overload", 1, true);
  {
    std_msgs::Bool b;  // latched: a late subscriber learns the current state
    overload_pub_.publish(b);
  }
  reset_srv_ = pnh_.advertiseService("reset", &RockingMonitor::on_reset, this);
  upright_srv_ = pnh_.advertiseService("set_upright", &RockingMonitor::on_set_upright, this);

  states_msg_.items.resize(items_.size());
  for (std::size_t i = 0; i < items_.size(); ++i) states_msg_.items[i].id = items_[i].entry.spec.id;
}

// /diagnostics: each sensor's input rate and samples, the catalogue, the journal, the snapshot, catch-up.
void RockingMonitor::add_diagnostics() {
  diagnostics_ = std::make_unique<diagnostic_updater::Updater>(nh_, pnh_);
  diagnostics_->setHardwareID("rocking_monitor");
  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    Sensor& s = sensors_[i];
    s.min_freq = 0.9 * s.spec.rate;
    s.max_freq = 1.1 * s.spec.rate;
    s.topic_diag = std::make_unique<diagnostic_updater::TopicDiagnostic>(
        "sensor " + s.spec.name + " input " + s.spec.topic, *diagnostics_,
        diagnostic_updater::FrequencyStatusParam(&s.min_freq, &s.max_freq, 0.0, 10),
        diagnostic_updater::TimeStampStatusParam(-1.0, 5.0));
    diagnostics_->add("sensor " + s.spec.name + " samples",
                      [this, i](diagnostic_updater::DiagnosticStatusWrapper& st) { sensor_diagnostics(i, st); });
  }
  diagnostics_->add("catalogue", this, &RockingMonitor::catalogue_diagnostics);
  diagnostics_->add("alarm journal", this, &RockingMonitor::journal_diagnostics);
  diagnostics_->add("state snapshot", this, &RockingMonitor::snapshot_diagnostics);
  if (!catch_up_service_.empty()) diagnostics_->add("catch-up", this, &RockingMonitor::catch_up_diagnostics);
}

void RockingMonitor::subscribe_sensors() {
  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    Sensor& s = sensors_[i];
    const auto hints = ::ros::TransportHints().tcpNoDelay();
    if (s.spec.type == SensorSpec::Type::Imu) {
      s.sub = nh_.subscribe<sensor_msgs::Imu>(
          s.spec.topic, 2000,
          boost::function<void(const ::ros::MessageEvent<sensor_msgs::Imu const>&)>(
              [this, i](const ::ros::MessageEvent<sensor_msgs::Imu const>& m) { on_imu(i, m); }),
          {}, hints);
    } else {
      s.sub = nh_.subscribe<geometry_msgs::AccelStamped>(
          s.spec.topic, 2000,
          boost::function<void(const ::ros::MessageEvent<geometry_msgs::AccelStamped const>&)>(
              [this, i](const ::ros::MessageEvent<geometry_msgs::AccelStamped const>& m) { on_accel(i, m); }),
          {}, hints);
    }
  }
}

void RockingMonitor::start_timers() {
  // Full ~states of a large catalogue at a lower rate: items x rate <= ~state_items_per_s.
  if (state_rate_ > 0.0 && state_items_per_s_ > 0.0)
    full_state_every_ = std::max(1, static_cast<int>(std::ceil(static_cast<double>(items_.size()) * state_rate_ /
                                                               state_items_per_s_ - 1e-9)));
  if (state_rate_ > 0.0) state_timer_ = nh_.createTimer(::ros::Duration(1.0 / state_rate_), &RockingMonitor::on_state_timer, this);
  else state_timer_ = nh_.createTimer(::ros::Duration(0.5), &RockingMonitor::on_state_timer, this);
  // Wall time: under sim time nothing ticks until a /clock arrives, which is what we warn about.
  startup_timer_ = nh_.createWallTimer(::ros::WallDuration(5.0), &RockingMonitor::on_startup_timer, this);
  last_now_ = ::ros::Time::now();
}

// What runs: the items, the solver, and which items rock in one plane only.
void RockingMonitor::log_startup() const {
  ROS_INFO("rocking_monitor: %zu items on %zu sensors, method %s (%s model, tol %g, substeps %d), fidelity %s",
           items_.size(), sensors_.size(), core::to_string(options_.solver.method),
           core::to_string(options_.solver.model), options_.solver.tol, options_.solver.substeps,
           core::to_string(options_.fidelity));
  std::size_t single = 0;
  std::string names;
  for (const Item& it : items_) {
    if (it.monitor->two_planes()) continue;
    if (++single <= 10) names += (names.empty() ? "'" : ", '") + it.entry.spec.id + "'";
  }
  if (single > 0)
    ROS_INFO("rocking_monitor: %zu of %zu items have no depth in the catalogue and rock in their x-z plane only "
             "(give depth to add the y-z plane): %s%s", single, items_.size(), names.c_str(), single > 10 ? ", ..." : "");
}

// Which model each item starts on and why (issue 7): one line per item for small catalogues,
// counts per reason for large ones.
void RockingMonitor::log_initial_models() const {
  if (options_.fidelity != core::Fidelity::Adaptive) return;
  std::map<std::string, int> per_reason;
  for (const Item& it : items_) {
    for (int p = 0; p < it.monitor->plane_count(); ++p) {
      const core::Plane plane = static_cast<core::Plane>(p);
      if (it.monitor->plane(plane).adaptive() == nullptr) {  // no mu_s: pure rocking
        ++per_reason["pure rocking: no mu_s in the catalogue (sliding not checked, flight flagged)"];
        continue;
      }
      const core::AdaptiveModel& a = *it.monitor->plane(plane).adaptive();
      const double need = a.sliding_bound().required_mu();
      if (items_.size() <= 50) {
        ROS_INFO("rocking_monitor: item '%s' plane %s starts on the rocking model: %s (mu_s %g; friction the scene "
                 "can demand: %s)",
                 it.entry.spec.id.c_str(), core::to_string(plane), core::to_string(a.initial_reason()),
                 a.body().mu_s(), std::isinf(need) ? "unbounded" : std::to_string(need).c_str());
      }
      ++per_reason[core::to_string(a.initial_reason())];
    }
  }
  for (const auto& [reason, n] : per_reason) ROS_INFO("rocking_monitor: %d item planes: %s", n, reason.c_str());
}

void RockingMonitor::reset_all(const std::string& why) {
  ROS_WARN("rocking_monitor: resetting all %zu items: %s", items_.size(), why.c_str());
  for (Sensor& s : sensors_) {
    s.timing.restart();
    s.baseline.reset();
    s.have_first = false;
    s.plausibility.clear();
    s.held_count = 0;
    s.suspect_count = 0;
    s.have_min_offset = false;
    ++s.resets;
  }
  for (Item& it : items_) make_models(it);
  for (Sensor& s : sensors_) s.batch.reset();
  journal_reset(why);  // closes the event: the items alarm again from here
  take_snapshot(last_snapshot_stamp_);  // items at rest: a restart must not bring back the state before
}

void RockingMonitor::rebuild_batch(Sensor& s) {
  std::vector<core::ItemMonitor*> monitors;
  monitors.reserve(s.items.size());
  for (std::size_t idx : s.items) monitors.push_back(items_[idx].monitor.get());
  s.batch = std::make_unique<core::MonitorBatch>(std::move(monitors));
  s.in_x.assign(s.items.size(), 0.0);
  s.in_y.assign(s.items.size(), 0.0);
  s.in_z.assign(s.items.size(), 0.0);
  s.gains.clear();
  for (std::size_t idx : s.items) s.gains.push_back(items_[idx].entry.spec.input_gain);
  s.in_ready.assign(s.items.size(), 0);
  s.rotations.assign(s.items.size(), Eigen::Matrix3d::Identity());
  s.all_ready = false;
  // The new batch's summaries start their own revisions: every publication refills these items.
  for (std::size_t idx : s.items)
    items_[idx].states_revision = items_[idx].changes_revision = items_[idx].markers_revision = Item::kUnsent;
  s.has_ensembles = false;
  for (std::size_t idx : s.items) s.has_ensembles = s.has_ensembles || items_[idx].ensemble != nullptr;
}

void RockingMonitor::sync_items() {
  for (Sensor& s : sensors_)
    if (s.batch) s.batch->sync_all();
}

void RockingMonitor::make_models(Item& it) {
  it.monitor = std::make_unique<core::ItemMonitor>(it.entry.spec, options_);
  if (!it.members.empty()) it.ensemble = std::make_unique<core::ItemEnsemble>(it.members, options_, alarm_probability_);
}

bool RockingMonitor::on_reset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  reset_all("~reset called");
  res.success = true;
  res.message = "re-armed " + std::to_string(items_.size()) + " items; they restart at rest with the next sample";
  return true;
}

bool RockingMonitor::on_set_upright(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  sync_items();
  std::size_t n = 0;
  for (Sensor& s : sensors_) {
    for (std::size_t idx : s.items) {
      Item& it = items_[idx];
      if (!it.monitor->started() || it.monitor->mode() != core::ItemMode::Overturned) continue;
      make_models(it);  // at rest; started with the sensor's next sample (the step path starts it)
      ++n;
    }
    s.batch.reset();
  }
  ROS_WARN("rocking_monitor: ~set_upright: %zu items on their side set upright again: they restart at rest", n);
  res.success = true;
  res.message = std::to_string(n) + " items set upright; they restart at rest with the next sample";
  return true;
}

void RockingMonitor::on_startup_timer(const ::ros::WallTimerEvent&) {
  bool waiting = false;
  for (const Sensor& s : sensors_) {
    if (s.received == 0) {
      ROS_WARN("rocking_monitor: still waiting for data on %s (sensor '%s')", s.sub.getTopic().c_str(), s.spec.name.c_str());
      waiting = true;
    }
  }
  if (!waiting) startup_timer_.stop();
}

}  // namespace rocking_monitor::live
