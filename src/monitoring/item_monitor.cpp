#include "rocking_monitor/monitoring/item_monitor.hpp"

#include <stdexcept>

namespace rocking_monitor::core {
namespace {

const ItemSpec& checked(const ItemSpec& spec) {
  if (const std::string e = validate(spec); !e.empty()) throw std::invalid_argument(e);
  return spec;
}

int level_index(ItemMode m) { return static_cast<int>(m) - static_cast<int>(ItemMode::BeyondTipping); }

}  // namespace

ItemMonitor::ItemMonitor(const ItemSpec& spec, const Options& options) : spec_(checked(spec)) {
  planes_[0] = std::make_unique<PlaneMonitor>(spec_.body, options);
  if (spec_.two_planes()) planes_[1] = std::make_unique<PlaneMonitor>(y_plane_body(spec_.body, spec_.depth), options);
}

void ItemMonitor::start(double t, double ax, double ay, double az, double dt_nominal) {
  planes_[0]->start(t, ax, az, dt_nominal);
  if (planes_[1]) planes_[1]->start(t, ay, az, dt_nominal);
  last_input_[0] = {ax, az};
  last_input_[1] = {ay, az};
  alarmed_ = marked_;
  events_ = ItemEvents{};
  started_ = true;
}

const ItemEvents& ItemMonitor::step(double ax, double ay, double az, double dt) {
  events_.change_count = 0;
  events_.alarm_count = 0;
  const PlaneEvents* ev[kPlaneCount] = {&planes_[0]->step(ax, az, dt), nullptr};
  last_input_[0] = {ax, az};
  if (planes_[1]) {
    ev[1] = &planes_[1]->step(ay, az, dt);
    last_input_[1] = {ay, az};
  }
  for (int p = 0; p < kPlaneCount; ++p) {
    if (ev[p] == nullptr) continue;
    for (int i = 0; i < ev[p]->change_count; ++i) {
      CriterionChange& c = events_.changes[events_.change_count++];
      c = ev[p]->changes[i];
      c.plane = static_cast<Plane>(p);
    }
  }
  // Item-level alarms: each level once, from the plane that reached it first in this sample (tie: x).
  for (ItemMode level : {ItemMode::BeyondTipping, ItemMode::Committed, ItemMode::Overturned}) {
    const int l = level_index(level);
    if (alarmed_[l]) continue;
    const AlarmEvent* first = nullptr;
    Plane first_plane = Plane::X;
    for (int p = 0; p < kPlaneCount; ++p) {
      if (ev[p] == nullptr) continue;
      for (int i = 0; i < ev[p]->alarm_count; ++i) {
        const AlarmEvent& a = ev[p]->alarms[i];
        if (a.level == level && (first == nullptr || a.time < first->time)) {
          first = &a;
          first_plane = static_cast<Plane>(p);
        }
      }
    }
    if (first == nullptr) continue;
    alarmed_[l] = true;
    AlarmEvent& out = events_.alarms[events_.alarm_count++];
    out = *first;
    out.plane = first_plane;
  }
  return events_;
}

void ItemMonitor::mark_alarmed(ItemMode level) {
  const int l = level_index(level);
  if (l < 0 || l >= static_cast<int>(marked_.size())) throw std::invalid_argument("mark_alarmed: not an alarm level");
  marked_[l] = alarmed_[l] = true;
}

bool ItemMonitor::alarmed(ItemMode level) const {
  const int l = level_index(level);
  return l >= 0 && l < static_cast<int>(alarmed_.size()) && alarmed_[l];
}

ItemMode ItemMonitor::mode() const {
  const ItemMode x = planes_[0]->mode();
  if (!planes_[1]) return x;
  const ItemMode y = planes_[1]->mode();
  return y > x ? y : x;
}

Plane ItemMonitor::worst_plane() const {
  if (!planes_[1]) return Plane::X;
  const ItemMode x = planes_[0]->mode(), y = planes_[1]->mode();
  if (y != x) return y > x ? Plane::Y : Plane::X;
  return planes_[1]->rotation_ratio() > planes_[0]->rotation_ratio() ? Plane::Y : Plane::X;
}

}  // namespace rocking_monitor::core
