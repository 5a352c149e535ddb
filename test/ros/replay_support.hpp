#pragma once
// Offline counterpart of the monitor for the rostests: runs the ROS-free core on the same samples
// (same catalogue and parameters, read from the parameter server), so live and offline can be
// compared sample for sample.

#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <ros/ros.h>

#include "rocking_monitor/motion/gravity_baseline.hpp"
#include "rocking_monitor/monitoring/item_ensemble.hpp"
#include "rocking_monitor/monitoring/item_monitor.hpp"
#include "rocking_monitor/monitoring/uncertain_item.hpp"
#include "rocking_monitor/motion/sample_timing.hpp"
#include "rocking_monitor/ros/catalogue.hpp"

namespace rocking_monitor::test {

struct OfflineState {
  std::uint8_t mode = 0;
  double theta[core::kPlaneCount] = {0.0, 0.0};  // x, y plane
  std::uint32_t impacts[core::kPlaneCount] = {0, 0};
  int ensemble_size = 0;
  double p[core::kLevelCount] = {0.0, 0.0, 0.0};  // beyond tipping, committed, overturned
};

struct OfflineCrossing {
  std::string item;
  int level = 0;  // 2, 3, 4 as in the messages
  double time_since_first_sample = 0.0;
  double probability = 0.0;
};

struct OfflineAlarm {
  std::string item;
  std::uint8_t level = 0;
  double stamp = 0.0;  // input stamp, s
  std::string plane;   // "x" or "y"
  double time_since_first_sample = 0.0;  // s
};

/// Reads the monitor's catalogue and solver parameters from `ns` and replays samples through
/// core::ItemMonitor exactly as the node does for one Imu sensor whose frame is `sensor_frame`.
class OfflineMonitor {
 public:
  OfflineMonitor(const std::string& ns, const std::string& sensor_frame) {
    ::ros::NodeHandle nh(ns);
    XmlRpc::XmlRpcValue sensors, items;
    if (!nh.getParam("sensors", sensors) || !nh.getParam("items", items))
      throw std::runtime_error("no catalogue under " + ns);
    catalogue_ = live::parse_catalogue(sensors, items);
    std::string method = "dopri5";
    nh.getParam("method", method);
    core::parse_method(method, options_.solver.method);
    options_.solver.tol = number(nh, "tol", options_.solver.tol);
    nh.getParam("substeps", options_.solver.substeps);
    std::string fidelity = "adaptive";
    nh.getParam("fidelity", fidelity);
    core::parse_fidelity(fidelity.c_str(), options_.fidelity);
    const double scene_h = number(nh, "scene_envelope/horizontal", 0.0);
    const double scene_v = number(nh, "scene_envelope/vertical", 0.0);
    options_.scene = core::SceneEnvelope::from_parameters(scene_h, scene_v);
    options_.velocity_highpass_hz = number(nh, "velocity_highpass_hz", options_.velocity_highpass_hz);
    std::string mode = "tracked";
    nh.getParam("gravity_baseline/mode", mode);
    core::GravityBaseline::Config bc;
    bc.mode = mode == "fixed" ? core::GravityBaseline::Mode::Fixed
              : mode == "initial" ? core::GravityBaseline::Mode::Initial
                                  : core::GravityBaseline::Mode::Tracked;
    bc.time_constant = number(nh, "gravity_baseline/time_constant", bc.time_constant);
    bc.quiet_threshold = number(nh, "gravity_baseline/quiet_threshold", bc.quiet_threshold);
    baseline_ = core::GravityBaseline(bc);
    core::SampleTiming::Config tc;
    tc.max_gap = number(nh, "max_gap", tc.max_gap);
    tc.backward_jump = number(nh, "backward_jump", tc.backward_jump);
    timing_ = core::SampleTiming(tc);
    int ensemble_size = 32, ensemble_seed = 1;
    nh.getParam("ensemble_size", ensemble_size);
    nh.getParam("ensemble_seed", ensemble_seed);
    const double alarm_probability = number(nh, "alarm_probability", 0.5);
    for (const auto& entry : catalogue_.items) {
      items_.emplace_back(entry.spec, options_);
      ensembles_.emplace_back();
      if (entry.uncertain.uncertain())
        ensembles_.back() = std::make_unique<core::ItemEnsemble>(
            core::draw_members(entry.uncertain, entry.ensemble_size > 0 ? entry.ensemble_size : ensemble_size,
                               static_cast<std::uint64_t>(ensemble_seed)),
            options_,
            alarm_probability);
      // The pose gives the item frame in its parent (the sensor frame here): v_item = q^-1 v_sensor.
      Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
      if (entry.pose.given && entry.pose.parent_frame == sensor_frame) {
        const Eigen::Quaterniond q = Eigen::AngleAxisd(entry.pose.yaw, Eigen::Vector3d::UnitZ()) *
                                     Eigen::AngleAxisd(entry.pose.pitch, Eigen::Vector3d::UnitY()) *
                                     Eigen::AngleAxisd(entry.pose.roll, Eigen::Vector3d::UnitX());
        r = q.conjugate().toRotationMatrix();
      }
      rotations_.push_back(r);
    }
  }

  /// One Imu reading (specific force, m/s^2) with its stamp. Time as the node keeps it: seconds
  /// since the first sample, from integer-nanosecond stamp differences.
  void push(const ::ros::Time& stamp, const Eigen::Vector3d& f) {
    double dt = 0.0;
    const auto v = timing_.classify(stamp.toSec(), dt);
    using V = core::SampleTiming::Verdict;
    if (v == V::Duplicate || v == V::OutOfOrder) return;
    if (v == V::First || v == V::BackwardJump) {
      epoch_ = stamp;
      last_t_ = 0.0;
    }
    const double t = (stamp - epoch_).toSec();
    if (v == V::Accept || v == V::AcceptGap) {
      dt = t - last_t_;
      last_t_ = t;
    }
    const Eigen::Vector3d a = baseline_.remove(f, dt);
    if (v == V::First || v == V::BackwardJump) {
      first_a_ = a;
      have_first_ = true;
      return;
    }
    if (have_first_) {
      for (std::size_t i = 0; i < items_.size(); ++i) {
        const Eigen::Vector3d ai = rotations_[i] * first_a_;
        const Eigen::Vector3d gi = items_[i].spec().input_gain * ai;  // the nominal item's scale (issue 41)
        items_[i].start(0.0, gi.x(), gi.y(), gi.z(), dt);
        if (ensembles_[i]) ensembles_[i]->start(0.0, ai.x(), ai.y(), ai.z(), dt);
      }
      have_first_ = false;
    }
    std::vector<OfflineState>& row = states_[stamp_key(stamp.toSec())];
    for (std::size_t i = 0; i < items_.size(); ++i) {
      const Eigen::Vector3d ai = rotations_[i] * a;
      const Eigen::Vector3d gi = items_[i].spec().input_gain * ai;  // members: ItemEnsemble scales its own
      const core::ItemEvents& ev = items_[i].step(gi.x(), gi.y(), gi.z(), dt);
      for (int k = 0; k < ev.alarm_count; ++k)
        alarms_.push_back({items_[i].spec().id, static_cast<std::uint8_t>(ev.alarms[k].level), stamp.toSec(),
                           core::to_string(ev.alarms[k].plane), ev.alarms[k].time});
      OfflineState s;
      if (ensembles_[i]) {
        const core::EnsembleEvents& ee = ensembles_[i]->step(ai.x(), ai.y(), ai.z(), dt);
        for (int k = 0; k < ee.count; ++k)
          if (ee.crossings[k].level != core::Level::BeyondTipping)
            crossings_.push_back({items_[i].spec().id, static_cast<int>(ee.crossings[k].level) + 2, ee.crossings[k].time,
                                  ensembles_[i]->probability(ee.crossings[k].level)});
        s.ensemble_size = ensembles_[i]->size();
        for (int l = 0; l < core::kLevelCount; ++l) s.p[l] = ensembles_[i]->probability(static_cast<core::Level>(l));
      }
      s.mode = static_cast<std::uint8_t>(items_[i].mode());
      for (int p = 0; p < items_[i].plane_count(); ++p) {
        const core::PlaneMonitor& pm = items_[i].plane(static_cast<core::Plane>(p));
        s.theta[p] = pm.theta();
        s.impacts[p] = static_cast<std::uint32_t>(pm.impacts());
      }
      row.push_back(s);
    }
  }

  static long long stamp_key(double t) { return std::llround(t * 1e6); }  // microseconds
  const std::map<long long, std::vector<OfflineState>>& states() const { return states_; }
  const std::vector<OfflineAlarm>& alarms() const { return alarms_; }
  const std::vector<OfflineCrossing>& crossings() const { return crossings_; }
  const live::Catalogue& catalogue() const { return catalogue_; }
  const std::vector<core::ItemMonitor>& items() const { return items_; }

 private:
  static double number(::ros::NodeHandle& nh, const std::string& key, double fallback) {
    XmlRpc::XmlRpcValue v;
    if (!nh.getParam(key, v)) return fallback;
    if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) return static_cast<double>(v);
    if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) return static_cast<int>(v);
    if (v.getType() == XmlRpc::XmlRpcValue::TypeString) return std::stod(static_cast<std::string>(v));
    return fallback;
  }

  live::Catalogue catalogue_;
  core::ItemMonitor::Options options_;
  core::GravityBaseline baseline_;
  core::SampleTiming timing_;
  std::vector<core::ItemMonitor> items_;
  std::vector<std::unique_ptr<core::ItemEnsemble>> ensembles_;
  std::vector<OfflineCrossing> crossings_;
  std::vector<Eigen::Matrix3d> rotations_;
  bool have_first_ = false;
  ::ros::Time epoch_;
  double last_t_ = 0.0;
  Eigen::Vector3d first_a_ = Eigen::Vector3d::Zero();
  std::map<long long, std::vector<OfflineState>> states_;
  std::vector<OfflineAlarm> alarms_;
};

}  // namespace rocking_monitor::test
