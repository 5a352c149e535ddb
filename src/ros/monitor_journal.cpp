// RockingMonitor's alarm journal (issue 19, part 2; docs/journal.md): parameters, reading the journal
// on start (the open event's alarms are marked in the items and kept to be sent to every new
// subscriber), journaling each alarm before it is published, resets, and its diagnostics.
#include "rocking_monitor/ros/monitor.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <unordered_map>

namespace rocking_monitor::live {
namespace {

// $ROS_HOME/rocking_monitor/journal.jsonl for the usual node name; another name (a second monitor,
// a shard) gets a file of its own, journal<name>.jsonl, so that two monitors never share one event.
std::string default_journal_path(const std::string& node_name) {
  std::string file = "journal";
  if (node_name != "/rocking_monitor") {
    for (char c : node_name) file += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  }
  file += ".jsonl";
  const char* ros_home = std::getenv("ROS_HOME");
  if (ros_home != nullptr && *ros_home != '\0') return std::string(ros_home) + "/rocking_monitor/" + file;
  const char* home = std::getenv("HOME");
  return std::string(home != nullptr ? home : ".") + "/.ros/rocking_monitor/" + file;
}

}  // namespace

bool RockingMonitor::load_journal_parameters() {
  journal_path_ = default_journal_path(pnh_.getNamespace());
  if (pnh_.hasParam("journal") && !pnh_.getParam("journal", journal_path_)) {
    ROS_FATAL("rocking_monitor: parameter ~journal has the wrong type (expected a path; \"\" = off)");
    return false;
  }
  pnh_.setParam("journal", journal_path_);  // the file in use, for the dashboard and the report
  if (pnh_.hasParam("journal_window")) {
    XmlRpc::XmlRpcValue v;
    pnh_.getParam("journal_window", v);
    if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) journal_window_ = static_cast<double>(v);
    else if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) journal_window_ = static_cast<int>(v);
    else journal_window_ = -1.0;
  }
  // ~event_quiet_time and ~event_quiet_threshold are read with the other numbers (load_parameters).
  if (!(event_quiet_time_ > 0.0) || !std::isfinite(event_quiet_time_) || !(event_quiet_threshold_ > 0.0) ||
      !std::isfinite(event_quiet_threshold_)) {
    ROS_FATAL("rocking_monitor: ~event_quiet_time = %g s of input and ~event_quiet_threshold = %g m/s^2 must be > 0",
              event_quiet_time_, event_quiet_threshold_);
    return false;
  }
  if (!(journal_window_ > 0.0) || !std::isfinite(journal_window_)) {
    ROS_FATAL("rocking_monitor: ~journal_window must be a number > 0 s (how long an event stays open after its "
              "last record)");
    return false;
  }
  return true;
}

// The node's clock in s since 1970; while sim time has no /clock yet (zero), the wall clock.
double RockingMonitor::journal_clock(const ::ros::Time& fallback) const {
  const ::ros::Time now = ::ros::Time::now();
  if (!now.isZero()) return now.toSec();
  return fallback.isZero() ? ::ros::WallTime::now().toSec() : fallback.toSec();
}

void RockingMonitor::open_journal() {
  const double now = journal_clock(::ros::Time());
  if (const std::string e = journal_.open(journal_path_, journal_window_, now); !e.empty()) {
    journal_status_ = e;
    ROS_ERROR("rocking_monitor: alarm journal: %s: alarms are NOT kept across a restart (events in memory only)",
              e.c_str());
    journal_.open("", journal_window_, now);
  } else if (journal_path_.empty()) {
    journal_status_ = "off (~journal is \"\")";
    ROS_WARN("rocking_monitor: alarm journal off (~journal is \"\"): alarms are not kept across a restart");
  }
  for (const std::string& w : journal_.reading().warnings) ROS_WARN("rocking_monitor: alarm journal: %s", w.c_str());
  for (const std::string& e : journal_.reading().errors) ROS_ERROR("rocking_monitor: alarm journal: %s", e.c_str());
  journal_errors_ += journal_.reading().errors.size();
  // The open event's alarms are marked (not alarmed again) and re-sent; those of an event that ended
  // (its shaking stopped, issue 29) within the window are only re-sent: a new shaking alarms them again.
  const bool open = journal_.event().open();
  const core::OpenEvent shown = open ? core::OpenEvent{} : core::shown_event(journal_.reading(), now, journal_window_);
  const core::OpenEvent& ev = open ? journal_.event() : shown;
  if (!ev.open()) {
    if (!journal_path_.empty() && journal_status_.empty())
      ROS_INFO("rocking_monitor: alarm journal %s: %lu events, none open (window %g s)", journal_path_.c_str(),
               static_cast<unsigned long>(journal_.reading().events), journal_window_);
    return;
  }
  // id -> item: an event may hold an alarm of each of tens of thousands of items.
  std::unordered_map<std::string, Item*> by_id;
  for (Item& it : items_) by_id.emplace(it.entry.spec.id, &it);
  std::size_t foreign = 0;
  for (const core::JournalRecord& r : ev.records) {
    if (r.kind != core::JournalKind::Alarm && r.kind != core::JournalKind::ProbabilityAlarm) continue;
    const auto found = by_id.find(r.item);
    Item* item = found == by_id.end() ? nullptr : found->second;
    const CatalogueItem* entry = item == nullptr ? nullptr : &item->entry;
    if (entry == nullptr) {  // another shard's item, or a catalogue since changed: not ours to re-send
      ++foreign;
      continue;
    }
    ::ros::Time stamp;
    if (r.stamp_ns > 0) stamp.fromNSec(static_cast<std::uint64_t>(r.stamp_ns));
    else stamp = ::ros::Time(r.time);
    if (r.kind == core::JournalKind::Alarm) {
      OverturnAlarm m = alarm_for<OverturnAlarm>(entry->spec, stamp);
      m.level = static_cast<std::uint8_t>(r.level);
      m.plane = r.plane;
      m.event_time = r.time;
      m.time_since_first_sample = r.since_event_start;  // from the journal: since the event's first sample
      m.rotation_ratio = r.rotation_ratio;
      m.cause = static_cast<std::uint8_t>(r.cause);
      m.frozen_s = std::numeric_limits<double>::quiet_NaN();  // not journaled
      m.event_id = r.event;
      m.sequence = r.sequence;
      event_alarms_.push_back(m);
      if (open) item->monitor->mark_alarmed(static_cast<core::ItemMode>(r.level));
    } else {
      ProbabilityAlarm m = alarm_for<ProbabilityAlarm>(entry->spec, stamp);
      m.level = static_cast<std::uint8_t>(r.level);
      m.threshold = r.threshold;
      m.ensemble_size = static_cast<std::uint16_t>(r.ensemble_size);
      m.time_since_first_sample = r.since_event_start;
      m.event_time = r.time;
      m.value.probability = r.probability;
      m.value.lower = r.lower;
      m.value.upper = r.upper;
      m.event_id = r.event;
      m.sequence = r.sequence;
      event_probability_alarms_.push_back(m);
    }
    ++journal_relatched_;
  }
  ROS_WARN("rocking_monitor: alarm journal %s: event %s %s (last record %.0f s ago, window %g s): %zu alarms "
           "and %zu probability alarms read back and sent again to every subscriber; %s%s",
           journal_path_.c_str(), ev.id.c_str(), open ? "still open" : "ended (its shaking stopped)",
           now - ev.last_written, journal_window_, event_alarms_.size(), event_probability_alarms_.size(),
           open ? "these levels are not alarmed again until the event ends or ~reset"
                : "a new shaking is a new event and alarms them again",
           foreign > 0 ? (" (" + std::to_string(foreign) + " records of items not in this catalogue ignored)").c_str()
                       : "");
}

bool RockingMonitor::journal_alarm(Item& it, OverturnAlarm& m, double run_start) {
  const core::ItemMode level = static_cast<core::ItemMode>(m.level);
  if (journal_.holds(core::JournalKind::Alarm, m.item_id, m.level)) {
    // Already alarmed in this event (before a restart, or before the items were restarted): never twice.
    ++journal_repeats_;
    it.monitor->mark_alarmed(level);
    return false;
  }
  core::JournalRecord r;
  r.kind = core::JournalKind::Alarm;
  r.item = m.item_id;
  r.level = m.level;
  r.plane = m.plane;
  r.sensor = sensors_[it.sensor].spec.name;
  r.time = m.event_time;
  r.stamp_ns = static_cast<std::int64_t>(m.header.stamp.toNSec());
  r.rotation_ratio = m.rotation_ratio;
  r.cause = static_cast<core::AlarmCause>(m.cause);
  const std::string before = journal_.event().id;
  if (const std::string e = journal_.append(r, run_start, journal_clock(m.header.stamp), false); !e.empty()) {
    ++journal_errors_;
    ROS_ERROR("rocking_monitor: alarm journal: %s: alarm of '%s' published without being journaled", e.c_str(),
              m.item_id.c_str());
  } else {
    if (journal_.event().id != before) {  // a new event: what a new subscriber gets starts again
      event_alarms_.clear();
      event_probability_alarms_.clear();
    }
    m.event_id = r.event;
    m.sequence = r.sequence;
  }
  it.monitor->mark_alarmed(level);
  event_alarms_.push_back(m);
  return true;
}

bool RockingMonitor::journal_probability_alarm(Item& it, ProbabilityAlarm& m, double run_start) {
  if (journal_.holds(core::JournalKind::ProbabilityAlarm, m.item_id, m.level)) {
    ++journal_repeats_;
    return false;
  }
  core::JournalRecord r;
  r.kind = core::JournalKind::ProbabilityAlarm;
  r.item = m.item_id;
  r.level = m.level;
  r.sensor = sensors_[it.sensor].spec.name;
  r.time = m.event_time;
  r.stamp_ns = static_cast<std::int64_t>(m.header.stamp.toNSec());
  r.probability = m.value.probability;
  r.lower = m.value.lower;
  r.upper = m.value.upper;
  r.threshold = m.threshold;
  r.ensemble_size = m.ensemble_size;
  const std::string before = journal_.event().id;
  if (const std::string e = journal_.append(r, run_start, journal_clock(m.header.stamp), false); !e.empty()) {
    ++journal_errors_;
    ROS_ERROR("rocking_monitor: alarm journal: %s: probability alarm of '%s' published without being journaled",
              e.c_str(), m.item_id.c_str());
  } else {
    if (journal_.event().id != before) {
      event_alarms_.clear();
      event_probability_alarms_.clear();
    }
    m.event_id = r.event;
    m.sequence = r.sequence;
  }
  event_probability_alarms_.push_back(m);
  return true;
}

void RockingMonitor::journal_reset(const std::string& why) {
  event_alarms_.clear();
  event_probability_alarms_.clear();
  if (const std::string e = journal_.append_reset(why, journal_clock(::ros::Time())); !e.empty()) {
    ++journal_errors_;
    ROS_ERROR("rocking_monitor: alarm journal: %s: reset not journaled", e.c_str());
  }
}

// A stale period (the sensor's items frozen: no sample for > max_gap, or a new time base pending) is
// journaled when it opens (to: NaN) and again when it closes, with the stamps of the samples around it.
void RockingMonitor::journal_stale_period(Sensor& s) {
  const bool now_stale = stale(s);
  if (now_stale == s.stale_journaled) return;
  const double from = now_stale ? s.last_stamp.toSec() : s.stale_from;
  const double to = now_stale ? std::numeric_limits<double>::quiet_NaN() : s.last_stamp.toSec();
  if (const std::string e = journal_.append_stale(s.spec.name, from, to, s.epoch.toSec(), journal_clock(::ros::Time::now()));
      !e.empty()) {
    ++journal_errors_;
    ROS_ERROR("rocking_monitor: alarm journal: %s: stale period of sensor '%s' not journaled", e.c_str(),
              s.spec.name.c_str());
  }
  s.stale_from = from;
  s.stale_journaled = now_stale;
}

// Per sample: whether the sensor's input (gravity removed) is quiet, and since when.
void RockingMonitor::track_quiet(Sensor& s, const Eigen::Vector3d& a, const ::ros::Time& stamp) {
  const bool quiet = std::hypot(a.x(), a.y()) < event_quiet_threshold_ && std::abs(a.z()) < event_quiet_threshold_;
  if (!quiet) s.quiet_from = std::numeric_limits<double>::quiet_NaN();
  else if (std::isnan(s.quiet_from)) s.quiet_from = stamp.toSec();
}

// After a sample: the open event ends once every sensor has been quiet for ~event_quiet_time and no
// item moves (checked at most every 0.5 s of input: reading every item costs at 10,000 of them). Its
// levels are then re-armed: the next shaking (an aftershock) is a new event and alarms them again.
void RockingMonitor::check_event_end(const ::ros::Time& stamp) {
  if (!journal_.event().open()) return;
  const double now = stamp.toSec();
  for (const Sensor& s : sensors_) {
    if (!s.timing.started()) continue;
    if (std::isnan(s.quiet_from) || s.last_stamp.toSec() - s.quiet_from < event_quiet_time_) return;
  }
  if (std::abs(now - last_end_check_) < 0.5) return;
  last_end_check_ = now;
  sync_items();
  for (const Item& it : items_) {
    const core::ItemMode m = it.monitor->mode();
    if (m != core::ItemMode::Rest && m != core::ItemMode::Overturned) return;
  }
  char why[160];
  std::snprintf(why, sizeof why, "shaking stopped: every sensor below %g m/s^2 and every item at rest or overturned "
                "for %g s", event_quiet_threshold_, event_quiet_time_);
  const std::string id = journal_.event().id;
  if (const std::string e = journal_.append_end(why, now, journal_clock(stamp)); !e.empty()) {
    ++journal_errors_;
    ROS_ERROR("rocking_monitor: alarm journal: %s: end of event %s not journaled", e.c_str(), id.c_str());
  }
  // event_alarms_ stay: a late subscriber is still sent the ended event's alarms until a new one opens.
  std::size_t upright = 0;
  for (Item& it : items_) {
    upright += it.monitor->mode() == core::ItemMode::Rest;
    const double t = sensors_[it.sensor].last_t;  // the items' clock: s since the sensor's epoch
    it.monitor->new_event(t);
    if (it.ensemble) it.ensemble->new_event(t);
  }
  for (Sensor& s : sensors_) {
    s.batch.reset();  // the items were restarted
    s.frozen_s = 0.0;  // re-armed: the next event's alarms say what they were frozen through from here
  }
  ++events_ended_;
  ROS_WARN("rocking_monitor: event %s ended: %s; %zu items at rest are re-armed (a later shaking is a new event "
           "and alarms them again), %zu on their side stay so until ~reset", id.c_str(), why, upright,
           items_.size() - upright);
  take_snapshot(stamp);
}

void RockingMonitor::journal_diagnostics(diagnostic_updater::DiagnosticStatusWrapper& st) {
  using diagnostic_msgs::DiagnosticStatus;
  if (!journal_status_.empty() && !journal_path_.empty())
    st.summary(DiagnosticStatus::ERROR, "alarm journal not on file: " + journal_status_);
  else if (journal_errors_ > 0)
    st.summary(DiagnosticStatus::ERROR, std::to_string(journal_errors_.load()) + " journal errors (see the log)");
  else if (journal_path_.empty())
    st.summary(DiagnosticStatus::WARN, "alarm journal off: alarms are not kept across a restart");
  else
    st.summary(DiagnosticStatus::OK, "alarm journal on file");
  st.add("file", journal_path_.empty() ? std::string("(off)") : journal_path_);
  st.add("window s", journal_window_);
  st.add("open event", journal_.event().open() ? journal_.event().id : std::string("(none)"));
  st.add("records in the open event", journal_.event().records.size());
  st.add("alarms read back at start", journal_relatched_);
  st.add("repeats not alarmed again", journal_repeats_);
  st.add("journal errors", journal_errors_.load());
  st.add("events ended (shaking stopped)", events_ended_);
}

}  // namespace rocking_monitor::live
