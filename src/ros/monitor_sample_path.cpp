// RockingMonitor's per-sample path: an IMU or AccelStamped message in, checked, timed and freed
// of gravity, rotated into each item's frame (tf2), the items started or stepped (in parallel
// when ~threads > 1), and their events published.
#include "rocking_monitor/ros/monitor.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include <geometry_msgs/TransformStamped.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "rocking_monitor/feeds/conflict_mark.hpp"

namespace rocking_monitor::live {

void RockingMonitor::on_imu(std::size_t sensor, const ::ros::MessageEvent<sensor_msgs::Imu const>& e) {
  const sensor_msgs::ImuConstPtr& m = e.getConstMessage();
  sensors_[sensor].backlog_s = queue_wait(e.getReceiptTime());
  if (feeds::conflict_marked(m->linear_acceleration_covariance)) return skip_conflicting(sensor, m->header);
  on_sample(sensor, m->header,
            Eigen::Vector3d(m->linear_acceleration.x, m->linear_acceleration.y, m->linear_acceleration.z));
}

// Issue 52 item 3: a sample the bridge marked as conflicting (two sources gave its sequence number
// different values; docs/inputs.md) is not ground motion anyone vouches for. It is not stepped: its
// place is a gap, which the next sample treats as any gap (bridged within ~max_gap, else frozen;
// issue 19). It counts as received, so the gap's accounting does not call it lost in transport.
void RockingMonitor::skip_conflicting(std::size_t si, const std_msgs::Header& header) {
  Sensor& s = sensors_[si];
  ++s.received;
  ++s.conflicting;
  s.last_conflicting_stamp = header.stamp;
  ROS_ERROR_THROTTLE(5.0, "rocking_monitor: sensor '%s': sample stamped %.6f marked as conflicting by its bridge "
                     "(two sources disagree): not stepped, a gap in its place (%lu so far)", s.spec.name.c_str(),
                     header.stamp.toSec(), static_cast<unsigned long>(s.conflicting));
  if (s.conflicting == 1) diagnostics_->force_update();  // the first one at once; the rest at the updater's rate
}

void RockingMonitor::on_accel(std::size_t sensor, const ::ros::MessageEvent<geometry_msgs::AccelStamped const>& e) {
  const geometry_msgs::AccelStampedConstPtr& m = e.getConstMessage();
  sensors_[sensor].backlog_s = queue_wait(e.getReceiptTime());
  on_sample(sensor, m->header, Eigen::Vector3d(m->accel.linear.x, m->accel.linear.y, m->accel.linear.z));
}

// How long a sample waited in the subscriber queue, s. Not under sim time: the receipt time is on
// /clock, which may jump (a bag started, a test's next case) between receipt and processing; there
// the lag (stamp vs /clock) tells the overload.
double RockingMonitor::queue_wait(const ::ros::Time& receipt) {
  if (::ros::Time::isSimTime() || receipt.isZero()) return 0.0;
  return (::ros::Time::now() - receipt).toSec();
}

bool RockingMonitor::lookup_rotation(Item& item, const std::string& sensor_frame) {
  // Called only while the item has no rotation. The last one found stops the listener: nothing
  // else reads tf, and it would otherwise take the node's own body transforms back in.
  auto found = [&] {
    item.has_rotation = true;
    if (items_without_rotation_ > 0 && --items_without_rotation_ == 0 && tf_listener_) {
      tf_listener_.reset();
      tf_buffer_->clear();
      ROS_DEBUG("rocking_monitor: every item has its transform: tf listener stopped");
    }
    return true;
  };
  if (sensor_frame.empty() || sensor_frame == item.entry.spec.frame) {
    item.rotation.setIdentity();
    return found();
  }
  try {
    // Static mounting: the latest transform is the one.
    const geometry_msgs::TransformStamped t =
        tf_buffer_->lookupTransform(item.entry.spec.frame, sensor_frame, ::ros::Time(0));
    item.rotation = tf2::transformToEigen(t).rotation();
    ROS_DEBUG("rocking_monitor: item '%s' uses the transform %s <- %s", item.entry.spec.id.c_str(),
              item.entry.spec.frame.c_str(), sensor_frame.c_str());
    return found();
  } catch (const tf2::TransformException& e) {
    ROS_WARN_THROTTLE(5.0, "rocking_monitor: item '%s' is not monitored yet: no transform %s <- %s (%s)",
                      item.entry.spec.id.c_str(), item.entry.spec.frame.c_str(), sensor_frame.c_str(), e.what());
    return false;
  }
}

void RockingMonitor::start_items(Sensor& s, double t, const Eigen::Vector3d& a) {
  for (std::size_t idx : s.items) {
    Item& it = items_[idx];
    if (!it.has_rotation && !lookup_rotation(it, s.frame)) continue;
    const Eigen::Vector3d ai = it.rotation * a;
    const Eigen::Vector3d gi = it.entry.spec.input_gain * ai;  // the nominal item's scale; members their own
    it.monitor->start(t, gi.x(), gi.y(), gi.z(), s.dt_nominal);
    if (it.ensemble) it.ensemble->start(t, ai.x(), ai.y(), ai.z(), s.dt_nominal);
    it.stamp = s.epoch + ::ros::Duration(t);
  }
}

void RockingMonitor::on_sample(std::size_t si, const std_msgs::Header& header, const Eigen::Vector3d& reading) {
  const auto wall_start = std::chrono::steady_clock::now();
  Sensor& s = sensors_[si];
  ++s.received;
  if (!reading.allFinite()) {
    ++s.rejected_nonfinite;
    ROS_WARN_THROTTLE(5.0, "rocking_monitor: sensor '%s': non-finite sample rejected (%lu so far)",
                      s.spec.name.c_str(), static_cast<unsigned long>(s.rejected_nonfinite));
    return;
  }
  if (header.stamp.isZero()) {
    ++s.zero_stamps;
    ROS_WARN_THROTTLE(5.0, "rocking_monitor: sensor '%s': sample with a zero stamp dropped", s.spec.name.c_str());
    return;
  }
  const double expected = s.spec.type == SensorSpec::Type::Imu ? core::kGravity : 0.0;
  if ((reading - Eigen::Vector3d(0.0, 0.0, expected)).norm() > max_abs_acceleration_) {
    ++s.rejected_limit;
    ROS_WARN_THROTTLE(5.0, "rocking_monitor: sensor '%s': |a| = %.1f m/s^2 beyond ~max_abs_acceleration %.1f: rejected",
                      s.spec.name.c_str(), reading.norm(), max_abs_acceleration_);
    return;
  }
  // Issue 29: the first sample after a restart continues the sensor's items from the state snapshot,
  // after the samples it missed if the bridge's history has them (part 2), else across a frozen gap.
  if (resume_ && resume_pending_[si] && !s.timing.started() && !(!catch_up_service_.empty() && catch_up(si)))
    resume_sensor(si, header.stamp);
  if (!s.caught_up_to.isZero()) {
    if (header.stamp <= s.caught_up_to) {  // stepped from the history already: received live meanwhile
      ++s.caught_up_dropped;
      return;
    }
    s.caught_up_to = ::ros::Time();  // joined the live stream
  }
  // Issue 19: a stamp is checked against the node's clock and the last accepted stamp before it
  // steps anything; a lone bad stamp is dropped and counted, a new time base needs
  // ~rebase_samples consistent samples (held meanwhile, replayed when confirmed).
  using P = core::StampPlausibility::Verdict;
  const P plausible = s.plausibility.check(header.stamp.toSec(), ::ros::Time::now().toSec(), s.timing.started(),
                                           s.timing.last_stamp());
  auto suspect = [&] {
    if (s.suspect_count < s.suspects.size()) s.suspects[s.suspect_count] = {header.stamp, reading};
    ++s.suspect_count;  // beyond the buffer: counted, so that the sequence no longer fits
  };
  switch (plausible) {
    case P::Plausible:
      if (s.suspect_count > 0 && !restamp_suspects(si, header))
        ROS_WARN("rocking_monitor: sensor '%s': rejected %zu sample(s) with an implausible stamp (%.3f s from the "
                 "last; %lu rejected so far)", s.spec.name.c_str(), s.suspect_count,
                 s.plausibility.counters().last_rejected_jump,
                 static_cast<unsigned long>(s.plausibility.counters().rejected));
      s.held_count = 0;
      s.suspect_count = 0;
      break;
    case P::Rejected:
      s.held_count = 0;
      suspect();
      ROS_WARN_THROTTLE(5.0, "rocking_monitor: sensor '%s': rejected implausible stamp %.6f, %.3f s ahead of the "
                        "node's clock (%lu rejected so far)", s.spec.name.c_str(), header.stamp.toSec(),
                        (header.stamp - ::ros::Time::now()).toSec(),
                        static_cast<unsigned long>(s.plausibility.counters().rejected));
      return;
    case P::Held:
      if (s.plausibility.held() == 1 && s.held_count > 0) {  // a new run: the previous one was dropped (counted)
        ROS_WARN_THROTTLE(5.0, "rocking_monitor: sensor '%s': rejected implausible stamp (%lu rejected so far)",
                          s.spec.name.c_str(), static_cast<unsigned long>(s.plausibility.counters().rejected));
        s.held_count = 0;
      }
      if (s.held_count < s.held.size()) s.held[s.held_count++] = {header.stamp, reading};
      suspect();
      return;
    case P::RebaseForward:
    case P::RebaseBackward:
      if (s.held_count < s.held.size()) s.held[s.held_count++] = {header.stamp, reading};
      s.suspect_count = 0;
      replay_held(si, header);
      return;
  }
  step_sample(si, header, reading, wall_start);
}

// Overload (issue 19 part 3): the sensor's lag behind the node's clock, or the time its samples wait
// in the subscriber queue, beyond ~max_lag. Recovers below half of it (no flapping). On a change
// ~overload is published (latched) and the diagnostics at once.
void RockingMonitor::update_overload(Sensor& s) {
  s.max_backlog_s = std::max(s.max_backlog_s, s.backlog_s);
  // Idle for longer than ~max_lag (nothing waits, else it would be processed): caught up.
  const bool idle = !s.last_input_clock.isZero() && (::ros::Time::now() - s.last_input_clock).toSec() > max_lag_;
  const double behind = idle ? 0.0 : std::max(s.lag_s, s.backlog_s);
  const bool was = s.overloaded;
  if (!s.overloaded && behind > max_lag_) {
    s.overloaded = true;
    ++s.overload_episodes;
  } else if (s.overloaded && behind < 0.5 * max_lag_) {
    s.overloaded = false;
  }
  if (s.overloaded == was) return;
  bool any = false;
  for (const Sensor& o : sensors_) any = any || o.overloaded;
  if (any != overload_) {
    overload_ = any;
    overload_since_ = ::ros::WallTime::now();
    std_msgs::Bool b;
    b.data = any;
    overload_pub_.publish(b);
    if (any) ROS_ERROR("rocking_monitor: overload: sensor '%s' %.3f s behind (> ~max_lag %.3f s): shedding markers and "
                       "tf, then the states rate", s.spec.name.c_str(), behind, max_lag_);
    else ROS_WARN("rocking_monitor: overload over: every sensor within ~max_lag again");
  }
  diagnostics_->force_update();
}

bool RockingMonitor::shedding_states() const {
  return overload_ && (::ros::WallTime::now() - overload_since_).toSec() > max_lag_;
}

bool RockingMonitor::stale(const Sensor& s) const {
  if (s.plausibility.held() > 0) return true;
  if (s.last_input_clock.isZero()) return false;
  return (::ros::Time::now() - s.last_input_clock).toSec() > timing_config_.max_gap;
}

// The nominal sample period, s: the catalogue's rate when the shortest step seen confirms it (within
// 20 %), else that shortest step (not a mean: gaps would inflate it); before any step, the rate.
double RockingMonitor::nominal_period(const Sensor& s) {
  if (s.min_dt == 0.0) return s.spec.rate > 0.0 ? 1.0 / s.spec.rate : 0.0;
  return std::abs(s.min_dt * s.spec.rate - 1.0) < 0.2 ? 1.0 / s.spec.rate : s.min_dt;
}

// The samples dropped for their stamps since the last one stepped, when this good stamp lies exactly
// as many periods after the last as they fill and nothing else arrived in between: only their stamps
// were bad (a glitch in the packets), so their readings are stepped at the stamps of their places in
// the sequence (spaced evenly between the two good stamps) rather than lost (issue 19).
bool RockingMonitor::restamp_suspects(std::size_t si, const std_msgs::Header& header) {
  Sensor& s = sensors_[si];
  const std::size_t k = s.suspect_count;
  const bool in_sequence = k <= s.suspects.size() && s.received == s.received_at_last_step + k + 1;
  if (!restamp_in_sequence_ || !in_sequence || !s.timing.started() || s.have_first ||
      !s.plausibility.restamp(s.timing.last_stamp(), header.stamp.toSec(), k, nominal_period(s)))
    return false;
  ROS_WARN("rocking_monitor: sensor '%s': %zu sample(s) with an implausible stamp (%.3f s from the last) sat in "
           "sequence: re-stamped in place and stepped (%lu re-stamped so far)", s.spec.name.c_str(), k,
           s.plausibility.counters().last_rejected_jump,
           static_cast<unsigned long>(s.plausibility.counters().restamped));
  const ::ros::Time last = s.last_stamp;
  const ::ros::Duration span = header.stamp - last;
  std_msgs::Header h = header;
  for (std::size_t i = 0; i < k; ++i) {
    h.stamp = last + span * (static_cast<double>(i + 1) / static_cast<double>(k + 1));
    step_sample(si, h, s.suspects[i].reading, std::chrono::steady_clock::now());
  }
  return true;
}

// A new time base confirmed by ~rebase_samples consistent stamps: later base, the items continue with
// the offset absorbed (the first held sample one nominal period after the last one stepped); earlier
// base, the items restart (a bag loop or a simulation restarted). Then the held samples are stepped.
void RockingMonitor::replay_held(std::size_t si, const std_msgs::Header& header) {
  Sensor& s = sensors_[si];
  const bool forward = s.held_count > 0 && s.held[0].stamp.toSec() > s.timing.last_stamp();
  if (forward) {
    const double period = nominal_period(s);
    const ::ros::Duration offset = s.held[0].stamp - (s.epoch + ::ros::Duration(s.last_t + period));
    ROS_WARN("rocking_monitor: sensor '%s': new time base confirmed by %zu consistent samples (%.3f s later): "
             "its %zu items continue", s.spec.name.c_str(), s.held_count, offset.toSec(), s.items.size());
    s.timing.shift(offset.toSec());
    s.epoch += offset;
    s.have_min_offset = false;
  } else {
    ++s.resets;
    ROS_WARN("rocking_monitor: sensor '%s': earlier time base confirmed by %zu consistent samples: restarting its "
             "%zu items", s.spec.name.c_str(), s.held_count, s.items.size());
    s.timing.restart();
    s.baseline.reset();
    s.have_first = false;
    s.have_min_offset = false;
    for (std::size_t idx : s.items) make_models(items_[idx]);
    s.batch.reset();  // it points into the old models
  }
  std_msgs::Header h = header;
  const std::size_t n = s.held_count;
  s.held_count = 0;
  for (std::size_t k = 0; k < n; ++k) {
    h.stamp = s.held[k].stamp;
    step_sample(si, h, s.held[k].reading, std::chrono::steady_clock::now());
  }
}

// The sample's stamp against the sensor's last: false for a duplicate or out-of-order one (dropped);
// a jump back restarts the sensor's items, a gap is skipped (issue 19). `dt`: between the stamps, s.
bool RockingMonitor::admit_stamp(Sensor& s, const std_msgs::Header& header, core::SampleTiming::Verdict& verdict,
                                 double& dt) {
  using V = core::SampleTiming::Verdict;
  verdict = s.timing.classify(header.stamp.toSec(), dt);
  switch (verdict) {
    case V::Duplicate:
    case V::OutOfOrder:
      ROS_WARN_THROTTLE(5.0, "rocking_monitor: sensor '%s': %s stamp %.6f dropped (last %.6f)", s.spec.name.c_str(),
                        verdict == V::Duplicate ? "duplicate" : "out-of-order", header.stamp.toSec(), s.timing.last_stamp());
      return false;
    case V::BackwardJump:
      ++s.resets;
      ROS_WARN("rocking_monitor: sensor '%s': time jumped back to %.3f s: restarting its %zu items",
               s.spec.name.c_str(), header.stamp.toSec(), s.items.size());
      s.baseline.reset();
      for (std::size_t idx : s.items) make_models(items_[idx]);
      s.batch.reset();
      break;
    case V::AcceptGap: {
      // Issue 19: a data gap is not bridged by invented motion. The items were frozen (stale) through
      // it and continue from their state as if this sample followed the last one by one period: the
      // gap's time is skipped (the epoch moves), its missing periods are counted as lost in transport.
      const double period = nominal_period(s);
      if (period > 0.0 && period < dt) {
        s.epoch += ::ros::Duration(dt - period);
        s.frozen_s += dt - period;
        ROS_WARN_THROTTLE(5.0, "rocking_monitor: sensor '%s': %.3f s data gap, not bridged: its items were frozen and "
                          "continue from their state (%lu gaps)", s.spec.name.c_str(), dt,
                          static_cast<unsigned long>(s.timing.counters().gaps));
      }
      break;
    }
    default: break;
  }
  return true;
}

// Lost in transport: whole periods missing at the nominal rate, from the stamps alone.
void RockingMonitor::count_lost_in_transport(Sensor& s, double stamp_dt) {
  if (stamp_dt > 0.0 && (s.min_dt == 0.0 || stamp_dt < s.min_dt)) s.min_dt = stamp_dt;
  const double period = nominal_period(s);
  // Samples that arrived but were not stepped (rejected, dropped: counted as such) are not lost.
  const long arrived = static_cast<long>(s.received - s.received_at_last_step) - 1;
  const long missing = (period > 0.0 ? std::lround(stamp_dt / period) - 1 : 0) - std::max(0L, arrived);
  if (missing > 0) s.lost_in_transport += static_cast<std::uint64_t>(missing);
}

// Serial: items still waiting for their transform, or starting late, are not stepped. Once all
// step, that stays so until the batch is rebuilt: the check (a cache miss per item) is skipped.
void RockingMonitor::ready_items(Sensor& s, double t, const Eigen::Vector3d& a, const ::ros::Time& stamp) {
  bool all = true;
  for (std::size_t k = 0; k < s.items.size(); ++k) {
    Item& it = items_[s.items[k]];
    if (it.ready) it.stamp = s.stepped_stamp;  // keeps its last step's stamp while not ready
    it.ready = false;
    s.in_ready[k] = 0;
    if (!it.has_rotation && !lookup_rotation(it, s.frame)) {
      ++it.samples_without_transform;
      all = false;
      continue;
    }
    if (!it.monitor->started()) {  // its transform arrived late: start now
      const Eigen::Vector3d ai = it.rotation * a;
      const Eigen::Vector3d gi = it.entry.spec.input_gain * ai;  // the nominal item's scale; members their own
      it.monitor->start(t, gi.x(), gi.y(), gi.z(), s.dt_nominal);
      if (it.ensemble) it.ensemble->start(t, ai.x(), ai.y(), ai.z(), s.dt_nominal);
      it.stamp = stamp;
      s.batch->refresh(k);
      all = false;
      continue;
    }
    it.ready = true;
    s.in_ready[k] = 1;
    s.rotations[k] = it.rotation;
  }
  s.all_ready = all;
}

// Items are independent: step them in parallel when ~threads > 1 (results do not depend on it).
// The batch defers item-samples that change nothing reported (at rest, overturned, or rocking without
// an event: docs/performance.md), exactly.
void RockingMonitor::step_items(Sensor& s, const Eigen::Vector3d& a, double dt) {
  std::atomic<std::uint64_t> deferred{0};
  auto step_range = [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      if (!s.in_ready[k]) continue;
      // the nominal item at its catalogue input_gain (1 unless given); ensembles scale per member
      // (rotated first, then scaled: Eigen would fold the scalar into the product and round otherwise)
      const Eigen::Vector3d ri = s.rotations[k] * a;
      const Eigen::Vector3d ai = s.gains[k] * ri;
      s.in_x[k] = ai.x();
      s.in_y[k] = ai.y();
      s.in_z[k] = ai.z();
    }
    deferred += s.batch->step(begin, end, s.in_x.data(), s.in_y.data(), s.in_z.data(), dt, s.in_ready.data());
    if (!s.has_ensembles) return;
    for (std::size_t k = begin; k < end; ++k) {
      Item& it = items_[s.items[k]];
      if (!s.in_ready[k] || !it.ensemble) continue;
      const Eigen::Vector3d ai = s.rotations[k] * a;  // unscaled: each member applies its own input_gain
      const auto e0 = std::chrono::steady_clock::now();
      it.ensemble->step(ai.x(), ai.y(), ai.z(), dt);
      it.ensemble_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - e0).count();
    }
  };
  if (arena_ && s.items.size() >= 64) {
    arena_->execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, s.items.size(), 32),
                        [&](const tbb::blocked_range<std::size_t>& r) { step_range(r.begin(), r.end()); });
    });
  } else {
    step_range(0, s.items.size());
  }
  s.deferred += deferred.load();
}

// Serial: publish what happened, in catalogue order (an Item is touched only when it has events).
void RockingMonitor::publish_sample_events(Sensor& s, const ::ros::Time& stamp) {
  criteria_wanted_ = criteria_pub_.getNumSubscribers() > 0;
  for (std::size_t k = 0; k < s.items.size(); ++k) {
    if (!s.in_ready[k]) continue;
    // From the batch's compact flags: most items have no event, and reading each item's own
    // event counts was a cache miss per item on this (serial) path.
    const std::uint8_t f = s.batch->event_flags(k);
    if ((criteria_wanted_ && (f & core::MonitorBatch::kHasChanges)) || (f & core::MonitorBatch::kHasAlarms))
      publish_events(items_[s.items[k]], s.batch->events(k), stamp);
    if (!s.has_ensembles) continue;
    Item& it = items_[s.items[k]];
    if (it.ensemble && it.ensemble->events().count > 0) publish_crossings(it, it.ensemble->events(), stamp);
  }
  publish_pending_alarms();  // one fsync of the journal, then the sample's alarms
}

// The sample's accounting (processing time, lag, overload), the event's end, the snapshot and the states.
void RockingMonitor::finish_sample(Sensor& s, const ::ros::Time& stamp, std::chrono::steady_clock::time_point wall_start) {
  s.last_processing_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  s.max_processing_s = std::max(s.max_processing_s, s.last_processing_s);
  s.total_processing_s += s.last_processing_s;
  ++s.processed;
  s.last_input_clock = ::ros::Time::now();
  s.received_at_last_step = s.received;
  // Lag: how much later than its best so far this sample is stepped (node clock - stamp, minus its
  // minimum): a sensor clock offset from the node's (own clock, epoch records) is no lag.
  const double offset = (s.last_input_clock - stamp).toSec();
  if (s.last_input_clock.isZero() || catching_up_) {
    // No clock yet (sim time before the first /clock): no lag to measure.
  } else if (!s.have_min_offset || offset < s.min_offset_s) {
    s.min_offset_s = offset;
    s.have_min_offset = true;
  }
  s.lag_s = s.have_min_offset && !catching_up_ ? offset - s.min_offset_s : 0.0;
  s.max_lag_s = std::max(s.max_lag_s, s.lag_s);
  if (!catching_up_) update_overload(s);  // history samples are old by design: no overload from their age
  check_event_end(stamp);  // issue 29: the shaking stopped: the event ends, its levels re-armed
  // Issue 29: a state snapshot every ~snapshot_period of input time, spaced further for a catalogue
  // that takes long to encode (~snapshot_max_load); encoded now, written by the writer's thread.
  if (snapshot_writer_ && (last_snapshot_stamp_.isZero() || stamp < last_snapshot_stamp_ ||
                           (stamp - last_snapshot_stamp_).toSec() >= snapshot_interval_))
    take_snapshot(stamp);
  if (state_rate_ == 0.0) {
    // A state per sample unless overloaded for long: then 1 Hz of the node's clock.
    if (!shedding_states() || last_shed_states_.isZero() || (s.last_input_clock - last_shed_states_).toSec() >= 1.0 ||
        s.last_input_clock < last_shed_states_) {
      publish_states();
      last_shed_states_ = s.last_input_clock;
    } else {
      ++shed_states_;
    }
  }
}

void RockingMonitor::step_sample(std::size_t si, const std_msgs::Header& header, const Eigen::Vector3d& reading,
                                 std::chrono::steady_clock::time_point wall_start) {
  Sensor& s = sensors_[si];
  double dt = 0.0;
  using V = core::SampleTiming::Verdict;
  V verdict;
  if (!admit_stamp(s, header, verdict, dt)) return;
  if (verdict == V::First || verdict == V::BackwardJump) {
    s.epoch = header.stamp;
    s.last_t = 0.0;
    s.frozen_s = 0.0;  // the items start afresh
  }
  const double stamp_dt = dt;  // between the stamps, s (a gap's full length)
  const double t = (header.stamp - s.epoch).toSec();
  if (verdict == V::Accept || verdict == V::AcceptGap) {
    dt = t - s.last_t;
    s.last_t = t;
  }
  s.frame = s.spec.frame_id.empty() ? header.frame_id : s.spec.frame_id;
  const Eigen::Vector3d a = s.baseline.remove(reading, dt);
  track_quiet(s, a, header.stamp);
  if (s.topic_diag) s.topic_diag->tick(header.stamp);
  s.last_stamp = header.stamp;
  if (verdict == V::First || verdict == V::BackwardJump) {
    s.have_first = true;
    s.first_t = t;
    s.first_a = a;
    return;
  }
  if (s.have_first) {
    s.dt_nominal = dt;
    start_items(s, s.first_t, s.first_a);
    s.have_first = false;
    s.batch.reset();
  }
  if (!s.batch) rebuild_batch(s);  // allocates: only after a (re)start
  s.mean_dt = s.mean_dt == 0.0 ? dt : 0.99 * s.mean_dt + 0.01 * dt;
  count_lost_in_transport(s, stamp_dt);
  if (!s.all_ready) ready_items(s, t, a, header.stamp);
  step_items(s, a, dt);
  s.stepped_stamp = header.stamp;  // the input stamp of every ready item (input_stamp())
  publish_sample_events(s, header.stamp);
  finish_sample(s, header.stamp, wall_start);
}

}  // namespace rocking_monitor::live
