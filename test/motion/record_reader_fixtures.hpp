#pragma once
// Shared fixtures of the record reader tests (test_record_reader*.cpp): a temp dir, error
// checks and builders of small synthetic AT2/SMC/BBP files with known values.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/motion/record_reader.hpp"

#ifndef ROCKING_RECORDS_DIR
#define ROCKING_RECORDS_DIR "/work/shared/records"
#endif

namespace fs = std::filesystem;
using rocking_monitor::core::AccelUnits;
using rocking_monitor::core::Component;
using rocking_monitor::core::detect_format;
using rocking_monitor::core::kGravity;
using rocking_monitor::core::read_record;
using rocking_monitor::core::ReadOptions;
using rocking_monitor::core::RecordError;
using rocking_monitor::core::RecordFormat;

namespace {

// ------------------------------------------------------------------ helpers

/// A fresh directory under the system temp dir, removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = fs::temp_directory_path() /
            ("rocking_record_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  /// Writes `content` byte for byte and returns the full path.
  std::string write(const std::string& name, const std::string& content) const {
    const fs::path p = path_ / name;
    std::ofstream out(p, std::ios::binary);
    out << content;
    return p.string();
  }
  std::string path(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline std::vector<std::string> split_lines_keep(const std::string& text, std::string* eol) {
  *eol = text.find("\r\n") != std::string::npos ? "\r\n" : "\n";
  std::vector<std::string> lines;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t e = text.find('\n', pos);
    if (e == std::string::npos) e = text.size();
    std::string l = text.substr(pos, e - pos);
    if (!l.empty() && l.back() == '\r') l.pop_back();
    lines.push_back(l);
    pos = e + 1;
  }
  return lines;
}

inline std::string join_lines(const std::vector<std::string>& lines, const std::string& eol) {
  std::string out;
  for (const auto& l : lines) out += l + eol;
  return out;
}

/// Runs fn and returns the RecordError message ("" if nothing was thrown). Any other exception
/// type fails the test.
inline std::string error_of(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const RecordError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected RecordError, got another exception: " << e.what();
    return "<wrong exception>";
  }
  return "";
}

/// Expects read_record(path) to throw a one-line RecordError that names the file, the line (if
/// line > 0: "<path>:<line>: ") and contains every `parts` text.
inline void expect_record_error(const std::string& path, std::size_t line, const std::vector<std::string>& parts,
                         const ReadOptions& options = {}) {
  const std::string msg = error_of([&] { read_record(path, options); });
  ASSERT_FALSE(msg.empty()) << "no RecordError for " << path;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << "message is not one line: " << msg;
  const std::string prefix = line > 0 ? path + ":" + std::to_string(line) + ": " : path + ": ";
  EXPECT_EQ(msg.rfind(prefix, 0), 0u) << "message should start with '" << prefix << "': " << msg;
  for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "missing '" << p << "' in: " << msg;
}

inline double peak_abs(const std::vector<double>& a) {
  double m = 0.0;
  for (double v : a) m = std::max(m, std::fabs(v));
  return m;
}

// ------------------------------------------------------------------ synthetic file builders

inline const char* kNgaTitle = "PEER NGA STRONG MOTION DATABASE RECORD";
inline const char* kNgaUnits = "ACCELERATION TIME SERIES IN UNITS OF G";

inline std::string at2(const std::string& title, const std::string& line2, const std::string& units,
                const std::string& line4, const std::vector<std::string>& value_lines, const std::string& eol = "\n") {
  std::string s = title + eol + line2 + eol + units + eol + line4 + eol;
  for (const auto& l : value_lines) s += l + eol;
  return s;
}

/// A 7-value NGA-West2 AT2 with the given NPTS/DT line.
inline std::string at2_seven(const std::string& line4, const std::string& eol = "\n") {
  return at2(kNgaTitle, "Test Event, 1/2/2003, Some Station, 090", kNgaUnits, line4,
             {"  -.2556093E-02   .1000000E+00  0.795256E-03  -.5000000E-01   1.0000000E+00",
              "   .2500000E-00  -.1234567E-05"},
             eol);
}
inline const std::vector<double> kSevenG = {-.2556093E-02, .1000000E+00, 0.795256E-03, -.5000000E-01,
                                     1.0,           .25,          -.1234567E-05};

inline void expect_values(const Component& c, const std::vector<double>& expected, double scale) {
  ASSERT_EQ(c.accel.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(c.accel[i], expected[i] * scale, 1e-12 * std::max(1.0, std::fabs(expected[i] * scale)))
        << "sample " << i;
  }
}

/// A synthetic USGS SMC V2 file: 11 text lines, 6x8 integers (10 wide), 10x5 reals (15 wide),
/// `n_comments` comment lines, then the values in 10-character fields, 8 per line.
inline std::string smc(const std::vector<std::string>& value_fields, int npts, double sps, int n_comments,
                const std::string& component = "360", const std::string& eol = "\n") {
  std::vector<std::string> lines = {
      "2 CORRECTED ACCELEROGRAM",
      "*",
      "SAF0A",
      "     1989  10  18    0004 Loma Prieta, CA",
      "Moment Mag=      7.1 Ms=      7.1 Ml=      7.0",
      "station = San Francisco, 1295 Shafter, F component=    " + component,
      "epicentral dist =     89.0       pk     =    104.4",
      "inst type=SMA-1      data source = USGS",
      "*",
      "*",
      "*"};
  std::vector<long long> ints(48, -32768);
  ints[1] = 1989;
  ints[15] = n_comments;
  ints[16] = npts;
  for (int r = 0; r < 6; ++r) {
    std::string l;
    for (int k = 0; k < 8; ++k) {
      char buf[16];
      std::snprintf(buf, sizeof buf, "%10lld", ints[static_cast<std::size_t>(r * 8 + k)]);
      l += buf;
    }
    lines.push_back(l);
  }
  std::vector<double> reals(50, 0.17e39);
  reals[1] = sps;
  for (int r = 0; r < 10; ++r) {
    std::string l;
    for (int k = 0; k < 5; ++k) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%15.7E", reals[static_cast<std::size_t>(r * 5 + k)]);
      l += buf;
    }
    lines.push_back(l);
  }
  for (int k = 0; k < n_comments; ++k) lines.push_back("|comment " + std::to_string(k + 1));
  std::string cur;
  int in_line = 0;
  for (const auto& f : value_fields) {
    std::string field = f;
    if (field.size() < 10) field = std::string(10 - field.size(), ' ') + field;
    cur += field;
    if (++in_line == 8) {
      lines.push_back(cur);
      cur.clear();
      in_line = 0;
    }
  }
  if (!cur.empty()) lines.push_back(cur);
  return join_lines(lines, eol);
}

/// 20 values printed like the real files ("1.5057E+0-2.2223E+0...": negative values touch).
inline std::vector<std::string> smc_fields20() {
  std::vector<std::string> f;
  for (int i = 0; i < 20; ++i) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4fE+0", (i % 2 == 0 ? 1.0 : -1.0) * (1.5 + 0.25 * i));
    f.push_back(buf);
  }
  return f;
}
inline std::vector<double> smc_values20() {
  std::vector<double> v;
  for (int i = 0; i < 20; ++i) v.push_back((i % 2 == 0 ? 1.0 : -1.0) * (1.5 + 0.25 * i));
  return v;
}

inline const char* kBbpHeader =
    "# Strong motion recording for 1992 Landers EQ\n"
    "# Station: tst01\n"
    "#    Vs30 (m/s): 345\n"
    "# Column 1: Time (s)\n"
    "# Column 2: North-south acceleration (cm/s/s) (+ is northward)\n"
    "# Column 3: East-west acceleration (cm/s/s) (+ is eastward)\n"
    "# Column 4: Up-down acceleration (cm/s/s) (+ is upward)\n"
    "#\n";

}  // namespace
