// Dashboard's input chart: the monitor does not republish its input, so the dashboard subscribes to the
// sensor itself (the monitor's first catalogue sensor, or ~sensor_topic) and keeps the last 60 s in
// 50 ms bins, each bin its sample of largest magnitude (the peaks survive the thinning).
#include <cmath>

#include <nlohmann/json.hpp>

#include "rocking_monitor/json_text.hpp"
#include "rocking_monitor/ros/dashboard.hpp"

namespace rocking_monitor::live {
namespace {

constexpr double kBin = 0.05;             // s: 20 points per second on a chart a few hundred pixels wide
constexpr double kInputSeconds = 60.0;    // the chart's window

}  // namespace

void Dashboard::subscribe_input(const std::string& topic, bool imu) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (topic.empty() || topic == input_topic_) return;
    input_topic_ = topic;
    input_.clear();
    have_rest_ = false;
    input_pushed_ = 0;
  }
  input_sub_ = imu ? nh_.subscribe(topic, 200, &Dashboard::on_imu, this)
                   : nh_.subscribe(topic, 200, &Dashboard::on_accel, this);
  ROS_INFO("dashboard: input acceleration chart from %s (%s)", topic.c_str(),
           imu ? "sensor_msgs/Imu" : "geometry_msgs/AccelStamped");
}

void Dashboard::on_imu(const sensor_msgs::Imu::ConstPtr& m) {
  std::lock_guard<std::mutex> lock(mutex_);
  add_input_locked(m->header.stamp.toSec(), m->linear_acceleration.x, m->linear_acceleration.y,
                   m->linear_acceleration.z, true);
}

void Dashboard::on_accel(const geometry_msgs::AccelStamped::ConstPtr& m) {
  std::lock_guard<std::mutex> lock(mutex_);
  add_input_locked(m->header.stamp.toSec(), m->accel.linear.x, m->accel.linear.y, m->accel.linear.z, false);
}

void Dashboard::add_input_locked(double t, double x, double y, double z, bool gravity_included) {
  if (!std::isfinite(t) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return;
  if (!input_.empty() && t < input_.back().t - 1.0) {  // the clock went back: a new run
    input_.clear();
    have_rest_ = false;
    input_pushed_ = 0;
  }
  // REP 145 specific force: the at-rest reading (gravity, offsets) is the first sample's, as the
  // monitor's baseline starts; an AccelStamped is ground acceleration already.
  if (!have_rest_) {
    rest_[0] = gravity_included ? x : 0.0;
    rest_[1] = gravity_included ? y : 0.0;
    rest_[2] = gravity_included ? z : 0.0;
    have_rest_ = true;
  }
  const float a[3] = {static_cast<float>(x - rest_[0]), static_cast<float>(y - rest_[1]), static_cast<float>(z - rest_[2])};
  const double bin = std::floor(t / kBin) * kBin;
  if (!input_.empty() && input_.back().t == bin) {
    InputPoint& p = input_.back();
    const auto mag = [](const float* v) { return v[0] * v[0] + v[1] * v[1] + v[2] * v[2]; };
    if (mag(a) > mag(p.a)) std::copy(a, a + 3, p.a);
  } else {
    input_.push_back({bin, {a[0], a[1], a[2]}});
  }
  while (!input_.empty() && input_.front().t < bin - kInputSeconds) {
    input_.pop_front();
    if (input_pushed_ > 0) --input_pushed_;
  }
}

std::string Dashboard::input_json() const {
  nlohmann::json points = nlohmann::json::array();
  std::string topic;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    topic = input_topic_;
    for (const InputPoint& p : input_) points.push_back({p.t, p.a[0], p.a[1], p.a[2]});
  }
  return json_text(nlohmann::json{{"topic", topic}, {"points", std::move(points)}});
}

void Dashboard::push_input() {
  // Once a second, the bins completed since the last push (the newest bin may still grow).
  nlohmann::json points = nlohmann::json::array();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto now = ::ros::WallTime::now().toSec();
    if (now - input_pushed_t_ < 1.0 || input_.size() < 2) return;
    input_pushed_t_ = now;
    for (std::size_t i = input_pushed_; i + 1 < input_.size(); ++i)
      points.push_back({input_[i].t, input_[i].a[0], input_[i].a[1], input_[i].a[2]});
    input_pushed_ = input_.size() - 1;
  }
  if (!points.empty()) publish_event("input", json_text(nlohmann::json{{"points", std::move(points)}}));
}

}  // namespace rocking_monitor::live
