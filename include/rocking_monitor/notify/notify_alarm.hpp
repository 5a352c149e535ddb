#pragma once

// An alarm as the notifier sees it (issue 44): the fields of rocking_monitor/OverturnAlarm and
// ProbabilityAlarm that routing, deduplication and the messages read. ROS-free; the node fills it.

#include <cstdint>
#include <limits>
#include <string>

#include "rocking_monitor/monitoring/item_modes.hpp"

namespace rocking_monitor::notify {

/// OverturnAlarm level codes.
enum Level : int { kBeyondTipping = 2, kCommitted = 3, kOverturned = 4 };
/// "BEYOND_TIPPING", "COMMITTED", "OVERTURNED"; "LEVEL_<n>" for another code.
std::string level_name(int level);
/// The code of a level name (case-insensitive); 0 when it is none of the three.
int level_code(const std::string& name);

struct NotifyAlarm {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  bool probability = false;     ///< a ProbabilityAlarm (else an OverturnAlarm)
  std::string source;           ///< the monitor that sent it (its node name, e.g. /rocking_monitor_a)
  std::string item;             ///< item_id
  std::string description;      ///< the catalogue's description of the item
  int level = 0;                ///< Level code
  /// OverturnAlarm.cause: how the item got there (FellOffSupport: it slid off its plinth, shelf or pedestal)
  core::AlarmCause cause = core::AlarmCause::Rocking;
  std::int64_t stamp_ns = 0;    ///< header.stamp: the input sample, ns since 1970
  double event_time = kNaN;     ///< when the level was reached, s since 1970 (input clock)
  std::string event_id;         ///< the monitor journal's event id ("" when it has none)
  std::uint64_t sequence = 0;   ///< the record's position in that event's journal
  bool whole = true;            ///< OverturnAlarm.frozen_s == 0 (its items saw every sample)
  double probability_value = kNaN;  ///< ProbabilityAlarm: the share that reached the level, dimensionless
  double threshold = kNaN;      ///< ProbabilityAlarm: the monitor's ~alarm_probability, dimensionless
};

}  // namespace rocking_monitor::notify
