// ground_motion_player (see include/rocking_monitor/ros/ground_motion_player.hpp).

#include "rocking_monitor/ros/ground_motion_player.hpp"

#include <geometry_msgs/AccelStamped.h>
#include <sensor_msgs/Imu.h>
#include <std_msgs/Bool.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

namespace rocking_monitor::records {

namespace {

std::int64_t steady_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Reads an optional parameter that may be absent or given as an empty string (roslaunch args).
bool get_string(const ros::NodeHandle& pnh, const std::string& name, std::string& out) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam(name, v)) return false;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeString) throw std::invalid_argument("~" + name + ": must be a string");
  out = static_cast<std::string>(v);
  return !out.empty();
}

/// Number parameter (int or double); "" counts as absent.
bool get_number(const ros::NodeHandle& pnh, const std::string& name, double& out) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam(name, v)) return false;
  switch (v.getType()) {
    case XmlRpc::XmlRpcValue::TypeDouble:
      out = static_cast<double>(v);
      break;
    case XmlRpc::XmlRpcValue::TypeInt:
      out = static_cast<int>(v);
      break;
    case XmlRpc::XmlRpcValue::TypeString:
      if (static_cast<std::string>(v).empty()) return false;
      throw std::invalid_argument("~" + name + ": '" + static_cast<std::string>(v) + "' is not a number");
    default:
      throw std::invalid_argument("~" + name + ": must be a number");
  }
  if (!std::isfinite(out)) throw std::invalid_argument("~" + name + ": must be finite");
  return true;
}

bool get_bool(const ros::NodeHandle& pnh, const std::string& name, bool& out) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam(name, v)) return false;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeBoolean) throw std::invalid_argument("~" + name + ": must be true or false");
  out = static_cast<bool>(v);
  return true;
}

}  // namespace

PlayerConfig read_player_config(const ros::NodeHandle& pnh) {
  PlayerConfig c;
  std::string s;
  if (get_string(pnh, "file", s)) c.source.files.push_back(s);
  XmlRpc::XmlRpcValue list;
  if (pnh.getParam("files", list)) {
    if (list.getType() != XmlRpc::XmlRpcValue::TypeArray) throw std::invalid_argument("~files: must be a list of paths");
    for (int i = 0; i < list.size(); ++i) {
      if (list[i].getType() != XmlRpc::XmlRpcValue::TypeString) throw std::invalid_argument("~files: must be a list of paths");
      c.source.files.push_back(static_cast<std::string>(list[i]));
    }
  }
  get_string(pnh, "station", c.source.station);
  if (!get_string(pnh, "records_dir", c.source.records_dir)) c.source.records_dir = default_records_dir();
  get_string(pnh, "synthetic", c.source.synthetic);
  if (get_string(pnh, "units", s)) {
    if (s == "g") c.source.read.csv_units = core::AccelUnits::G;
    else if (s == "cm/s2") c.source.read.csv_units = core::AccelUnits::CentimetersPerSecond2;
    else if (s != "m/s2") throw std::invalid_argument("~units: '" + s + "' is not one of g, m/s2, cm/s2");
  }
  double v = 0.0;
  // miniSEED records: counts per m/s^2, the sensor's azimuth, a channel table (docs/records.md)
  if (get_number(pnh, "gain", v)) {
    if (!(v > 0.0)) throw std::invalid_argument("~gain: must be > 0 counts per m/s^2");
    c.source.read.gain_counts_per_mps2 = v;
  }
  if (get_number(pnh, "sensor_azimuth", v)) c.source.read.sensor_azimuth_deg = v;
  get_string(pnh, "channel_table", c.source.read.channel_table);
  if (get_number(pnh, "azimuth", v)) c.source.frame.azimuth_deg = v;
  if (get_number(pnh, "scale", v)) c.source.frame.scale = v;
  if (get_string(pnh, "length_mismatch", s)) {
    try {
      c.source.frame.length_mismatch = core::parse_length_mismatch(s);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("~length_mismatch: ") + e.what());
    }
  }
  get_string(pnh, "topic", c.topic);
  get_string(pnh, "accel_topic", c.accel_topic);
  get_string(pnh, "frame_id", c.frame_id);
  if (get_number(pnh, "rate_factor", v)) {
    if (!(v > 0.0)) throw std::invalid_argument("~rate_factor: must be > 0");
    c.rate_factor = v;
  }
  get_bool(pnh, "loop", c.loop);
  if (get_number(pnh, "start_delay", v)) {
    if (v < 0.0) throw std::invalid_argument("~start_delay: must be >= 0 s");
    c.start_delay = v;
  }
  if (get_number(pnh, "noise_density", v)) {
    if (v < 0.0) throw std::invalid_argument("~noise_density: must be >= 0");
    c.noise_density = v;
  }
  if (get_string(pnh, "stamp_source", s)) {
    if (s != "now" && s != "schedule") throw std::invalid_argument("~stamp_source: '" + s + "' is not one of now, schedule");
    c.stamp_now = s == "now";
  }
  if (get_number(pnh, "wait_for_subscribers", v)) {
    if (v < 0.0 || v != std::floor(v)) throw std::invalid_argument("~wait_for_subscribers: must be a whole number >= 0");
    c.wait_for_subscribers = static_cast<int>(v);
  }
  if (get_number(pnh, "linger", v)) {
    if (v < 0.0) throw std::invalid_argument("~linger: must be >= 0 s");
    c.linger = v;
  }
  c.history_length = live::read_history_length(pnh);
  if (c.topic == c.accel_topic) throw std::invalid_argument("~accel_topic: must differ from ~topic");
  if (c.frame_id.empty()) throw std::invalid_argument("~frame_id: must not be empty");
  const int sources = (c.source.files.empty() ? 0 : 1) + (c.source.station.empty() ? 0 : 1) + (c.source.synthetic.empty() ? 0 : 1);
  if (sources != 1) throw std::invalid_argument("give exactly one of ~file/~files, ~station (with ~records_dir), ~synthetic");
  if (!c.source.station.empty() && c.source.records_dir.empty()) throw std::invalid_argument("~station: needs ~records_dir");
  return c;
}

GroundMotionPlayer::GroundMotionPlayer(ros::NodeHandle& nh, ros::NodeHandle& pnh, PlayerConfig config, core::SensorFrameMotion motion)
    : config_(std::move(config)), motion_(std::move(motion)) {
  if (motion_.size() == 0) throw std::invalid_argument("the record has no samples");
  variance_ = accel_variance(config_.noise_density, motion_.dt);
  // Queue: a couple of seconds at the publishing rate, so a briefly slow subscriber loses nothing.
  const auto queue = static_cast<std::uint32_t>(std::clamp(2.0 * config_.rate_factor / motion_.dt, 100.0, 20000.0));
  imu_pub_ = nh.advertise<sensor_msgs::Imu>(config_.topic, queue);
  if (!config_.accel_topic.empty()) accel_pub_ = nh.advertise<geometry_msgs::AccelStamped>(config_.accel_topic, queue);
  finished_pub_ = pnh.advertise<std_msgs::Bool>("finished", 1, true);
  if (config_.history_length > 0.0) {
    // Samples per second of stamp time: the record's rate times ~rate_factor (either stamp source).
    const double rate = config_.rate_factor / motion_.dt;
    history_ = std::make_unique<live::SampleHistoryServer>(config_.history_length);
    imu_history_ = history_->add_topic(imu_pub_.getTopic(), "sensor_msgs/Imu", config_.frame_id, rate);
    if (accel_pub_)
      accel_history_ = history_->add_topic(accel_pub_.getTopic(), "geometry_msgs/AccelStamped", config_.frame_id, rate);
    history_->advertise(pnh);
    ROS_INFO("ground_motion_player: keeping the last %.6g s (%zu samples) of each topic, served as %s",
             config_.history_length, history_->capacity(imu_history_), pnh.resolveName("history").c_str());
  }
  std_msgs::Bool b;
  b.data = false;
  finished_pub_.publish(b);
}

bool GroundMotionPlayer::wait_until_wall(std::int64_t steady_ns) {
  // Sleep in slices so a shutdown request is honoured within 50 ms even during a long start delay.
  for (;;) {
    if (!ros::ok()) return false;
    const std::int64_t left = steady_ns - steady_now_ns();
    if (left <= 0) return true;
    std::this_thread::sleep_for(std::chrono::nanoseconds(std::min<std::int64_t>(left, 50'000'000)));
  }
}

bool GroundMotionPlayer::wait_until_ros(const ros::Time& t) {
  // ros::Time::sleepUntil follows /clock under sim time and returns false on shutdown.
  while (ros::Time::now() < t) {
    if (!ros::ok()) return false;
    if (!ros::Time::sleepUntil(std::min(t, ros::Time::now() + ros::Duration(0.05)))) return false;
  }
  return ros::ok();
}

bool GroundMotionPlayer::wait_to_start(bool sim) {
  if (sim) {
    ROS_INFO("ground_motion_player: /use_sim_time is set, waiting for /clock");
    if (!ros::Time::waitForValid()) return false;
  }
  if (config_.wait_for_subscribers > 0) {
    ROS_INFO("ground_motion_player: waiting for %d subscriber(s) on %s", config_.wait_for_subscribers, imu_pub_.getTopic().c_str());
    const auto t0 = std::chrono::steady_clock::now();
    auto next_log = t0 + std::chrono::seconds(5);
    while (ros::ok() && static_cast<int>(imu_pub_.getNumSubscribers()) < config_.wait_for_subscribers) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      if (std::chrono::steady_clock::now() > next_log) {
        ROS_INFO("ground_motion_player: still waiting for subscribers on %s (%u connected)", imu_pub_.getTopic().c_str(),
                 imu_pub_.getNumSubscribers());
        next_log += std::chrono::seconds(5);
      }
    }
  }
  return true;
}

void GroundMotionPlayer::publish_sample(std::size_t i, const ros::Time& stamp) {
  const core::AccelerometerSample s = motion_.sample(i);
  const sensor_msgs::Imu imu = make_imu_message(s, stamp, config_.frame_id, variance_);
  // Kept before it is published: a subscriber asking later finds whatever it did not receive.
  if (history_) history_->push(imu_history_, stamp, imu.linear_acceleration.x, imu.linear_acceleration.y,
                               imu.linear_acceleration.z);
  imu_pub_.publish(imu);
  if (accel_pub_) {
    const geometry_msgs::AccelStamped accel = make_accel_message(s, stamp, config_.frame_id);
    if (history_) history_->push(accel_history_, stamp, accel.accel.linear.x, accel.accel.linear.y, accel.accel.linear.z);
    accel_pub_.publish(accel);
  }
}

void GroundMotionPlayer::report_end(const Result& r, double wall) {
  const std::size_t n = motion_.size();
  if (r.interrupted) {
    ROS_WARN("ground_motion_player: interrupted after %llu of %zu samples of pass %llu", static_cast<unsigned long long>(r.published % n), n,
             static_cast<unsigned long long>(r.passes + 1));
    return;
  }
  ROS_INFO("ground_motion_player: finished %s: published %llu samples in %llu pass(es), %.3f s wall; %llu late by more than one "
           "sample interval (max %.1f ms)",
           motion_.station.c_str(), static_cast<unsigned long long>(r.published), static_cast<unsigned long long>(r.passes), wall,
           static_cast<unsigned long long>(r.late), r.max_lateness * 1e3);
  std_msgs::Bool b;
  b.data = true;
  finished_pub_.publish(b);
  // Give subscribers time to receive the queued samples and the latched end signal before exiting.
  wait_until_wall(steady_now_ns() + static_cast<std::int64_t>(std::llround(config_.linger * 1e9)));
}

GroundMotionPlayer::Result GroundMotionPlayer::run() {
  Result r;
  const bool sim = ros::Time::isSimTime();
  if (!wait_to_start(sim)) {
    r.interrupted = true;
    return r;
  }
  const std::size_t n = motion_.size();
  const double f = config_.rate_factor;
  const std::int64_t t_first = motion_.time_ns(0);
  const std::int64_t dt_ns = std::llround(motion_.dt * 1e9);
  // Due offsets of one pass, ns after the pass origin; the next pass starts one dt after the last sample.
  auto offset_ns = [&](std::size_t i) { return static_cast<std::int64_t>(std::llround(static_cast<double>(motion_.time_ns(i) - t_first) / f)); };
  const std::int64_t pass_ns = static_cast<std::int64_t>(std::llround(static_cast<double>(motion_.time_ns(n - 1) - t_first + dt_ns) / f));
  const double late_limit = motion_.dt / f;  // s

  ROS_INFO("ground_motion_player: playing %s on %s at %.6g x real time%s in %.3g s: %s", motion_.station.c_str(),
           imu_pub_.getTopic().c_str(), f, config_.loop ? " (loop)" : "", config_.start_delay, describe(motion_).c_str());
  for (const std::string& note : motion_.notes) ROS_WARN("ground_motion_player: %s", note.c_str());

  const auto delay_ns = static_cast<std::int64_t>(std::llround(config_.start_delay * 1e9));
  const std::int64_t steady_origin = steady_now_ns() + delay_ns;
  const ros::Time ros_origin = ros::Time::now() + ros::Duration().fromNSec(delay_ns);
  const auto wall_start = std::chrono::steady_clock::now();
  for (std::uint64_t pass = 0; ros::ok(); ++pass) {
    for (std::size_t i = 0; i < n; ++i) {
      const std::int64_t due = static_cast<std::int64_t>(pass) * pass_ns + offset_ns(i);
      const ros::Time due_ros = ros_origin + ros::Duration().fromNSec(due);
      double lateness = 0.0;
      if (sim) {
        if (!wait_until_ros(due_ros)) {
          r.interrupted = true;
          break;
        }
        lateness = (ros::Time::now() - due_ros).toSec();
      } else {
        if (!wait_until_wall(steady_origin + due)) {
          r.interrupted = true;
          break;
        }
        lateness = static_cast<double>(steady_now_ns() - (steady_origin + due)) * 1e-9;
      }
      if (lateness > late_limit) ++r.late;
      r.max_lateness = std::max(r.max_lateness, lateness);
      publish_sample(i, config_.stamp_now ? ros::Time::now() : due_ros);
      ++r.published;
    }
    if (r.interrupted) break;
    ++r.passes;
    if (!config_.loop) break;
    ROS_INFO("ground_motion_player: pass %llu done, looping", static_cast<unsigned long long>(r.passes));
  }
  report_end(r, std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
  return r;
}

}  // namespace rocking_monitor::records
