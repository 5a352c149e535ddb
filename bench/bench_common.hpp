#pragma once
// Inputs, bodies and solver settings shared by the benchmarks (rocking_benchmarks) and the
// accuracy / stability drivers (rocking_accuracy). Header-only, no ROS.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <time.h>

#include "rocking_monitor/physics/body.hpp"
#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/motion/ground_motion.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "rocking_monitor/model/rocking_model.hpp"
#include "rocking_monitor/integrate/solver_settings.hpp"

#include <cstdio>
#include <cstdlib>

#include "test_helpers.hpp"

namespace rocking_monitor::bench {

using namespace rocking_monitor::core;

/// CPU time of the calling thread, s. The benchmarks time with it rather than the wall clock so
/// that other processes on a shared machine do not inflate the cost of one core's work.
inline double thread_cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// CPU time of the whole process (all threads), s: what several threads cost together.
inline double process_cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// The live feed rate the capacity figures refer to.
inline constexpr double kFeedRate = 200.0;  // Hz
inline constexpr double kFeedDt = 1.0 / kFeedRate;

// The same oracle builders as the tests (deg, rectangle_with, one_sine_pulse).
using rocking_monitor::core::testing::deg;
using rocking_monitor::core::testing::one_sine_pulse;
using rocking_monitor::core::testing::rectangle_with;

/// One named solver setting (method + parameters), e.g. "dopri5 tol=1e-8".
struct MethodSetting {
  std::string method;  ///< "dopri5", "rk4", "analytic"
  std::string label;   ///< human-readable, e.g. "dopri5 tol=1e-08"
  double param = 0.0;  ///< tol (dopri5), substeps (rk4), 0 (analytic)
  SolverSettings settings;
};

inline MethodSetting dopri5_setting(double tol, ModelKind model) {
  MethodSetting m;
  m.method = "dopri5";
  char buf[64];
  std::snprintf(buf, sizeof buf, "dopri5 tol=%.0e", tol);
  m.label = buf;
  m.param = tol;
  m.settings.method = Method::Dopri5;
  m.settings.model = model;
  m.settings.tol = tol;
  return m;
}

inline MethodSetting rk4_setting(int substeps, ModelKind model) {
  MethodSetting m;
  m.method = "rk4";
  m.label = "rk4 substeps=" + std::to_string(substeps);
  m.param = substeps;
  m.settings.method = Method::Rk4;
  m.settings.model = model;
  m.settings.substeps = substeps;
  return m;
}

inline MethodSetting analytic_setting() {
  MethodSetting m;
  m.method = "analytic";
  m.label = "analytic";
  m.param = 0.0;
  m.settings.method = Method::Analytic;
  m.settings.model = ModelKind::Linearized;
  return m;
}

/// Every method and setting the benchmarks and charts compare, for one model.
inline std::vector<MethodSetting> all_settings(ModelKind model, bool fine = false) {
  std::vector<MethodSetting> out;
  const std::vector<double> tols =
      fine ? std::vector<double>{1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12}
           : std::vector<double>{1e-4, 1e-6, 1e-8, 1e-10};
  const std::vector<int> subs = fine ? std::vector<int>{1, 2, 4, 8, 16, 32, 64}
                                     : std::vector<int>{1, 2, 4, 8, 16};
  for (double t : tols) out.push_back(dopri5_setting(t, model));
  for (int n : subs) out.push_back(rk4_setting(n, model));
  if (model == ModelKind::Linearized) out.push_back(analytic_setting());
  return out;
}

/// Linear interpolation of a uniformly sampled series onto a new step (first-order hold, i.e.
/// exactly the piecewise-linear signal the model sees, sampled at the new rate).
inline std::vector<double> resample(const std::vector<double>& x, double dt_in, double dt_out) {
  if (x.empty()) return {};
  const double duration = dt_in * static_cast<double>(x.size() - 1);
  const auto n = static_cast<std::size_t>(std::floor(duration / dt_out + 1e-9)) + 1;
  std::vector<double> y(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double pos = static_cast<double>(i) * dt_out / dt_in;
    const auto k = std::min(static_cast<std::size_t>(pos), x.size() - 1);
    const double f = pos - static_cast<double>(k);
    y[i] = k + 1 < x.size() ? x[k] + f * (x[k + 1] - x[k]) : x[k];
  }
  return y;
}

inline GroundMotion resample(const GroundMotion& g, double dt_out) {
  GroundMotion r;
  r.t0 = g.t0;
  r.dt = dt_out;
  r.description = g.description;
  r.horizontal = resample(g.horizontal, g.dt, dt_out);
  if (!g.vertical.empty()) r.vertical = resample(g.vertical, g.dt, dt_out);
  return r;
}

/// Reads the first horizontal component of a record file, multiplied by `scale`.
inline GroundMotion load_record(const std::string& path, double scale = 1.0) {
  const std::vector<Component> comps = read_record(path);
  for (const Component& c : comps)
    if (!c.vertical) return make_ground_motion(c, nullptr, scale);
  throw RecordError(path + ": no horizontal component");
}

/// Every PEER .AT2 file under `dir` (recursively), sorted; empty when `dir` does not exist.
inline std::vector<std::string> at2_files(const std::string& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir, ec)) {
    if (!e.is_regular_file()) continue;
    std::string ext = e.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (ext == ".at2") out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

#ifndef ROCKING_RECORDS_DIR
#define ROCKING_RECORDS_DIR "../shared/records"
#endif

/// Records directory: $ROCKING_RECORDS_DIR if set, else the build's default.
inline std::string records_dir() {
  if (const char* env = std::getenv("ROCKING_RECORDS_DIR")) return env;
  return ROCKING_RECORDS_DIR;
}

/// "/tol:1e-08" for dopri5, "/substeps:4" for rk4, "" for analytic (benchmark names).
inline std::string setting_suffix(const MethodSetting& ms) {
  if (ms.method == "dopri5") {
    char buf[32];
    std::snprintf(buf, sizeof buf, "/tol:%.0e", ms.param);
    return buf;
  }
  if (ms.method == "rk4") return "/substeps:" + std::to_string(static_cast<int>(ms.param));
  return {};
}

inline bool records_available(const std::string& dir) {
  std::error_code ec;
  return std::filesystem::is_directory(dir, ec);
}

inline GroundMotion zeros(double dt, double t_end) {
  GroundMotion g;
  g.dt = dt;
  g.horizontal.assign(static_cast<std::size_t>(std::llround(t_end / dt)) + 1, 0.0);
  g.description = "no ground motion";
  return g;
}

/// Minimum one-sine pulse amplitude a_p / (alpha g) that overturns a linearized block without any
/// impact (Zhang & Makris 2001, eq. 47; table in ../shared/paper/NOTES.md), by bisection.
inline double pulse_min_amplitude_ratio(double wp_over_p) {
  auto f = [&](double psi) {
    return wp_over_p * std::sin(psi) - std::cos(psi) + std::exp(-(2.0 * kPi - psi) / wp_over_p);
  };
  double lo = 1e-9, hi = kPi / 2;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < 0.0 ? lo : hi) = mid;
  }
  return 1.0 / std::sin(0.5 * (lo + hi));
}

/// Deterministic 64-bit generator (SplitMix64): the same catalogue on every machine.
struct SplitMix64 {
  std::uint64_t s;
  explicit SplitMix64(std::uint64_t seed) : s(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform(double a, double b) { return a + (b - a) * (next() >> 11) * 0x1.0p-53; }
};

/// A catalogue of n realistic free-standing items: base 0.15-1.2 m, centre of mass 0.2-1.5 m high,
/// eccentricity nu1 in [0.3, 0.7], tipping angles between 5 and 35 degrees.
inline std::vector<BodyParameters> catalogue(std::size_t n, std::uint64_t seed = 42) {
  SplitMix64 rng(seed);
  std::vector<BodyParameters> out;
  out.reserve(n);
  while (out.size() < n) {
    BodyParameters b;
    b.width = rng.uniform(0.15, 1.2);
    b.cg_height = rng.uniform(0.2, 1.5);
    b.nu1 = rng.uniform(0.3, 0.7);
    const double a_min = std::atan(std::min(b.nu1, 1.0 - b.nu1) * b.width / b.cg_height);
    const double a_max = std::atan(std::max(b.nu1, 1.0 - b.nu1) * b.width / b.cg_height);
    if (a_min < deg(5) || a_max > deg(35)) continue;
    out.push_back(b);
  }
  return out;
}

}  // namespace rocking_monitor::bench
