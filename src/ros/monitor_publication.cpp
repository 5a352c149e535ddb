// RockingMonitor's publication: criterion changes and overturn alarms, the item states (every
// sample or on the state timer), and the markers and tf of each item's rotated body.
#include "rocking_monitor/ros/monitor.hpp"

#include <cstdio>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>

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

// An item's body as drawn: its pose in the item frame (origin on the floor below the centre of
// mass), its depth, the y of its centre and whether the pure-rocking model holds (else faded).
struct DrawnBody {
  Eigen::Isometry3d pose;
  double depth;
  double centre_y;
  bool valid;
};

// The contact mode of a 3-D item, as the planar contact model's (RockingState::CONTACT_*).
std::uint8_t contact_mode_3d(const core::Rocking3DModel& solid) {
  switch (solid.mode()) {
    case core::Mode3D::Rest: return RockingState::CONTACT_REST;
    case core::Mode3D::Slide: return RockingState::CONTACT_SLIDE;
    case core::Mode3D::Flight: return RockingState::CONTACT_FLIGHT;
    case core::Mode3D::Overturned: return RockingState::CONTACT_OVERTURNED;
    default: return solid.pivot_slip_velocity().squaredNorm() > 0.0 ? RockingState::CONTACT_SLIDE_ROCK : RockingState::CONTACT_ROCK;
  }
}

Eigen::Isometry3d about_pivot(const Eigen::Vector3d& pivot, const Eigen::Matrix3d& r) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = r;
  t.translation() = pivot - r * pivot;
  return t;
}

// Item frame: origin on the floor below the centre of mass, x across the width, y across the
// depth, z up. x plane: corner 1 at x = -nu1 B, corner 2 at x = +nu2 B, theta > 0 about -y. y plane:
// corner 1 at y = -nu1_y D, corner 2 at y = +nu2_y D, theta > 0 about +x. The body drawn is tilted
// by the y plane's rotation, then the x plane's (the planes are independent: a picture, not a model).
DrawnBody drawn_body(const core::ItemMonitor& monitor, const core::ItemSummary& sm) {
  const core::PlaneSummary& px = sm.plane[0];
  const core::Body& b = monitor.plane(core::Plane::X).body();  // geometry: constant
  DrawnBody out;
  out.pose = about_pivot(Eigen::Vector3d(px.side >= 0 ? -b.nu1() * b.width() : b.nu2() * b.width(), 0.0, 0.0),
                         Eigen::AngleAxisd(-px.theta, Eigen::Vector3d::UnitY()).toRotationMatrix());
  out.depth = 0.5 * b.width();  // no depth given: drawn half as deep as wide
  out.centre_y = 0.0;
  out.valid = px.violations == 0;
  if (sm.planes > 1) {
    const core::PlaneSummary& py = sm.plane[1];
    const core::Body& d = monitor.plane(core::Plane::Y).body();
    out.pose = out.pose * about_pivot(Eigen::Vector3d(0.0, py.side >= 0 ? -d.nu1() * d.width() : d.nu2() * d.width(), 0.0),
                                      Eigen::AngleAxisd(py.theta, Eigen::Vector3d::UnitX()).toRotationMatrix());
    out.depth = d.width();
    out.valid = out.valid && py.violations == 0;
    out.centre_y = (d.nu2() - d.nu1()) * d.width() / 2.0;
  }
  if (const core::Rocking3DModel* solid = monitor.solid(); solid && sm.solid_active) {
    // The 3-D model's own pose (full orientation, the pivot it turns about), moved from the
    // catalogue's floor frame to the item frame (origin on the floor below the centre of mass).
    const Eigen::Vector3d& c = solid->body().centre_of_mass();
    const Eigen::Vector3d below(c.x(), c.y(), 0.0);
    out.pose.linear() = solid->rotation();
    out.pose.translation() = solid->rotation() * below + solid->translation() - below;
  }
  return out;
}

// The item frame -> drawn body transform (child frame: the item's frame + ~marker_frame_suffix).
void fill_transform(geometry_msgs::TransformStamped& t, const Eigen::Isometry3d& pose, const std::string& frame,
                    const std::string& suffix) {
  const Eigen::Matrix3d r = pose.linear();
  const Eigen::Vector3d shift = pose.translation();
  t.header.frame_id = frame;
  t.child_frame_id.assign(frame).append(suffix);
  t.transform.translation.x = shift.x();
  t.transform.translation.y = shift.y();
  t.transform.translation.z = shift.z();
  t.transform.rotation = tf2::toMsg(Eigen::Quaterniond(r));
}

// The body's box, coloured by its mode.
void fill_box(visualization_msgs::Marker& mk, int id, const std::string& frame, const core::Body& b,
              const DrawnBody& drawn, const core::ItemSummary& sm) {
  const Eigen::Matrix3d r = drawn.pose.linear();
  mk.header.frame_id = frame;
  mk.ns = "items";
  mk.id = id;
  mk.type = visualization_msgs::Marker::CUBE;
  mk.action = visualization_msgs::Marker::ADD;
  const Eigen::Vector3d centre((b.nu2() - b.nu1()) * b.width() / 2.0, drawn.centre_y, b.cg_height());
  const Eigen::Vector3d c = drawn.pose * centre;
  mk.pose.position.x = c.x();
  mk.pose.position.y = c.y();
  mk.pose.position.z = c.z();
  mk.pose.orientation = tf2::toMsg(Eigen::Quaterniond(r));
  mk.scale.x = b.width();
  mk.scale.y = drawn.depth;
  mk.scale.z = 2.0 * b.cg_height();
  mk.color = color(sm.mode, drawn.valid);
}

// The label above the box: "<id> <mode>" (and the worst plane's mode of a two-plane item).
void fill_label(visualization_msgs::Marker& label, const visualization_msgs::Marker& mk, const core::Body& b,
                const std::string& id, const core::ItemSummary& sm) {
  // The label: the box's fields but these (what a copy of the box, then changed, would be).
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
  label.text.assign(id).append(" ").append(core::to_string(sm.mode));
  if (sm.planes > 1 && sm.mode != ItemMode::Rest) label.text.append(" (").append(core::to_string(sm.worst)).append(")");
  label.color.r = label.color.g = label.color.b = label.color.a = 1.0f;
}

}  // namespace

void RockingMonitor::publish_events(Item& it, const core::ItemEvents& ev, const ::ros::Time& stamp) {
  const core::ItemSpec& spec = it.entry.spec;
  for (int i = 0; i < (criteria_wanted_ ? ev.change_count : 0); ++i) {
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
    m.cause = static_cast<std::uint8_t>(a.cause);
    // the 3-D model decides the item: it reached the level on its base polygon, not in a plane
    const bool solid = it.monitor->solid_active();
    m.plane = solid ? "3d" : core::to_string(a.plane);
    const double epoch = sensors_[it.sensor].epoch.toSec();
    m.event_time = epoch + a.time;
    m.time_since_first_sample = a.time;
    m.rotation_ratio = a.rotation_ratio;
    m.frozen_s = sensors_[it.sensor].frozen_s;
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
        const char* how = a.cause == core::AlarmCause::FellOffSupport ? " (fell off its support)" : "";
        std::snprintf(text, sizeof text, "rocking_monitor: OVERTURNED%s: %s (%s), %s (plane %s), %s [event %s #%lu]",
                      how, spec.id.c_str(), spec.description.c_str(), across, m.plane.c_str(), when.c_str(),
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
  auto batch = std::make_shared<AlarmBatch>();
  batch->alarms.swap(pending_alarms_);
  batch->probability_alarms.swap(pending_probability_alarms_);
  batch->logs.swap(pending_logs_);
  const std::size_t unlogged = unlogged_overturned_ + unlogged_committed_ + unlogged_beyond_ + unlogged_probability_;
  if (unlogged > 0) {
    char text[512];
    std::snprintf(text, sizeof text,
                  "rocking_monitor: and %zu more alarms of this sample (%zu OVERTURNED, %zu COMMITTED, %zu BEYOND_TIPPING, "
                  "%zu probability alarms), not logged one by one: each is on ~alarms / ~probability_alarms and in "
                  "the journal",
                  unlogged, unlogged_overturned_, unlogged_committed_, unlogged_beyond_, unlogged_probability_);
    batch->logs.push_back({unlogged_overturned_ > 0, text});
    unlogged_overturned_ = unlogged_committed_ = unlogged_beyond_ = unlogged_probability_ = 0;
  }
  // Published once the journal has them on disk, by its thread; the next sample's alarms wait for it.
  journal_.sync_async([this, batch](const std::string& e) { publish_alarm_batch(*batch, e); });
}

void RockingMonitor::publish_alarm_batch(const AlarmBatch& batch, const std::string& journal_error) {
  if (!journal_error.empty()) {
    ++journal_errors_;
    ROS_ERROR("rocking_monitor: alarm journal: %s: %zu alarms published without being on disk", journal_error.c_str(),
              batch.alarms.size() + batch.probability_alarms.size());
  }
  for (const OverturnAlarm& m : batch.alarms) {
    ++alarms_published_;
    alarms_pub_.publish(m);
  }
  for (const ProbabilityAlarm& m : batch.probability_alarms) probability_alarms_pub_.publish(m);
  for (const PendingLog& l : batch.logs) {
    if (l.error) ROS_ERROR("%s", l.text.c_str());
    else ROS_WARN("%s", l.text.c_str());
  }
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

void RockingMonitor::fill_plane(const core::PlaneSummary& p, PlaneState& out) {
  out.mode = static_cast<std::uint8_t>(p.mode);
  out.pivot = p.side;
  out.theta = p.theta;
  out.theta_dot = p.omega;
  out.rotation_ratio = p.rotation_ratio;
  out.energy_margin = p.energy_margin;
  out.impacts = p.impacts;
  out.violations = p.violations;
  out.contact_mode = static_cast<std::uint8_t>(p.contact_mode);
  out.slip = p.slip;
  out.model = core::to_string(p.model);
}

const core::ItemSummary& RockingMonitor::summary(Item& it) {
  Sensor& s = sensors_[it.sensor];
  if (s.batch) return s.batch->summary(it.slot);
  core::summarize(*it.monitor, it.summary);  // no batch (before the first step after a start): nothing deferred
  return it.summary;
}

// The item's state from its summary; a 3-D item's pose from its model (never deferred by the batch,
// so it needs no sync). Not the ensemble, input stamp and staleness (filled at every publication).
void RockingMonitor::fill_state(const Item& it, const core::ItemSummary& sm, RockingState& out) const {
  fill_plane(sm.plane[0], out.x);
  if (sm.planes > 1) fill_plane(sm.plane[1], out.y);
  const PlaneState& w = sm.worst == core::Plane::X ? out.x : out.y;
  out.mode = static_cast<std::uint8_t>(sm.mode);
  out.plane_count = sm.planes;
  out.plane = core::to_string(sm.worst);
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
  out.tilt = 0.0;
  out.contact.clear();
  out.support_margin = std::numeric_limits<double>::quiet_NaN();
  if (const core::Rocking3DModel* solid = it.monitor->solid(); solid && sm.solid_active) {
    out.model = "rocking_3d";
    out.pivot = 0;
    out.tilt = solid->tilt();
    out.theta = out.tilt;
    out.theta_dot = solid->angular_velocity().norm();
    out.rotation_ratio = solid->rotation_ratio();
    out.impacts = static_cast<std::uint32_t>(solid->outcome().impacts);
    out.energy_margin = solid->margin().margin;
    out.contact_mode = contact_mode_3d(*solid);
    const int k = solid->contact(), face = solid->face();
    const bool base_vertex = k < solid->body().vertex_count();
    // (on a support, numbered as the catalogue's base polygon, or on the support's own edge)
    const int own = solid->base_contact();
    if (solid->mode() == core::Mode3D::Edge)
      out.contact = own >= 0 ? "edge " + std::to_string(own + 1) : std::string("the support's edge");
    if (solid->mode() == core::Mode3D::Vertex)
      out.contact = !base_vertex ? "hull vertex " + std::to_string(k + 1)
                    : own >= 0   ? "vertex " + std::to_string(own + 1)
                                 : std::string("a corner on the support's edge");
    // Off its base (a hull, docs/rocking_3d.md): which hull face it rocks or rests on.
    if (face != 0 && solid->mode() == core::Mode3D::Edge) out.contact.append(" of hull face ").append(std::to_string(face));
    if (face != 0 && solid->mode() == core::Mode3D::Rest) out.contact.append("hull face ").append(std::to_string(face));
    // Sliding flat on its face (issue 51): the contact mode and the slip as for the planar contact model.
    if (solid->mode() == core::Mode3D::Slide) {
      out.contact.append(face != 0 ? "sliding on hull face " + std::to_string(face) : std::string("sliding"));
    }
    if (solid->mode() == core::Mode3D::Flight) out.contact = "in flight";  // (the floor dropped faster than gravity)
    out.slip = solid->slip().norm();
    if (solid->outcome_3d().fell_off_support) out.contact = "fell off its support";
    const double margin = solid->support_margin();
    out.support_margin = std::isfinite(margin) ? margin : std::numeric_limits<double>::quiet_NaN();
  }
}

void RockingMonitor::fill_ensemble(const Item& it, RockingState& out) const {
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

// Issue 28: no sync and no walk over the items' model objects. Each item's state comes from the
// summary its batch keeps, and the kept message is refilled only for items whose summary changed
// since it was last sent (an 3-D or uncertain item: every time); input stamp and staleness for all.
// A full message of a large catalogue goes out every full_state_every_ ticks (~state_items_per_s);
// ~state_changes carries the changed items at every tick.
void RockingMonitor::publish_states() {
  const auto wall_start = std::chrono::steady_clock::now();
  for (Sensor& s : sensors_) s.stale_now = stale(s);
  ::ros::Time newest;
  for (const Item& it : items_) newest = std::max(newest, input_stamp(it));
  const bool full = state_ticks_++ % static_cast<std::uint64_t>(full_state_every_) == 0;
  if (full && states_pub_.getNumSubscribers() > 0) {
    for (std::size_t i = 0; i < items_.size(); ++i) {
      Item& it = items_[i];
      RockingState& out = states_msg_.items[i];
      const core::ItemSummary& sm = summary(it);
      if (it.states_revision != sm.revision || sm.solid_active) {
        fill_state(it, sm, out);
        it.states_revision = sm.revision;
      }
      if (it.ensemble) fill_ensemble(it, out);
      out.input_stamp = input_stamp(it);
      out.stale = sensors_[it.sensor].stale_now;
    }
    states_msg_.header.stamp = newest;
    states_pub_.publish(states_msg_);
  }
  if (state_changes_pub_.getNumSubscribers() > 0) publish_state_changes(newest);
  states_cost_.add(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
}

// The items whose state (or staleness) changed since the previous ~state_changes message; an item's
// first message after a (re)start of its sensor's items is always sent. Subscribers take one full
// ~states first, then apply these by id.
void RockingMonitor::publish_state_changes(const ::ros::Time& newest) {
  std::vector<RockingState>& out = changes_msg_.items;
  std::size_t n = 0;
  for (Item& it : items_) {
    const core::ItemSummary& sm = summary(it);
    const Sensor& s = sensors_[it.sensor];
    if (it.changes_revision == sm.revision && !sm.solid_active && !it.ensemble && s.stale_now == s.stale_in_changes)
      continue;
    if (n == out.size()) out.emplace_back();  // grows to the largest burst, then reused
    RockingState& st = out[n++];
    st.id = it.entry.spec.id;
    fill_state(it, sm, st);
    if (it.ensemble) fill_ensemble(it, st);
    else st.ensemble_size = 0;
    st.input_stamp = input_stamp(it);
    st.stale = s.stale_now;
    it.changes_revision = sm.revision;
  }
  for (Sensor& s : sensors_) s.stale_in_changes = s.stale_now;
  out.resize(n);  // keeps the capacity; elements cut off are made again when a larger burst needs them
  changes_msg_.header.stamp = newest;
  state_changes_pub_.publish(changes_msg_);
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

// Issue 28: from the items' summaries, without a sync. Kept messages: an item's marker, label and
// transform are recomputed only when its summary changed since they were last sent (or its 3-D
// model decides its pose); every item's stamps are renewed. Nothing is filled for a topic nobody
// subscribes to (its items stay due and are filled when somebody does).
void RockingMonitor::publish_markers_and_tf() {
  const auto wall_start = std::chrono::steady_clock::now();
  const bool markers_due = publish_markers_ && markers_pub_.getNumSubscribers() > 0;
  const bool tf_due = publish_tf_ && tf_pub_.getNumSubscribers() > 0;
  if (!markers_due && !tf_due) return;
  // Kept messages, refilled in place: a field's strings keep their capacity (no allocation per item).
  std::vector<visualization_msgs::Marker>& markers = markers_msg_.markers;
  std::vector<geometry_msgs::TransformStamped>& transforms = tf_msg_.transforms;
  // Both are sized for every item whenever they are filled: an item's revision covers both.
  if (markers.size() != 2 * items_.size() || transforms.size() != items_.size()) {
    markers.resize(2 * items_.size());
    transforms.resize(items_.size());
    for (Item& it : items_) it.markers_revision = Item::kUnsent;
  }
  const ::ros::Time now = ::ros::Time::now();
  for (std::size_t i = 0; i < items_.size(); ++i) {
    Item& it = items_[i];
    const core::ItemSummary& sm = summary(it);
    visualization_msgs::Marker& mk = markers[2 * i];
    visualization_msgs::Marker& label = markers[2 * i + 1];
    geometry_msgs::TransformStamped& t = transforms[i];
    mk.header.stamp = label.header.stamp = t.header.stamp = now;
    if (it.markers_revision == sm.revision && !sm.solid_active) continue;
    it.markers_revision = sm.revision;
    const core::Body& b = it.monitor->plane(core::Plane::X).body();  // geometry: constant
    const DrawnBody drawn = drawn_body(*it.monitor, sm);
    fill_transform(t, drawn.pose, it.entry.spec.frame, marker_frame_suffix_);
    fill_box(mk, static_cast<int>(i), it.entry.spec.frame, b, drawn, sm);
    fill_label(label, mk, b, it.entry.spec.id, sm);
  }
  // tf2 rejects a second transform with the same stamp (sim time may not have advanced).
  if (tf_due && !transforms.empty() && now > last_tf_stamp_) {
    tf_pub_.publish(tf_msg_);
    last_tf_stamp_ = now;
  }
  if (markers_due) markers_pub_.publish(markers_msg_);
  markers_cost_.add(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
}

}  // namespace rocking_monitor::live
