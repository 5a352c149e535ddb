// Dashboard's state cache: the ROS callbacks that fill it, the deltas the update timer pushes, and the
// JSON snapshot served at /api/snapshot.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include <nlohmann/json.hpp>

#include "rocking_monitor/json_text.hpp"
#include "rocking_monitor/monitoring/item_modes.hpp"
#include "rocking_monitor/ros/dashboard.hpp"

namespace rocking_monitor::live {
namespace {

using nlohmann::json;

const char* mode_name(std::uint8_t mode) {
  switch (mode) {
    case RockingState::REST: return "REST";
    case RockingState::ROCKING: return "ROCKING";
    case RockingState::BEYOND_TIPPING: return "BEYOND_TIPPING";
    case RockingState::COMMITTED: return "COMMITTED";
    case RockingState::OVERTURNED: return "OVERTURNED";
    default: return "UNKNOWN";
  }
}

// Seconds since 1970 as ISO 8601 UTC with milliseconds ("2001-09-09T01:46:43.381Z").
std::string utc(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "";
  const auto whole = static_cast<std::time_t>(std::floor(seconds));
  int ms = static_cast<int>(std::lround((seconds - static_cast<double>(whole)) * 1000.0));
  std::time_t t = whole;
  if (ms >= 1000) { ms -= 1000; ++t; }
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[40];
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900, tm.tm_mon + 1,
                tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec, ms);
  return text;
}

json plane_json(const PlaneState& p) {
  return {{"mode", mode_name(p.mode)}, {"pivot", p.pivot}, {"theta", p.theta}, {"theta_dot", p.theta_dot},
          {"rotation_ratio", p.rotation_ratio}, {"energy_margin", p.energy_margin}, {"impacts", p.impacts},
          {"slip", p.slip}, {"model", p.model}};
}

json state_json(const RockingState& s) {
  json j = {{"mode", mode_name(s.mode)}, {"plane", s.plane}, {"plane_count", s.plane_count},
            {"pivot", s.pivot}, {"theta", s.theta}, {"theta_dot", s.theta_dot},
            {"rotation_ratio", s.rotation_ratio}, {"energy_margin", s.energy_margin}, {"impacts", s.impacts},
            {"model_valid", s.model_valid}, {"model", s.model}, {"slip", s.slip},
            {"stamp", s.input_stamp.toSec()}, {"x", plane_json(s.x)}};
  if (s.plane_count >= 2) j["y"] = plane_json(s.y);
  if (s.model == "rocking_3d") {  // the 3-D model decides: the side view turns about its contact
    j["tilt"] = s.tilt;
    j["contact"] = s.contact;
    // on a support: how far the centre of mass is inside its nearest edge, m (NaN, no JSON number: left out)
    if (std::isfinite(s.support_margin)) j["support_margin"] = s.support_margin;
  }
  if (s.ensemble_size > 0) {  // an item with uncertain parameters: P(level) over its members
    j["ensemble_size"] = s.ensemble_size;
    j["p_overturned"] = s.p_overturned.probability;
    j["p_overturned_interval"] = {s.p_overturned.lower, s.p_overturned.upper};
    j["p_committed"] = s.p_committed.probability;
  }
  return j;
}

// A delta's numbers to 6 significant digits: a screen needs no more, and 10,000 rocking items make
// every byte count (the snapshot keeps full precision).
double short_number(double v) {
  if (!std::isfinite(v)) return v;
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return std::strtod(text, nullptr);
}

// Changes smaller than these are not worth a delta: 10,000 quiet items must cost nothing.
constexpr double kRatioStep = 1e-3;   // of alpha
constexpr double kMarginStep = 1e-3;  // of the energy margin's range [-1, 1]
constexpr double kSupportStep = 1e-3;  // m: the support margin (a sliding item at rest moves only in it)
constexpr double kHistorySeconds = 60.0;  // the page's chart window

// NaN (no support) on both sides is no change.
bool same_support_margin(double a, double b) {
  return (std::isnan(a) && std::isnan(b)) || std::abs(a - b) < kSupportStep;
}

}  // namespace

void Dashboard::rebuild_index_locked(const RockingStateArray& msg, bool reread_catalogue) {
  // A restarted or reconfigured monitor may publish other items, in another order or number.
  if (reread_catalogue && !state_to_item_.empty() && state_to_item_.size() != msg.items.size()) catalogue_dirty_ = true;
  state_to_item_.resize(msg.items.size());
  for (std::size_t i = 0; i < msg.items.size(); ++i) {
    const std::string& id = msg.items[i].id;
    auto it = index_of_.find(id);
    if (it == index_of_.end()) {
      ItemGeometry g;
      g.entry.spec.id = id;
      g.from_catalogue = false;
      it = index_of_.emplace(id, items_.size()).first;
      items_.push_back(std::move(g));
      sent_.emplace_back();
      history_.emplace_back();
      if (reread_catalogue) catalogue_dirty_ = true;  // the catalogue on the parameter server may have it now
    }
    state_to_item_[i] = it->second;
  }
}

void Dashboard::on_states(const RockingStateArray::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  // Usually the same items in the same order: a pointer swap and one id comparison per item.
  bool same = state_to_item_.size() == msg->items.size();
  for (std::size_t i = 0; same && i < msg->items.size(); ++i)
    same = items_[state_to_item_[i]].entry.spec.id == msg->items[i].id;
  if (!same) rebuild_index_locked(*msg, true);
  latest_ = msg;
  latest_sent_ = false;
  ++states_received_;
}

void Dashboard::on_alarm_from(const std::string& source, const OverturnAlarm::ConstPtr& msg) {
  json frame;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // One alarm, however often it arrives (journal at start, re-sent by a restarted monitor, reconnect,
    // the pair's other monitor): core::AlarmDedup's rule, as rocking_report's and monitor_table.py's.
    const core::AlarmDedup::Result r = dedup_.add({source, msg->item_id, msg->level,
                                                   static_cast<std::int64_t>(msg->header.stamp.toNSec()),
                                                   msg->event_id, msg->sequence, msg->frozen_s == 0.0});
    if (r.outcome == core::AlarmDedup::Outcome::Repeat) return;
    if (r.outcome == core::AlarmDedup::Outcome::Merged) {
      // The same alarm from the other monitor: not shown again, unless it is the better copy (its items
      // saw every sample, the one shown came after a gap): then it replaces it, on the pages too.
      if (!r.replaces) return;
      for (Alarm& a : alarms_) {
        if (a.row != r.row) continue;
        frame = alarm_json(*msg);
        frame["replaces"] = a.msg.header.stamp.toSec();  // the page's key of the copy it showed
        a.msg = *msg;
        break;
      }
      if (frame.is_null()) return;  // already forgotten
    } else {
      alarms_.push_front({*msg, r.row});
      frame = alarm_json(*msg);
      constexpr std::size_t kMaxAlarms = 10000;  // three per item of a large site, then the oldest go
      while (alarms_.size() > kMaxAlarms) {
        dedup_.forget(alarms_.back().row);
        alarms_.pop_back();
      }
    }
  }
  // Immediately, not at the next tick: an alarm is what the operator waits for.
  publish_event("alarm", json_text(frame));
}

void Dashboard::on_criterion(const CriterionExceedance::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::string name = msg->plane + ":" + msg->criterion_name;
  auto& set = criteria_[msg->item_id];
  if (msg->exceeded) set.insert(name);
  else set.erase(name);
  latest_sent_ = false;  // criteria travel with the next delta of that item
  if (msg->item_id.size() && index_of_.count(msg->item_id)) sent_[index_of_[msg->item_id]].valid = false;
}

void Dashboard::on_diagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& msg) {
  const std::string prefix = monitor_.substr(1) + ": ";  // diagnostic_updater: "<node name>: <task>"
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& s : msg->status)
    if (s.name.compare(0, prefix.size(), prefix) == 0) health_[s.name.substr(prefix.size())] = s;
}

json Dashboard::alarm_json(const OverturnAlarm& a) {
  return {{"item", a.item_id}, {"description", a.description}, {"level", mode_name(a.level)},
          {"cause", core::to_string(static_cast<core::AlarmCause>(a.cause))},
          {"plane", a.plane}, {"event_time", a.event_time}, {"utc", utc(a.event_time)},
          {"t", a.time_since_first_sample}, {"rotation_ratio", a.rotation_ratio},
          {"stamp", a.header.stamp.toSec()}, {"predicted_by", a.predicted_by},
          {"not_predicted_by", a.not_predicted_by}, {"event_id", a.event_id}, {"sequence", a.sequence},
          {"frozen_s", std::isnan(a.frozen_s) ? json(nullptr) : json(a.frozen_s)}};
}

json Dashboard::health_json_locked() const {
  json out = json::array();
  for (const auto& [name, s] : health_) {
    json values = json::object();
    for (const auto& kv : s.values) values[kv.key] = kv.value;
    out.push_back({{"name", name}, {"level", static_cast<int>(s.level)}, {"message", s.message},
                   {"values", std::move(values)}});
  }
  return out;
}

json Dashboard::item_json_locked(std::size_t index, const RockingState* state) const {
  const ItemGeometry& g = items_[index];
  const auto& spec = g.entry.spec;
  json j = {{"id", spec.id}, {"description", spec.description}, {"known", g.from_catalogue}};
  if (g.from_catalogue) {
    j["width"] = spec.body.width;
    j["cg_height"] = spec.body.cg_height;
    j["eccentricity"] = spec.body.nu1;
    if (spec.depth.given()) {
      j["depth"] = spec.depth.depth;
      j["eccentricity_y"] = spec.depth.eccentricity_y;
    }
    if (spec.solid) {  // the 3-D description: the side view draws the base polygon and its contact
      json base = json::array();
      for (const auto& v : spec.solid->base) base.push_back({v.x(), v.y()});
      j["base_polygon"] = std::move(base);
      const auto& c = spec.solid->centre_of_mass;
      j["centre_of_mass"] = {c.x(), c.y(), c.z()};
    }
    const ItemPose& p = g.entry.pose;
    if (p.given) j["pose"] = {{"frame", p.parent_frame}, {"x", p.x}, {"y", p.y}, {"yaw", p.yaw}};
  }
  if (state != nullptr) j["state"] = state_json(*state);
  if (auto c = criteria_.find(spec.id); c != criteria_.end() && !c->second.empty()) j["criteria"] = c->second;
  return j;
}

std::string Dashboard::snapshot_json() const {
  // Copy under the lock (a shared pointer and small containers); format outside it, so a large
  // snapshot never holds up the ROS callbacks.
  json out;
  RockingStateArray::ConstPtr latest;
  std::vector<const RockingState*> state_of;
  json items = json::array();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    latest = latest_;
    state_of.assign(items_.size(), nullptr);
    if (latest)
      for (std::size_t i = 0; i < latest->items.size() && i < state_to_item_.size(); ++i)
        state_of[state_to_item_[i]] = &latest->items[i];
    for (std::size_t i = 0; i < items_.size(); ++i) items.push_back(item_json_locked(i, state_of[i]));
    json alarms = json::array();
    for (const auto& a : alarms_) alarms.push_back(alarm_json(a.msg));
    out["alarms"] = std::move(alarms);
    out["health"] = health_json_locked();
    out["states_received"] = states_received_;
    // Copies not shown, counted: the pair's other monitor's (merged) and ones received again (repeats).
    out["alarm_copies"] = {{"merged", dedup_.merged()}, {"replaced", dedup_.replaced()}, {"repeats", dedup_.repeats()}};
  }
  out["monitor"] = monitor_;
  out["pair"] = pair_;
  out["update_rate"] = update_rate_;
  out["stamp"] = latest ? latest->header.stamp.toSec() : 0.0;
  out["items"] = std::move(items);
  return json_text(out);
}

std::string Dashboard::item_json(const std::string& id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = index_of_.find(id);
  if (it == index_of_.end()) return "";
  const RockingState* state = nullptr;
  if (latest_)
    for (std::size_t i = 0; i < latest_->items.size() && i < state_to_item_.size(); ++i)
      if (state_to_item_[i] == it->second) state = &latest_->items[i];
  return json_text(item_json_locked(it->second, state));
}

std::string Dashboard::history_json(const std::string& id) const {
  json points = json::array();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (const auto it = index_of_.find(id); it != index_of_.end() && it->second < history_.size())
      for (const Point& p : history_[it->second]) points.push_back({p.t, p.ratio, p.margin});
  }
  return json_text(json{{"id", id}, {"points", std::move(points)}});
}

void Dashboard::on_update_timer(const ::ros::WallTimerEvent&) {
  json changed = json::array();
  double stamp = 0.0;
  bool push_health = false;
  json health;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (latest_ && !latest_sent_) {
      stamp = latest_->header.stamp.toSec();
      for (std::size_t i = 0; i < latest_->items.size() && i < state_to_item_.size(); ++i) {
        const RockingState& s = latest_->items[i];
        Sent& last = sent_[state_to_item_[i]];
        const double p = s.ensemble_size > 0 ? s.p_overturned.probability : -1.0;
        if (last.valid && last.mode == s.mode && last.plane == s.plane && last.impacts == s.impacts &&
            std::abs(last.rotation_ratio - s.rotation_ratio) < kRatioStep &&
            std::abs(last.energy_margin - s.energy_margin) < kMarginStep && std::abs(last.p_overturned - p) < kRatioStep &&
            same_support_margin(last.support_margin, s.support_margin))
          continue;
        last = {s.mode, s.plane, s.rotation_ratio, s.energy_margin, s.theta, s.impacts, true, p, s.support_margin};
        auto& h = history_[state_to_item_[i]];
        const double t = s.input_stamp.toSec();
        if (!h.empty() && t < h.back().t - 1.0) h.clear();  // the clock went back: monitor restarted, bag looped
        h.push_back({t, static_cast<float>(s.theta < 0.0 ? -s.rotation_ratio : s.rotation_ratio),
                     static_cast<float>(s.energy_margin)});
        while (h.front().t < t - kHistorySeconds) h.pop_front();
        // Compact: the item-level fields (the governing plane's) as one array; the page asks
        // /api/item for the full state of the one item it shows in detail.
        json row = {s.id, mode_name(s.mode), s.plane, short_number(s.theta), short_number(s.rotation_ratio),
                    short_number(s.energy_margin), s.impacts, s.input_stamp.toSec()};
        const auto c = criteria_.find(s.id);
        const bool has_criteria = c != criteria_.end() && !c->second.empty();
        if (has_criteria) row.push_back(c->second);
        else if (p >= 0.0) row.push_back(nullptr);
        if (p >= 0.0) row.push_back(short_number(p));  // only ensemble items carry it
        changed.push_back(std::move(row));
      }
      latest_sent_ = true;
    }
    const auto now = ::ros::WallTime::now();
    if (!health_.empty() && (now - last_health_push_).toSec() >= 1.0) {  // health at 1 Hz is plenty
      last_health_push_ = now;
      health = health_json_locked();
      push_health = true;
    }
  }
  if (!changed.empty())
    publish_event("states", json_text(json{{"stamp", stamp},
                                           {"fields", {"id", "mode", "plane", "theta", "rotation_ratio", "energy_margin",
                                                       "impacts", "stamp", "criteria", "p_overturned"}},
                                           {"items", std::move(changed)}}));
  if (push_health) publish_event("health", json_text(health));
  push_input();
}

}  // namespace rocking_monitor::live
