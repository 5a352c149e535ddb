// RockingMonitor's state snapshots (issue 29; docs/journal.md "State snapshots"): parameters, reading
// the snapshot at start (refused with the reason when damaged, foreign or stale), each sensor's items
// resumed from it at the sensor's first sample, snapshots taken between samples and written by a
// thread, and their diagnostics. The format and the models' state are the core's
// (monitoring/state_snapshot.hpp).
#include "rocking_monitor/ros/monitor.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include <nlohmann/json.hpp>

#include "rocking_monitor/integrate/solver_settings.hpp"
#include "rocking_monitor/json_text.hpp"

namespace rocking_monitor::live {

bool RockingMonitor::load_snapshot_parameters() {
  // Beside the journal by default (journal.jsonl -> journal.snapshot); off with the journal.
  snapshot_path_.clear();
  if (!journal_path_.empty()) {
    const std::string ext = ".jsonl";
    const bool jsonl = journal_path_.size() > ext.size() &&
                       journal_path_.compare(journal_path_.size() - ext.size(), ext.size(), ext) == 0;
    snapshot_path_ = (jsonl ? journal_path_.substr(0, journal_path_.size() - ext.size()) : journal_path_) + ".snapshot";
  }
  if (pnh_.hasParam("snapshot") && !pnh_.getParam("snapshot", snapshot_path_)) {
    ROS_FATAL("rocking_monitor: parameter ~snapshot has the wrong type (expected a path; \"\" = off)");
    return false;
  }
  pnh_.setParam("snapshot", snapshot_path_);
  // ~snapshot_period and ~snapshot_max_load are read with the other numbers (load_parameters).
  if (!(snapshot_period_ >= 0.0) || !std::isfinite(snapshot_period_)) {
    ROS_FATAL("rocking_monitor: ~snapshot_period = %g must be >= 0 s of input time (0 = after every sample)",
              snapshot_period_);
    return false;
  }
  if (!(snapshot_max_load_ > 0.0 && snapshot_max_load_ <= 1.0)) {
    ROS_FATAL("rocking_monitor: ~snapshot_max_load must be a share in (0, 1] (of input time spent encoding snapshots)");
    return false;
  }
  snapshot_interval_ = snapshot_period_;
  return true;
}

// Reads the snapshot left by the previous run. What can be checked before any sample (checksums,
// version, this catalogue and options) is checked here; staleness is per sensor, at its first sample.
void RockingMonitor::open_snapshot(const XmlRpc::XmlRpcValue& sensors, const XmlRpc::XmlRpcValue& items) {
  // Everything the models' state depends on: the catalogue as given, this shard, the ensembles'
  // draw and every model option (a snapshot of other items or models is foreign).
  char options[512];
  std::snprintf(options, sizeof options,
                "shard %s; method %s; model %s; tol %.17g; substeps %d; rest_capture %.17g; max_events %d; "
                "fidelity %s; scene %.17g %.17g; linearized %.17g; solid %s; bidirectional %.17g; highpass %.17g; "
                "ensemble %d seed %d p %.17g; baseline %d",
                shard_.c_str(), core::to_string(options_.solver.method), core::to_string(options_.solver.model),
                options_.solver.tol, options_.solver.substeps, options_.solver.rest_capture_ratio,
                options_.solver.max_events_per_sample, core::to_string(options_.fidelity), options_.scene.horizontal,
                options_.scene.vertical, options_.linearized_max_alpha, core::to_string(options_.solid),
                options_.bidirectional_ratio, options_.velocity_highpass_hz, ensemble_size_, ensemble_seed_,
                alarm_probability_, static_cast<int>(baseline_config_.mode));
  fingerprint_ = core::configuration_fingerprint(json_text(to_json(sensors)) + "\n" + json_text(to_json(items)) + "\n" + options);
  resume_pending_.assign(sensors_.size(), false);
  if (snapshot_path_.empty()) {
    snapshot_start_ = "off (~snapshot is \"\")";
    ROS_WARN("rocking_monitor: state snapshots off (~snapshot is \"\"): a restarted monitor starts every item at rest");
    return;
  }
  auto snap = std::make_unique<core::StateSnapshot>();
  bool exists = false;
  std::string e = core::read_snapshot(snapshot_path_, *snap, &exists);
  if (e.empty()) {
    std::vector<std::string> sensor_names, item_ids;
    for (const Sensor& s : sensors_) sensor_names.push_back(s.spec.name);
    for (const Item& it : items_) item_ids.push_back(it.entry.spec.id);
    if (const std::string f = core::foreign_snapshot(*snap, fingerprint_, sensor_names, item_ids); !f.empty())
      e = snapshot_path_ + ": foreign: " + f;
  }
  if (!exists) {
    snapshot_start_ = "none (no snapshot file: first start)";
  } else if (!e.empty()) {
    snapshot_start_ = "refused: " + e;
    ROS_ERROR("rocking_monitor: state snapshot refused: %s; every item starts at rest", e.c_str());
  } else {
    resume_ = std::move(snap);
    for (std::size_t i = 0; i < sensors_.size(); ++i) resume_pending_[i] = resume_->sensors[i].samples > 0;
    snapshot_start_ = "read: each sensor's items resume at its first sample if it is within ~max_bridge";
    ROS_INFO("rocking_monitor: state snapshot %s read (%zu items, taken %.3f s ago by the node's clock)",
             snapshot_path_.c_str(), resume_->items.size(), ::ros::WallTime::now().toSec() - resume_->written);
  }
  snapshot_writer_ = std::make_unique<core::SnapshotFileWriter>(snapshot_path_);
}

// The sensor's first sample after a restart, at `stamp`: its items continue from the snapshot when the
// snapshot's last sample of it lies at most ~max_bridge before (and not ~backward_jump after) this one.
// The samples in between are a gap, as issue 19 treats one: the items stay frozen through it, and the
// first sample continues them as if it followed the last by one period (step_sample's AcceptGap).
void RockingMonitor::resume_sensor(std::size_t si, const ::ros::Time& stamp, bool next_in_history) {
  resume_pending_[si] = false;
  const bool last = std::none_of(resume_pending_.begin(), resume_pending_.end(), [](bool p) { return p; });
  const core::SnapshotSensor& ss = resume_->sensors[si];
  Sensor& s = sensors_[si];
  ::ros::Time before;
  before.fromNSec(static_cast<std::uint64_t>(ss.last_stamp_ns));
  const double gap = (stamp - before).toSec();
  auto refuse = [&](const std::string& why) {
    snapshot_start_ = "refused for sensor '" + s.spec.name + "': " + why;
    ROS_ERROR("rocking_monitor: state snapshot %s: sensor '%s': %s; its %zu items start at rest", snapshot_path_.c_str(),
              s.spec.name.c_str(), why.c_str(), s.items.size());
  };
  if (gap > plausibility_config_.max_bridge) {
    refuse("stale: its last sample is " + std::to_string(gap) + " s before this one (more than ~max_bridge " +
           std::to_string(plausibility_config_.max_bridge) + " s)");
  } else if (gap <= -timing_config_.backward_jump) {
    refuse("stale: its last sample is " + std::to_string(-gap) + " s after this one (the stream went back: a replay?)");
  } else {
    try {
      for (std::size_t idx : s.items) {
        Item& it = items_[idx];
        const core::SnapshotItem& saved = resume_->items[idx];
        it.monitor->restore(saved.monitor);
        if (it.ensemble && saved.has_ensemble) it.ensemble->restore(saved.ensemble);
        it.stamp = before;
      }
    } catch (const std::exception& e) {
      for (std::size_t idx : s.items) make_models(items_[idx]);
      refuse(std::string("does not fit: ") + e.what());
      if (last) resume_.reset();
      return;
    }
    double dt = 0.0;
    s.timing.classify(before.toSec(), dt);  // started, last stamp = the snapshot's
    s.epoch.fromNSec(static_cast<std::uint64_t>(ss.epoch_ns));
    s.last_t = ss.last_t;
    s.dt_nominal = ss.dt_nominal;
    s.min_dt = ss.min_dt;
    s.baseline.restore(ss.baseline_initialized, Eigen::Vector3d(ss.baseline[0], ss.baseline[1], ss.baseline[2]));
    s.last_stamp = before;
    s.stepped_stamp = before;
    s.have_first = false;
    s.batch.reset();
    s.received_at_last_step = s.received - 1;  // this sample is the next after the snapshot's: the rest are lost
    const double period = nominal_period(s);
    Resumed r;
    r.sensor = s.spec.name;
    r.gap_s = gap;
    r.missing = period > 0.0 && !next_in_history ? std::max(0L, std::lround(gap / period) - 1) : 0;
    r.items = s.items.size();
    resumed_.push_back(r);
    snapshot_start_ = "resumed";
    if (r.missing > 0)
      ROS_WARN("rocking_monitor: sensor '%s': its %zu items continue from the state snapshot %s: its last sample is "
               "%.3f s before this one, %ld samples missing: a gap, frozen, not bridged", s.spec.name.c_str(),
               s.items.size(), snapshot_path_.c_str(), gap, r.missing);
    else  // the feed sent its history again (a bridge's, or a replay): nothing is missing
      ROS_WARN("rocking_monitor: sensor '%s': its %zu items continue from the state snapshot %s: its last sample is "
               "%.3f s %s this one, 0 samples missing (%s)",
               s.spec.name.c_str(), s.items.size(), snapshot_path_.c_str(), std::abs(gap),
               gap > 0.0 ? "before" : "after",
               next_in_history ? "this is the next sample, from the bridge's history"
                               : "samples up to it are dropped as already stepped");
    if (gap > 0.0 && r.missing > 0) {
      // The gap in the journal, as a stale period that opened at the snapshot's last sample.
      if (const std::string e = journal_.append_stale(s.spec.name, before.toSec(), stamp.toSec(), s.epoch.toSec(),
                                                      journal_clock(stamp));
          !e.empty()) {
        ++journal_errors_;
        ROS_ERROR("rocking_monitor: alarm journal: %s: the restart's gap of sensor '%s' not journaled", e.c_str(),
                  s.spec.name.c_str());
      }
    }
  }
  if (diagnostics_) diagnostics_->force_update();
  if (last) resume_.reset();  // every sensor has had its part
}

// Between two samples: every item brought up to date (the batches' deferred samples) and encoded into
// the writer's free buffer; the thread seals and writes it. Allocates nothing once the buffers have
// grown to a snapshot's size.
void RockingMonitor::take_snapshot(const ::ros::Time& stamp) {
  if (!snapshot_writer_) return;
  const auto t0 = std::chrono::steady_clock::now();
  last_snapshot_stamp_ = stamp;
  // The journal's alarms on disk before a snapshot that has their items alarmed: a crash in between
  // must not leave an item marked alarmed with no alarm in the journal.
  journal_.drain();
  sync_items();
  std::vector<std::uint8_t>& buf = snapshot_writer_->buffer();
  snapshot_encoder_.begin(buf, fingerprint_, ::ros::WallTime::now().toSec(), sensors_.size(), items_.size());
  for (const Sensor& s : sensors_) {
    core::SnapshotSensor ss;
    ss.name = s.spec.name;
    ss.samples = s.timing.started() && !s.have_first ? s.processed + 1 : 0;  // 0: nothing to resume
    ss.last_stamp_ns = static_cast<std::int64_t>(s.last_stamp.toNSec());
    ss.epoch_ns = static_cast<std::int64_t>(s.epoch.toNSec());
    ss.last_t = s.last_t;
    ss.dt_nominal = s.dt_nominal;
    ss.min_dt = s.min_dt;
    ss.baseline_initialized = s.baseline.initialized();
    for (int k = 0; k < 3; ++k) ss.baseline[k] = s.baseline.baseline()[k];
    snapshot_encoder_.sensor(ss);
  }
  for (const Item& it : items_) snapshot_encoder_.item(it.entry.spec.id, *it.monitor, it.ensemble.get());
  snapshot_encoder_.finish(false);  // the writer's thread computes the checksums
  snapshot_writer_->submit();
  const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  snapshot_cost_.add(spent);
  // A large catalogue takes tens of ms to encode: snapshots are then spaced so that they cost at most
  // ~snapshot_max_load of the input time (10,000 items: ~0.5 s apart; docs/journal.md).
  snapshot_interval_ = std::max(snapshot_period_, spent / snapshot_max_load_);
  // A failed write (disk full, ...) is loud but does not stop the monitor: the previous file stays.
  const core::SnapshotFileWriter::Status st = snapshot_writer_->status();
  if (st.failed > snapshot_failures_seen_) {
    snapshot_failures_seen_ = st.failed;
    ROS_ERROR_THROTTLE(10.0, "rocking_monitor: state snapshot NOT written (%lu failures so far): %s; the monitor goes "
                       "on, a restart would resume from the last snapshot written", static_cast<unsigned long>(st.failed),
                       st.last_error.c_str());
  }
}

void RockingMonitor::snapshot_diagnostics(diagnostic_updater::DiagnosticStatusWrapper& st) {
  using diagnostic_msgs::DiagnosticStatus;
  const core::SnapshotFileWriter::Status w =
      snapshot_writer_ ? snapshot_writer_->status() : core::SnapshotFileWriter::Status{};
  if (snapshot_path_.empty()) st.summary(DiagnosticStatus::WARN, "state snapshots off: a restart starts items at rest");
  else if (!w.last_error.empty()) st.summary(DiagnosticStatus::ERROR, "state snapshot not written: " + w.last_error);
  else if (snapshot_start_.rfind("refused", 0) == 0) st.summary(DiagnosticStatus::WARN, "at start: " + snapshot_start_);
  else if (!resumed_.empty()) st.summary(DiagnosticStatus::WARN, "resumed from the snapshot after a restart, with a gap");
  else st.summary(DiagnosticStatus::OK, "state snapshots written");
  st.add("file", snapshot_path_.empty() ? std::string("(off)") : snapshot_path_);
  st.add("period (s of input)", snapshot_period_);
  st.add("interval in use (s of input, for ~snapshot_max_load)", snapshot_interval_);
  st.add("at start", snapshot_start_);
  for (const Resumed& r : resumed_) {
    st.add("resumed sensor " + r.sensor + ": items", r.items);
    st.add("resumed sensor " + r.sensor + ": gap (s)", r.gap_s);
    st.add("resumed sensor " + r.sensor + ": samples missing (frozen, not bridged)", r.missing);
  }
  st.add("snapshots written", w.written);
  st.add("snapshots failed", w.failed);
  st.add("last error", w.last_error);
  st.add("superseded before written", w.superseded);
  st.add("size (bytes)", w.last_bytes);
  st.add("encode, mean (ms)", 1e3 * snapshot_cost_.mean());
  st.add("encode, max (ms)", 1e3 * snapshot_cost_.max_s);
  st.add("write with fsync, last (ms)", 1e3 * w.last_write_s);
  st.add("write with fsync, max (ms)", 1e3 * w.max_write_s);
}

}  // namespace rocking_monitor::live
