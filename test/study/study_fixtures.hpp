#pragma once
// Shared fixtures of the study tests (test_study*.cpp): scratch folders, a command runner, an
// independent CSV split, synthetic pulse records, a small grid and the case CSV of a result.

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/motion/response_spectrum.hpp"
#include "rocking_monitor/study/study.hpp"
#include "rocking_monitor/study/study_io.hpp"

#include "temp_root.hpp"

namespace rocking_monitor::core::study {
namespace {

namespace fs = std::filesystem;

// Scratch files of this binary, removed when it ends.
inline const rocking_monitor::core::testing::TempRoot& kTemp = rocking_monitor::core::testing::TempRoot::registered("rocking_study_test_");
inline const fs::path& temp_root() { return kTemp.path(); }

inline fs::path temp_dir(const std::string& tag) {
  const fs::path d = temp_root() / tag;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

inline std::string run_command(const std::string& cmd, int* status) {
  std::string out;
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return out;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), pipe) != nullptr) out += buf.data();
  const int st = pclose(pipe);
  *status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return out;
}

// Quote-aware CSV split, written independently of the library's.
inline std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> f(1);
  bool q = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (q) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        f.back() += '"';
        ++i;
      } else if (c == '"') {
        q = false;
      } else {
        f.back() += c;
      }
    } else if (c == '"') {
      q = true;
    } else if (c == ',') {
      f.emplace_back();
    } else {
      f.back() += c;
    }
  }
  return f;
}

// Synthetic records: one-sine pulses (the Zhang & Makris family) in m/s^2, written as CSV.
struct Pulse {
  std::string name;
  double amplitude, omega, vertical_amplitude;  // vertical_amplitude < 0: no vertical column
};

inline void write_pulse_csv(const fs::path& path, const Pulse& p, double polarity, double dt = 0.01,
                     double t_end = 8.0) {
  std::ofstream out(path);
  out << (p.vertical_amplitude >= 0 ? "time_s,accel_h,accel_v\n" : "time_s,accel\n");
  const auto n = static_cast<std::size_t>(std::llround(t_end / dt)) + 1;
  const double tp = 2.0 * kPi / p.omega;
  char line[160];
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    const double a = t <= tp ? p.amplitude * std::sin(p.omega * t) : 0.0;
    // The vertical: a pulse at twice the frequency (starts upward), present during the horizontal one.
    const double v = t <= tp ? p.vertical_amplitude * std::sin(2.0 * p.omega * t) : 0.0;
    if (p.vertical_amplitude >= 0)
      std::snprintf(line, sizeof line, "%.6f,%.17g,%.17g\n", t, polarity * a, v);
    else
      std::snprintf(line, sizeof line, "%.6f,%.17g\n", t, polarity * a);
    out << line;
  }
}

inline const std::vector<Pulse> kPulses{
    {"p1_strong", 4.0, 2.0 * kPi * 0.8, -1.0},   // 4 m/s^2 at 0.8 Hz
    {"p2_mid", 2.5, 2.0 * kPi * 1.5, -1.0},      // 2.5 m/s^2 at 1.5 Hz
    {"p3_vert", 3.5, 2.0 * kPi * 1.0, 3.0},      // with a vertical component
};

inline fs::path synthetic_records(const std::string& tag) {
  const fs::path dir = temp_dir(tag) / "records";
  fs::create_directories(dir / "synthetic");
  for (const auto& p : kPulses) write_pulse_csv(dir / "synthetic" / (p.name + ".csv"), p, 1.0);
  std::ofstream(dir / "README.md") << "not a record\n";
  return dir;
}

inline StudyGrid small_grid() {
  StudyGrid g;
  g.heights = 2;
  g.widths = 3;
  g.eccentricities = {0.5, 0.3};
  return g;
}

inline bool same_double(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

inline std::string csv_of(const std::vector<CaseResult>& r, const std::vector<StudyBody>& b,
                   const std::vector<StudyRecord>& rec) {
  std::ostringstream os;
  write_case_csv_rows(os, r, b, rec);
  return os.str();
}

}  // namespace
}  // namespace rocking_monitor::core::study
