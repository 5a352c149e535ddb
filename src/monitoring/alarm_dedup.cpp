#include "rocking_monitor/monitoring/alarm_dedup.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace rocking_monitor::core {

AlarmDedup::AlarmDedup(double window_s) {
  if (!(window_s >= 0.0) || !std::isfinite(window_s))
    throw std::invalid_argument("alarm dedup window must be >= 0 s, got " + std::to_string(window_s));
  window_ns_ = static_cast<std::int64_t>(std::llround(window_s * 1e9));
}

AlarmDedup::Result AlarmDedup::add(const AlarmIdentity& a) {
  Result r;
  // A repeat from the same source: its journal names it by (event id, sequence); without one, by stamp.
  auto seen = a.event_id.empty() ? std::make_tuple(a.source, std::string(), std::uint64_t{0}, a.item, a.level, a.stamp_ns)
                                 : std::make_tuple(a.source, a.event_id, a.sequence, std::string(), 0, std::int64_t{0});
  if (!seen_.insert(std::move(seen)).second) {
    ++repeats_;
    r.outcome = Outcome::Repeat;
    return r;
  }
  auto& candidates = by_item_level_[{a.item, a.level}];
  for (std::size_t id : candidates) {
    Row& row = rows_.at(id);
    if (row.sources.count(a.source) || std::llabs(row.stamp_ns - a.stamp_ns) > window_ns_) continue;
    row.sources.insert(a.source);
    ++merged_;
    r.outcome = Outcome::Merged;
    r.row = id;
    // The better copy: from every sample first (a copy after a gap is another motion), then the earlier.
    r.replaces = std::make_pair(!a.whole, a.stamp_ns) < std::make_pair(!row.whole, row.stamp_ns);
    if (r.replaces) {
      row.stamp_ns = a.stamp_ns;
      row.whole = a.whole;
      ++replaced_;
    }
    return r;
  }
  r.row = next_row_++;
  rows_.emplace(r.row, Row{a.stamp_ns, a.whole, {a.source}});
  candidates.push_back(r.row);
  return r;
}

void AlarmDedup::forget(std::size_t id) {
  auto it = rows_.find(id);
  if (it == rows_.end()) return;
  for (auto& [key, ids] : by_item_level_) {
    auto pos = std::find(ids.begin(), ids.end(), id);
    if (pos == ids.end()) continue;
    ids.erase(pos);
    if (ids.empty()) by_item_level_.erase(key);
    break;
  }
  rows_.erase(it);
}

}  // namespace rocking_monitor::core
