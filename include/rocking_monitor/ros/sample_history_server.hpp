#pragma once

// A bridge's recent samples served as the service ~history (rocking_monitor/SampleHistory, issue 29
// part 2): a restarted monitor asks for what it missed since its state snapshot and steps it before
// it joins the live stream. The rings are the core's (feeds/sample_history.hpp), one per published
// topic, allocated when the topic is added: push() takes a lock and copies, nothing else. Used by
// ground_motion_player, udp_accel_bridge and seedlink_bridge.

#include <cstddef>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "rocking_monitor/SampleHistory.h"
#include "rocking_monitor/feeds/sample_history.hpp"

namespace rocking_monitor::live {

/// Default ~history_length, s: a few minutes, longer than a monitor takes to be restarted (respawn).
inline constexpr double kDefaultHistoryLength = 300.0;

/// ~history_length (s of samples kept; 0 = none, no service). Throws std::invalid_argument naming it.
double read_history_length(const ros::NodeHandle& pnh);

class SampleHistoryServer {
 public:
  explicit SampleHistoryServer(double length_s) : length_s_(length_s) {}

  /// Keeps the samples published on `topic` (resolved name) with this type and frame; `rate_hz` (the
  /// samples per second of stamp time) sizes its ring. Returns the index to push() with. Throws
  /// std::invalid_argument (bad rate or length). Call before advertise().
  std::size_t add_topic(const std::string& topic, const std::string& type, const std::string& frame_id, double rate_hz);

  /// Offers the service ~history (`pnh`'s namespace).
  void advertise(ros::NodeHandle& pnh);

  /// Keeps one sample as published, m/s^2. Call before the sample is published, so that anything a
  /// subscriber has not received by the time it asks is in the answer.
  void push(std::size_t topic, const ros::Time& stamp, double x, double y, double z);

  std::size_t capacity(std::size_t topic) const { return topics_[topic]->history.capacity(); }

 private:
  bool serve(SampleHistory::Request& req, SampleHistory::Response& res);

  struct Topic {
    std::string name, type, frame_id;
    feeds::SampleHistory history;
    Topic(std::string n, std::string t, std::string f, std::size_t capacity)
        : name(std::move(n)), type(std::move(t)), frame_id(std::move(f)), history(capacity) {}
  };
  double length_s_;
  std::mutex mutex_;  // push() on the publishing thread, serve() on the spinner's
  std::mutex serve_mutex_;  // one request at a time (a multi-threaded spinner)
  std::vector<std::unique_ptr<Topic>> topics_;
  std::vector<feeds::HistorySample> scratch_;  // a request's samples, copied under the lock
  ros::ServiceServer server_;
};

}  // namespace rocking_monitor::live
