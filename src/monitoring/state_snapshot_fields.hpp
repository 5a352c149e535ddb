#pragma once

// Private to src/monitoring/state_snapshot.cpp: the field-by-field layout of a snapshot's payload,
// one visit() per saved struct serving both directions (Writer appends, Reader reads back and checks),
// so that the layout cannot differ between them. Not part of the public API
// (include/rocking_monitor/monitoring/state_snapshot.hpp).

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "rocking_monitor/monitoring/state_snapshot.hpp"

namespace rocking_monitor::core::snapshot_fields {

// Sanity bounds on counts read from a file (a damaged count must not make us allocate gigabytes).
constexpr std::size_t kMaxCount = 1u << 24;
constexpr std::size_t kMaxText = 1u << 16;

// ---------------------------------------------------------------- the two directions of one layout
// Every Saved struct is visited field by field by visit(); Writer appends each field, Reader reads it
// back and checks it. One function per struct serves both, so the layout cannot differ between them.

// Writes at out[pos], growing out only when it is full: after the first snapshot the buffer has its
// size already, and each field is a bounds check and a memcpy (no per-field vector insert).
class Writer {
 public:
  Writer(std::vector<std::uint8_t>& out, std::size_t& pos) : out_(out), pos_(pos) {}
  void operator()(const char*, double& x) { put(x); }
  void operator()(const char*, bool& x) { put(static_cast<std::uint8_t>(x ? 1 : 0)); }
  void operator()(const char*, int& x) { put(static_cast<std::int32_t>(x)); }
  void operator()(const char*, long& x) { put(static_cast<std::int64_t>(x)); }
  void operator()(const char*, unsigned long& x) { put(static_cast<std::uint64_t>(x)); }
  void operator()(const char*, std::uint8_t& x) { put(x); }
  void operator()(const char*, std::string& x) {
    put(static_cast<std::uint32_t>(x.size()));
    room(x.size());
    std::memcpy(out_.data() + pos_, x.data(), x.size());
    pos_ += x.size();
  }
  template <class E>
  void enumeration(const char*, E& e, int) { put(static_cast<std::uint8_t>(e)); }
  void count(const char*, std::size_t& n, std::size_t) { put(static_cast<std::uint32_t>(n)); }
  template <class F>
  void group(const char*, F&& f) { f(); }
  bool failed() const { return false; }

 private:
  void room(std::size_t n) {
    if (pos_ + n > out_.size()) out_.resize(std::max(2 * out_.size(), pos_ + n + 4096));
  }
  template <class T>
  void put(T x) {
    room(sizeof(T));
    std::memcpy(out_.data() + pos_, &x, sizeof(T));
    pos_ += sizeof(T);
  }
  std::vector<std::uint8_t>& out_;
  std::size_t& pos_;
};

class Reader {
 public:
  Reader(const std::uint8_t* begin, const std::uint8_t* end) : begin_(begin), p_(begin), end_(end) {}
  void operator()(const char* name, double& x) { get(name, x); }
  void operator()(const char* name, bool& x) {
    std::uint8_t b = 0;
    if (!get(name, b)) return;
    if (b > 1) return fail(name, std::to_string(b) + " is not a flag (0 or 1)");
    x = b != 0;
  }
  void operator()(const char* name, int& x) {
    std::int32_t v = 0;
    if (get(name, v)) x = v;
  }
  void operator()(const char* name, long& x) {
    std::int64_t v = 0;
    if (get(name, v)) x = v;
  }
  void operator()(const char* name, unsigned long& x) {
    std::uint64_t v = 0;
    if (get(name, v)) x = v;
  }
  void operator()(const char* name, std::uint8_t& x) { get(name, x); }
  void operator()(const char* name, std::string& x) {
    std::uint32_t n = 0;
    if (!get(name, n)) return;
    if (n > kMaxText || static_cast<std::size_t>(end_ - p_) < n)
      return fail(name, "length " + std::to_string(n) + " beyond the data");
    x.assign(reinterpret_cast<const char*>(p_), n);
    p_ += n;
  }
  template <class E>
  void enumeration(const char* name, E& e, int values) {
    std::uint8_t v = 0;
    if (!get(name, v)) return;
    if (v >= values) return fail(name, std::to_string(v) + " is not one of the " + std::to_string(values) + " values");
    e = static_cast<E>(v);
  }
  void count(const char* name, std::size_t& n, std::size_t max) {
    std::uint32_t v = 0;
    n = 0;
    if (!get(name, v)) return;
    if (v > max) return fail(name, std::to_string(v) + " exceeds " + std::to_string(max));
    n = v;
  }
  template <class F>
  void group(const char* name, F&& f) {
    if (failed()) return;
    path_.emplace_back(name);
    f();
    if (!failed()) path_.pop_back();
  }
  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }
  std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }
  std::size_t offset() const { return static_cast<std::size_t>(p_ - begin_); }

 private:
  template <class T>
  bool get(const char* name, T& x) {
    if (failed()) return false;
    if (remaining() < sizeof(T)) {
      fail(name, "the data ends at byte " + std::to_string(offset()));
      return false;
    }
    std::memcpy(&x, p_, sizeof(T));
    p_ += sizeof(T);
    return true;
  }
  void fail(const char* name, const std::string& what) {
    if (failed()) return;
    std::string where;
    for (const std::string& s : path_) where += s + ": ";
    error_ = where + name + ": " + what;
  }
  const std::uint8_t* begin_;
  const std::uint8_t* p_;
  const std::uint8_t* end_;
  std::vector<std::string> path_;
  std::string error_;
};

template <class V, class T, std::size_t N>
void visit_array(V& v, const char* name, std::array<T, N>& a) {
  for (T& x : a) v(name, x);
}
template <class V, class M>
void visit_matrix(V& v, const char* name, M& m) {
  for (Eigen::Index i = 0; i < m.size(); ++i) v(name, m.data()[i]);
}

template <class V>
void visit(V& v, StepReport& r) {
  v("uplift", r.uplift);
  v("impacts", r.impacts);
  v("rest_capture", r.rest_capture);
  v("forced_rest", r.forced_rest);
  v("beyond_tipping_entered", r.beyond_tipping_entered);
  v("committed_entered", r.committed_entered);
  v("overturned", r.overturned);
  v("violation_onsets", r.violation_onsets);
  v("integrator_steps", r.integrator_steps);
  v("first_impact_time", r.first_impact_time);
  v("peak_ratio", r.peak_ratio);
}

template <class V>
void visit(V& v, RockingOutcome& o) {
  v("beyond_tipping", o.beyond_tipping);
  v("committed", o.committed);
  v("overturned", o.overturned);
  v("max_rotation_ratio", o.max_rotation_ratio);
  v("max_rotation_side", o.max_rotation_side);
  v("impacts", o.impacts);
  v("rest_captures", o.rest_captures);
  v("forced_rest_captures", o.forced_rest_captures);
  v("integrator_steps", o.integrator_steps);
  v("samples", o.samples);
  v("uplift_time", o.uplift_time);
  v("beyond_tipping_time", o.beyond_tipping_time);
  v("committed_time", o.committed_time);
  v("overturn_time", o.overturn_time);
}

template <class V>
void visit(V& v, Dopri5Stepper::Saved& s) {
  v("h", s.h);
  v("fsal_valid", s.fsal_valid);
  v("k1_theta", s.k1_theta);
  v("k1_omega", s.k1_omega);
}

template <class V>
void visit(V& v, RockingModel::Saved& s) {
  v.enumeration("mode", s.mode, 3);
  v("side", s.side);
  v("theta", s.theta);
  v("omega", s.omega);
  v("t", s.t);
  v("ax_prev", s.ax_prev);
  v("ay_prev", s.ay_prev);
  v("violations", s.violations);
  v.group("report", [&] { visit(v, s.report); });
  v.group("outcome", [&] { visit(v, s.outcome); });
  v.group("dopri5", [&] { visit(v, s.dopri5); });
}

template <class V>
void visit(V& v, ContactModel::Saved& s) {
  constexpr int kContactModes = static_cast<int>(ContactMode::Overturned) + 1;
  v.enumeration("mode", s.mode, kContactModes);
  v("side", s.side);
  v("sigma", s.sigma);
  v("pivot_x", s.pivot_x);
  visit_array(v, "x", s.x);
  v("t", s.t);
  v("ax_prev", s.ax_prev);
  v("ay_prev", s.ay_prev);
  v("dt", s.dt);
  v.group("report", [&] {
    ContactReport& r = s.report;
    v.enumeration("mode", r.mode, kContactModes);
    v("side", r.side);
    v("slip", r.slip);
    v("slip_velocity", r.slip_velocity);
    v("theta", r.theta);
    v("slip_episodes", r.slip_episodes);
    v("impacts", r.impacts);
    v("flight_episodes", r.flight_episodes);
    v("transitions", r.transitions);
    v("overturned", r.overturned);
    v("forced_rest", r.forced_rest);
    v("integrator_steps", r.integrator_steps);
  });
  v.group("outcome", [&] {
    ContactOutcome& o = s.outcome;
    v("slip_episodes", o.slip_episodes);
    v("impacts", o.impacts);
    v("flight_episodes", o.flight_episodes);
    v("forced_rests", o.forced_rests);
    v("samples", o.samples);
    v("overturned", o.overturned);
    v("max_abs_slip", o.max_abs_slip);
    v("max_rotation_ratio", o.max_rotation_ratio);
    v("first_slip_time", o.first_slip_time);
    v("first_uplift_time", o.first_uplift_time);
    v("first_flight_time", o.first_flight_time);
    v("overturn_time", o.overturn_time);
  });
}

constexpr int kSwitchReasons = static_cast<int>(SwitchReason::SharedFrictionCone) + 1;
constexpr int kActiveModels = static_cast<int>(ActiveModel::Contact) + 1;

template <class V>
void visit(V& v, AdaptiveModel::Saved& s) {
  v.group("rocking", [&] { visit(v, s.rock); });
  v("has_linearized", s.has_lin);
  if (s.has_lin) v.group("linearized", [&] { visit(v, s.lin); });
  v.group("contact", [&] { visit(v, s.contact); });
  v("lin_active", s.lin_active);
  v.enumeration("active", s.active, kActiveModels);
  v.enumeration("initial_reason", s.initial_reason, kSwitchReasons);
  v("scene_guarantee", s.scene_guarantee);
  v("t", s.t);
  v("ax_prev", s.ax_prev);
  v("ay_prev", s.ay_prev);
  v("hold", s.hold);
  v("rock_slip", s.rock_slip);
  std::size_t n = s.switches.size();
  v.count("switches", n, kMaxCount);
  s.switches.resize(n);  // writing: no change
  for (SwitchRecord& r : s.switches) {
    v.group("switch", [&] {
      v("time", r.time);
      v.enumeration("to", r.to, kActiveModels);
      v.enumeration("reason", r.reason, kSwitchReasons);
      v("onset_time", r.onset_time);
    });
  }
  v.group("report", [&] {
    AdaptiveReport& r = s.report;
    v.enumeration("model", r.model, kActiveModels);
    v("switched", r.switched);
    v.enumeration("reason", r.reason, kSwitchReasons);
    v("recomputed_samples", r.recomputed_samples);
    v("rocking_samples", r.rocking_samples);
    v("linearized_samples", r.linearized_samples);
    v("contact_samples", r.contact_samples);
    v("rocking_steps", r.rocking_steps);
    v("contact_steps", r.contact_steps);
    v("integrator_steps", r.integrator_steps);
  });
  v.group("outcome", [&] {
    AdaptiveOutcome& o = s.outcome;
    v("beyond_tipping", o.beyond_tipping);
    v("committed", o.committed);
    v("overturned", o.overturned);
    v("beyond_tipping_time", o.beyond_tipping_time);
    v("committed_time", o.committed_time);
    v("overturn_time", o.overturn_time);
    v("uplift_time", o.uplift_time);
    v("first_slip_time", o.first_slip_time);
    v("first_flight_time", o.first_flight_time);
    v("max_rotation_ratio", o.max_rotation_ratio);
    v("max_abs_slip", o.max_abs_slip);
    v("impacts", o.impacts);
    v("slip_episodes", o.slip_episodes);
    v("flight_episodes", o.flight_episodes);
    v("samples", o.samples);
    v("samples_rocking_model", o.samples_rocking_model);
    v("samples_contact_model", o.samples_contact_model);
    v("rocking_steps", o.rocking_steps);
    v("contact_steps", o.contact_steps);
    v("recomputed_samples", o.recomputed_samples);
    v("samples_linearized_model", o.samples_linearized_model);
    v("linearized_fallbacks", o.linearized_fallbacks);
    v("model_switches", o.model_switches);
    v("sliding_ruled_out", o.sliding_ruled_out);
    v("scene_exceeded_time", o.scene_exceeded_time);
    v("samples_outside_scene", o.samples_outside_scene);
  });
}

template <class V>
void visit(V& v, StreamingIntensity::FilterState& f) {
  v("x1", f.x1);
  v("x2", f.x2);
  v("y1", f.y1);
  v("y2", f.y2);
}

template <class V>
void visit(V& v, StreamingIntensity::Saved& s) {
  v.group("velocity_filter", [&] { visit(v, s.velocity_filter); });
  v.group("oscillator_filter", [&] { visit(v, s.oscillator_filter); });
  std::size_t n = s.osc_u.size();
  v.count("periods", n, kMaxCount);
  s.osc_u.resize(n);
  s.osc_v.resize(n);
  s.max_u.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    v("oscillator_u", s.osc_u[j]);
    v("oscillator_v", s.osc_v[j]);
    v("max_u", s.max_u[j]);
  }
  v("count", s.count);
  v("prev_drive", s.prev_drive);
  v("pga", s.pga);
  v("pga_time", s.pga_time);
  v("vel", s.vel);
  v("pgv", s.pgv);
  v("pgv_time", s.pgv_time);
}

template <class V>
void visit(V& v, PlaneMonitor::Saved& s) {
  v("started", s.started);
  if (!s.started) return;
  v("dt_nominal", s.dt_nominal);
  v("has_adaptive", s.has_adaptive);
  if (s.has_adaptive) v.group("adaptive", [&] { visit(v, s.adaptive); });
  else v.group("rocking", [&] { visit(v, s.model); });
  v.group("intensity", [&] { visit(v, s.intensity); });
  v("slid_at_uplift", s.slid_at_uplift);
  v.enumeration("last_switch_criterion", s.last_switch_criterion, kCriterionIdCount);
  visit_array(v, "exceeded", s.exceeded);
}

template <class V>
void visit(V& v, Rocking3DOutcome& o) {
  v("edge_to_vertex", o.edge_to_vertex);
  v("vertex_impacts", o.vertex_impacts);
  v("flat_impacts", o.flat_impacts);
  v("max_tilt", o.max_tilt);
  v("max_impact_energy_ratio", o.max_impact_energy_ratio);
  v("max_landing_violation", o.max_landing_violation);
  v("max_friction_demand", o.max_friction_demand);
  v("slipping_landings", o.slipping_landings);
  v("frictional_landings", o.frictional_landings);
  v("landing_slides", o.landing_slides);
  v("pivot_slip_landings", o.pivot_slip_landings);
  v("unresolved_landings", o.unresolved_landings);
  v("edge_captures", o.edge_captures);
  v("hull_landings", o.hull_landings);
  v("rests_off_base", o.rests_off_base);
  v("slides", o.slides);
  v("sticks", o.sticks);
  v("slide_to_rock", o.slide_to_rock);
  v("first_slip_time", o.first_slip_time);
  v("max_slip", o.max_slip);
  v("max_slip_speed", o.max_slip_speed);
  v("max_twist", o.max_twist);
  v("slip_time", o.slip_time);
  v("fell_off_support", o.fell_off_support);
  v("fell_off_time", o.fell_off_time);
  v("slides_over_support_edge", o.slides_over_support_edge);
  v("pedestal_beyond_base", o.pedestal_beyond_base);
  v("vertex_refits", o.vertex_refits);
  v("forced_overturns", o.forced_overturns);
  v("lip_trips", o.lip_trips);
  v("lip_holds", o.lip_holds);
  v("lip_slipping_trips", o.lip_slipping_trips);
  v("lip_ends_passed", o.lip_ends_passed);
  v("max_lip_overhang", o.max_lip_overhang);
  v("lip_face_impacts", o.lip_face_impacts);
  v("lip_faces_not_followed", o.lip_faces_not_followed);
  v("max_pivot_friction_demand", o.max_pivot_friction_demand);
  v("pivot_slips", o.pivot_slips);
  v("pivot_lifts", o.pivot_lifts);
  v("first_pivot_slip_time", o.first_pivot_slip_time);
  v("pivot_sticks", o.pivot_sticks);
  v("pivot_slip_time", o.pivot_slip_time);
  v("pivot_slip_distance", o.pivot_slip_distance);
  v("pivot_slips_not_followed", o.pivot_slips_not_followed);
  v("pulled_pivots", o.pulled_pivots);
  v("flights", o.flights);
  v("first_flight_time", o.first_flight_time);
  v("flight_time", o.flight_time);
  v("max_flight_height", o.max_flight_height);
  v("flight_landings", o.flight_landings);
  v("corner_slip_landings", o.corner_slip_landings);
  v("transitions", o.transitions);
}

template <class V>
void visit(V& v, Rocking3DModel::Saved& s) {
  v.enumeration("mode", s.mode, static_cast<int>(Mode3D::Flight) + 1);
  v("contact", s.contact);
  v("face", s.face);
  v("theta", s.theta);
  v("omega", s.omega);
  visit_matrix(v, "y", s.y);
  visit_matrix(v, "pivot_world", s.pivot_world);
  v("yaw", s.yaw);
  visit_matrix(v, "shift", s.shift);
  v("fit_yaw", s.fit_yaw);
  visit_matrix(v, "fit_shift", s.fit_shift);
  v("t", s.t);
  visit_matrix(v, "a_prev", s.a_prev);
  for (bool& a : s.armed) v("armed", a);
  v.group("report", [&] { visit(v, s.report); });
  v.group("outcome", [&] { visit(v, s.outcome); });
  v.group("outcome_3d", [&] { visit(v, s.outcome_3d); });
  v("pivot_outside_cone", s.pivot_outside_cone);
  v("pivot_slipping", s.pivot_slipping);
  v("pivot_pulled", s.pivot_pulled);
  v("lip_held", s.lip_held);
  visit_matrix(v, "slip_state", s.slip_state);
  visit_matrix(v, "slip_direction", s.slip_direction);
  v.group("slip_stepper", [&] {
    v("h", s.slip_stepper.h);
    v("fsal_valid", s.slip_stepper.fsal_valid);
    visit_matrix(v, "k1", s.slip_stepper.k1);
  });
  v("last_probe_t", s.last_probe_t);
  v.group("dopri5", [&] { visit(v, s.dopri5); });
  v.group("dopri5_vector", [&] {
    v("h", s.vector.h);
    v("fsal_valid", s.vector.fsal_valid);
    visit_matrix(v, "k1", s.vector.k1);
  });
  visit_matrix(v, "slide", s.slide);
  v.group("slide_stepper", [&] {
    v("h", s.slide_stepper.h);
    v("fsal_valid", s.slide_stepper.fsal_valid);
    visit_matrix(v, "k1", s.slide_stepper.k1);
  });
  visit_matrix(v, "flight", s.flight);
  v.group("flight_stepper", [&] {
    v("h", s.flight_stepper.h);
    v("fsal_valid", s.flight_stepper.fsal_valid);
    visit_matrix(v, "k1", s.flight_stepper.k1);
  });
}

template <class V>
void visit(V& v, ItemMonitor::Saved& s) {
  v("started", s.started);
  if (!s.started) return;
  v("two_planes", s.two_planes);
  v.group("plane x", [&] { visit(v, s.planes[0]); });
  if (s.two_planes) v.group("plane y", [&] { visit(v, s.planes[1]); });
  visit_array(v, "alarmed", s.alarmed);
  for (auto& plane : s.last_input) visit_array(v, "last_input", plane);
  v("has_solid", s.has_solid);
  if (s.has_solid) v.group("3-D model", [&] { visit(v, s.solid); });
  v("solid_active", s.solid_active);
  v("peak_x", s.peak_x);
  v("peak_y", s.peak_y);
  v("t", s.t);
  visit_matrix(v, "last_a", s.last_a);
}

template <class V>
void visit(V& v, ItemEnsemble::Saved& s) {
  v("started", s.started);
  if (!s.started) return;
  std::size_t n = s.members.size();
  v.count("members", n, kMaxCount);
  s.members.resize(n);
  for (std::size_t i = 0; i < n && !v.failed(); ++i) {
    if constexpr (std::is_same_v<V, Reader>) {  // the name only where an error can name it
      const std::string name = "member " + std::to_string(i);
      v.group(name.c_str(), [&] { visit(v, s.members[i]); });
    } else {
      visit(v, s.members[i]);
    }
  }
  visit_array(v, "reached", s.reached);
  visit_array(v, "crossed", s.crossed);
  s.member_reached.resize(n);
  for (auto& r : s.member_reached) visit_array(v, "member_reached", r);
}

template <class V>
void visit(V& v, SnapshotSensor& s) {
  v("name", s.name);
  long stamp = s.last_stamp_ns, epoch = s.epoch_ns;
  v("last_stamp_ns", stamp);
  v("epoch_ns", epoch);
  s.last_stamp_ns = stamp;
  s.epoch_ns = epoch;
  v("last_t", s.last_t);
  v("dt_nominal", s.dt_nominal);
  v("min_dt", s.min_dt);
  v("baseline_initialized", s.baseline_initialized);
  for (double& b : s.baseline) v("baseline", b);
  unsigned long samples = s.samples;
  v("samples", samples);
  s.samples = samples;
}
}  // namespace rocking_monitor::core::snapshot_fields
