#include "rocking_monitor/monitoring/item_summary.hpp"

namespace rocking_monitor::core {

const char* to_string(ActiveModelName m) {
  switch (m) {
    case ActiveModelName::Rocking: return "rocking";
    case ActiveModelName::RockingLinearized: return "rocking_linearized";
    case ActiveModelName::Contact: return "contact";
  }
  return "rocking";
}

bool PlaneSummary::operator==(const PlaneSummary& o) const {
  return theta == o.theta && omega == o.omega && rotation_ratio == o.rotation_ratio &&
         energy_margin == o.energy_margin && slip == o.slip && impacts == o.impacts && mode == o.mode &&
         side == o.side && violations == o.violations && contact_mode == o.contact_mode && model == o.model;
}

bool ItemSummary::same_state(const ItemSummary& o) const {
  if (mode != o.mode || worst != o.worst || planes != o.planes || solid_active != o.solid_active) return false;
  for (int p = 0; p < planes; ++p)
    if (!(plane[p] == o.plane[p])) return false;
  return true;
}

namespace {

void summarize_plane(const PlaneMonitor& pm, PlaneSummary& out) {
  out.theta = pm.theta();
  out.omega = pm.omega();
  out.rotation_ratio = pm.rotation_ratio();
  out.energy_margin = pm.margin().margin;
  out.slip = pm.slip();
  out.impacts = static_cast<std::uint32_t>(pm.impacts());
  out.mode = pm.mode();
  out.side = static_cast<std::int8_t>(pm.side());
  out.violations = pm.violations();
  out.contact_mode = pm.contact_mode();
  const AdaptiveModel* a = pm.adaptive();
  out.model = a == nullptr                          ? ActiveModelName::Rocking
              : a->active() == ActiveModel::Contact ? ActiveModelName::Contact
              : a->linearized()                     ? ActiveModelName::RockingLinearized
                                                    : ActiveModelName::Rocking;
}

}  // namespace

// Taken after every full step of an item (MonitorBatch::refresh): each plane's mode and margin are
// evaluated once (each may take a cosine), and the item's mode and worst plane follow from them by
// ItemMonitor::mode / worst_plane's rules instead of evaluating the planes again.
void summarize(const ItemMonitor& item, ItemSummary& out) {
  ItemSummary now;
  now.planes = static_cast<std::uint8_t>(item.plane_count());
  for (int p = 0; p < now.planes; ++p) summarize_plane(item.plane(static_cast<Plane>(p)), now.plane[p]);
  now.solid_active = item.solid() != nullptr && item.solid_active();
  if (now.solid_active) {
    now.mode = item.mode();
    now.worst = item.worst_plane();
  } else if (now.planes == 1) {
    now.mode = now.plane[0].mode;
    now.worst = Plane::X;
  } else {
    const PlaneSummary &x = now.plane[0], &y = now.plane[1];
    now.mode = y.mode > x.mode ? y.mode : x.mode;
    now.worst = y.mode != x.mode ? (y.mode > x.mode ? Plane::Y : Plane::X)
                                 : (y.rotation_ratio > x.rotation_ratio ? Plane::Y : Plane::X);
  }
  now.revision = out.revision;
  if (!now.same_state(out)) {
    ++now.revision;
    out = now;
  }
}

}  // namespace rocking_monitor::core
