#pragma once

// The verdict for a whole item from the verdicts of its rocking planes: the item is at the more
// severe level of its planes, and reaches each level when its first plane does.
// In physics/ (not monitoring/) because it is a pure rule over plane verdicts, which both the live
// monitor and the offline study (which may not include monitoring/) apply.

#include <array>
#include <limits>

#include "rocking_monitor/physics/principal_planes.hpp"

namespace rocking_monitor::core {

/// Overturning levels in increasing severity (also RockingState/OverturnAlarm codes 2, 3, 4).
enum class Level : int { BeyondTipping = 0, Committed = 1, Overturned = 2 };
inline constexpr int kLevelCount = 3;

/// One plane's (or the item's) levels: when each was first reached (NaN = never), in seconds on the
/// clock of the run.
struct LevelTimes {
  std::array<double, kLevelCount> time{std::numeric_limits<double>::quiet_NaN(),
                                       std::numeric_limits<double>::quiet_NaN(),
                                       std::numeric_limits<double>::quiet_NaN()};
  bool reached(Level l) const { return time[static_cast<int>(l)] == time[static_cast<int>(l)]; }
  double at(Level l) const { return time[static_cast<int>(l)]; }
};

struct ItemVerdict {
  LevelTimes levels;                   ///< the item's: per level the earliest plane's time
  std::array<Plane, kLevelCount> plane{Plane::X, Plane::X, Plane::X};  ///< which plane reached it first
  bool overturned() const { return levels.reached(Level::Overturned); }
};

/// Combines the planes (y may be null: single-plane item). A level is reached by the item when any
/// plane reaches it, at the earliest such time; on a tie the x plane is named.
ItemVerdict combine(const LevelTimes& x, const LevelTimes* y);

}  // namespace rocking_monitor::core
