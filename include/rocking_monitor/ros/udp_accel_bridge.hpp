#pragma once

// udp_accel_bridge: a shaking-table controller's (or DAQ program's) UDP stream, one datagram per
// sample (feeds/udp_datagram.hpp: text "time,ax,ay,az" or the 48-byte binary layout), published as
// sensor_msgs/Imu (REP 145) for the monitor, in sequence order (feeds/sample_sequencer.hpp), with
// drops, reordering, late and malformed datagrams counted in /diagnostics. Issue 52: only
// ~allowed_senders are read; with ~key_file only authenticated (version-2) datagrams are published,
// every refusal counted per source; a conflicting held sample is published marked (variance +inf).
// Parameters and the stamp rule: README "Connect a shaking table". The last ~history_length s
// published are served as ~history for a restarted monitor to catch up (docs/journal.md).

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <sensor_msgs/Imu.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "rocking_monitor/feeds/sample_sequencer.hpp"
#include "rocking_monitor/feeds/sender_filter.hpp"
#include "rocking_monitor/feeds/source_counter.hpp"
#include "rocking_monitor/feeds/time_grid.hpp"
#include "rocking_monitor/feeds/udp_datagram.hpp"
#include "rocking_monitor/ros/sample_history_server.hpp"

namespace rocking_monitor::live {

class UdpAccelBridge {
 public:
  UdpAccelBridge(ros::NodeHandle nh, ros::NodeHandle pnh);
  ~UdpAccelBridge();
  UdpAccelBridge(const UdpAccelBridge&) = delete;
  UdpAccelBridge& operator=(const UdpAccelBridge&) = delete;

  /// Reads the parameters, binds the socket, starts receiving. False (after a FATAL line naming
  /// the parameter) on a bad parameter or a port that cannot be bound.
  bool init();

 private:
  enum class Clock { FirstArrival, Controller };

  bool open_socket();
  void receive_loop();
  void on_datagram(const char* data, std::size_t size, std::uint32_t address, std::uint16_t port,
                   const ros::Time& arrival);
  void publish_ready(const ros::Time& arrival);
  void diagnostics(diagnostic_updater::DiagnosticStatusWrapper& st);
  bool read_allowed_senders();
  void sender_summary(diagnostic_updater::DiagnosticStatusWrapper& st) const;
  bool read_key();
  bool count_refusal(feeds::DatagramError err, std::uint32_t address, std::uint16_t port);
  void auth_status(diagnostic_updater::DiagnosticStatusWrapper& st) const;

  ros::NodeHandle nh_, pnh_;
  ros::Publisher imu_pub_;
  std::unique_ptr<SampleHistoryServer> history_;  // ~history (issue 29 part 2); null: ~history_length 0
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::Timer diag_timer_;

  // parameters
  // Loopback unless told otherwise (issue 52): a deployment names the controller-facing interface.
  std::string bind_address_ = "127.0.0.1";
  int port_ = 15600;
  double rate_hz_ = 0.0;
  int window_ = 4;
  double idle_flush_s_ = 0.1;
  Clock clock_ = Clock::FirstArrival;
  bool add_gravity_ = true;
  double accel_variance_ = 0.0;
  std::string frame_id_ = "accelerometer";  // the example catalogue poses its items in this frame

  // ~allowed_senders (issue 52): empty means anyone, which /diagnostics warns about.
  feeds::SenderFilter senders_;
  // ~key_file (issue 52): with a key only authenticated (version 2) datagrams are accepted.
  std::string key_file_;
  std::vector<unsigned char> key_;
  feeds::DatagramKey datagram_key_;  // views key_; size 0 without a key

  int socket_ = -1;
  int rcvbuf_bytes_ = 0;  ///< the kernel's receive buffer as read back (it may cap what was asked)
  std::thread thread_;
  std::atomic<bool> running_{false};

  // Owned by the receive thread; diagnostics read them under mutex_.
  std::mutex mutex_;
  std::unique_ptr<feeds::SampleSequencer> sequencer_;
  std::unique_ptr<feeds::TimeGrid> grid_;
  sensor_msgs::Imu msg_;  // reused: only the stamp and the acceleration change per sample
  // FirstArrival: the first published sample's arrival (ROS time) and controller time. Stamps are
  // that arrival + (controller time - first controller time) in whole nanoseconds, so the spacing is
  // the controller's to the nanosecond (an epoch-sized double would round it to 0.24 us).
  std::optional<ros::Time> first_arrival_;
  double first_time_s_ = 0.0;
  feeds::SenderTally tally_;  // per source: admitted and dropped datagrams
  // Refused by authentication, per source: no tag while a key is set, a wrong tag, a tag but no key.
  feeds::SourceCounter unauthenticated_, bad_tag_, no_key_;
  std::uint64_t datagrams_ = 0;
  std::uint64_t malformed_ = 0;
  std::uint64_t off_grid_ = 0;
  std::uint64_t published_ = 0;
  std::uint64_t flushes_ = 0;
  const char* last_error_ = "none";
  std::string last_sender_;
  double last_arrival_minus_stamp_s_ = 0.0;
  double max_arrival_minus_stamp_s_ = 0.0;
  bool mixed_forms_ = false;
  int form_ = 0;  // 0 none yet, 1 text, 2 binary
};

}  // namespace rocking_monitor::live
