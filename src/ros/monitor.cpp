#include "rocking_monitor/ros/monitor.hpp"

#include <chrono>
#include <limits>
#include <map>
#include <cmath>
#include <cstdlib>
#include <type_traits>

#include <geometry_msgs/TransformStamped.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <visualization_msgs/MarkerArray.h>

#include "rocking_monitor/integrate/solver_settings.hpp"

namespace rocking_monitor::live {
namespace {

using core::ItemMode;

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

std_msgs::ColorRGBA color(ItemMode m, bool valid) {
  std_msgs::ColorRGBA c;
  c.a = 0.85f;
  switch (m) {
    case ItemMode::Rest: c.r = 0.2f; c.g = 0.75f; c.b = 0.3f; break;
    case ItemMode::Rocking: c.r = 0.95f; c.g = 0.85f; c.b = 0.1f; break;
    case ItemMode::BeyondTipping: c.r = 1.0f; c.g = 0.5f; c.b = 0.0f; break;
    case ItemMode::Committed: c.r = 0.95f; c.g = 0.1f; c.b = 0.1f; break;
    case ItemMode::Overturned: c.r = 0.45f; c.g = 0.0f; c.b = 0.35f; break;
  }
  if (!valid) c.a = 0.45f;  // pure-rocking model not valid at the moment: drawn faded
  return c;
}

constexpr std::array<core::CriterionId, core::kScreeningCount> kScreening = {
    core::CriterionId::Housner, core::CriterionId::Ishiyama, core::CriterionId::IshiyamaEquivalent,
    core::CriterionId::Proposed};

}  // namespace

RockingMonitor::RockingMonitor(::ros::NodeHandle nh, ::ros::NodeHandle pnh) : nh_(nh), pnh_(pnh) {}

RockingMonitor::~RockingMonitor() = default;

bool RockingMonitor::load_parameters() {
  std::string method = "dopri5", model = "nonlinear", baseline = "tracked", fidelity = "rocking";
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
            param(pnh_, "max_abs_acceleration", max_abs_acceleration_, "number") &&
            param(pnh_, "state_rate", state_rate_, "number") &&
            param(pnh_, "publish_markers", publish_markers_, "bool") &&
            param(pnh_, "publish_tf", publish_tf_, "bool") && param(pnh_, "threads", threads_, "integer") &&
            param(pnh_, "marker_rate", marker_rate_, "number") &&
            param(pnh_, "fidelity", fidelity, "string");
  double scene_h = 0.0, scene_v = 0.0;
  ok = ok && param(pnh_, "linearized_max_alpha", options_.linearized_max_alpha, "number") &&
       param(pnh_, "scene_envelope/horizontal", scene_h, "number") &&
       param(pnh_, "scene_envelope/vertical", scene_v, "number");
  if (!ok) return false;
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
  if (threads_ < 1) {
    ROS_FATAL("rocking_monitor: ~threads = %d must be >= 1", threads_);
    return false;
  }
  if (threads_ > 1) arena_ = std::make_unique<tbb::task_arena>(threads_);
  if (!core::parse_method(method, options_.solver.method)) {
    ROS_FATAL("rocking_monitor: ~method '%s' is not one of dopri5, rk4, analytic", method.c_str());
    return false;
  }
  if (!core::parse_fidelity(fidelity.c_str(), options_.fidelity)) {
    ROS_FATAL("rocking_monitor: ~fidelity '%s' is not one of rocking, adaptive, contact", fidelity.c_str());
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
  using Mode = core::GravityBaseline::Mode;
  if (baseline == "tracked") baseline_config_.mode = Mode::Tracked;
  else if (baseline == "initial") baseline_config_.mode = Mode::Initial;
  else if (baseline == "fixed") baseline_config_.mode = Mode::Fixed;
  else {
    ROS_FATAL("rocking_monitor: ~gravity_baseline/mode '%s' is not one of tracked, initial, fixed", baseline.c_str());
    return false;
  }
  auto positive = [](double v, const char* name, const char* unit) {
    if (std::isfinite(v) && v > 0.0) return true;
    ROS_FATAL("rocking_monitor: ~%s = %g must be > 0 %s", name, v, unit);
    return false;
  };
  return positive(baseline_config_.time_constant, "gravity_baseline/time_constant", "s") &&
         positive(baseline_config_.quiet_threshold, "gravity_baseline/quiet_threshold", "m/s^2") &&
         positive(timing_config_.max_gap, "max_gap", "s") &&
         positive(timing_config_.backward_jump, "backward_jump", "s") &&
         positive(max_abs_acceleration_, "max_abs_acceleration", "m/s^2") &&
         positive(options_.velocity_highpass_hz, "velocity_highpass_hz", "Hz") &&
         positive(marker_rate_, "marker_rate", "Hz") &&
         (state_rate_ >= 0.0 || positive(state_rate_, "state_rate", "Hz (0 = every input sample)"));
}

bool RockingMonitor::init() {
  if (!load_parameters()) return false;
  XmlRpc::XmlRpcValue sensors, items;
  if (!pnh_.getParam("sensors", sensors) || !pnh_.getParam("items", items)) {
    ROS_FATAL("rocking_monitor: no catalogue: parameters ~sensors and ~items are required "
              "(load one, e.g. rosparam load config/catalogue_example.yaml into the node's namespace)");
    return false;
  }
  Catalogue cat;
  try {
    cat = parse_catalogue(sensors, items);
  } catch (const CatalogueError& e) {
    ROS_FATAL("rocking_monitor: bad catalogue: %s", e.what());
    return false;
  }

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
    sensors_.push_back(std::move(s));
  }
  static_broadcaster_ = std::make_unique<tf2_ros::StaticTransformBroadcaster>();
  std::vector<geometry_msgs::TransformStamped> statics;
  for (const CatalogueItem& entry : cat.items) {
    Item it;
    it.entry = entry;
    it.monitor = std::make_unique<core::ItemMonitor>(entry.spec, options_);
    for (std::size_t i = 0; i < sensors_.size(); ++i)
      if (sensors_[i].spec.name == entry.spec.sensor) it.sensor = i;
    sensors_[it.sensor].items.push_back(items_.size());
    if (entry.pose.given) {
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
      statics.push_back(t);
    }
    items_.push_back(std::move(it));
  }
  if (!statics.empty()) static_broadcaster_->sendTransform(statics);

  tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
  tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_, nh_);
  tf_broadcaster_ = std::make_unique<tf2_ros::TransformBroadcaster>();

  states_pub_ = pnh_.advertise<RockingStateArray>("states", 10);
  criteria_pub_ = pnh_.advertise<CriterionExceedance>("criteria", 100);
  alarms_pub_ = pnh_.advertise<OverturnAlarm>("alarms", 1000, true);
  if (publish_markers_) markers_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 2);
  reset_srv_ = pnh_.advertiseService("reset", &RockingMonitor::on_reset, this);

  states_msg_.items.resize(items_.size());
  for (std::size_t i = 0; i < items_.size(); ++i) states_msg_.items[i].id = items_[i].entry.spec.id;

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

  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    Sensor& s = sensors_[i];
    const auto hints = ::ros::TransportHints().tcpNoDelay();
    if (s.spec.type == SensorSpec::Type::Imu) {
      s.sub = nh_.subscribe<sensor_msgs::Imu>(
          s.spec.topic, 2000, [this, i](const sensor_msgs::ImuConstPtr& m) { on_imu(i, m); }, {}, hints);
    } else {
      s.sub = nh_.subscribe<geometry_msgs::AccelStamped>(
          s.spec.topic, 2000, [this, i](const geometry_msgs::AccelStampedConstPtr& m) { on_accel(i, m); }, {},
          hints);
    }
  }
  if (state_rate_ > 0.0) state_timer_ = nh_.createTimer(::ros::Duration(1.0 / state_rate_), &RockingMonitor::on_state_timer, this);
  else state_timer_ = nh_.createTimer(::ros::Duration(0.5), &RockingMonitor::on_state_timer, this);
  // Wall time: under sim time nothing ticks until a /clock arrives, which is what we warn about.
  startup_timer_ = nh_.createWallTimer(::ros::WallDuration(5.0), &RockingMonitor::on_startup_timer, this);
  last_now_ = ::ros::Time::now();
  ROS_INFO("rocking_monitor: %zu items on %zu sensors, method %s (%s model, tol %g, substeps %d), fidelity %s",
           items_.size(), sensors_.size(), core::to_string(options_.solver.method),
           core::to_string(options_.solver.model), options_.solver.tol, options_.solver.substeps,
           core::to_string(options_.fidelity));
  log_initial_models();
  return true;
}

// Which model each item starts on and why (issue 7): one line per item for small catalogues,
// counts per reason for large ones.
void RockingMonitor::log_initial_models() const {
  if (options_.fidelity != core::Fidelity::Adaptive) return;
  std::map<std::string, int> per_reason;
  for (const Item& it : items_) {
    const core::AdaptiveModel& a = *it.monitor->adaptive();
    const double need = a.sliding_bound().required_mu();
    if (items_.size() <= 50) {
      ROS_INFO("rocking_monitor: item '%s' starts on the rocking model: %s (mu_s %g; friction the scene can "
               "demand: %s)",
               it.entry.spec.id.c_str(), core::to_string(a.initial_reason()), a.body().mu_s(),
               std::isinf(need) ? "unbounded" : std::to_string(need).c_str());
    }
    ++per_reason[core::to_string(a.initial_reason())];
  }
  for (const auto& [reason, n] : per_reason) ROS_INFO("rocking_monitor: %d items: %s", n, reason.c_str());
}

void RockingMonitor::on_imu(std::size_t sensor, const sensor_msgs::ImuConstPtr& m) {
  on_sample(sensor, m->header,
            Eigen::Vector3d(m->linear_acceleration.x, m->linear_acceleration.y, m->linear_acceleration.z));
}

void RockingMonitor::on_accel(std::size_t sensor, const geometry_msgs::AccelStampedConstPtr& m) {
  on_sample(sensor, m->header, Eigen::Vector3d(m->accel.linear.x, m->accel.linear.y, m->accel.linear.z));
}

bool RockingMonitor::lookup_rotation(Item& item, const std::string& sensor_frame) {
  if (sensor_frame.empty() || sensor_frame == item.entry.spec.frame) {
    item.rotation.setIdentity();
    item.has_rotation = true;
    return true;
  }
  try {
    // Static mounting: the latest transform is the one.
    const geometry_msgs::TransformStamped t =
        tf_buffer_->lookupTransform(item.entry.spec.frame, sensor_frame, ::ros::Time(0));
    item.rotation = tf2::transformToEigen(t).rotation();
    item.has_rotation = true;
    ROS_DEBUG("rocking_monitor: item '%s' uses the transform %s <- %s", item.entry.spec.id.c_str(),
              item.entry.spec.frame.c_str(), sensor_frame.c_str());
    return true;
  } catch (const tf2::TransformException& e) {
    ROS_WARN_THROTTLE(5.0, "rocking_monitor: item '%s' is not monitored yet: no transform %s <- %s (%s)",
                      item.entry.spec.id.c_str(), item.entry.spec.frame.c_str(), sensor_frame.c_str(), e.what());
    return false;
  }
}

void RockingMonitor::start_items(Sensor& s, double t, const Eigen::Vector3d& a) {
  for (std::size_t idx : s.items) {
    Item& it = items_[idx];
    if (!it.has_rotation && !lookup_rotation(it, s.frame)) continue;
    const Eigen::Vector3d ai = it.rotation * a;
    it.monitor->start(t, ai.x(), ai.z(), s.dt_nominal);
    it.stamp.fromSec(t);
  }
}

void RockingMonitor::on_sample(std::size_t si, const std_msgs::Header& header, const Eigen::Vector3d& reading) {
  const auto wall_start = std::chrono::steady_clock::now();
  Sensor& s = sensors_[si];
  ++s.received;
  if (!reading.allFinite()) {
    ++s.rejected_nonfinite;
    ROS_WARN_THROTTLE(5.0, "rocking_monitor: sensor '%s': non-finite sample rejected (%lu so far)",
                      s.spec.name.c_str(), static_cast<unsigned long>(s.rejected_nonfinite));
    return;
  }
  if (header.stamp.isZero()) {
    ++s.zero_stamps;
    ROS_WARN_THROTTLE(5.0, "rocking_monitor: sensor '%s': sample with a zero stamp dropped", s.spec.name.c_str());
    return;
  }
  const double expected = s.spec.type == SensorSpec::Type::Imu ? core::kGravity : 0.0;
  if ((reading - Eigen::Vector3d(0.0, 0.0, expected)).norm() > max_abs_acceleration_) {
    ++s.rejected_limit;
    ROS_WARN_THROTTLE(5.0, "rocking_monitor: sensor '%s': |a| = %.1f m/s^2 beyond ~max_abs_acceleration %.1f: rejected",
                      s.spec.name.c_str(), reading.norm(), max_abs_acceleration_);
    return;
  }
  const double t = header.stamp.toSec();
  double dt = 0.0;
  using V = core::SampleTiming::Verdict;
  const V verdict = s.timing.classify(t, dt);
  switch (verdict) {
    case V::Duplicate:
    case V::OutOfOrder:
      ROS_WARN_THROTTLE(5.0, "rocking_monitor: sensor '%s': %s stamp %.6f dropped (last %.6f)", s.spec.name.c_str(),
                        verdict == V::Duplicate ? "duplicate" : "out-of-order", t, s.timing.last_stamp());
      return;
    case V::BackwardJump:
      ++s.resets;
      ROS_WARN("rocking_monitor: sensor '%s': time jumped back to %.3f s: restarting its %zu items",
               s.spec.name.c_str(), t, s.items.size());
      s.baseline.reset();
      for (std::size_t idx : s.items) {
        items_[idx].monitor = std::make_unique<core::ItemMonitor>(items_[idx].entry.spec, options_);
      }
      break;
    case V::AcceptGap:
      ROS_WARN_THROTTLE(5.0, "rocking_monitor: sensor '%s': %.3f s gap bridged by a straight line (%lu gaps)",
                        s.spec.name.c_str(), dt, static_cast<unsigned long>(s.timing.counters().gaps));
      break;
    default: break;
  }
  s.frame = s.spec.frame_id.empty() ? header.frame_id : s.spec.frame_id;
  const Eigen::Vector3d a = s.baseline.remove(reading, dt);
  if (s.topic_diag) s.topic_diag->tick(header.stamp);
  s.last_stamp = header.stamp;
  if (verdict == V::First || verdict == V::BackwardJump) {
    s.have_first = true;
    s.first_t = t;
    s.first_a = a;
    return;
  }
  if (s.have_first) {
    s.dt_nominal = dt;
    start_items(s, s.first_t, s.first_a);
    s.have_first = false;
  }
  s.mean_dt = s.mean_dt == 0.0 ? dt : 0.99 * s.mean_dt + 0.01 * dt;
  // Serial: items still waiting for their transform, or starting late, are not stepped.
  for (std::size_t idx : s.items) {
    Item& it = items_[idx];
    it.ready = false;
    if (!it.has_rotation && !lookup_rotation(it, s.frame)) {
      ++it.samples_without_transform;
      continue;
    }
    if (!it.monitor->started()) {  // its transform arrived late: start now
      const Eigen::Vector3d ai = it.rotation * a;
      it.monitor->start(t, ai.x(), ai.z(), s.dt_nominal);
      it.stamp = header.stamp;
      continue;
    }
    it.ready = true;
  }
  // Items are independent: step them in parallel when ~threads > 1 (results do not depend on it).
  auto step_range = [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      Item& it = items_[s.items[k]];
      if (!it.ready) continue;
      const Eigen::Vector3d ai = it.rotation * a;
      it.monitor->step(ai.x(), ai.z(), dt);
      it.stamp = header.stamp;
    }
  };
  if (arena_ && s.items.size() >= 64) {
    arena_->execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, s.items.size(), 32),
                        [&](const tbb::blocked_range<std::size_t>& r) { step_range(r.begin(), r.end()); });
    });
  } else {
    step_range(0, s.items.size());
  }
  // Serial: publish what happened, in catalogue order.
  for (std::size_t idx : s.items) {
    Item& it = items_[idx];
    if (!it.ready) continue;
    const core::ItemEvents& ev = it.monitor->events();
    if (ev.change_count > 0 || ev.alarm_count > 0) publish_events(it, ev, header.stamp);
  }
  s.last_processing_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  s.max_processing_s = std::max(s.max_processing_s, s.last_processing_s);
  s.total_processing_s += s.last_processing_s;
  ++s.processed;
  if (state_rate_ == 0.0) publish_states();
}

void RockingMonitor::publish_events(Item& it, const core::ItemEvents& ev, const ::ros::Time& stamp) {
  const core::ItemSpec& spec = it.entry.spec;
  for (int i = 0; i < ev.change_count; ++i) {
    const core::CriterionChange& c = ev.changes[i];
    CriterionExceedance m;
    m.header.stamp = stamp;
    m.header.frame_id = spec.frame;
    m.item_id = spec.id;
    m.criterion = static_cast<std::uint8_t>(c.id);
    m.criterion_name = core::to_string(c.id);
    m.exceeded = c.exceeded;
    m.value = c.value;
    m.threshold = c.threshold;
    m.second_value = c.second_value;
    m.second_threshold = c.second_threshold;
    criteria_pub_.publish(m);
  }
  for (int i = 0; i < ev.alarm_count; ++i) {
    const core::AlarmEvent& a = ev.alarms[i];
    OverturnAlarm m;
    m.header.stamp = stamp;
    m.header.frame_id = spec.frame;
    m.item_id = spec.id;
    m.description = spec.description;
    m.level = static_cast<std::uint8_t>(a.level);
    m.event_time = a.time;
    m.rotation_ratio = a.rotation_ratio;
    for (core::CriterionId id : kScreening)
      (it.monitor->screening_exceeded(id) ? m.predicted_by : m.not_predicted_by).push_back(core::to_string(id));
    alarms_pub_.publish(m);
    ++alarms_published_;
    if (a.level == ItemMode::Overturned) {
      ROS_ERROR("rocking_monitor: OVERTURNED: %s (%s) at t = %.3f s", spec.id.c_str(), spec.description.c_str(), a.time);
    } else {
      ROS_WARN("rocking_monitor: %s: %s (%s) at t = %.3f s", core::to_string(a.level), spec.id.c_str(),
               spec.description.c_str(), a.time);
    }
  }
}

void RockingMonitor::fill_state(const Item& it, RockingState& out) const {
  const core::ItemMonitor& im = *it.monitor;
  out.mode = static_cast<std::uint8_t>(im.mode());
  out.pivot = static_cast<std::int8_t>(im.side());
  out.theta = im.theta();
  out.theta_dot = im.omega();
  out.rotation_ratio = im.rotation_ratio();
  out.energy_margin = im.margin().margin;
  out.impacts = static_cast<std::uint32_t>(im.impacts());
  out.violations = im.violations();
  out.model_valid = out.violations == 0;
  out.contact_mode = static_cast<std::uint8_t>(im.contact_mode());
  out.slip = im.slip();
  out.model = im.active_model();
  out.input_stamp = it.stamp;
}

void RockingMonitor::publish_states() {
  ::ros::Time newest;
  for (std::size_t i = 0; i < items_.size(); ++i) {
    fill_state(items_[i], states_msg_.items[i]);
    if (items_[i].stamp > newest) newest = items_[i].stamp;
  }
  states_msg_.header.stamp = newest;
  states_pub_.publish(states_msg_);
}

void RockingMonitor::on_state_timer(const ::ros::TimerEvent&) {
  const ::ros::Time now = ::ros::Time::now();
  if (!last_now_.isZero() && now + ::ros::Duration(timing_config_.backward_jump) < last_now_) {
    reset_all("ROS time jumped back (sim time restarted?)");
  }
  last_now_ = now;
  if (state_rate_ > 0.0) publish_states();  // else after every input sample
  if (last_marker_time_.isZero() || (now - last_marker_time_).toSec() >= 1.0 / marker_rate_ ||
      now < last_marker_time_) {
    publish_markers_and_tf();
    last_marker_time_ = now;
  }
  diagnostics_->update();
}

void RockingMonitor::publish_markers_and_tf() {
  if (!publish_markers_ && !publish_tf_) return;
  visualization_msgs::MarkerArray markers;
  std::vector<geometry_msgs::TransformStamped> transforms;
  const ::ros::Time now = ::ros::Time::now();
  for (std::size_t i = 0; i < items_.size(); ++i) {
    const Item& it = items_[i];
    const core::Body& b = it.monitor->body();
    const double theta = it.monitor->theta();
    const int side = it.monitor->side();
    // Item frame: origin on the floor below the centre of mass, x across the base, z up.
    // Corner 1 at x = -nu1 B, corner 2 at x = +nu2 B; theta > 0 rotates about corner 1 (about -y).
    const Eigen::Vector3d pivot(side >= 0 ? -b.nu1() * b.width() : b.nu2() * b.width(), 0.0, 0.0);
    const Eigen::Matrix3d r = Eigen::AngleAxisd(-theta, Eigen::Vector3d::UnitY()).toRotationMatrix();
    const Eigen::Vector3d shift = pivot - r * pivot;
    if (publish_tf_) {
      geometry_msgs::TransformStamped t;
      t.header.stamp = now;
      t.header.frame_id = it.entry.spec.frame;
      t.child_frame_id = it.entry.spec.frame + marker_frame_suffix_;
      t.transform.translation.x = shift.x();
      t.transform.translation.z = shift.z();
      t.transform.rotation = tf2::toMsg(Eigen::Quaterniond(r));
      transforms.push_back(t);
    }
    if (publish_markers_) {
      visualization_msgs::Marker mk;
      mk.header.stamp = now;
      mk.header.frame_id = it.entry.spec.frame;
      mk.ns = "items";
      mk.id = static_cast<int>(i);
      mk.type = visualization_msgs::Marker::CUBE;
      mk.action = visualization_msgs::Marker::ADD;
      const Eigen::Vector3d centre((b.nu2() - b.nu1()) * b.width() / 2.0, 0.0, b.cg_height());
      const Eigen::Vector3d c = r * centre + shift;
      mk.pose.position.x = c.x();
      mk.pose.position.y = c.y();
      mk.pose.position.z = c.z();
      mk.pose.orientation = tf2::toMsg(Eigen::Quaterniond(r));
      mk.scale.x = b.width();
      mk.scale.y = 0.5 * b.width();
      mk.scale.z = 2.0 * b.cg_height();
      mk.color = color(it.monitor->mode(), it.monitor->violations() == 0);
      markers.markers.push_back(mk);
      visualization_msgs::Marker label = mk;
      label.ns = "labels";
      label.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
      label.pose.orientation.w = 1.0;
      label.pose.orientation.x = label.pose.orientation.y = label.pose.orientation.z = 0.0;
      label.pose.position.z = 2.0 * b.cg_height() + 0.15;
      label.scale.z = 0.1;
      label.text = it.entry.spec.id + " " + core::to_string(it.monitor->mode());
      label.color.r = label.color.g = label.color.b = label.color.a = 1.0f;
      markers.markers.push_back(label);
    }
  }
  // tf2 rejects a second transform with the same stamp (sim time may not have advanced).
  if (publish_tf_ && !transforms.empty() && now > last_tf_stamp_) {
    tf_broadcaster_->sendTransform(transforms);
    last_tf_stamp_ = now;
  }
  if (publish_markers_) markers_pub_.publish(markers);
}

void RockingMonitor::reset_all(const std::string& why) {
  ROS_WARN("rocking_monitor: resetting all %zu items: %s", items_.size(), why.c_str());
  for (Sensor& s : sensors_) {
    s.timing.restart();
    s.baseline.reset();
    s.have_first = false;
    ++s.resets;
  }
  for (Item& it : items_) it.monitor = std::make_unique<core::ItemMonitor>(it.entry.spec, options_);
}

bool RockingMonitor::on_reset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  reset_all("~reset called");
  res.success = true;
  res.message = "re-armed " + std::to_string(items_.size()) + " items; they restart at rest with the next sample";
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

void RockingMonitor::sensor_diagnostics(std::size_t i, diagnostic_updater::DiagnosticStatusWrapper& st) {
  const Sensor& s = sensors_[i];
  const core::SampleTiming::Counters& c = s.timing.counters();
  const std::uint64_t dropped = c.duplicates + c.out_of_order + s.zero_stamps;
  const std::uint64_t rejected = s.rejected_nonfinite + s.rejected_limit;
  if (s.received == 0) st.summary(diagnostic_msgs::DiagnosticStatus::WARN, "no data yet");
  else if (s.mean_dt > 0.0 && s.last_processing_s > s.mean_dt)
    st.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "processing slower than the sample rate");
  else if (dropped + rejected > 0 || c.gaps > 0)
    st.summary(diagnostic_msgs::DiagnosticStatus::WARN, "samples dropped, rejected or bridged");
  else st.summary(diagnostic_msgs::DiagnosticStatus::OK, "ok");
  st.add("topic", s.spec.topic);
  st.add("received", s.received);
  st.add("accepted", c.accepted);
  st.add("dropped duplicate stamp", c.duplicates);
  st.add("dropped out-of-order stamp", c.out_of_order);
  st.add("dropped zero stamp", s.zero_stamps);
  st.add("rejected non-finite", s.rejected_nonfinite);
  st.add("rejected beyond max_abs_acceleration", s.rejected_limit);
  st.add("gaps bridged", c.gaps);
  st.add("longest gap (s)", c.longest_gap);
  st.add("resets (time jumped back)", s.resets);
  st.add("mean sample period (s)", s.mean_dt);
  st.add("processing per sample, last (s)", s.last_processing_s);
  st.add("processing per sample, max (s)", s.max_processing_s);
  st.add("processing per sample, mean (s)", s.processed > 0 ? s.total_processing_s / s.processed : 0.0);
  st.add("processing / sample period", s.mean_dt > 0.0 ? s.last_processing_s / s.mean_dt : 0.0);
  st.add("gravity baseline (m/s^2)", std::to_string(s.baseline.baseline().x()) + " " +
                                        std::to_string(s.baseline.baseline().y()) + " " +
                                        std::to_string(s.baseline.baseline().z()));
}

void RockingMonitor::catalogue_diagnostics(diagnostic_updater::DiagnosticStatusWrapper& st) {
  std::array<int, 5> counts{};
  int without_tf = 0, invalid = 0;
  std::uint64_t skipped = 0;
  for (const Item& it : items_) {
    skipped += it.samples_without_transform;
    ++counts[static_cast<int>(it.monitor->mode())];
    if (!it.has_rotation) ++without_tf;
    if (it.monitor->violations() != 0) ++invalid;
  }
  if (without_tf > 0) st.summary(diagnostic_msgs::DiagnosticStatus::WARN, std::to_string(without_tf) + " items without transform");
  else if (counts[4] > 0) st.summary(diagnostic_msgs::DiagnosticStatus::WARN, std::to_string(counts[4]) + " items overturned");
  else st.summary(diagnostic_msgs::DiagnosticStatus::OK, "monitoring " + std::to_string(items_.size()) + " items");
  st.add("items", items_.size());
  for (int m = 0; m < 5; ++m) st.add(core::to_string(static_cast<ItemMode>(m)), counts[m]);
  st.add("pure-rocking model not valid now", invalid);
  st.add("items without transform", without_tf);
  st.add("item-samples skipped for want of a transform", skipped);
  st.add("alarms published", alarms_published_);
  st.add("method", core::to_string(options_.solver.method));
  st.add("fidelity", core::to_string(options_.fidelity));
  int on_contact = 0;
  for (const Item& it : items_) on_contact += std::string(it.monitor->active_model()) == "contact";
  st.add("items on the contact model now", on_contact);
  if (options_.fidelity == core::Fidelity::Adaptive) {
    int ruled_out = 0;
    long outside = 0;
    for (const Item& it : items_) {
      const core::AdaptiveModel& a = *it.monitor->adaptive();
      ruled_out += a.initial_reason() == core::SwitchReason::SceneRulesOutContact;
      outside = std::max(outside, a.outcome().samples_outside_scene);
    }
    st.add("items whose friction rules out the contact model in the scene envelope", ruled_out);
    st.add("input samples outside the scene envelope", outside);
    if (outside > 0 && without_tf == 0)
      st.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN,
                      "input outside ~scene_envelope: pre-check guarantee void, margins apply");
  }
}

}  // namespace rocking_monitor::live
