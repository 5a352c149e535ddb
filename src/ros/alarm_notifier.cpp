#include "rocking_monitor/ros/alarm_notifier.hpp"


#include <cmath>
#include <cstdlib>
#include <sstream>

#include "rocking_monitor/notify/channels.hpp"

namespace rocking_monitor::live {

namespace {

double wall_now() { return ros::WallTime::now().toSec(); }

std::vector<std::string> monitor_names(const ros::NodeHandle& pnh) {
  std::vector<std::string> names;
  XmlRpc::XmlRpcValue v;
  if (pnh.getParam("monitors", v)) {
    if (v.getType() == XmlRpc::XmlRpcValue::TypeArray) {
      for (int i = 0; i < v.size(); ++i)
        if (v[i].getType() == XmlRpc::XmlRpcValue::TypeString) names.push_back(static_cast<std::string>(v[i]));
    } else if (v.getType() == XmlRpc::XmlRpcValue::TypeString) {
      std::stringstream s(static_cast<std::string>(v));
      for (std::string name; std::getline(s, name, ',');)
        if (!name.empty()) names.push_back(name);
    }
  } else {
    names.push_back("/rocking_monitor");
  }
  return names;
}

}  // namespace

AlarmNotifier::AlarmNotifier(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh), pnh_(pnh) {}

bool AlarmNotifier::init() {
  std::string config_path;
  if (!pnh_.getParam("config", config_path) || config_path.empty()) {
    ROS_FATAL("alarm_notifier: ~config: missing (the routing YAML, e.g. config/notify.yaml; docs/notify.md)");
    return false;
  }
  const auto monitors = monitor_names(pnh_);
  if (monitors.empty()) {
    ROS_FATAL("alarm_notifier: ~monitors: a list of monitor node names, e.g. [/rocking_monitor_a, /rocking_monitor_b]");
    return false;
  }
  std::string outbox;
  if (!pnh_.getParam("outbox", outbox) || outbox.empty()) {
    const char* home = std::getenv("ROS_HOME");
    const char* user = std::getenv("HOME");
    outbox = (home ? std::string(home) : std::string(user ? user : ".") + "/.ros") + "/rocking_monitor/notify_outbox.jsonl";
  }
  const double period = pnh_.param("tick_period", 0.05);
  if (!(period > 0.0) || !std::isfinite(period)) {
    ROS_FATAL("alarm_notifier: ~tick_period: must be a positive number of seconds, got %g", period);
    return false;
  }
  try {
    notify::NotifyConfig config = notify::load_notify_config(config_path);
    if (pnh_.param("check_hosts", true)) notify::check_hosts(config);
    for (const auto& w : config.warnings) ROS_WARN("alarm_notifier: %s", w.c_str());  // every start (issue 52)
    notifier_ = std::make_unique<notify::Notifier>(std::move(config), outbox, notify::make_channel, wall_now());
  } catch (const std::exception& e) {
    ROS_FATAL("alarm_notifier: %s", e.what());
    return false;
  }
  for (const auto& w : notifier_->warnings()) ROS_WARN("alarm_notifier: %s", w.c_str());
  for (const auto& m : monitors) {
    // queue_size: a burst of thousands of items must not be dropped before the core counts it.
    subs_.push_back(nh_.subscribe<OverturnAlarm>(m + "/alarms", 100000, [this, m](const OverturnAlarm::ConstPtr& a) { on_alarm(m, a); }));
    subs_.push_back(nh_.subscribe<ProbabilityAlarm>(m + "/probability_alarms", 100000,
                                                    [this, m](const ProbabilityAlarm::ConstPtr& a) { on_probability(m, a); }));
  }
  diag_pub_ = nh_.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 10);
  tick_timer_ = nh_.createWallTimer(ros::WallDuration(period), &AlarmNotifier::tick, this);
  diag_timer_ = nh_.createWallTimer(ros::WallDuration(1.0), &AlarmNotifier::publish_diagnostics, this);
  std::string list;
  for (const auto& m : monitors) list += (list.empty() ? "" : ", ") + m;
  ROS_INFO("alarm_notifier: %s -> %s (outbox %s, %zu unacknowledged messages from before)", list.c_str(),
           config_path.c_str(), outbox.c_str(), [&] {
             std::size_t q = 0;
             for (const auto& s : notifier_->status()) q += s.queued;
             return q;
           }());
  return true;
}

namespace {
// The fields both alarm messages carry.
template <class Message>
notify::NotifyAlarm common_fields(const std::string& monitor, const Message& m) {
  notify::NotifyAlarm a;
  a.source = monitor;
  a.item = m.item_id;
  a.description = m.description;
  a.level = m.level;
  a.stamp_ns = static_cast<std::int64_t>(m.header.stamp.toNSec());
  a.event_time = m.event_time;
  a.event_id = m.event_id;
  a.sequence = m.sequence;
  return a;
}
}  // namespace

void AlarmNotifier::on_alarm(const std::string& monitor, const OverturnAlarm::ConstPtr& m) {
  notify::NotifyAlarm a = common_fields(monitor, *m);
  a.whole = m->frozen_s == 0.0;
  a.cause = static_cast<core::AlarmCause>(m->cause);
  accept(a);
}

void AlarmNotifier::on_probability(const std::string& monitor, const ProbabilityAlarm::ConstPtr& m) {
  notify::NotifyAlarm a = common_fields(monitor, *m);
  a.probability = true;
  a.probability_value = m->value.probability;
  a.threshold = m->threshold;
  accept(a);
}

void AlarmNotifier::accept(const notify::NotifyAlarm& a) {
  const auto r = notifier_->accept(a, wall_now());
  if (r == notify::Notifier::Accepted::Routed && a.level >= notify::kCommitted)
    tick(ros::WallTimerEvent());  // lead time: a COMMITTED item is not kept waiting for the timer
}

void AlarmNotifier::tick(const ros::WallTimerEvent&) {
  if (const std::string e = notifier_->tick(wall_now()); !e.empty())
    ROS_ERROR_THROTTLE(10.0, "alarm_notifier: outbox: %s (nothing is sent that is not on disk)", e.c_str());
  std::lock_guard<std::mutex> lock(reported_mutex_);
  for (const auto& s : notifier_->status()) {
    std::uint64_t& refused = reported_refused_[s.name];
    if (s.refused != refused)
      ROS_ERROR("alarm_notifier: channel %s: %s", s.name.c_str(), s.last_error.c_str());  // never retried: said once
    refused = s.refused;
    std::string& said = reported_[s.name];
    const std::string now = s.failing_attempts > 0 ? s.last_error : "";
    if (now == said) continue;
    if (!now.empty())
      ROS_WARN("alarm_notifier: channel %s cannot deliver (%zu waiting, retrying): %s", s.name.c_str(), s.queued, now.c_str());
    else
      ROS_INFO("alarm_notifier: channel %s delivers again (%lu delivered)", s.name.c_str(), static_cast<unsigned long>(s.delivered));
    said = now;
  }
}

void AlarmNotifier::publish_diagnostics(const ros::WallTimerEvent&) {
  diagnostic_msgs::DiagnosticArray array;
  array.header.stamp = ros::Time::now();
  const std::string node = ros::this_node::getName();
  auto kv = [](const std::string& k, const std::string& v) {
    diagnostic_msgs::KeyValue x;
    x.key = k;
    x.value = v;
    return x;
  };
  for (const auto& s : notifier_->status()) {
    diagnostic_msgs::DiagnosticStatus st;
    st.name = node + ": channel " + s.name + " (" + notify::to_string(s.type) + ")";
    st.hardware_id = node;
    if (s.failing_attempts > 0) {
      st.level = diagnostic_msgs::DiagnosticStatus::ERROR;
      st.message = "cannot deliver: " + s.last_error;
    } else if (s.refused > 0) {  // delivering, but messages were refused for good: someone must look
      st.level = diagnostic_msgs::DiagnosticStatus::WARN;
      st.message = std::to_string(s.refused) + " message(s) refused for good (not retried); last error: " + s.last_error;
    } else {
      st.level = diagnostic_msgs::DiagnosticStatus::OK;
      st.message = s.queued > 0 ? "delivering" : "ok";
    }
    st.values = {kv("waiting", std::to_string(s.queued)), kv("delivered", std::to_string(s.delivered)),
                 kv("failed attempts", std::to_string(s.failures)),
                 kv("refused for good (not retried)", std::to_string(s.refused)), kv("last error", s.last_error)};
    array.status.push_back(st);
  }
  const auto c = notifier_->counts();
  diagnostic_msgs::DiagnosticStatus st;
  st.name = node + ": alarms";
  st.hardware_id = node;
  st.level = diagnostic_msgs::DiagnosticStatus::OK;
  st.message = std::to_string(c.accepted) + " alarms, " + std::to_string(c.messages) + " messages";
  st.values = {kv("accepted", std::to_string(c.accepted)), kv("repeats dropped", std::to_string(c.repeats)),
               kv("pair copies merged", std::to_string(c.merged)), kv("routed to nobody", std::to_string(c.unrouted)),
               kv("messages formed", std::to_string(c.messages))};
  array.status.push_back(st);
  diag_pub_.publish(array);
}

}  // namespace rocking_monitor::live
