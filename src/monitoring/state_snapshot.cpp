#include "rocking_monitor/monitoring/state_snapshot.hpp"

#include <fcntl.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <type_traits>

namespace rocking_monitor::core {
namespace {

constexpr char kMagic[8] = {'R', 'M', 'S', 'N', 'A', 'P', 'S', 'H'};
constexpr std::uint32_t kByteOrderMark = 0x01020304u;
// Sanity bounds on counts read from a file (a damaged count must not make us allocate gigabytes).
constexpr std::size_t kMaxCount = 1u << 24;
constexpr std::size_t kMaxText = 1u << 16;

std::uint32_t crc(const std::uint8_t* data, std::size_t size) {
  return static_cast<std::uint32_t>(crc32_z(0L, data, size));
}

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

constexpr int kSwitchReasons = static_cast<int>(SwitchReason::RockHeld) + 1;
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
void visit(V& v, Rocking3DModel::Saved& s) {
  v.enumeration("mode", s.mode, static_cast<int>(Mode3D::Overturned) + 1);
  v("contact", s.contact);
  v("theta", s.theta);
  v("omega", s.omega);
  visit_matrix(v, "y", s.y);
  visit_matrix(v, "pivot_world", s.pivot_world);
  v("yaw", s.yaw);
  visit_matrix(v, "shift", s.shift);
  v("t", s.t);
  visit_matrix(v, "a_prev", s.a_prev);
  for (bool& a : s.armed) v("armed", a);
  v.group("report", [&] { visit(v, s.report); });
  v.group("outcome", [&] { visit(v, s.outcome); });
  v.group("outcome_3d", [&] {
    v("edge_to_vertex", s.outcome_3d.edge_to_vertex);
    v("vertex_impacts", s.outcome_3d.vertex_impacts);
    v("flat_impacts", s.outcome_3d.flat_impacts);
    v("max_tilt", s.outcome_3d.max_tilt);
    v("max_impact_energy_ratio", s.outcome_3d.max_impact_energy_ratio);
  });
  v("last_probe_t", s.last_probe_t);
  v.group("dopri5", [&] { visit(v, s.dopri5); });
  v.group("dopri5_vector", [&] {
    v("h", s.vector.h);
    v("fsal_valid", s.vector.fsal_valid);
    visit_matrix(v, "k1", s.vector.k1);
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

template <class T>
void put_le(std::uint8_t* at, T x) {
  std::memcpy(at, &x, sizeof(T));
}
template <class T>
T get_le(const std::uint8_t* at) {
  T x;
  std::memcpy(&x, at, sizeof(T));
  return x;
}

// Header offsets.
constexpr std::size_t kVersionAt = 8, kMarkAt = 12, kSizeAt = 16, kPayloadCrcAt = 24, kHeaderCrcAt = 28;

}  // namespace

std::uint32_t configuration_fingerprint(const std::string& text) {
  return crc(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

void SnapshotEncoder::begin(std::vector<std::uint8_t>& out, std::uint32_t fingerprint, double written,
                            std::size_t sensors, std::size_t items) {
  out_ = &out;
  out.resize(std::max(out.capacity(), 2 * kSnapshotHeaderBytes));  // within the capacity: no allocation
  std::fill(out.begin(), out.begin() + kSnapshotHeaderBytes, 0);
  pos_ = kSnapshotHeaderBytes;
  Writer w(out, pos_);
  unsigned long fp = fingerprint;
  w("fingerprint", fp);
  w("written", written);
  w.count("sensors", sensors, kMaxCount);
  w.count("items", items, kMaxCount);
}

void SnapshotEncoder::sensor(const SnapshotSensor& s) {
  Writer w(*out_, pos_);
  SnapshotSensor copy = s;  // visit() takes the fields by reference (the reader fills them)
  visit(w, copy);
}

void SnapshotEncoder::item(const std::string& id, const ItemMonitor& monitor, const ItemEnsemble* ensemble) {
  Writer w(*out_, pos_);
  // The id is written straight from the caller's string (Writer only reads it).
  w("id", const_cast<std::string&>(id));
  monitor.save(monitor_);
  visit(w, monitor_);
  bool has_ensemble = ensemble != nullptr;
  w("has_ensemble", has_ensemble);
  if (ensemble != nullptr) {
    ensemble->save(ensemble_);
    visit(w, ensemble_);
  }
}

void SnapshotEncoder::finish(bool checksums) {
  std::vector<std::uint8_t>& out = *out_;
  out.resize(pos_);  // shrinking keeps the capacity for the next snapshot
  std::memcpy(out.data(), kMagic, sizeof kMagic);
  put_le<std::uint32_t>(out.data() + kVersionAt, kSnapshotVersion);
  put_le<std::uint32_t>(out.data() + kMarkAt, kByteOrderMark);
  put_le<std::uint64_t>(out.data() + kSizeAt, out.size() - kSnapshotHeaderBytes);
  if (checksums) seal_snapshot(out);
}

void seal_snapshot(std::vector<std::uint8_t>& bytes) {
  if (bytes.size() < kSnapshotHeaderBytes) return;
  const std::uint8_t* payload = bytes.data() + kSnapshotHeaderBytes;
  put_le<std::uint32_t>(bytes.data() + kPayloadCrcAt, crc(payload, bytes.size() - kSnapshotHeaderBytes));
  put_le<std::uint32_t>(bytes.data() + kHeaderCrcAt, crc(bytes.data(), kHeaderCrcAt));
}

std::string decode_snapshot(const std::uint8_t* data, std::size_t size, StateSnapshot& out) {
  out = StateSnapshot{};
  if (size < kSnapshotHeaderBytes)
    return "truncated: " + std::to_string(size) + " bytes, shorter than the " + std::to_string(kSnapshotHeaderBytes) +
           "-byte header";
  if (std::memcmp(data, kMagic, sizeof kMagic) != 0) return "not a state snapshot (no RMSNAPSH magic)";
  if (get_le<std::uint32_t>(data + kHeaderCrcAt) != crc(data, kHeaderCrcAt))
    return "header checksum mismatch: the header is damaged";
  const auto version = get_le<std::uint32_t>(data + kVersionAt);
  if (version != kSnapshotVersion)
    return "format version " + std::to_string(version) + ", this monitor reads version " +
           std::to_string(kSnapshotVersion);
  if (get_le<std::uint32_t>(data + kMarkAt) != kByteOrderMark) return "written on a machine of another byte order";
  const auto payload_size = get_le<std::uint64_t>(data + kSizeAt);
  if (payload_size != size - kSnapshotHeaderBytes)
    return "truncated or extended: the header says " + std::to_string(payload_size) + " payload bytes, the file has " +
           std::to_string(size - kSnapshotHeaderBytes);
  const std::uint8_t* payload = data + kSnapshotHeaderBytes;
  if (get_le<std::uint32_t>(data + kPayloadCrcAt) != crc(payload, payload_size))
    return "payload checksum mismatch: the file is damaged";

  Reader r(payload, payload + payload_size);
  unsigned long fp = 0;
  r("fingerprint", fp);
  out.fingerprint = static_cast<std::uint32_t>(fp);
  r("written", out.written);
  std::size_t sensors = 0, items = 0;
  r.count("sensors", sensors, kMaxCount);
  r.count("items", items, kMaxCount);
  out.sensors.resize(sensors);
  for (std::size_t i = 0; i < sensors && !r.failed(); ++i) {
    const std::string name = "sensor " + std::to_string(i + 1) + " of " + std::to_string(sensors);
    r.group(name.c_str(), [&] { visit(r, out.sensors[i]); });
  }
  out.items.resize(items);
  for (std::size_t i = 0; i < items && !r.failed(); ++i) {
    SnapshotItem& item = out.items[i];
    r("item id", item.id);
    const std::string name = "item '" + item.id + "' (" + std::to_string(i + 1) + " of " + std::to_string(items) + ")";
    r.group(name.c_str(), [&] {
      visit(r, item.monitor);
      r("has_ensemble", item.has_ensemble);
      if (item.has_ensemble) r.group("ensemble", [&] { visit(r, item.ensemble); });
    });
  }
  if (!r.failed() && r.remaining() > 0)
    return "payload: " + std::to_string(r.remaining()) + " bytes after the last item";
  if (r.failed()) {
    const std::string e = r.error();
    out = StateSnapshot{};
    return e;
  }
  return {};
}

std::string read_snapshot(const std::string& path, StateSnapshot& out, bool* exists) {
  out = StateSnapshot{};
  std::error_code ec;
  const bool there = std::filesystem::exists(path, ec);
  if (exists != nullptr) *exists = there;
  if (!there) return path + ": no such file";
  std::ifstream in(path, std::ios::binary);
  if (!in) return path + ": cannot open: " + std::strerror(errno);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return path + ": cannot read: " + std::strerror(errno);
  if (std::string e = decode_snapshot(bytes.data(), bytes.size(), out); !e.empty()) return path + ": " + e;
  return {};
}

std::string foreign_snapshot(const StateSnapshot& snapshot, std::uint32_t fingerprint,
                             const std::vector<std::string>& sensor_names, const std::vector<std::string>& item_ids) {
  if (snapshot.sensors.size() != sensor_names.size())
    return "written for " + std::to_string(snapshot.sensors.size()) + " sensors, this catalogue has " +
           std::to_string(sensor_names.size());
  for (std::size_t i = 0; i < sensor_names.size(); ++i)
    if (snapshot.sensors[i].name != sensor_names[i])
      return "sensor " + std::to_string(i + 1) + " is '" + snapshot.sensors[i].name + "', this catalogue's is '" +
             sensor_names[i] + "'";
  if (snapshot.items.size() != item_ids.size())
    return "written for " + std::to_string(snapshot.items.size()) + " items, this catalogue has " +
           std::to_string(item_ids.size());
  for (std::size_t i = 0; i < item_ids.size(); ++i)
    if (snapshot.items[i].id != item_ids[i])
      return "item " + std::to_string(i + 1) + " is '" + snapshot.items[i].id + "', this catalogue's is '" +
             item_ids[i] + "'";
  if (snapshot.fingerprint != fingerprint)
    return "written with another configuration (catalogue parameters or model options; fingerprint " +
           std::to_string(snapshot.fingerprint) + ", this monitor's " + std::to_string(fingerprint) + ")";
  return {};
}

std::string write_file_durably(const std::string& path, const std::uint8_t* data, std::size_t size) {
  auto failed = [](const std::string& what, const std::string& p) { return what + " " + p + ": " + std::strerror(errno); };
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return failed("cannot create", tmp);
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::write(fd, data + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string e = failed("cannot write", tmp);
      ::close(fd);
      ::unlink(tmp.c_str());
      return e;
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const std::string e = failed("cannot fsync", tmp);
    ::close(fd);
    ::unlink(tmp.c_str());
    return e;
  }
  ::close(fd);
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string e = failed("cannot rename " + tmp + " to", path);
    ::unlink(tmp.c_str());
    return e;
  }
  // The rename itself is durable only once the directory is synced.
  std::string dir = std::filesystem::path(path).parent_path().string();
  if (dir.empty()) dir = ".";
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    const int rc = ::fsync(dfd);
    ::close(dfd);
    if (rc != 0) return failed("cannot fsync the directory", dir);
  }
  return {};
}

SnapshotFileWriter::SnapshotFileWriter(std::string path) : path_(std::move(path)) {
  const std::filesystem::path dir = std::filesystem::path(path_).parent_path();
  std::error_code ec;
  if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  thread_ = std::thread([this] { run(); });
}

SnapshotFileWriter::~SnapshotFileWriter() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

std::vector<std::uint8_t>& SnapshotFileWriter::buffer() {
  std::lock_guard<std::mutex> lock(mutex_);
  const int idx = writing_ == 0 ? 1 : 0;
  if (pending_ == idx) {  // not picked up yet: the newer state replaces it
    pending_ = -1;
    ++status_.superseded;
  }
  encoding_ = idx;
  return buffers_[idx];
}

void SnapshotFileWriter::submit() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (encoding_ < 0) return;
    pending_ = encoding_;
    encoding_ = -1;
  }
  wake_.notify_one();
}

void SnapshotFileWriter::flush() {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] { return pending_ < 0 && writing_ < 0; });
}

SnapshotFileWriter::Status SnapshotFileWriter::status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_;
}

void SnapshotFileWriter::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || pending_ >= 0; });
    if (pending_ < 0) return;  // stopping with nothing to write
    writing_ = pending_;
    pending_ = -1;
    std::vector<std::uint8_t>& buf = buffers_[writing_];
    lock.unlock();
    const auto t0 = std::chrono::steady_clock::now();
    seal_snapshot(buf);  // the checksums here, off the sample path (~1 ms per MB)
    const std::string e = write_file_durably(path_, buf.data(), buf.size());
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    lock.lock();
    if (e.empty()) {
      ++status_.written;
      status_.last_error.clear();
      status_.last_bytes = buf.size();
    } else {
      ++status_.failed;
      status_.last_error = e;
    }
    status_.last_write_s = s;
    status_.max_write_s = std::max(status_.max_write_s, s);
    writing_ = -1;
    idle_.notify_all();
    if (stop_ && pending_ < 0) return;
  }
}

}  // namespace rocking_monitor::core
