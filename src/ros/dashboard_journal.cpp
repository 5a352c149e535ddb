// Dashboard: the alarms of the monitor's open event read from its journal at start (issue 19), so a
// dashboard started after the alarms (or while the monitor is down) shows them. Parameters ~journal
// and ~journal_window default to the monitor's own (then to the monitor's defaults).
#include "rocking_monitor/ros/dashboard.hpp"

#include <cstdlib>

#include <boost/make_shared.hpp>

#include "rocking_monitor/monitoring/alarm_journal.hpp"

namespace rocking_monitor::live {

void Dashboard::read_journal() {
  const char* ros_home = std::getenv("ROS_HOME");
  const char* home = std::getenv("HOME");
  std::string path = (ros_home != nullptr && *ros_home != '\0') ? std::string(ros_home) + "/rocking_monitor/journal.jsonl"
                                                               : std::string(home != nullptr ? home : ".") +
                                                                     "/.ros/rocking_monitor/journal.jsonl";
  double window = 3600.0;
  nh_.getParam(monitor_ + "/journal", path);
  nh_.getParam(monitor_ + "/journal_window", window);
  pnh_.getParam("journal", path);
  pnh_.getParam("journal_window", window);
  if (path.empty()) {
    ROS_INFO("dashboard: no alarm journal (~journal is \"\")");
    return;
  }
  const core::JournalReading reading = core::read_journal(path);
  for (const std::string& w : reading.warnings) ROS_WARN("dashboard: alarm journal: %s", w.c_str());
  for (const std::string& e : reading.errors) ROS_ERROR("dashboard: alarm journal: %s", e.c_str());
  ::ros::Time now = ::ros::Time::now();
  const double now_s = now.isZero() ? ::ros::WallTime::now().toSec() : now.toSec();
  // The open event, or the last one ended by its shaking stopping (issue 29), within the window.
  const core::OpenEvent ev = core::shown_event(reading, now_s, window);
  if (!ev.open()) {
    ROS_INFO("dashboard: alarm journal %s: %s", path.c_str(), reading.exists ? "no event open" : "not there (yet)");
    return;
  }
  int n = 0;
  for (const core::JournalRecord& r : ev.records) {
    if (r.kind != core::JournalKind::Alarm) continue;
    auto m = boost::make_shared<OverturnAlarm>();
    if (r.stamp_ns > 0) m->header.stamp.fromNSec(static_cast<std::uint64_t>(r.stamp_ns));
    else m->header.stamp = ::ros::Time(r.time);
    m->item_id = r.item;
    m->level = static_cast<std::uint8_t>(r.level);
    m->plane = r.plane;
    m->event_time = r.time;
    m->time_since_first_sample = r.since_event_start;
    m->rotation_ratio = r.rotation_ratio;
    m->cause = static_cast<std::uint8_t>(r.cause);
    m->event_id = r.event;
    m->sequence = r.sequence;
    on_alarm(m);
    ++n;
  }
  ROS_INFO("dashboard: alarm journal %s: event %s open, %d alarms shown", path.c_str(), ev.id.c_str(), n);
}

}  // namespace rocking_monitor::live
