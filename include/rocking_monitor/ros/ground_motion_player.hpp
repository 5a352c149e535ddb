#pragma once

// ground_motion_player: streams a record, a station or a synthetic spec live as sensor_msgs/Imu
// (same REP 145 content as record_to_bag) at the record's own sample rate times ~rate_factor.
//
// Timing: sample i of pass k is due at origin + (k * pass_length + t_i - t_0) / rate_factor, computed
// from the record time in integer nanoseconds, never by accumulating sleeps, so there is no drift
// however long it plays. Wall time uses std::chrono::steady_clock (immune to clock changes); under
// /use_sim_time the schedule runs on ros::Time, i.e. follows /clock. A sample that is late is still
// published (never dropped) and counted.
//
// History (issue 29 part 2): the last ~history_length s of each published topic are kept and served
// as ~history (rocking_monitor/SampleHistory): a restarted monitor catches up on what it missed.

#include <cstdint>
#include <memory>
#include <string>

#include <ros/ros.h>

#include "rocking_monitor/motion/sensor_frame.hpp"
#include "rocking_monitor/ros/ground_motion_source.hpp"
#include "rocking_monitor/ros/sample_history_server.hpp"

namespace rocking_monitor::records {

struct PlayerConfig {
  SourceSpec source;                     ///< ~file / ~files / ~station + ~records_dir / ~synthetic, ~units, ~azimuth, ...
  std::string topic = kDefaultImuTopic;  ///< ~topic
  std::string accel_topic;               ///< ~accel_topic: AccelStamped of the ground acceleration; empty = off
  std::string frame_id = kDefaultFrameId;  ///< ~frame_id
  double rate_factor = 1.0;              ///< ~rate_factor: 2 plays twice as fast (> 0)
  bool loop = false;                     ///< ~loop: start again after the last sample (the next pass starts one dt later)
  double start_delay = 1.0;              ///< ~start_delay, s (after ~wait_for_subscribers)
  double noise_density = kDefaultNoiseDensity;  ///< ~noise_density, (m/s^2)/sqrt(Hz), fills the covariance only
  bool stamp_now = true;                 ///< ~stamp_source: "now" (ros::Time::now() at publish) | "schedule" (the due time)
  int wait_for_subscribers = 0;          ///< ~wait_for_subscribers: wait for this many Imu subscribers before starting
  double linger = 1.0;                   ///< ~linger, s: stay up after the end so the last messages and ~finished are delivered
  double history_length = live::kDefaultHistoryLength;  ///< ~history_length, s of samples kept for ~history (0 = off)
};

/// Reads the private parameters; throws std::invalid_argument naming the parameter ("~azimuth: ...").
PlayerConfig read_player_config(const ros::NodeHandle& pnh);

class GroundMotionPlayer {
 public:
  struct Result {
    std::uint64_t published = 0;  ///< Imu messages
    std::uint64_t passes = 0;     ///< complete passes over the record
    std::uint64_t late = 0;       ///< samples published more than one (scaled) sample interval after their due time
    double max_lateness = 0.0;    ///< s
    bool interrupted = false;     ///< shut down before the end
  };

  GroundMotionPlayer(ros::NodeHandle& nh, ros::NodeHandle& pnh, PlayerConfig config, core::SensorFrameMotion motion);

  /// Plays until the end of the record (or, with loop, until shutdown). Blocking; needs a spinner
  /// only for connection callbacks. Publishes ~finished = true (latched) and logs a summary at the end.
  Result run();

 private:
  bool wait_until_wall(std::int64_t steady_ns);  ///< false on shutdown
  bool wait_until_ros(const ros::Time& t);       ///< false on shutdown
  // run()'s steps: /clock (sim time) and ~wait_for_subscribers, false on shutdown; one sample's
  // messages and history; the end's log, ~finished and linger.
  bool wait_to_start(bool sim);
  void publish_sample(std::size_t i, const ros::Time& stamp);
  void report_end(const Result& r, double wall);

  PlayerConfig config_;
  core::SensorFrameMotion motion_;
  double variance_ = 0.0;
  ros::Publisher imu_pub_;
  ros::Publisher accel_pub_;
  ros::Publisher finished_pub_;
  std::unique_ptr<live::SampleHistoryServer> history_;  // null: ~history_length 0
  std::size_t imu_history_ = 0, accel_history_ = 0;
};

}  // namespace rocking_monitor::records
