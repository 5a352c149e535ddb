#pragma once

// One alarm, however many monitors raised it (issue 29 part 3: launch/monitor_pair.launch). The same
// rule as scripts/alarm_dedup.py (rocking_report, monitor_table.py); docs/journal.md "A redundant pair".
//
// (event_id, sequence) names an alarm only within one monitor's journal: the event id's prefix is the
// first sample of that monitor's own sensor run and the sequence counts all of that journal's records,
// so a restarted monitor's gap (a stale record) shifts its later numbers. Across the pair an alarm is
// named by what both take from the sensor: the item, the level and the input stamp at which it was
// reached, within a window (a monitor restarted on a plain topic may reach a level later).
//  - From one source, an alarm with an (event id, sequence) already seen is a repeat (re-sent from its
//    journal after a restart, a reconnect): dropped and counted. Without an event id: item, level, stamp.
//  - From another source, the same item and level with a stamp within `window` of a shown alarm that
//    source has not contributed to is the same alarm: merged. The copy shown is the best: one from a
//    monitor whose items saw every sample (OverturnAlarm.frozen_s 0) before one after a gap (a monitor
//    respawned on a plain topic: its motion differs from the gap on, earlier or later), then the earliest.
// A monitor alarms a level once per item and event, and an event needs ~event_quiet_time of quiet before
// the next, so one source's alarms are never merged with each other.

#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace rocking_monitor::core {

/// The fields of an alarm (rocking_monitor/OverturnAlarm) the rule reads.
struct AlarmIdentity {
  std::string source;    ///< the monitor that sent it (its node name)
  std::string item;      ///< item_id
  int level = 0;         ///< OverturnAlarm level code
  std::int64_t stamp_ns = 0;  ///< header.stamp: the input sample at which the level was reached
  std::string event_id;  ///< as sent; empty when the monitor has none
  std::uint64_t sequence = 0;
  bool whole = true;     ///< frozen_s == 0: its items saw every sample (false also for NaN: not known)
};

class AlarmDedup {
 public:
  static constexpr double kDefaultWindow = 10.0;  ///< s; scripts/alarm_dedup.py WINDOW

  enum class Outcome { New, Merged, Repeat };
  struct Result {
    Outcome outcome = Outcome::New;
    std::size_t row = 0;      ///< the shown alarm it is (New, Merged); rows are numbered in arrival order
    bool replaces = false;    ///< Merged: this copy is better than the one shown, which it replaces
  };

  /// Throws std::invalid_argument for a negative or NaN window.
  explicit AlarmDedup(double window_s = kDefaultWindow);

  Result add(const AlarmIdentity& alarm);

  /// Forgets shown alarm `row` (a consumer that keeps only its newest alarms): copies from other sources
  /// are then new rows; repeats from a source already seen are still dropped.
  void forget(std::size_t row);

  std::size_t repeats() const { return repeats_; }
  std::size_t merged() const { return merged_; }
  std::size_t replaced() const { return replaced_; }

 private:
  struct Row {
    std::int64_t stamp_ns;  // of the copy shown
    bool whole;             // of the copy shown
    std::set<std::string> sources;
  };
  std::int64_t window_ns_;
  std::size_t next_row_ = 0;
  std::map<std::size_t, Row> rows_;
  std::map<std::pair<std::string, int>, std::vector<std::size_t>> by_item_level_;
  std::set<std::tuple<std::string, std::string, std::uint64_t, std::string, int, std::int64_t>> seen_;
  std::size_t repeats_ = 0, merged_ = 0, replaced_ = 0;
};

}  // namespace rocking_monitor::core
