#include "rocking_monitor/monitoring/item_ensemble.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rocking_monitor::core {

WilsonInterval wilson_interval(long k, long n, double z) {
  if (n <= 0) return {0.0, 1.0};
  const double nn = static_cast<double>(n), p = static_cast<double>(k) / nn, z2 = z * z;
  const double centre = (p + z2 / (2.0 * nn)) / (1.0 + z2 / nn);
  const double half = z * std::sqrt(p * (1.0 - p) / nn + z2 / (4.0 * nn * nn)) / (1.0 + z2 / nn);
  // Exact at the ends (k = 0: lower 0; k = n: upper 1), where rounding would leave 1e-17.
  return {k == 0 ? 0.0 : std::max(0.0, centre - half), k == n ? 1.0 : std::min(1.0, centre + half)};
}

ItemEnsemble::ItemEnsemble(const std::vector<ItemSpec>& members, const ItemMonitor::Options& options, double threshold)
    : threshold_(threshold) {
  if (members.empty()) throw std::invalid_argument("ensemble: no member");
  if (!(threshold > 0.0 && threshold <= 1.0))
    throw std::invalid_argument("ensemble: alarm probability " + std::to_string(threshold) + " is not in (0, 1]");
  members_.reserve(members.size());
  for (std::size_t i = 0; i < members.size(); ++i) {
    try {
      members_.emplace_back(members[i], options);
    } catch (const std::exception& e) {
      throw std::invalid_argument("ensemble member " + std::to_string(i) + ": " + e.what());
    }
  }
  for (const ItemSpec& m : members) gain_.push_back(m.input_gain);
  member_reached_.resize(members.size());
  times_.reserve(members.size());
}

void ItemEnsemble::make_batch() {
  std::vector<ItemMonitor*> ptrs;
  for (ItemMonitor& m : members_) ptrs.push_back(&m);
  batch_ = std::make_unique<MonitorBatch>(std::move(ptrs));
  in_x_.assign(members_.size(), 0.0);
  in_y_.assign(members_.size(), 0.0);
  in_z_.assign(members_.size(), 0.0);
}

void ItemEnsemble::new_event(double t) {
  if (!batch_) return;
  batch_->sync_all();
  for (std::size_t i = 0; i < members_.size(); ++i) {
    members_[i].new_event(t);
    batch_->refresh(i);  // restarted members: the batch reads them again
  }
  reached_.fill(0);
  crossed_.fill(false);
  for (auto& r : member_reached_) r.fill(false);
  events_ = EnsembleEvents{};
}

void ItemEnsemble::save(Saved& out) const {
  out.started = started();
  if (!out.started) return;
  batch_->sync_all();
  out.members.resize(members_.size());
  for (std::size_t i = 0; i < members_.size(); ++i) members_[i].save(out.members[i]);
  out.reached = reached_;
  out.crossed = crossed_;
  out.member_reached.assign(member_reached_.begin(), member_reached_.end());
}

void ItemEnsemble::restore(const Saved& in) {
  if (!in.started) {
    batch_.reset();
    return;
  }
  if (in.members.size() != members_.size() || in.member_reached.size() != members_.size())
    throw std::invalid_argument("ensemble: " + std::to_string(in.members.size()) + " members saved, this one has " +
                                std::to_string(members_.size()));
  batch_.reset();  // it holds the members' old state
  for (std::size_t i = 0; i < members_.size(); ++i) {
    try {
      members_[i].restore(in.members[i]);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("ensemble member " + std::to_string(i) + ": " + e.what());
    }
  }
  make_batch();
  reached_ = in.reached;
  crossed_ = in.crossed;
  std::copy(in.member_reached.begin(), in.member_reached.end(), member_reached_.begin());
  events_ = EnsembleEvents{};
}

void ItemEnsemble::start(double t, double ax, double ay, double az, double dt_nominal) {
  for (std::size_t i = 0; i < members_.size(); ++i)
    members_[i].start(t, gain_[i] * ax, gain_[i] * ay, gain_[i] * az, dt_nominal);
  make_batch();
  reached_.fill(0);
  crossed_.fill(false);
  for (auto& r : member_reached_) r.fill(false);
  events_ = EnsembleEvents{};
}

const EnsembleEvents& ItemEnsemble::step(double ax, double ay, double az, double dt) {
  events_.count = 0;
  if (!batch_) throw std::logic_error("ItemEnsemble::step before start()");
  for (std::size_t i = 0; i < members_.size(); ++i) {
    in_x_[i] = gain_[i] * ax;
    in_y_[i] = gain_[i] * ay;
    in_z_[i] = gain_[i] * az;
  }
  batch_->step(0, members_.size(), in_x_.data(), in_y_.data(), in_z_.data(), dt);
  for (int l = 0; l < kLevelCount; ++l) {
    // Member times of this level in this sample, in order, to find the one that crossed.
    times_.clear();
    for (std::size_t i = 0; i < members_.size(); ++i) {
      if (!(batch_->event_flags(i) & MonitorBatch::kHasAlarms)) continue;
      const ItemEvents& ev = batch_->events(i);
      for (int k = 0; k < ev.alarm_count; ++k) {
        if (static_cast<int>(ev.alarms[k].level) - static_cast<int>(ItemMode::BeyondTipping) != l) continue;
        if (!member_reached_[i][l]) {
          member_reached_[i][l] = true;
          times_.push_back(ev.alarms[k].time);
        }
      }
    }
    if (times_.empty()) continue;
    std::sort(times_.begin(), times_.end());
    const long before = reached_[l];
    reached_[l] += static_cast<long>(times_.size());
    if (crossed_[l]) continue;
    // Smallest count that reaches the threshold: ceil(threshold * n), robust to rounding.
    const double n = static_cast<double>(members_.size());
    long needed = static_cast<long>(std::ceil(threshold_ * n - 1e-9));
    needed = std::max(needed, 1L);
    if (reached_[l] < needed) continue;
    crossed_[l] = true;
    ProbabilityCrossing& c = events_.crossings[events_.count++];
    c.level = static_cast<Level>(l);
    c.time = times_[static_cast<std::size_t>(needed - before - 1)];
    c.probability = static_cast<double>(reached_[l]) / n;
  }
  return events_;
}

}  // namespace rocking_monitor::core
