#pragma once

// seedlink_bridge: strong-motion stations over SeedLink -> sensor_msgs/Imu (REP 145), one topic
// per station, for the monitor. The SeedLink client, miniSEED decoding and the merging of each
// station's three channels are the ROS-free feeds layer; this class is parameters, publication and
// /diagnostics around them. The client runs on a thread of its own; publish() is thread-safe.

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <sensor_msgs/Imu.h>

#include "rocking_monitor/feeds/mseed_record.hpp"
#include "rocking_monitor/feeds/seedlink_session.hpp"
#include "rocking_monitor/feeds/station_merger.hpp"
#include "rocking_monitor/ros/sample_history_server.hpp"

namespace rocking_monitor::live {

class SeedLinkBridge {
 public:
  SeedLinkBridge(::ros::NodeHandle nh, ::ros::NodeHandle pnh);
  ~SeedLinkBridge();  ///< stops the client thread

  /// Reads the parameters, advertises, starts the client. False (after a ROS_FATAL naming the
  /// parameter) on bad configuration.
  bool init();

 private:
  struct Station {
    feeds::StreamSpec spec;
    std::unique_ptr<feeds::StationMerger> merger;
    ::ros::Publisher pub;
    std::size_t history = 0;  // its topic in history_
    sensor_msgs::Imu msg;  // reused: header, covariances and frame set once
    std::uint64_t records = 0;
    std::uint64_t malformed = 0;         // records libmseed could not decode
    std::uint64_t unknown_encoding = 0;  // records of an encoding it does not decode
    int last_unknown_encoding = 0;
    double latency_min = 0.0, latency_max = 0.0;  // s, data time -> publication, since the last report
    bool latency_seen = false;
    double latency_last = 0.0;       // s, of the newest sample published
    double max_record_pause = 0.0;   // s of wall time between two records (an outage shows here)
    ::ros::WallTime last_record_wall;
    std::uint64_t reported_problems = 0;  // problem count at the last report (WARN while it grows)
  };

  // init()'s steps, in order; the bool ones are false after a ROS_FATAL naming the parameter.
  bool init_stations(const std::vector<feeds::StreamSpec>& streams, const std::string& frame_id, int queue_size);
  bool init_history();  ///< ~history_length, ~history_max_rate
  void init_diagnostics(const std::string& server);
  bool start_session(const feeds::SessionConfig& cfg);  ///< resumes from ~state_file, starts the thread
  void on_record(std::size_t stream, std::uint32_t sequence, const char* record, std::size_t length);
  /// Writes ~state_file when a last sequence number changed since the last write.
  void save_state();
  void connection_diagnostics(diagnostic_updater::DiagnosticStatusWrapper& st);
  void station_diagnostics(std::size_t i, diagnostic_updater::DiagnosticStatusWrapper& st);

  ::ros::NodeHandle nh_, pnh_;
  std::vector<Station> stations_;
  // ~history (issue 29 part 2): each station's last ~history_length s, sized for ~history_max_rate;
  // null: ~history_length 0.
  std::unique_ptr<SampleHistoryServer> history_;
  double gravity_ = 0.0;  // m/s^2 added to up: 9.80665 (~add_gravity) or 0
  std::unique_ptr<feeds::SeedLinkSession> session_;
  feeds::MseedDecoder decoder_;  // session thread only
  feeds::DecodedRecord decoded_;  // session thread only
  std::mutex mutex_;  // stations_' counters: session thread vs diagnostics
  std::atomic<bool> stop_{false};
  std::thread thread_;
  std::unique_ptr<diagnostic_updater::Updater> diagnostics_;
  ::ros::WallTimer diagnostics_timer_;
  std::uint64_t reported_session_problems_ = 0;
  std::string state_file_;  // ~state_file: last sequence numbers kept across restarts ("" = not kept)
  std::map<std::string, std::uint32_t> saved_state_;
  std::uint64_t state_write_failures_ = 0;
};

}  // namespace rocking_monitor::live
