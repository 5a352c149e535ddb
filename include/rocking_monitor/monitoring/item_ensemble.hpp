#pragma once

// An item whose parameters are uncertain, as an ensemble of members (each an ItemMonitor with its own
// drawn parameters, all under the same ground motion): the fraction of members that have reached
// each overturning level is the probability of that level given this record, with a Wilson interval.

#include <array>
#include <memory>
#include <vector>

#include "rocking_monitor/monitoring/item_monitor.hpp"
#include "rocking_monitor/monitoring/monitor_batch.hpp"
#include "rocking_monitor/physics/item_verdict.hpp"

namespace rocking_monitor::core {

/// Wilson score interval of a binomial proportion k / n (z = 1.96: 95 %). n = 0 gives [0, 1].
struct WilsonInterval {
  double lower = 0.0, upper = 1.0;
};
WilsonInterval wilson_interval(long k, long n, double z = 1.959963984540054);

/// A probability of a level crossed `threshold` during a sample.
struct ProbabilityCrossing {
  Level level = Level::Committed;
  double time = 0.0;         ///< s: when the member that made the fraction reach the threshold got there
  double probability = 0.0;  ///< the fraction at the end of that sample (members at the level / size)
};

struct EnsembleEvents {
  int count = 0;
  std::array<ProbabilityCrossing, kLevelCount> crossings;
};

class ItemEnsemble {
 public:
  /// members: one ItemSpec per member (e.g. draw_members()); at least one. Throws std::invalid_argument
  /// for an empty list or a bad member (the message names it). `threshold` in (0, 1].
  ItemEnsemble(const std::vector<ItemSpec>& members, const ItemMonitor::Options& options, double threshold = 0.5);

  void start(double t, double ax, double ay, double az, double dt_nominal);
  bool started() const { return batch_ != nullptr; }
  /// A new event at time t (ItemMonitor::new_event for every member): the counts of members at each level and
  /// the crossings start from zero; members on their side stay there.
  void new_event(double t);

  /// Everything one sample carries to the next (state snapshots, issue 29): the members and the
  /// counts of members at each level.
  struct Saved {
    bool started = false;
    std::vector<ItemMonitor::Saved> members;
    std::array<long, kLevelCount> reached{};
    std::array<bool, kLevelCount> crossed{};
    std::vector<std::array<bool, kLevelCount>> member_reached;
  };
  /// Brings the members up to date first. Reuses out's storage.
  void save(Saved& out) const;
  /// std::invalid_argument (naming the member) when in does not fit this ensemble: it is then to be
  /// remade. Allocates, as start() does.
  void restore(const Saved& in);
  /// Steps every member with the same sample, each scaled by its member's input_gain (ItemSpec). No
  /// allocation.
  const EnsembleEvents& step(double ax, double ay, double az, double dt);
  const EnsembleEvents& events() const { return events_; }

  int size() const { return static_cast<int>(members_.size()); }
  /// Member i, brought up to date (the members are stepped as a MonitorBatch).
  const ItemMonitor& member(int i) const {
    if (batch_) batch_->sync(static_cast<std::size_t>(i));
    return members_[static_cast<std::size_t>(i)];
  }
  long reached(Level l) const { return reached_[static_cast<int>(l)]; }
  double probability(Level l) const { return static_cast<double>(reached(l)) / static_cast<double>(size()); }
  WilsonInterval interval(Level l) const { return wilson_interval(reached(l), size()); }
  double threshold() const { return threshold_; }
  /// Whether P(level) has crossed the threshold (latched).
  bool crossed(Level l) const { return crossed_[static_cast<int>(l)]; }

 private:
  std::vector<ItemMonitor> members_;
  double threshold_;
  std::array<long, kLevelCount> reached_{};
  std::array<bool, kLevelCount> crossed_{};
  std::vector<std::array<bool, kLevelCount>> member_reached_;
  std::vector<double> times_;  // scratch: this sample's member times of one level (sized once)
  // The members share every sample: stepped together, quiet member-samples deferred (made at start()).
  mutable std::unique_ptr<MonitorBatch> batch_;
  std::vector<double> in_x_, in_y_, in_z_;  // the sample, once per member (sized once)
  std::vector<double> gain_;                // each member's input_gain (dimensionless)
  void make_batch();
  EnsembleEvents events_;
};

}  // namespace rocking_monitor::core
