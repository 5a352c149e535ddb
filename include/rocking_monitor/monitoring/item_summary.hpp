#pragma once

// What the node publishes of an item (~states, markers, tf, diagnostics), compact (issue 28).
//
// Why: reading these fields from the ItemMonitor walks ~10 KB of model objects per item (cache
// misses at 10,000 items) and needs the item's deferred samples applied first. MonitorBatch keeps
// one summary per item, taken when read if the item was stepped in full since; a deferred (quiet)
// sample changes none of these fields (at rest or overturned: no rotation, no impact, no slip), so
// neither a sync nor a walk over the quiet items is needed.

#include <cstdint>

#include "rocking_monitor/monitoring/item_monitor.hpp"

namespace rocking_monitor::core {

/// The model a plane's state comes from (PlaneMonitor::active_model()).
enum class ActiveModelName : std::uint8_t { Rocking = 0, RockingLinearized = 1, Contact = 2 };
const char* to_string(ActiveModelName m);

struct PlaneSummary {
  double theta = 0.0;           ///< rad, about the active corner
  double omega = 0.0;           ///< rad/s
  double rotation_ratio = 0.0;  ///< |theta| / alpha of the active corner
  double energy_margin = 1.0;   ///< OverturnMargin::margin, dimensionless
  double slip = 0.0;            ///< m, base relative to the floor
  std::uint32_t impacts = 0;    ///< count
  ItemMode mode = ItemMode::Rest;
  std::int8_t side = 0;          ///< +1 corner 1, -1 corner 2, 0 at rest
  std::uint8_t violations = 0;   ///< RockingState VIOLATION_* bitmask
  ContactMode contact_mode = ContactMode::Rest;
  ActiveModelName model = ActiveModelName::Rocking;
  bool operator==(const PlaneSummary& o) const;
};

struct ItemSummary {
  PlaneSummary plane[kPlaneCount];
  ItemMode mode = ItemMode::Rest;  ///< ItemMonitor::mode()
  Plane worst = Plane::X;          ///< ItemMonitor::worst_plane()
  std::uint8_t planes = 1;         ///< plane_count()
  /// The 3-D model decides the item: its pose is read from the model (such items are never deferred).
  bool solid_active = false;
  /// Bumped whenever a field above changes: a publisher compares it with the revision it last sent.
  std::uint32_t revision = 0;
  /// Same fields (revision not compared).
  bool same_state(const ItemSummary& o) const;
};

/// The summary of `item` now (revision left as it is in `out`, bumped if a field changed).
void summarize(const ItemMonitor& item, ItemSummary& out);

}  // namespace rocking_monitor::core
