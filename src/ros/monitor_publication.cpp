// RockingMonitor's publication: criterion changes and overturn alarms, the item states (every
// sample or on the state timer), and the markers and tf of each item's rotated body.
#include "rocking_monitor/ros/monitor.hpp"

#include <cstdio>

#include <array>
#include <chrono>
#include <cstdint>

#include <Eigen/Geometry>

#include <geometry_msgs/TransformStamped.h>
#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/MarkerArray.h>

#include "rocking_monitor/monitoring/event_clock.hpp"

namespace rocking_monitor::live {
namespace {

using core::ItemMode;

std_msgs::ColorRGBA color(ItemMode m, bool valid) {
  std_msgs::ColorRGBA c;
  c.a = 0.85f;
  switch (m) {
    case ItemMode::Rest: c.r = 0.2f; c.g = 0.75f; c.b = 0.3f; break;
    case ItemMode::Rocking: c.r = 0.95f; c.g = 0.85f; c.b = 0.1f; break;
    case ItemMode::BeyondTipping: c.r = 1.0f; c.g = 0.5f; c.b = 0.0f; break;
    case ItemMode::Committed: c.r = 0.95f; c.g = 0.1f; c.b = 0.1f; break;
    case ItemMode::Overturned: c.r = 0.45f; c.g = 0.0f; c.b = 0.35f; break;
  }
  if (!valid) c.a = 0.45f;  // pure-rocking model not valid at the moment: drawn faded
  return c;
}

constexpr std::array<core::CriterionId, core::kScreeningCount> kScreening = {
    core::CriterionId::Housner, core::CriterionId::Ishiyama, core::CriterionId::IshiyamaEquivalent,
    core::CriterionId::Proposed};

}  // namespace

void RockingMonitor::publish_events(Item& it, const core::ItemEvents& ev, const ::ros::Time& stamp) {
  const core::ItemSpec& spec = it.entry.spec;
  for (int i = 0; i < ev.change_count; ++i) {
    const core::CriterionChange& c = ev.changes[i];
    CriterionExceedance m;
    m.header.stamp = stamp;
    m.header.frame_id = spec.frame;
    m.item_id = spec.id;
    m.plane = core::to_string(c.plane);
    m.criterion = static_cast<std::uint8_t>(c.id);
    m.criterion_name = core::to_string(c.id);
    m.exceeded = c.exceeded;
    m.value = c.value;
    m.threshold = c.threshold;
    m.second_value = c.second_value;
    m.second_threshold = c.second_threshold;
    criteria_pub_.publish(m);
  }
  for (int i = 0; i < ev.alarm_count; ++i) {
    const core::AlarmEvent& a = ev.alarms[i];
    OverturnAlarm m = alarm_for<OverturnAlarm>(spec, stamp);
    m.level = static_cast<std::uint8_t>(a.level);
    // the 3-D model decides the item: it reached the level on its base polygon, not in a plane
    const bool solid = it.monitor->solid_active();
    m.plane = solid ? "3d" : core::to_string(a.plane);
    const double epoch = sensors_[it.sensor].epoch.toSec();
    m.event_time = epoch + a.time;
    m.time_since_first_sample = a.time;
    m.rotation_ratio = a.rotation_ratio;
    for (core::CriterionId id : kScreening)
      (it.monitor->screening_exceeded(a.plane, id) ? m.predicted_by : m.not_predicted_by).push_back(core::to_string(id));
    if (!journal_alarm(it, m, epoch)) continue;  // journaled (fsync'd before publication); never twice
    if (pending_logs_.size() < kAlarmLinesPerSample) {
      const std::string when = core::event_time_text(epoch + a.time, epoch);
      const char* across = solid                      ? "on its base polygon (3-D model)"
                           : a.plane == core::Plane::X ? "across its width"
                                                       : "across its depth";
      char text[512];
      if (a.level == ItemMode::Overturned) {
        std::snprintf(text, sizeof text, "rocking_monitor: OVERTURNED: %s (%s), %s (plane %s), %s [event %s #%lu]",
                      spec.id.c_str(), spec.description.c_str(), across, m.plane.c_str(), when.c_str(),
                      m.event_id.c_str(), static_cast<unsigned long>(m.sequence));
      } else {
        std::snprintf(text, sizeof text, "rocking_monitor: %s: %s (%s), %s (plane %s), %s", core::to_string(a.level),
                      spec.id.c_str(), spec.description.c_str(), across, m.plane.c_str(), when.c_str());
      }
      pending_logs_.push_back({a.level == ItemMode::Overturned, text});
    } else if (a.level == ItemMode::Overturned) {
      ++unlogged_overturned_;
    } else if (a.level == ItemMode::Committed) {
      ++unlogged_committed_;
    } else {
      ++unlogged_beyond_;
    }
    pending_alarms_.push_back(std::move(m));
  }
}

void RockingMonitor::publish_pending_alarms() {
  if (pending_alarms_.empty() && pending_probability_alarms_.empty()) return;
  if (const std::string e = journal_.sync(); !e.empty()) {
    ++journal_errors_;
    ROS_ERROR("rocking_monitor: alarm journal: %s: %zu alarms published without being on disk", e.c_str(),
              pending_alarms_.size() + pending_probability_alarms_.size());
  }
  for (const OverturnAlarm& m : pending_alarms_) {
    alarms_pub_.publish(m);
    ++alarms_published_;
  }
  for (const ProbabilityAlarm& m : pending_probability_alarms_) probability_alarms_pub_.publish(m);
  for (const PendingLog& l : pending_logs_) {
    if (l.error) ROS_ERROR("%s", l.text.c_str());
    else ROS_WARN("%s", l.text.c_str());
  }
  const std::size_t unlogged = unlogged_overturned_ + unlogged_committed_ + unlogged_beyond_ + unlogged_probability_;
  if (unlogged > 0) {
    char text[512];
    std::snprintf(text, sizeof text,
                  "rocking_monitor: and %zu more alarms of this sample (%zu OVERTURNED, %zu COMMITTED, %zu BEYOND_TIPPING, "
                  "%zu probability alarms), not logged one by one: each is on ~alarms / ~probability_alarms and in "
                  "the journal",
                  unlogged, unlogged_overturned_, unlogged_committed_, unlogged_beyond_, unlogged_probability_);
    if (unlogged_overturned_ > 0) ROS_ERROR("%s", text);
    else ROS_WARN("%s", text);
    unlogged_overturned_ = unlogged_committed_ = unlogged_beyond_ = unlogged_probability_ = 0;
  }
  pending_alarms_.clear();
  pending_probability_alarms_.clear();
  pending_logs_.clear();
}

void RockingMonitor::publish_crossings(Item& it, const core::EnsembleEvents& ev, const ::ros::Time& stamp) {
  const core::ItemSpec& spec = it.entry.spec;
  const core::ItemEnsemble& e = *it.ensemble;
  for (int i = 0; i < ev.count; ++i) {
    const core::ProbabilityCrossing& c = ev.crossings[i];
    ProbabilityAlarm m = alarm_for<ProbabilityAlarm>(spec, stamp);
    m.level = static_cast<std::uint8_t>(static_cast<int>(c.level) + static_cast<int>(ItemMode::BeyondTipping));
    m.threshold = e.threshold();
    m.ensemble_size = static_cast<std::uint16_t>(e.size());
    const double epoch = sensors_[it.sensor].epoch.toSec();
    m.time_since_first_sample = c.time;
    m.event_time = epoch + c.time;
    const core::WilsonInterval w = e.interval(c.level);
    m.value.probability = e.probability(c.level);
    m.value.lower = w.lower;
    m.value.upper = w.upper;
    // Beyond tipping is not an alarm level of its own here (it says little about falling).
    if (c.level == core::Level::BeyondTipping) continue;
    if (!journal_probability_alarm(it, m, epoch)) continue;  // journaled before it is published; never twice
    if (pending_logs_.size() < kAlarmLinesPerSample) {
      char text[512];
      std::snprintf(text, sizeof text,
                    "rocking_monitor: P(%s) of %s (%s) reached %.2f [%.2f, %.2f] over %d members (threshold %.2f), %s",
                    core::to_string(static_cast<ItemMode>(m.level)), spec.id.c_str(), spec.description.c_str(),
                    m.value.probability, w.lower, w.upper, e.size(), e.threshold(),
                    core::event_time_text(epoch + c.time, epoch).c_str());
      pending_logs_.push_back({false, text});
    } else {
      ++unlogged_probability_;
    }
    pending_probability_alarms_.push_back(std::move(m));
  }
}

void RockingMonitor::fill_plane(const core::PlaneMonitor& pm, PlaneState& out) {
  out.mode = static_cast<std::uint8_t>(pm.mode());
  out.pivot = static_cast<std::int8_t>(pm.side());
  out.theta = pm.theta();
  out.theta_dot = pm.omega();
  out.rotation_ratio = pm.rotation_ratio();
  out.energy_margin = pm.margin().margin;
  out.impacts = static_cast<std::uint32_t>(pm.impacts());
  out.violations = pm.violations();
  out.contact_mode = static_cast<std::uint8_t>(pm.contact_mode());
  out.slip = pm.slip();
  out.model = pm.active_model();
}

void RockingMonitor::fill_state(const Item& it, RockingState& out) const {
  const core::ItemMonitor& im = *it.monitor;
  fill_plane(im.plane(core::Plane::X), out.x);
  if (im.two_planes()) fill_plane(im.plane(core::Plane::Y), out.y);
  const core::Plane worst = im.worst_plane();
  const PlaneState& w = worst == core::Plane::X ? out.x : out.y;
  out.mode = static_cast<std::uint8_t>(im.mode());
  out.plane_count = static_cast<std::uint8_t>(im.plane_count());
  out.plane = core::to_string(worst);
  out.pivot = w.pivot;
  out.theta = w.theta;
  out.theta_dot = w.theta_dot;
  out.rotation_ratio = w.rotation_ratio;
  out.energy_margin = w.energy_margin;
  out.impacts = w.impacts;
  out.violations = out.x.violations | out.y.violations;
  out.model_valid = out.violations == 0;
  out.contact_mode = w.contact_mode;
  out.slip = w.slip;
  out.model = w.model;
  if (const core::Rocking3DModel* solid = im.solid(); solid && im.solid_active()) {
    out.model = "rocking_3d";
    out.pivot = 0;
    out.tilt = solid->tilt();
    out.theta = out.tilt;
    out.theta_dot = solid->angular_velocity().norm();
    out.rotation_ratio = solid->rotation_ratio();
    out.impacts = static_cast<std::uint32_t>(solid->outcome().impacts);
    out.energy_margin = solid->margin().margin;
    const int k = solid->contact();
    out.contact.clear();
    if (solid->mode() == core::Mode3D::Edge) out.contact.append("edge ").append(std::to_string(k + 1));
    if (solid->mode() == core::Mode3D::Vertex) out.contact.append("vertex ").append(std::to_string(k + 1));
  }
  out.input_stamp = input_stamp(it);
  out.stale = sensors_[it.sensor].stale_now;
  if (it.ensemble) {
    const core::ItemEnsemble& e = *it.ensemble;
    out.ensemble_size = static_cast<std::uint16_t>(e.size());
    auto fill = [&](core::Level l, LevelProbability& p) {
      const core::WilsonInterval w = e.interval(l);
      p.probability = e.probability(l);
      p.lower = w.lower;
      p.upper = w.upper;
    };
    fill(core::Level::BeyondTipping, out.p_beyond_tipping);
    fill(core::Level::Committed, out.p_committed);
    fill(core::Level::Overturned, out.p_overturned);
  }
}

void RockingMonitor::publish_states() {
  const auto wall_start = std::chrono::steady_clock::now();
  sync_items();
  for (Sensor& s : sensors_) s.stale_now = stale(s);
  ::ros::Time newest;
  for (std::size_t i = 0; i < items_.size(); ++i) {
    fill_state(items_[i], states_msg_.items[i]);
    if (states_msg_.items[i].input_stamp > newest) newest = states_msg_.items[i].input_stamp;
  }
  states_msg_.header.stamp = newest;
  states_pub_.publish(states_msg_);
  states_cost_.add(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
}

void RockingMonitor::on_state_timer(const ::ros::TimerEvent&) {
  const ::ros::Time now = ::ros::Time::now();
  if (!last_now_.isZero() && now + ::ros::Duration(timing_config_.backward_jump) < last_now_) {
    reset_all("ROS time jumped back (sim time restarted?)");
  }
  last_now_ = now;
  for (Sensor& s : sensors_) {
    if (s.overloaded) update_overload(s);  // recovers once the input is drained
    journal_stale_period(s);
  }
  // Overload sheds in this order: markers and tf at once; ~states thinned to 1 Hz once the overload
  // lasted ~max_lag more (wall time: it must work when sim time stalls too).
  const bool shed_states = shedding_states();
  if (state_rate_ > 0.0) {
    if (!shed_states || last_shed_states_.isZero() || (now - last_shed_states_).toSec() >= 1.0 || now < last_shed_states_) {
      publish_states();  // else after every input sample
      last_shed_states_ = now;
    } else {
      ++shed_states_;
    }
  }
  if (last_marker_time_.isZero() || (now - last_marker_time_).toSec() >= 1.0 / marker_rate_ ||
      now < last_marker_time_) {
    if (!overload_) publish_markers_and_tf();
    else if (publish_markers_ || publish_tf_) ++shed_markers_;
    last_marker_time_ = now;
  }
  diagnostics_->update();
}

void RockingMonitor::publish_markers_and_tf() {
  if (!publish_markers_ && !publish_tf_) return;
  sync_items();
  const auto wall_start = std::chrono::steady_clock::now();
  // Kept messages, refilled in place: a field's strings keep their capacity (no allocation per item).
  std::vector<visualization_msgs::Marker>& markers = markers_msg_.markers;
  std::vector<geometry_msgs::TransformStamped>& transforms = tf_msg_.transforms;
  if (publish_markers_) markers.resize(2 * items_.size());
  if (publish_tf_) transforms.resize(items_.size());
  const ::ros::Time now = ::ros::Time::now();
  for (std::size_t i = 0; i < items_.size(); ++i) {
    const Item& it = items_[i];
    const core::PlaneMonitor& px = it.monitor->plane(core::Plane::X);
    const core::Body& b = px.body();
    // Item frame: origin on the floor below the centre of mass, x across the width, y across the
    // depth, z up. x plane: corner 1 at x = -nu1 B, corner 2 at x = +nu2 B, theta > 0 about -y. y plane:
    // corner 1 at y = -nu1_y D, corner 2 at y = +nu2_y D, theta > 0 about +x. The body drawn is tilted
    // by the y plane's rotation, then the x plane's (the planes are independent: a picture, not a model).
    auto about_pivot = [](const Eigen::Vector3d& pivot, const Eigen::Matrix3d& r) {
      Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
      t.linear() = r;
      t.translation() = pivot - r * pivot;
      return t;
    };
    const int sx = px.side();
    Eigen::Isometry3d pose = about_pivot(Eigen::Vector3d(sx >= 0 ? -b.nu1() * b.width() : b.nu2() * b.width(), 0.0, 0.0),
                                         Eigen::AngleAxisd(-px.theta(), Eigen::Vector3d::UnitY()).toRotationMatrix());
    double depth = 0.5 * b.width(), centre_y = 0.0;  // no depth given: drawn half as deep as wide
    bool valid = px.violations() == 0;
    if (it.monitor->two_planes()) {
      const core::PlaneMonitor& py = it.monitor->plane(core::Plane::Y);
      const core::Body& d = py.body();
      const int sy = py.side();
      pose = pose * about_pivot(Eigen::Vector3d(0.0, sy >= 0 ? -d.nu1() * d.width() : d.nu2() * d.width(), 0.0),
                                Eigen::AngleAxisd(py.theta(), Eigen::Vector3d::UnitX()).toRotationMatrix());
      depth = d.width();
      valid = valid && py.violations() == 0;
      centre_y = (d.nu2() - d.nu1()) * d.width() / 2.0;
    }
    if (const core::Rocking3DModel* solid = it.monitor->solid(); solid && it.monitor->solid_active()) {
      // The 3-D model's own pose (full orientation, the pivot it turns about), moved from the
      // catalogue's floor frame to the item frame (origin on the floor below the centre of mass).
      const Eigen::Vector3d& c = solid->body().centre_of_mass();
      const Eigen::Vector3d below(c.x(), c.y(), 0.0);
      pose.linear() = solid->rotation();
      pose.translation() = solid->rotation() * below + solid->translation() - below;
    }
    const Eigen::Matrix3d r = pose.linear();
    const Eigen::Vector3d shift = pose.translation();
    if (publish_tf_) {
      geometry_msgs::TransformStamped& t = transforms[i];
      t.header.stamp = now;
      t.header.frame_id = it.entry.spec.frame;
      t.child_frame_id.assign(it.entry.spec.frame).append(marker_frame_suffix_);
      t.transform.translation.x = shift.x();
      t.transform.translation.y = shift.y();
      t.transform.translation.z = shift.z();
      t.transform.rotation = tf2::toMsg(Eigen::Quaterniond(r));
    }
    if (publish_markers_) {
      visualization_msgs::Marker& mk = markers[2 * i];
      mk.header.stamp = now;
      mk.header.frame_id = it.entry.spec.frame;
      mk.ns = "items";
      mk.id = static_cast<int>(i);
      mk.type = visualization_msgs::Marker::CUBE;
      mk.action = visualization_msgs::Marker::ADD;
      const Eigen::Vector3d centre((b.nu2() - b.nu1()) * b.width() / 2.0, centre_y, b.cg_height());
      const Eigen::Vector3d c = pose * centre;
      mk.pose.position.x = c.x();
      mk.pose.position.y = c.y();
      mk.pose.position.z = c.z();
      mk.pose.orientation = tf2::toMsg(Eigen::Quaterniond(r));
      mk.scale.x = b.width();
      mk.scale.y = depth;
      mk.scale.z = 2.0 * b.cg_height();
      mk.color = color(it.monitor->mode(), valid);
      // The label: the box's fields but these (what a copy of the box, then changed, would be).
      visualization_msgs::Marker& label = markers[2 * i + 1];
      label.header = mk.header;
      label.ns = "labels";
      label.id = mk.id;
      label.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
      label.action = mk.action;
      label.pose.position.x = mk.pose.position.x;
      label.pose.position.y = mk.pose.position.y;
      label.pose.position.z = 2.0 * b.cg_height() + 0.15;
      label.pose.orientation.w = 1.0;
      label.pose.orientation.x = label.pose.orientation.y = label.pose.orientation.z = 0.0;
      label.scale.x = mk.scale.x;
      label.scale.y = mk.scale.y;
      label.scale.z = 0.1;
      const ItemMode mode = it.monitor->mode();
      label.text.assign(it.entry.spec.id).append(" ").append(core::to_string(mode));
      if (it.monitor->two_planes() && mode != ItemMode::Rest)
        label.text.append(" (").append(core::to_string(it.monitor->worst_plane())).append(")");
      label.color.r = label.color.g = label.color.b = label.color.a = 1.0f;
    }
  }
  // tf2 rejects a second transform with the same stamp (sim time may not have advanced).
  if (publish_tf_ && !transforms.empty() && now > last_tf_stamp_) {
    tf_pub_.publish(tf_msg_);
    last_tf_stamp_ = now;
  }
  if (publish_markers_) markers_pub_.publish(markers_msg_);
  markers_cost_.add(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
}

}  // namespace rocking_monitor::live
