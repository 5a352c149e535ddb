// RockingMonitor's per-sample path: an IMU or AccelStamped message in, checked, timed and freed
// of gravity, rotated into each item's frame (tf2), the items started or stepped (in parallel
// when ~threads > 1), and their events published.
#include "rocking_monitor/ros/monitor.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>

#include <geometry_msgs/TransformStamped.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace rocking_monitor::live {

void RockingMonitor::on_imu(std::size_t sensor, const sensor_msgs::ImuConstPtr& m) {
  on_sample(sensor, m->header,
            Eigen::Vector3d(m->linear_acceleration.x, m->linear_acceleration.y, m->linear_acceleration.z));
}

void RockingMonitor::on_accel(std::size_t sensor, const geometry_msgs::AccelStampedConstPtr& m) {
  on_sample(sensor, m->header, Eigen::Vector3d(m->accel.linear.x, m->accel.linear.y, m->accel.linear.z));
}

bool RockingMonitor::lookup_rotation(Item& item, const std::string& sensor_frame) {
  if (sensor_frame.empty() || sensor_frame == item.entry.spec.frame) {
    item.rotation.setIdentity();
    item.has_rotation = true;
    return true;
  }
  try {
    // Static mounting: the latest transform is the one.
    const geometry_msgs::TransformStamped t =
        tf_buffer_->lookupTransform(item.entry.spec.frame, sensor_frame, ::ros::Time(0));
    item.rotation = tf2::transformToEigen(t).rotation();
    item.has_rotation = true;
    ROS_DEBUG("rocking_monitor: item '%s' uses the transform %s <- %s", item.entry.spec.id.c_str(),
              item.entry.spec.frame.c_str(), sensor_frame.c_str());
    return true;
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
    it.monitor->start(t, ai.x(), ai.y(), ai.z(), s.dt_nominal);
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
  double dt = 0.0;
  using V = core::SampleTiming::Verdict;
  const V verdict = s.timing.classify(header.stamp.toSec(), dt);
  switch (verdict) {
    case V::Duplicate:
    case V::OutOfOrder:
      ROS_WARN_THROTTLE(5.0, "rocking_monitor: sensor '%s': %s stamp %.6f dropped (last %.6f)", s.spec.name.c_str(),
                        verdict == V::Duplicate ? "duplicate" : "out-of-order", header.stamp.toSec(), s.timing.last_stamp());
      return;
    case V::BackwardJump:
      ++s.resets;
      ROS_WARN("rocking_monitor: sensor '%s': time jumped back to %.3f s: restarting its %zu items",
               s.spec.name.c_str(), header.stamp.toSec(), s.items.size());
      s.baseline.reset();
      for (std::size_t idx : s.items) make_models(items_[idx]);
      s.batch.reset();
      break;
    case V::AcceptGap:
      ROS_WARN_THROTTLE(5.0, "rocking_monitor: sensor '%s': %.3f s gap bridged by a straight line (%lu gaps)",
                        s.spec.name.c_str(), dt, static_cast<unsigned long>(s.timing.counters().gaps));
      break;
    default: break;
  }
  if (verdict == V::First || verdict == V::BackwardJump) {
    s.epoch = header.stamp;
    s.last_t = 0.0;
  }
  const double t = (header.stamp - s.epoch).toSec();
  if (verdict == V::Accept || verdict == V::AcceptGap) {
    dt = t - s.last_t;
    s.last_t = t;
  }
  s.frame = s.spec.frame_id.empty() ? header.frame_id : s.spec.frame_id;
  const Eigen::Vector3d a = s.baseline.remove(reading, dt);
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
  // Serial: items still waiting for their transform, or starting late, are not stepped.
  for (std::size_t k = 0; k < s.items.size(); ++k) {
    Item& it = items_[s.items[k]];
    it.ready = false;
    s.in_ready[k] = 0;
    if (!it.has_rotation && !lookup_rotation(it, s.frame)) {
      ++it.samples_without_transform;
      continue;
    }
    if (!it.monitor->started()) {  // its transform arrived late: start now
      const Eigen::Vector3d ai = it.rotation * a;
      it.monitor->start(t, ai.x(), ai.y(), ai.z(), s.dt_nominal);
      if (it.ensemble) it.ensemble->start(t, ai.x(), ai.y(), ai.z(), s.dt_nominal);
      it.stamp = header.stamp;
      s.batch->refresh(k);
      continue;
    }
    it.ready = true;
    s.in_ready[k] = 1;
  }
  // Items are independent: step them in parallel when ~threads > 1 (results do not depend on it).
  // The batch defers quiet item-samples (at rest or overturned: docs/performance.md), exactly.
  std::atomic<std::uint64_t> deferred{0};
  auto step_range = [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      if (!s.in_ready[k]) continue;
      const Eigen::Vector3d ai = items_[s.items[k]].rotation * a;
      s.in_x[k] = ai.x();
      s.in_y[k] = ai.y();
      s.in_z[k] = ai.z();
    }
    deferred += s.batch->step(begin, end, s.in_x.data(), s.in_y.data(), s.in_z.data(), dt, s.in_ready.data());
    for (std::size_t k = begin; k < end; ++k) {
      Item& it = items_[s.items[k]];
      if (!it.ready) continue;
      if (it.ensemble) {
        const Eigen::Vector3d ai(s.in_x[k], s.in_y[k], s.in_z[k]);
        const auto e0 = std::chrono::steady_clock::now();
        it.ensemble->step(ai.x(), ai.y(), ai.z(), dt);
        it.ensemble_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - e0).count();
      }
      it.stamp = header.stamp;
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
  // Serial: publish what happened, in catalogue order.
  for (std::size_t k = 0; k < s.items.size(); ++k) {
    Item& it = items_[s.items[k]];
    if (!it.ready) continue;
    const core::ItemEvents& ev = s.batch->events(k);
    if (ev.change_count > 0 || ev.alarm_count > 0) publish_events(it, ev, header.stamp);
    if (it.ensemble && it.ensemble->events().count > 0) publish_crossings(it, it.ensemble->events(), header.stamp);
  }
  publish_pending_alarms();  // one fsync of the journal, then the sample's alarms
  s.last_processing_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  s.max_processing_s = std::max(s.max_processing_s, s.last_processing_s);
  s.total_processing_s += s.last_processing_s;
  ++s.processed;
  if (state_rate_ == 0.0) publish_states();
}

}  // namespace rocking_monitor::live
