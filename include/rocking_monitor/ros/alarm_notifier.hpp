#pragma once

// alarm_notifier (issue 44, docs/notify.md): the ROS shim around notify::Notifier. Subscribes to the
// ~alarms and ~probability_alarms of one monitor or of a redundant pair, hands each alarm to the core
// (which deduplicates, routes, groups, keeps the outbox and delivers by e-mail, webhook and MQTT), and
// reports each channel's deliveries and failures (with the server's reason) in /diagnostics and the log.
// Parameters:
//   ~config       the routing YAML (config/notify.yaml); required
//   ~monitors     monitor node names, a list or "a,b" (default /rocking_monitor; a pair:
//                 [/rocking_monitor_a, /rocking_monitor_b])
//   ~outbox       outbox file (default $ROS_HOME/rocking_monitor/notify_outbox.jsonl)
//   ~tick_period  s between outbox syncs / grouping decisions (default 0.05)
//   ~check_hosts  resolve every channel's host at start; an unknown host is a fatal error (default true)
// The notifier's clock is the wall clock (windows and retries are about people and servers), also
// under sim time; the alarms' own times are the monitor's.

#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/ros.h>

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "rocking_monitor/OverturnAlarm.h"
#include "rocking_monitor/ProbabilityAlarm.h"
#include "rocking_monitor/notify/notifier.hpp"

namespace rocking_monitor::live {

class AlarmNotifier {
 public:
  AlarmNotifier(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Reads the parameters and the configuration, opens the outbox, subscribes. False (after a FATAL
  /// line naming the file, line and field, or the parameter) when anything is wrong.
  bool init();

 private:
  void on_alarm(const std::string& monitor, const OverturnAlarm::ConstPtr& m);
  void on_probability(const std::string& monitor, const ProbabilityAlarm::ConstPtr& m);
  void accept(const notify::NotifyAlarm& a);
  void tick(const ros::WallTimerEvent&);
  void publish_diagnostics(const ros::WallTimerEvent&);

  ros::NodeHandle nh_, pnh_;
  std::unique_ptr<notify::Notifier> notifier_;
  std::vector<ros::Subscriber> subs_;
  ros::Publisher diag_pub_;
  ros::WallTimer tick_timer_, diag_timer_;
  std::mutex reported_mutex_;                    // tick() runs on the timer and on a COMMITTED alarm's callback
  std::map<std::string, std::string> reported_;  // channel -> the failure last logged ("" while it works)
  std::map<std::string, std::uint64_t> reported_refused_;  // channel -> messages refused for good, as last logged
};

}  // namespace rocking_monitor::live
