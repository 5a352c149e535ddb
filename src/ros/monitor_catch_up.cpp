// RockingMonitor catching up after a restart (issue 29 part 2; docs/journal.md "Catching up"): the
// samples missed since the state snapshot's last are fetched from a bridge's history service and
// stepped through the ordinary sample path before the live stream goes on.
#include "rocking_monitor/ros/monitor.hpp"

#include <chrono>
#include <cmath>
#include <future>
#include <memory>
#include <thread>

namespace rocking_monitor::live {

bool RockingMonitor::load_catch_up_parameters() {
  if (pnh_.hasParam("catch_up_service") && !pnh_.getParam("catch_up_service", catch_up_service_)) {
    ROS_FATAL("rocking_monitor: parameter ~catch_up_service has the wrong type (expected a service name; \"\" = off)");
    return false;
  }
  XmlRpc::XmlRpcValue v;
  if (pnh_.getParam("catch_up_timeout", v)) {
    if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) catch_up_timeout_ = static_cast<double>(v);
    else if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) catch_up_timeout_ = static_cast<int>(v);
    else catch_up_timeout_ = -1.0;
    if (!(catch_up_timeout_ > 0.0) || !std::isfinite(catch_up_timeout_)) {
      ROS_FATAL("rocking_monitor: ~catch_up_timeout must be a number of seconds > 0 (the wait for ~catch_up_service)");
      return false;
    }
  }
  if (!catch_up_service_.empty() && snapshot_path_.empty())
    ROS_WARN("rocking_monitor: ~catch_up_service '%s' is set but state snapshots are off: nothing to catch up from",
             catch_up_service_.c_str());
  return true;
}

bool RockingMonitor::catch_up(std::size_t si) {
  Sensor& s = sensors_[si];
  const core::SnapshotSensor& ss = resume_->sensors[si];
  ::ros::Time after;
  after.fromNSec(static_cast<std::uint64_t>(ss.last_stamp_ns));
  CaughtUp c;
  c.sensor = s.spec.name;
  const auto t0 = std::chrono::steady_clock::now();
  const std::string service = nh_.resolveName(catch_up_service_);
  auto give_up = [&](const std::string& why) {
    c.outcome = "not caught up from " + service + ": " + why + "; the missed samples are a frozen gap";
    ROS_WARN("rocking_monitor: sensor '%s': %s", s.spec.name.c_str(), c.outcome.c_str());
    caught_up_.push_back(c);
    return false;
  };
  // Once per sensor and restart: the waits below (each at most ~catch_up_timeout) happen before the
  // first live sample is stepped; live samples queue meanwhile.
  if (!::ros::service::waitForService(service, ::ros::Duration(catch_up_timeout_)))
    return give_up("the service is not there (waited ~catch_up_timeout " + std::to_string(catch_up_timeout_) + " s)");
  // The call on a thread of its own, so that a bridge that stops answering costs at most the timeout
  // (roscpp's call has none); given up, the thread finishes on its own with its own copy.
  auto srv = std::make_shared<SampleHistory>();
  srv->request.topic = s.sub.getTopic();
  srv->request.after = after;
  auto answered = std::make_shared<std::promise<bool>>();
  std::future<bool> done = answered->get_future();
  std::thread([service, srv, answered] { answered->set_value(::ros::service::call(service, *srv)); }).detach();
  if (done.wait_for(std::chrono::duration<double>(catch_up_timeout_)) != std::future_status::ready)
    return give_up("no answer within ~catch_up_timeout " + std::to_string(catch_up_timeout_) + " s");
  if (!done.get()) return give_up("the call failed");
  const SampleHistory::Response& r = srv->response;
  if (!r.ok) return give_up("refused: " + r.message);
  const char* type = s.spec.type == SensorSpec::Type::Imu ? "sensor_msgs/Imu" : "geometry_msgs/AccelStamped";
  if (r.type != type) return give_up("its samples are " + r.type + ", this sensor's topic is " + type);
  const std::size_t n = r.stamps.size();
  if (r.x.size() != n || r.y.size() != n || r.z.size() != n)
    return give_up("malformed answer: " + std::to_string(n) + " stamps but " + std::to_string(r.x.size()) + ", " +
                   std::to_string(r.y.size()) + ", " + std::to_string(r.z.size()) + " values");
  if (!r.complete) return give_up("its history does not reach back to the snapshot's last sample (" + r.message + ")");
  if (n == 0) return give_up("it has no sample after the snapshot's last");
  for (std::size_t i = 0; i < n; ++i)
    if (r.stamps[i] <= (i == 0 ? after : r.stamps[i - 1]))
      return give_up("malformed answer: stamp " + std::to_string(i) + " is not after the one before");

  // The items continue at the first missed sample (nothing missing), then every missed one is stepped
  // through the sample path as if it had arrived; the live samples wait in the subscriber queue.
  resume_sensor(si, r.stamps[0], true);
  catching_up_ = true;
  std_msgs::Header h;
  h.frame_id = r.frame_id;
  for (std::size_t i = 0; i < n; ++i) {
    h.seq = static_cast<std::uint32_t>(i);
    h.stamp = r.stamps[i];
    on_sample(si, h, Eigen::Vector3d(r.x[i], r.y[i], r.z[i]));
  }
  catching_up_ = false;
  s.caught_up_to = r.stamps[n - 1];
  c.ok = true;
  c.samples = n;
  c.input_s = (r.stamps[n - 1] - r.stamps[0]).toSec();
  c.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  char text[320];
  std::snprintf(text, sizeof text, "caught up from %s: %zu missed samples (%.3f s of input after the snapshot's last) "
                "stepped in %.3f s (%.0f samples/s, %.1fx real time)", service.c_str(), n, c.input_s, c.wall_s,
                static_cast<double>(n) / c.wall_s, c.input_s / c.wall_s);
  c.outcome = text;
  ROS_WARN("rocking_monitor: sensor '%s': %s; live samples up to %.6f are dropped as already stepped",
           s.spec.name.c_str(), text, s.caught_up_to.toSec());
  caught_up_.push_back(c);
  if (diagnostics_) diagnostics_->force_update();
  return true;
}

void RockingMonitor::catch_up_diagnostics(diagnostic_updater::DiagnosticStatusWrapper& st) {
  using diagnostic_msgs::DiagnosticStatus;
  bool failed = false;
  for (const CaughtUp& c : caught_up_) failed = failed || !c.ok;
  if (caught_up_.empty()) st.summary(DiagnosticStatus::OK, "no restart to catch up on");
  else if (failed) st.summary(DiagnosticStatus::WARN, "a restart's missed samples are a frozen gap: not caught up");
  else st.summary(DiagnosticStatus::OK, "caught up after a restart: nothing missed");
  st.add("service", nh_.resolveName(catch_up_service_));
  st.add("timeout (s)", catch_up_timeout_);
  for (const CaughtUp& c : caught_up_) {
    st.add("sensor " + c.sensor, c.outcome);
    st.add("sensor " + c.sensor + ": samples stepped from the history", c.samples);
    st.add("sensor " + c.sensor + ": catch-up wall time (s)", c.wall_s);
  }
  for (const Sensor& s : sensors_)
    st.add("sensor " + s.spec.name + ": live samples dropped as already stepped", s.caught_up_dropped);
}

}  // namespace rocking_monitor::live
