// Ground-motion sources for record_to_bag and ground_motion_player (see ground_motion_source.hpp).

#include "rocking_monitor/ros/ground_motion_source.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/motion/synthetic_motion.hpp"

namespace rocking_monitor::records {

namespace {

/// Error in a YAML spec: "<file>:<line>: <problem>" (yaml-cpp marks are 0-based).
struct SpecError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void spec_fail(const std::string& path, const YAML::Node& node, const std::string& problem) {
  const YAML::Mark m = node.Mark();
  std::string where = path;
  if (m.line >= 0) where += ":" + std::to_string(m.line + 1);
  throw SpecError(where + ": " + problem);
}

double number(const std::string& path, const YAML::Node& node, const std::string& key) {
  if (!node.IsScalar()) spec_fail(path, node, "'" + key + "' must be a number");
  double v = 0.0;
  try {
    v = node.as<double>();
  } catch (const YAML::Exception&) {
    spec_fail(path, node, "'" + key + "' must be a number, found '" + node.Scalar() + "'");
  }
  if (!std::isfinite(v)) spec_fail(path, node, "'" + key + "' must be finite");
  return v;
}

/// Reads the keys of a term's mapping, refusing unknown ones and requiring the required ones.
std::map<std::string, double> term_params(const std::string& path, const YAML::Node& body, const std::string& term,
                                          const std::vector<std::string>& required, const std::map<std::string, double>& optional) {
  if (!body.IsMap()) spec_fail(path, body, "'" + term + "' needs a mapping of parameters");
  std::map<std::string, double> out = optional;
  for (const auto& kv : body) {
    const std::string key = kv.first.as<std::string>();
    const bool known = optional.count(key) != 0 || std::find(required.begin(), required.end(), key) != required.end();
    if (!known) {
      std::string all;
      for (const auto& r : required) all += (all.empty() ? "" : ", ") + r;
      for (const auto& o : optional) all += (all.empty() ? "" : ", ") + o.first;
      spec_fail(path, kv.first, "unknown parameter '" + key + "' of " + term + " (known: " + all + ")");
    }
    out[key] = number(path, kv.second, key);
  }
  for (const auto& r : required) {
    if (!body[r]) spec_fail(path, body, term + " needs '" + r + "'");
  }
  return out;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// The spec file as a YAML mapping of known keys.
YAML::Node load_spec(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw SpecError(path + ": cannot open file");
  } catch (const YAML::ParserException& e) {
    throw SpecError(path + ":" + std::to_string(e.mark.line + 1) + ": YAML syntax error: " + e.msg);
  }
  if (!root.IsMap()) throw SpecError(path + ": a synthetic spec must be a YAML mapping (rate_hz, duration_s, x, y, z)");
  for (const auto& kv : root) {
    const std::string key = kv.first.as<std::string>();
    if (key != "description" && key != "rate_hz" && key != "duration_s" && key != "x_azimuth_deg" && key != "x" && key != "y" &&
        key != "z") {
      spec_fail(path, kv.first, "unknown key '" + key + "' (known: description, rate_hz, duration_s, x_azimuth_deg, x, y, z)");
    }
  }
  return root;
}

// One term of an axis as a function of time (gaussian_noise: of the call order), and its
// description appended to `what`.
std::function<double(double)> synthetic_term(const std::string& path, const YAML::Node& term, std::string& what) {
  if (!term.IsMap() || term.size() != 1) {
    spec_fail(path, term, "each term is a mapping with one key: ricker, sine_pulse, gaussian_noise or constant");
  }
  const std::string kind = term.begin()->first.as<std::string>();
  const YAML::Node body = term.begin()->second;
  if (kind == "ricker") {
    const auto p = term_params(path, body, kind, {"peak_mps2", "frequency_hz", "center_s"}, {});
    if (!(p.at("frequency_hz") > 0.0)) spec_fail(path, body, "ricker frequency_hz must be > 0");
    what += fmt(" + ricker(%g m/s^2", p.at("peak_mps2")) + fmt(", %g Hz", p.at("frequency_hz")) + fmt(", at %g s)", p.at("center_s"));
    return [p](double t) { return core::ricker(t, p.at("peak_mps2"), p.at("frequency_hz"), p.at("center_s")); };
  }
  if (kind == "sine_pulse") {
    const auto p = term_params(path, body, kind, {"amplitude_mps2", "period_s"}, {{"start_s", 0.0}, {"cycles", 1.0}});
    if (!(p.at("period_s") > 0.0)) spec_fail(path, body, "sine_pulse period_s must be > 0");
    if (!(p.at("cycles") >= 0.0)) spec_fail(path, body, "sine_pulse cycles must be >= 0");
    what += fmt(" + sine_pulse(%g m/s^2", p.at("amplitude_mps2")) + fmt(", %g s", p.at("period_s")) + ")";
    return [p](double t) { return core::sine_pulse(t, p.at("amplitude_mps2"), p.at("period_s"), p.at("start_s"), p.at("cycles")); };
  }
  if (kind == "gaussian_noise") {
    const auto p = term_params(path, body, kind, {"rms_mps2", "seed"}, {});
    if (!(p.at("rms_mps2") >= 0.0)) spec_fail(path, body, "gaussian_noise rms_mps2 must be >= 0");
    const double seed = p.at("seed");
    if (seed < 0.0 || seed != std::floor(seed) || seed > 9.007199254740992e15) {
      spec_fail(path, body["seed"], "gaussian_noise seed must be a whole number >= 0");
    }
    auto noise = std::make_shared<core::GaussianNoise>(p.at("rms_mps2"), static_cast<std::uint64_t>(seed));
    what += fmt(" + gaussian_noise(%g m/s^2 RMS", p.at("rms_mps2")) + fmt(", seed %.0f)", seed);
    return [noise](double) { return noise->next(); };  // called once per sample, in order
  }
  if (kind == "constant") {
    const auto p = term_params(path, body, kind, {"value_mps2"}, {});
    what += fmt(" + constant(%g m/s^2)", p.at("value_mps2"));
    return [v = p.at("value_mps2")](double) { return v; };
  }
  spec_fail(path, term, "unknown term '" + kind + "' (known: ricker, sine_pulse, gaussian_noise, constant)");
}

// Axis k: the sum of its terms over n samples (zeros when not given).
void synthetic_axis(const std::string& path, const YAML::Node& root, std::size_t k, std::size_t n,
                    core::SensorFrameMotion& m) {
  const char* axes[3] = {"x", "y", "z"};
  std::vector<double>& out = m.ground[k];
  out.assign(n, 0.0);
  m.source[k] = "none (zeros)";
  const YAML::Node list = root[axes[k]];
  if (!list) return;
  if (!list.IsSequence()) spec_fail(path, list, std::string("'") + axes[k] + "' must be a list of terms");
  m.recorded[k] = true;
  std::string what;
  for (const YAML::Node& term : list) {
    const std::function<double(double)> f = synthetic_term(path, term, what);
    for (std::size_t i = 0; i < n; ++i) out[i] += f(static_cast<double>(i) * m.dt);
  }
  m.source[k] = what.empty() ? "zeros" : what.substr(3);
}

}  // namespace

core::SensorFrameMotion synthetic_motion_from_yaml(const std::string& path) {
  const YAML::Node root = load_spec(path);
  if (!root["rate_hz"]) throw SpecError(path + ": missing 'rate_hz'");
  if (!root["duration_s"]) throw SpecError(path + ": missing 'duration_s'");
  const double rate = number(path, root["rate_hz"], "rate_hz");
  const double duration = number(path, root["duration_s"], "duration_s");
  if (!(rate > 0.0)) spec_fail(path, root["rate_hz"], "rate_hz must be > 0 Hz");
  if (!(duration >= 0.0)) spec_fail(path, root["duration_s"], "duration_s must be >= 0 s");
  core::SensorFrameMotion m;
  m.dt = 1.0 / rate;
  m.t0 = 0.0;
  m.station = std::filesystem::path(path).stem().string();
  const std::size_t n = core::synthetic_sample_count(duration, m.dt);
  if (root["x_azimuth_deg"]) m.x_azimuth_deg = number(path, root["x_azimuth_deg"], "x_azimuth_deg");
  for (std::size_t k = 0; k < 3; ++k) synthetic_axis(path, root, k, n, m);
  return m;
}

std::string default_records_dir() {
#ifdef ROCKING_DEFAULT_RECORDS_DIR
  return ROCKING_DEFAULT_RECORDS_DIR;
#else
  return "";
#endif
}

core::SensorFrameMotion load_ground_motion(const SourceSpec& spec) {
  const int given = (spec.files.empty() ? 0 : 1) + (spec.station.empty() ? 0 : 1) + (spec.synthetic.empty() ? 0 : 1);
  if (given != 1) throw std::invalid_argument("give exactly one source: record file(s), a station, or a synthetic spec");
  if (!spec.synthetic.empty()) {
    if (spec.frame.azimuth_deg) throw std::invalid_argument("an azimuth cannot be applied to a synthetic spec (its axes are given)");
    core::SensorFrameMotion m = synthetic_motion_from_yaml(spec.synthetic);
    if (spec.frame.scale != 1.0) {
      if (!std::isfinite(spec.frame.scale)) throw std::invalid_argument("scale is not finite");
      for (auto& axis : m.ground) {
        for (double& v : axis) v *= spec.frame.scale;
      }
    }
    return m;
  }
  core::StationRecord rec;
  if (!spec.files.empty()) {
    if (spec.files.size() > 3) throw std::invalid_argument("at most 3 record files (two horizontals and a vertical)");
    rec = core::load_station(core::station_from_files(spec.files, spec.read), spec.read);
  } else {
    if (spec.records_dir.empty()) throw std::invalid_argument("a station needs a records directory");
    const core::StationListing listing = core::list_stations(spec.records_dir);
    rec = core::load_station(core::find_station(listing, spec.station), spec.read);
  }
  return core::to_sensor_frame(rec, spec.frame);
}

double accel_variance(double noise_density, double dt) {
  if (!(noise_density >= 0.0) || !std::isfinite(noise_density)) throw std::invalid_argument("noise density must be finite and >= 0");
  if (!(dt > 0.0)) throw std::invalid_argument("sample interval must be > 0");
  return noise_density * noise_density / (2.0 * dt);
}

sensor_msgs::Imu make_imu_message(const core::AccelerometerSample& s, const ros::Time& stamp, const std::string& frame_id,
                                  double variance) {
  sensor_msgs::Imu msg;  // value-initialised: orientation and angular_velocity all zeros
  msg.header.stamp = stamp;
  msg.header.frame_id = frame_id;
  msg.orientation_covariance[0] = -1.0;       // no orientation estimate (REP 145)
  msg.angular_velocity_covariance[0] = -1.0;  // no gyroscope
  msg.linear_acceleration.x = s.specific_force[0];
  msg.linear_acceleration.y = s.specific_force[1];
  msg.linear_acceleration.z = s.specific_force[2];
  msg.linear_acceleration_covariance[0] = variance;
  msg.linear_acceleration_covariance[4] = variance;
  msg.linear_acceleration_covariance[8] = variance;
  return msg;
}

geometry_msgs::AccelStamped make_accel_message(const core::AccelerometerSample& s, const ros::Time& stamp,
                                               const std::string& frame_id) {
  geometry_msgs::AccelStamped msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = frame_id;
  msg.accel.linear.x = s.ground[0];
  msg.accel.linear.y = s.ground[1];
  msg.accel.linear.z = s.ground[2];
  return msg;
}

std::int64_t parse_time_ns(const std::string& text) {
  const std::size_t dot = text.find('.');
  const std::string whole = text.substr(0, dot);
  const std::string frac = dot == std::string::npos ? "" : text.substr(dot + 1);
  auto digits = [](const std::string& s) {
    for (char c : s) {
      if (c < '0' || c > '9') return false;
    }
    return true;
  };
  if (whole.empty() || !digits(whole) || !digits(frac) || frac.size() > 9 || (dot != std::string::npos && frac.empty())) {
    throw std::invalid_argument("'" + text + "' is not a time in seconds (digits, optionally '.' and up to 9 decimals)");
  }
  if (whole.size() > 10) throw std::invalid_argument("'" + text + "' s is beyond the range of ros::Time");
  const std::int64_t sec = std::stoll(whole);
  if (sec > 4294967295LL) throw std::invalid_argument("'" + text + "' s is beyond the range of ros::Time (2^32 - 1 s)");
  std::int64_t ns = 0;
  if (!frac.empty()) ns = std::stoll(frac + std::string(9 - frac.size(), '0'));
  return sec * 1'000'000'000LL + ns;
}

std::string describe(const core::SensorFrameMotion& m) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%zu samples at %.6g Hz (%.6g s)", m.size(), 1.0 / m.dt, m.duration());
  std::string s = buf;
  s += "; x = " + m.source[0] + "; y = " + m.source[1] + "; z = " + m.source[2];
  if (m.x_azimuth_deg) s += "; x azimuth " + core::format_azimuth_label(*m.x_azimuth_deg) + " deg";
  return s;
}

}  // namespace rocking_monitor::records
