#include "rocking_monitor/physics/item_verdict.hpp"

namespace rocking_monitor::core {

ItemVerdict combine(const LevelTimes& x, const LevelTimes* y) {
  ItemVerdict v;
  v.levels = x;
  if (y == nullptr) return v;
  for (int l = 0; l < kLevelCount; ++l) {
    const double ty = y->time[l];
    if (ty == ty && !(v.levels.time[l] <= ty)) {  // y reached it, and x never or later
      v.levels.time[l] = ty;
      v.plane[l] = Plane::Y;
    }
  }
  return v;
}

}  // namespace rocking_monitor::core
