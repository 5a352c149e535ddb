#pragma once

// The vocabulary of the live monitor: item modes, criterion codes and the events of one step.

#include <array>
#include <cstdint>

#include "rocking_monitor/physics/principal_planes.hpp"

namespace rocking_monitor::core {

/// Live state codes (the values of RockingState.msg's constants).
enum class ItemMode : std::uint8_t { Rest = 0, Rocking = 1, BeyondTipping = 2, Committed = 3, Overturned = 4 };
const char* to_string(ItemMode mode);

/// Criterion codes (the values of CriterionExceedance.msg's constants).
enum class CriterionId : std::uint8_t {
  Housner = 0, Ishiyama = 1, IshiyamaEquivalent = 2, Proposed = 3,
  FreeFlight = 4, SlideFromRest = 5, SlideAtUplift = 6, SlideWhileRocking = 7,
};
inline constexpr int kCriterionIdCount = 8;
inline constexpr int kScreeningCount = 4;
const char* to_string(CriterionId id);

/// A criterion changed state at the end of a sample, in one rocking plane. Exceeded means value >
/// threshold (and, for the Ishiyama-type criteria, also second_value >= second_threshold).
struct CriterionChange {
  CriterionId id = CriterionId::Housner;
  Plane plane = Plane::X;
  bool exceeded = false;
  double value = 0.0, threshold = 0.0;               ///< SI (m/s, m/s^2 or a ratio)
  double second_value = 0.0, second_threshold = 0.0; ///< Ishiyama-type: PGA and its threshold, m/s^2
};

/// Why an item reached an alarm level (the values of OverturnAlarm.msg's CAUSE_* constants). The
/// level stays the severity (routing and latching read it); the cause says how the item got there.
enum class AlarmCause : std::uint8_t {
  Rocking = 0,         ///< it rocked or tipped about its base's edges or corners (every level)
  /// it slid off the edge of its plinth, shelf or pedestal (issue 51): Overturned, and the Committed
  /// that the 3-D model reaches at the same instant
  FellOffSupport = 1,
};
/// "rocking", "fell_off_support" (the journal's, dashboard's and notifier's words).
const char* to_string(AlarmCause cause);
/// The cause of a name from to_string; false when it is none.
bool parse_alarm_cause(const char* name, AlarmCause& cause);

/// An overturning level reached during a sample, in one rocking plane.
struct AlarmEvent {
  ItemMode level = ItemMode::BeyondTipping;  ///< BeyondTipping, Committed or Overturned
  AlarmCause cause = AlarmCause::Rocking;
  Plane plane = Plane::X;
  double time = 0.0;                         ///< s, when it was reached (inside the sample)
  double rotation_ratio = 0.0;
};

/// What one step produced. Fixed capacity: no allocation in the sample loop.
template <int Changes>
struct SampleEvents {
  int change_count = 0;
  std::array<CriterionChange, Changes> changes;
  int alarm_count = 0;
  std::array<AlarmEvent, 3> alarms;
};
using PlaneEvents = SampleEvents<kCriterionIdCount>;
using ItemEvents = SampleEvents<kPlaneCount * kCriterionIdCount>;

}  // namespace rocking_monitor::core
