// Tests of the strong-motion record readers (src/motion/record_reader.cpp and one *_reader.cpp per format).
//
//  * RecordReaderAt2/Bbp/Smc/Csv/Detect: small synthetic files written to a temp dir
//    (known values in -> known SI values out). They run without the records directory.
//  * RecordReaderErrors: corrupted synthetic files, each must throw RecordError naming the file,
//    the line and the problem.
//  * RecordReaderRealData: every component of $ROCKING_RECORDS_DIR/MANIFEST.csv, plus corrupted
//    copies of real files (written to the temp dir, never into the source tree). Skipped with a
//    notice when the records directory is absent.

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

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> split_lines_keep(const std::string& text, std::string* eol) {
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

std::string join_lines(const std::vector<std::string>& lines, const std::string& eol) {
  std::string out;
  for (const auto& l : lines) out += l + eol;
  return out;
}

/// Runs fn and returns the RecordError message ("" if nothing was thrown). Any other exception
/// type fails the test.
std::string error_of(const std::function<void()>& fn) {
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
void expect_record_error(const std::string& path, std::size_t line, const std::vector<std::string>& parts,
                         const ReadOptions& options = {}) {
  const std::string msg = error_of([&] { read_record(path, options); });
  ASSERT_FALSE(msg.empty()) << "no RecordError for " << path;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << "message is not one line: " << msg;
  const std::string prefix = line > 0 ? path + ":" + std::to_string(line) + ": " : path + ": ";
  EXPECT_EQ(msg.rfind(prefix, 0), 0u) << "message should start with '" << prefix << "': " << msg;
  for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "missing '" << p << "' in: " << msg;
}

double peak_abs(const std::vector<double>& a) {
  double m = 0.0;
  for (double v : a) m = std::max(m, std::fabs(v));
  return m;
}

// ------------------------------------------------------------------ synthetic file builders

const char* kNgaTitle = "PEER NGA STRONG MOTION DATABASE RECORD";
const char* kNgaUnits = "ACCELERATION TIME SERIES IN UNITS OF G";

std::string at2(const std::string& title, const std::string& line2, const std::string& units,
                const std::string& line4, const std::vector<std::string>& value_lines, const std::string& eol = "\n") {
  std::string s = title + eol + line2 + eol + units + eol + line4 + eol;
  for (const auto& l : value_lines) s += l + eol;
  return s;
}

/// A 7-value NGA-West2 AT2 with the given NPTS/DT line.
std::string at2_seven(const std::string& line4, const std::string& eol = "\n") {
  return at2(kNgaTitle, "Test Event, 1/2/2003, Some Station, 090", kNgaUnits, line4,
             {"  -.2556093E-02   .1000000E+00  0.795256E-03  -.5000000E-01   1.0000000E+00",
              "   .2500000E-00  -.1234567E-05"},
             eol);
}
const std::vector<double> kSevenG = {-.2556093E-02, .1000000E+00, 0.795256E-03, -.5000000E-01,
                                     1.0,           .25,          -.1234567E-05};

void expect_values(const Component& c, const std::vector<double>& expected, double scale) {
  ASSERT_EQ(c.accel.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(c.accel[i], expected[i] * scale, 1e-12 * std::max(1.0, std::fabs(expected[i] * scale)))
        << "sample " << i;
  }
}

/// A synthetic USGS SMC V2 file: 11 text lines, 6x8 integers (10 wide), 10x5 reals (15 wide),
/// `n_comments` comment lines, then the values in 10-character fields, 8 per line.
std::string smc(const std::vector<std::string>& value_fields, int npts, double sps, int n_comments,
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
std::vector<std::string> smc_fields20() {
  std::vector<std::string> f;
  for (int i = 0; i < 20; ++i) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4fE+0", (i % 2 == 0 ? 1.0 : -1.0) * (1.5 + 0.25 * i));
    f.push_back(buf);
  }
  return f;
}
std::vector<double> smc_values20() {
  std::vector<double> v;
  for (int i = 0; i < 20; ++i) v.push_back((i % 2 == 0 ? 1.0 : -1.0) * (1.5 + 0.25 * i));
  return v;
}

const char* kBbpHeader =
    "# Strong motion recording for 1992 Landers EQ\n"
    "# Station: tst01\n"
    "#    Vs30 (m/s): 345\n"
    "# Column 1: Time (s)\n"
    "# Column 2: North-south acceleration (cm/s/s) (+ is northward)\n"
    "# Column 3: East-west acceleration (cm/s/s) (+ is eastward)\n"
    "# Column 4: Up-down acceleration (cm/s/s) (+ is upward)\n"
    "#\n";

// ------------------------------------------------------------------ manifest

/// RFC-4180 style CSV line parser: quoted fields may hold commas and "" escapes.
std::vector<std::string> parse_csv_line(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < line.size() && line[i + 1] == '"') {
          cur.push_back('"');
          ++i;
        } else {
          quoted = false;
        }
      } else {
        cur.push_back(c);
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.push_back(cur);
      cur.clear();
    } else if (c != '\r') {
      cur.push_back(c);
    }
  }
  out.push_back(cur);
  return out;
}

struct ManifestRow {
  std::map<std::string, std::string> f;
  const std::string& operator[](const std::string& k) const { return f.at(k); }
};

std::vector<ManifestRow> read_manifest(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> cols;
  std::vector<ManifestRow> rows;
  while (std::getline(in, line)) {
    if (line.empty() || line == "\r") continue;
    const auto fields = parse_csv_line(line);
    if (cols.empty()) {
      cols = fields;
      continue;
    }
    EXPECT_EQ(fields.size(), cols.size()) << "manifest row with wrong field count: " << line;
    ManifestRow r;
    for (std::size_t i = 0; i < cols.size() && i < fields.size(); ++i) r.f[cols[i]] = fields[i];
    rows.push_back(std::move(r));
  }
  return rows;
}

/// Returns the records dir, or "" when it is absent.
std::string shared_records_dir() {
  const std::string dir = ROCKING_RECORDS_DIR;
  if (!fs::is_directory(dir) || !fs::is_regular_file(fs::path(dir) / "MANIFEST.csv")) return "";
  return dir;
}

#define SKIP_WITHOUT_RECORDS(dir)                                                         \
  const std::string dir = shared_records_dir();                                           \
  if (dir.empty()) {                                                                      \
    GTEST_SKIP() << "records directory not found: " << ROCKING_RECORDS_DIR                \
                 << " (set -DROCKING_RECORDS_DIR=...; real-data tests skipped)";          \
  }

}  // namespace

// =================================================================== PEER AT2

TEST(RecordReaderAt2, NgaHeaderWithoutComma) {
  TempDir tmp;
  const auto p = tmp.write("a.AT2", at2_seven("NPTS=      7  DT=   .0050 SEC,   4 POLE @    30.00000 HZ"));
  const auto comps = read_record(p);
  ASSERT_EQ(comps.size(), 1u);
  const Component& c = comps[0];
  expect_values(c, kSevenG, kGravity);
  EXPECT_DOUBLE_EQ(c.dt, 0.005);
  EXPECT_EQ(c.t0, 0.0);
  EXPECT_EQ(c.file, p);
  EXPECT_EQ(c.event, "Test Event");
  EXPECT_EQ(c.station, "Some Station");
  EXPECT_EQ(c.label, "090");
  EXPECT_FALSE(c.vertical);
  EXPECT_NEAR(c.duration(), 6 * 0.005, 1e-15);
}

TEST(RecordReaderAt2, NgaHeaderWithComma) {
  TempDir tmp;
  const auto p = tmp.write("b.AT2", at2_seven("NPTS=      7, DT=   .0100 SEC,   0 POLE @    30.00000 HZ,  -5 POLE"));
  const auto c = read_record(p).at(0);
  expect_values(c, kSevenG, kGravity);
  EXPECT_DOUBLE_EQ(c.dt, 0.01);
}

TEST(RecordReaderAt2, Peer1999Header) {
  TempDir tmp;
  const auto text = at2("PEER STRONG MOTION DATABASE RECORD. PROCESSING BY PACIFIC ENGINEERING.",
                        "IMPERIAL VALLEY 10/15/79 2316, EL CENTRO ARRAY #12, 140 (USGS STATION 931)",
                        "ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.1 Hz LP=40.0 Hz",
                        "NPTS=  7, DT= .00500 SEC",
                        {"  -.2556093E-02   .1000000E+00  0.795256E-03  -.5000000E-01   1.0000000E+00",
                         "   .2500000E-00  -.1234567E-05"});
  const auto p = tmp.write("H-E12140.at2", text);
  EXPECT_EQ(detect_format(p), RecordFormat::PeerAt2);
  const auto c = read_record(p).at(0);
  expect_values(c, kSevenG, kGravity);
  EXPECT_DOUBLE_EQ(c.dt, 0.005);
  EXPECT_EQ(c.event, "IMPERIAL VALLEY");
  EXPECT_EQ(c.station, "EL CENTRO ARRAY #12");
  EXPECT_EQ(c.label, "140");
}

TEST(RecordReaderAt2, OldNgaHeaderCountThenDt) {
  TempDir tmp;
  const auto text = at2(kNgaTitle, "KOBE 01/16/95 2046, NISHI-AKASHI, 090 (CUE)                ",
                        "ACCELERATION TIME HISTORY IN UNITS OF G", "7    0.0050    NPTS, DT",
                        {"   -.2556093E-02   0.100000E+00   0.795256E-03  -0.500000E-01   0.100000E+01",
                         "   0.250000E+00  -0.1234567E-05"});
  const auto p = tmp.write("NIS090.AT2", text);
  const auto c = read_record(p).at(0);
  expect_values(c, kSevenG, kGravity);
  EXPECT_DOUBLE_EQ(c.dt, 0.005);
  EXPECT_EQ(c.event, "KOBE");
  EXPECT_EQ(c.station, "NISHI-AKASHI");
  EXPECT_EQ(c.label, "090");
}

TEST(RecordReaderAt2, CrlfAndValuesAfterNptsIgnored) {
  TempDir tmp;
  // NPTS = 5 but 7 values (+ a text pad) follow: exactly 5 are read, the rest is ignored.
  const auto p = tmp.write("c.AT2", at2_seven("NPTS=      5, DT=   .0100 SEC", "\r\n") + "  .0  trailing-junk\r\n");
  const auto c = read_record(p).at(0);
  ASSERT_EQ(c.accel.size(), 5u);
  expect_values(c, std::vector<double>(kSevenG.begin(), kSevenG.begin() + 5), kGravity);
  EXPECT_EQ(c.station, "Some Station");  // no '\r' left in metadata
  EXPECT_EQ(c.label, "090");
}

TEST(RecordReaderAt2, TitleVariantsAndStationWithCommas) {
  struct Case {
    std::string line2, event, station, label;
  };
  const std::vector<Case> cases = {
      {"Loma Prieta, 10/18/1989, Emeryville; Pacific Park #2, Free Field, 260", "Loma Prieta",
       "Emeryville; Pacific Park #2, Free Field", "260"},
      {"NORTHRIDGE EQ 1/17/94, 12:31, BURBANK - HOWARD, 330 (USC STATION 90059)", "NORTHRIDGE EQ", "BURBANK - HOWARD",
       "330"},
      {"NORTHRIDGE, 1/17/94 12:31, VASQUEZ ROCKS PARK, 090 (CDMG STATION 24047)", "NORTHRIDGE", "VASQUEZ ROCKS PARK",
       "090"},
      {"LOMA PRIETA 10/18/89 00:05, GILROY GAVILAN COLL, 067 (CDMG STATION 47006)", "LOMA PRIETA",
       "GILROY GAVILAN COLL", "067"},
      {"Kobe Japan, 1/16/1995, Port Island (0 m), 0", "Kobe Japan", "Port Island (0 m)", "0"},
  };
  TempDir tmp;
  int k = 0;
  for (const auto& cs : cases) {
    SCOPED_TRACE(cs.line2);
    const auto p = tmp.write("t" + std::to_string(k++) + ".AT2",
                             at2(kNgaTitle, cs.line2, kNgaUnits, "NPTS= 2, DT= .01 SEC", {" .1E-01 -.2E-01"}));
    const auto c = read_record(p).at(0);
    EXPECT_EQ(c.event, cs.event);
    EXPECT_EQ(c.station, cs.station);
    EXPECT_EQ(c.label, cs.label);
  }
}

TEST(RecordReaderAt2, VerticalDwnIsFlippedToPositiveUp) {
  TempDir tmp;
  const auto dwn = tmp.write("x_DWN.AT2", at2(kNgaTitle, "San Fernando, 2/9/1971, Lake Hughes #1, DWN", kNgaUnits,
                                              "NPTS=  3, DT= .0100 SEC", {"  .1000000E+00  -.2000000E+00  .5E-01"}));
  const auto up = tmp.write("x_UP.AT2", at2(kNgaTitle, "Northridge-01, 1/17/1994, Rinaldi Receiving Sta, UP",
                                            kNgaUnits, "NPTS=  3, DT= .0100 SEC", {"  .1000000E+00  -.2000000E+00  .5E-01"}));
  const auto d = read_record(dwn).at(0);
  const auto u = read_record(up).at(0);
  EXPECT_TRUE(d.vertical);
  EXPECT_TRUE(u.vertical);
  EXPECT_EQ(d.label, "DWN");  // label kept as written
  EXPECT_EQ(u.label, "UP");
  expect_values(d, {-0.1, 0.2, -0.05}, kGravity);  // positive down in the file -> negated
  expect_values(u, {0.1, -0.2, 0.05}, kGravity);
  EXPECT_TRUE(rocking_monitor::core::label_is_positive_down("DWN"));
  EXPECT_TRUE(rocking_monitor::core::label_is_positive_down("down"));
  EXPECT_FALSE(rocking_monitor::core::label_is_positive_down("UP"));
  EXPECT_FALSE(rocking_monitor::core::label_is_positive_down("U-D"));
  EXPECT_TRUE(rocking_monitor::core::label_is_vertical("-UP"));
  EXPECT_TRUE(rocking_monitor::core::label_is_vertical("up"));
  EXPECT_TRUE(rocking_monitor::core::label_is_vertical("U-D"));
  EXPECT_TRUE(rocking_monitor::core::label_is_vertical("V"));
  EXPECT_FALSE(rocking_monitor::core::label_is_vertical("090"));
  EXPECT_FALSE(rocking_monitor::core::label_is_vertical("N-S"));
  EXPECT_FALSE(rocking_monitor::core::label_is_vertical("W"));
}

TEST(RecordReaderAt2, FortranDExponentAccepted) {
  TempDir tmp;
  const auto p = tmp.write("d.AT2", at2(kNgaTitle, "E, 1/1/2000, S, 0", kNgaUnits, "NPTS= 3, DT= .01 SEC",
                                        {"  .25D-01  -1.5d+00  +2.0E-3"}));
  expect_values(read_record(p).at(0), {0.025, -1.5, 0.002}, kGravity);
}

// =================================================================== SCEC BBP

TEST(RecordReaderBbp, ThreeComponentsCmPerS2ToSi) {
  TempDir tmp;
  const std::string rows =
      "5.000000e-01\t1.000000e+00\t-2.000000e+00\t3.000000e+00\n"
      "5.100000e-01\t-4.000000e+00\t5.000000e+00\t-6.000000e+00\n"
      "5.200000e-01\t7.000000e+00\t-8.000000e+00\t9.000000e+00\n";
  const auto p = tmp.write("tst01.bbp", std::string(kBbpHeader) + rows);
  EXPECT_EQ(detect_format(p), RecordFormat::Bbp);
  const auto comps = read_record(p);
  ASSERT_EQ(comps.size(), 3u);
  const char* labels[3] = {"N-S", "E-W", "U-D"};
  const std::vector<std::vector<double>> expect = {{1, -4, 7}, {-2, 5, -8}, {3, -6, 9}};
  for (int k = 0; k < 3; ++k) {
    const Component& c = comps[static_cast<std::size_t>(k)];
    SCOPED_TRACE(labels[k]);
    EXPECT_EQ(c.label, labels[k]);
    EXPECT_EQ(c.vertical, k == 2);
    EXPECT_NEAR(c.dt, 0.01, 1e-12);
    EXPECT_DOUBLE_EQ(c.t0, 0.5);
    EXPECT_EQ(c.station, "tst01");
    EXPECT_EQ(c.event, "1992 Landers EQ");
    EXPECT_EQ(c.file, p);
    expect_values(c, expect[static_cast<std::size_t>(k)], 0.01);  // U-D "+ is upward": not flipped
  }
}

TEST(RecordReaderBbp, LabelOnlyHeaderMixedSeparatorsAndRoundedTimes) {
  TempDir tmp;
  // gmsvtoolkit style header; rows switch from tab-separated %e to space-separated %f like the
  // Landers files; the printed time stamps carry rounding (3.000260e-02 ... 10.000000).
  std::string text = "#    time(sec)      N-S(cm/s/s)      E-W(cm/s/s)      U-D(cm/s/s)\r\n";
  const int n = 2001;
  for (int i = 0; i < n; ++i) {
    const double t = 0.0300026 + 0.005 * i;
    char buf[160];
    if (t < 5.0) {
      std::snprintf(buf, sizeof buf, "%.6e\t%.6e\t%.6e\t%.6e\r\n", t, 1.0 * i, -2.0, 0.5);
    } else {
      std::snprintf(buf, sizeof buf, " %.6f        %.4f          -2.0000          0.5000\r\n", t, 1.0 * i);
    }
    text += buf;
  }
  const auto p = tmp.write("2009-XYZ.bbp", text);
  const auto comps = read_record(p);
  ASSERT_EQ(comps.size(), 3u);
  EXPECT_EQ(comps[0].station, "2009-XYZ");  // no "# Station:" line: BBP id = file name
  EXPECT_EQ(comps[0].event, "");
  EXPECT_EQ(comps[0].accel.size(), static_cast<std::size_t>(n));
  EXPECT_NEAR(comps[0].dt, 0.005, 1e-9);
  EXPECT_NEAR(comps[0].t0, 0.0300026, 1e-12);
  EXPECT_NEAR(comps[0].accel[1234], 12.34, 1e-12);
  EXPECT_NEAR(comps[2].accel[2000], 0.005, 1e-15);
}

TEST(RecordReaderBbp, RejectsVelocityFileAndWrongColumnCount) {
  TempDir tmp;
  const auto vel = tmp.write("v.bbp",
                             "#    time(sec)      N-S(cm/s)      E-W(cm/s)      U-D(cm/s)\n"
                             "0.0 1 2 3\n0.01 1 2 3\n");
  expect_record_error(vel, 1, {"not an acceleration file"});
  const auto cols = tmp.write("c.bbp", std::string(kBbpHeader) + "0.0 1 2 3\n0.01 1 2\n0.02 1 2 3\n");
  expect_record_error(cols, 10, {"expected 4 columns", "found 3"});
}

// =================================================================== USGS SMC V2

TEST(RecordReaderSmc, TouchingFixedWidthFields) {
  TempDir tmp;
  // first data line as in 0111a.smc: the fields touch, so whitespace splitting would fail
  std::vector<std::string> f = {" 1.5057E+0", "-2.2223E+0", "-1.9234E+0", "-3.1562E+0", "-3.2440E+0",
                                "-3.5638E+0", "-5.1941E+0", "-5.7933E+0", "-5.0138E-1", " 1.9171E+0"};
  const auto p = tmp.write("0111a.smc", smc(f, 10, 200.0, 3));
  EXPECT_EQ(detect_format(p), RecordFormat::UsgsSmc);
  const auto comps = read_record(p);
  ASSERT_EQ(comps.size(), 1u);
  const Component& c = comps[0];
  expect_values(c, {1.5057, -2.2223, -1.9234, -3.1562, -3.2440, -3.5638, -5.1941, -5.7933, -0.50138, 1.9171}, 0.01);
  EXPECT_DOUBLE_EQ(c.dt, 0.005);
  EXPECT_EQ(c.t0, 0.0);
  EXPECT_EQ(c.station, "San Francisco, 1295 Shafter, F");
  EXPECT_EQ(c.label, "360");
  EXPECT_EQ(c.event, "Loma Prieta, CA");
  EXPECT_FALSE(c.vertical);
}

TEST(RecordReaderSmc, CrlfVerticalUpAndDown) {
  TempDir tmp;
  const auto up = tmp.write("b.smc", smc(smc_fields20(), 20, 100.0, 2, "up", "\r\n"));
  const auto c = read_record(up).at(0);
  EXPECT_TRUE(c.vertical);
  EXPECT_EQ(c.label, "up");
  EXPECT_DOUBLE_EQ(c.dt, 0.01);
  expect_values(c, smc_values20(), 0.01);
  const auto down = tmp.write("d.smc", smc(smc_fields20(), 20, 100.0, 2, "down"));
  const auto d = read_record(down).at(0);
  EXPECT_TRUE(d.vertical);
  expect_values(d, smc_values20(), -0.01);
}

TEST(RecordReaderSmc, ValuesAfterNptsIgnored) {
  TempDir tmp;
  const auto p = tmp.write("e.smc", smc(smc_fields20(), 13, 50.0, 0));
  const auto c = read_record(p).at(0);
  const auto all = smc_values20();
  expect_values(c, std::vector<double>(all.begin(), all.begin() + 13), 0.01);
  EXPECT_DOUBLE_EQ(c.dt, 0.02);
}

// =================================================================== CSV / whitespace

TEST(RecordReaderCsv, TwoColumnsCommaHeaderInG) {
  TempDir tmp;
  const auto p = tmp.write("rec.csv", "time_s,accel_g\n0.00,0.10\n0.01,-0.20\n0.02, 0.05\n\n");
  ReadOptions o;
  o.csv_units = AccelUnits::G;
  const auto comps = read_record(p, o);
  ASSERT_EQ(comps.size(), 1u);
  EXPECT_EQ(comps[0].label, "H");
  EXPECT_FALSE(comps[0].vertical);
  EXPECT_NEAR(comps[0].dt, 0.01, 1e-15);
  EXPECT_EQ(comps[0].t0, 0.0);
  expect_values(comps[0], {0.10, -0.20, 0.05}, kGravity);
}

TEST(RecordReaderCsv, ThreeColumnsWhitespaceCmPerS2WithOffsetStart) {
  TempDir tmp;
  const auto p = tmp.write("rec.txt", "  2.50  \t 10.0   -5.0\r\n  2.52  20.0  -10.0\r\n  2.54\t30.0\t-15.0\r\n");
  ReadOptions o;
  o.csv_units = AccelUnits::CentimetersPerSecond2;
  EXPECT_EQ(detect_format(p), RecordFormat::Csv);
  const auto comps = read_record(p, o);
  ASSERT_EQ(comps.size(), 2u);
  EXPECT_EQ(comps[1].label, "V");
  EXPECT_TRUE(comps[1].vertical);
  EXPECT_DOUBLE_EQ(comps[0].t0, 2.5);
  EXPECT_DOUBLE_EQ(comps[1].t0, 2.5);
  EXPECT_NEAR(comps[0].dt, 0.02, 1e-12);
  expect_values(comps[0], {10, 20, 30}, 0.01);
  expect_values(comps[1], {-5, -10, -15}, 0.01);
}

TEST(RecordReaderCsv, DefaultUnitsAreSi) {
  TempDir tmp;
  const auto p = tmp.write("si.csv", "0.0 , 1.5\n0.5 , -2.5\n1.0 , 3e-1\n");
  const auto c = read_record(p).at(0);
  expect_values(c, {1.5, -2.5, 0.3}, 1.0);
  EXPECT_DOUBLE_EQ(c.dt, 0.5);
}

// =================================================================== detection

TEST(RecordReaderDetect, ContentBeforeExtension) {
  TempDir tmp;
  const auto a = tmp.write("at2_content.txt", at2_seven("NPTS=      7, DT=   .0100 SEC"));
  const auto b = tmp.write("bbp_content.dat", std::string(kBbpHeader) + "0.0 1 2 3\n0.01 1 2 3\n");
  const auto s = tmp.write("smc_content.csv", smc(smc_fields20(), 20, 100.0, 1));
  const auto c = tmp.write("csv_content.foo", "t,a\n0,1\n0.1,2\n");
  EXPECT_EQ(detect_format(a), RecordFormat::PeerAt2);
  EXPECT_EQ(detect_format(b), RecordFormat::Bbp);
  EXPECT_EQ(detect_format(s), RecordFormat::UsgsSmc);
  EXPECT_EQ(detect_format(c), RecordFormat::Csv);
  EXPECT_EQ(read_record(a).size(), 1u);
  EXPECT_EQ(read_record(b).size(), 3u);
  EXPECT_EQ(read_record(s).size(), 1u);
  EXPECT_EQ(read_record(c).size(), 1u);
  // unknown content: the extension decides
  const auto ext = tmp.write("odd.AT2", "hello\nworld\n");
  EXPECT_EQ(detect_format(ext), RecordFormat::PeerAt2);
  EXPECT_STREQ(rocking_monitor::core::to_string(RecordFormat::UsgsSmc), "usgs_smc");
}

TEST(RecordReaderDetect, UnknownFormatAndForcedFormat) {
  TempDir tmp;
  const auto u = tmp.write("notes.xyz", "just some text\nnothing numeric here\n");
  EXPECT_EQ(detect_format(u), RecordFormat::Auto);
  expect_record_error(u, 0, {"unknown record format"});
  // a CSV forced to be read as AT2 fails on its header, not with a crash
  const auto c = tmp.write("forced.csv", "0,1\n0.1,2\n0.2,3\n");
  ReadOptions o;
  o.format = RecordFormat::PeerAt2;
  expect_record_error(c, 3, {"bad header"}, o);
  o.format = RecordFormat::Csv;
  EXPECT_EQ(read_record(c, o).at(0).accel.size(), 3u);
}

// =================================================================== errors (synthetic)

TEST(RecordReaderErrors, MissingFileAndDirectory) {
  TempDir tmp;
  const auto missing = tmp.path("does_not_exist.AT2");
  expect_record_error(missing, 0, {"does_not_exist.AT2", "cannot open"});
  EXPECT_NE(error_of([&] { detect_format(missing); }).find("cannot open"), std::string::npos);
  const auto dir = tmp.path("");
  EXPECT_FALSE(error_of([&] { read_record(dir); }).empty());
  const auto empty = tmp.write("empty.AT2", "");
  expect_record_error(empty, 0, {"empty file"});
}

TEST(RecordReaderErrors, At2FewerValuesThanNpts) {
  TempDir tmp;
  const auto p = tmp.write("short.AT2", at2_seven("NPTS=      9, DT=   .0050 SEC"));
  expect_record_error(p, 6, {"expected 9 values (NPTS), found 7"});
}

TEST(RecordReaderErrors, At2BadHeaderLine) {
  TempDir tmp;
  const auto garbage = tmp.write("g.AT2", at2_seven("NPTS=   x7y, DT=   .0050 SEC"));
  expect_record_error(garbage, 4, {"bad header", "NPTS", "'x7y'"});
  const auto partial = tmp.write("g2.AT2", at2_seven("NPTS=   7q, DT=   .0050 SEC"));
  expect_record_error(partial, 4, {"bad header", "NPTS"});
  const auto nodt = tmp.write("g3.AT2", at2_seven("NPTS=      7"));
  expect_record_error(nodt, 4, {"bad header", "missing DT"});
  const auto none = tmp.write("g4.AT2", at2_seven("@@@@ garbage ####"));
  expect_record_error(none, 4, {"bad header", "NPTS"});
  const auto baddt = tmp.write("g5.AT2", at2_seven("NPTS=      7, DT= .0.05 SEC"));
  expect_record_error(baddt, 4, {"bad header", "DT", "'.0.05'"});
  const auto units = tmp.write("g6.AT2", at2(kNgaTitle, "E, 1/1/2000, S, 0", "VELOCITY TIME SERIES IN UNITS OF CM/S",
                                             "NPTS= 2, DT= .01 SEC", {" .1 .2"}));
  expect_record_error(units, 3, {"bad header", "UNITS OF G"});
  const auto few = tmp.write("g7.AT2", "PEER NGA STRONG MOTION DATABASE RECORD\nonly two lines\n");
  expect_record_error(few, 2, {"bad header"});
}

TEST(RecordReaderErrors, At2NonPositiveDtAndEmptyData) {
  TempDir tmp;
  const auto zero = tmp.write("z.AT2", at2_seven("NPTS=      7, DT=   .0000 SEC"));
  expect_record_error(zero, 4, {"non-positive DT"});
  const auto neg = tmp.write("n.AT2", at2_seven("NPTS=      7, DT=   -.0100 SEC"));
  expect_record_error(neg, 4, {"non-positive DT"});
  const auto empty = tmp.write("e.AT2", at2_seven("NPTS=      0, DT=   .0100 SEC"));
  expect_record_error(empty, 4, {"empty data"});
}

TEST(RecordReaderErrors, NonNumericToken) {
  TempDir tmp;
  const auto p = tmp.write("bad.AT2", at2(kNgaTitle, "E, 1/1/2000, S, 0", kNgaUnits, "NPTS= 6, DT= .01 SEC",
                                          {" .1E-01  .2E-01  .3E-01", " .4E-01  1.2.3  .6E-01"}));
  expect_record_error(p, 6, {"non-numeric value '1.2.3'"});
  for (const std::string tok : {"0x10", "1e", "12abc", "--1", "1.0E+0x", "."}) {
    SCOPED_TRACE(tok);
    const auto q = tmp.write("tok.AT2", at2(kNgaTitle, "E, 1/1/2000, S, 0", kNgaUnits, "NPTS= 3, DT= .01 SEC",
                                            {" .1E-01 " + tok + " .3E-01"}));
    expect_record_error(q, 5, {"non-numeric value '" + tok + "'"});
  }
  const auto csv = tmp.write("bad.csv", "time,a\n0.0,1.0\n0.1,1.2.3\n");
  expect_record_error(csv, 3, {"non-numeric value '1.2.3'"});
}

TEST(RecordReaderErrors, NonFiniteValues) {
  TempDir tmp;
  for (const std::string tok : {"NaN", "nan", "-inf", "Infinity", "1e999"}) {
    SCOPED_TRACE(tok);
    const auto p = tmp.write("nan.AT2", at2(kNgaTitle, "E, 1/1/2000, S, 0", kNgaUnits, "NPTS= 3, DT= .01 SEC",
                                            {" .1E-01 .2E-01", " " + tok}));
    expect_record_error(p, 6, {"non-finite value '" + tok + "'"});
  }
  const auto bbp = tmp.write("nan.bbp", std::string(kBbpHeader) + "0.0 1 2 3\n0.01 1 NaN 3\n");
  expect_record_error(bbp, 10, {"non-finite value 'NaN'"});
  const auto csv = tmp.write("nan.csv", "0.0 1\n0.1 nan\n");
  expect_record_error(csv, 2, {"non-finite value 'nan'"});
  // underflow is not an error: the value is simply (nearly) zero
  const auto tiny = tmp.write("tiny.csv", "0.0 1e-400\n0.1 0\n");
  EXPECT_NEAR(read_record(tiny).at(0).accel[0], 0.0, 1e-300);
}

TEST(RecordReaderErrors, NonUniformTimeColumn) {
  TempDir tmp;
  const auto jump = tmp.write("jump.csv", "time_s,accel\n0.00,1\n0.01,2\n0.02,3\n0.04,4\n0.05,5\n");
  expect_record_error(jump, 5, {"non-uniform time step"});
  // small jitter beyond the printed-digit rounding
  const auto jitter = tmp.write("jitter.csv", "0.000000 1\n0.010000 2\n0.020000 3\n0.030200 4\n0.040000 5\n");
  expect_record_error(jitter, 4, {"non-uniform time step"});
  // a slow drift (each step within the tolerance, the grid not)
  std::string drift;
  for (int i = 0; i < 400; ++i) {
    char buf[64];
    // 5e-9 s extra per step after row 200: every step passes, the accumulated drift does not
    std::snprintf(buf, sizeof buf, "%.9f 0\n", i * 0.01 + (i > 200 ? (i - 200) * 5e-9 : 0.0));
    drift += buf;
  }
  const auto d = tmp.write("drift.csv", drift);
  expect_record_error(d, 201, {"non-uniform time step", "off the uniform grid"});
  const auto dup = tmp.write("dup.csv", "0.00 1\n0.01 2\n0.01 3\n0.02 4\n");
  expect_record_error(dup, 3, {"non-uniform time step", "not increasing"});
  // uniform, but dt = 1/300 s printed with 5 decimals: the rounding is not a reason to reject
  std::string coarse;
  for (int i = 0; i < 3000; ++i) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.5f,%d\n", i / 300.0, i % 7);
    coarse += buf;
  }
  const auto uc = read_record(tmp.write("coarse.csv", coarse)).at(0);
  EXPECT_NEAR(uc.dt, 1.0 / 300.0, 1e-8);
  const auto back = tmp.write("back.csv", "0.02 1\n0.01 2\n0.0 3\n");
  expect_record_error(back, 2, {"non-positive time step"});
  const auto bbp = tmp.write("gap.bbp", std::string(kBbpHeader) + "0.00 1 2 3\n0.01 1 2 3\n0.03 1 2 3\n");
  expect_record_error(bbp, 11, {"non-uniform time step"});
}

TEST(RecordReaderErrors, CsvShapeProblems) {
  TempDir tmp;
  expect_record_error(tmp.write("one.csv", "0.0\n0.1\n"), 1, {"expected 2 or 3 columns"});
  expect_record_error(tmp.write("cols.csv", "0.0 1 2\n0.1 1\n"), 2, {"expected 3 columns"});
  expect_record_error(tmp.write("gap.csv", "0.0,,1\n0.1,1,1\n"), 1, {"empty field"});
  expect_record_error(tmp.write("hdr2.csv", "time,a\nagain,b\n0,1\n"), 2, {"non-numeric value 'again'"});
  expect_record_error(tmp.write("onlyhdr.csv", "time,a\n\n"), 0, {"empty data"});
  expect_record_error(tmp.write("single.csv", "0.0,1\n"), 1, {"at least 2 samples"});
  expect_record_error(tmp.write("hdr.bbp", kBbpHeader), 0, {"empty data"});
}

TEST(RecordReaderErrors, SmcMissingOrDamagedLines) {
  TempDir tmp;
  const std::string good = smc(smc_fields20(), 20, 100.0, 2);
  std::string eol;
  const auto lines = split_lines_keep(good, &eol);
  ASSERT_EQ(lines.size(), 27u + 2u + 3u);

  auto without = [&](std::size_t line_no) {  // 1-based
    auto l = lines;
    l.erase(l.begin() + static_cast<long>(line_no - 1));
    return join_lines(l, eol);
  };
  // a missing data line (the middle one of three): 8 + 4 values left
  expect_record_error(tmp.write("m1.smc", without(31)), 31, {"expected 20 values (NPTS), found 12"});
  // the last data line missing
  expect_record_error(tmp.write("m2.smc", without(32)), 31, {"expected 20 values (NPTS), found 16"});
  // a missing comment line: the first data line is taken where a comment should be
  expect_record_error(tmp.write("m3.smc", without(29)), 29, {"expected comment line 2 of 2"});
  // a missing text header line shifts the integer block
  expect_record_error(tmp.write("m4.smc", without(5)), 17, {"bad header", "integer"});
  // a data line cut short in the middle of the data
  auto cut = lines;
  cut[29] = cut[29].substr(0, 50);
  expect_record_error(tmp.write("m5.smc", join_lines(cut, eol)), 30, {"short data line (5 of 8 values)"});
  // NPTS missing (-32768) and bad sampling rate
  expect_record_error(tmp.write("m6.smc", smc(smc_fields20(), -32768, 100.0, 2)), 14, {"missing NPTS"});
  expect_record_error(tmp.write("m7.smc", smc(smc_fields20(), 20, 0.0, 2)), 18, {"non-positive sampling rate"});
  // non-numeric field
  auto bad = lines;
  bad[29].replace(10, 10, "   1.2.3  ");
  expect_record_error(tmp.write("m8.smc", join_lines(bad, eol)), 30, {"non-numeric value '1.2.3'"});
  // V1 (uncorrected) is not read as V2
  auto v1 = lines;
  v1[0] = "1 UNCORRECTED ACCELEROGRAM";
  expect_record_error(tmp.write("m9.smc", join_lines(v1, eol)), 1, {"unsupported SMC file type"}, [] {
    ReadOptions o;
    o.format = RecordFormat::UsgsSmc;
    return o;
  }());
}

TEST(RecordReaderErrors, BinaryGarbageDoesNotCrash) {
  TempDir tmp;
  std::string junk;
  for (int i = 0; i < 5000; ++i) junk.push_back(static_cast<char>((i * 7919 + 13) % 256));
  const auto p = tmp.write("junk.AT2", junk);
  const std::string msg = error_of([&] { read_record(p); });
  EXPECT_FALSE(msg.empty());
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  for (RecordFormat f : {RecordFormat::Bbp, RecordFormat::UsgsSmc, RecordFormat::Csv}) {
    ReadOptions o;
    o.format = f;
    EXPECT_FALSE(error_of([&] { read_record(p, o); }).empty());
  }
}

// =================================================================== real records

TEST(RecordReaderRealData, EveryManifestComponentParses) {
  SKIP_WITHOUT_RECORDS(dir);
  const auto rows = read_manifest(dir + "/MANIFEST.csv");
  ASSERT_EQ(rows.size(), 300u) << "the README says 300 component time series";

  std::map<std::string, std::vector<Component>> cache;
  const auto start = std::chrono::steady_clock::now();
  for (const auto& r : rows) {
    const std::string path = dir + "/" + r["file"];
    if (cache.count(path) == 0) {
      try {
        cache[path] = read_record(path);
      } catch (const RecordError& e) {
        ADD_FAILURE() << e.what();
        cache[path] = {};
      }
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "[ timing   ] parsed " << cache.size() << " files (" << rows.size() << " components) in " << seconds
            << " s\n";
  EXPECT_LT(seconds, 10.0);

  std::size_t checked = 0;
  for (const auto& r : rows) {
    const std::string path = dir + "/" + r["file"];
    SCOPED_TRACE(r["file"] + " " + r["component"]);
    const auto& comps = cache[path];
    const std::string& comp = r["component"];
    ASSERT_GE(comp.size(), 3u);
    const bool want_vertical = comp[0] == 'V';
    const std::string label = comp.substr(2);
    const Component* c = nullptr;
    for (const auto& x : comps) {
      if (x.label == label) c = &x;
    }
    if (c == nullptr) {
      ADD_FAILURE() << "component " << label << " not found in " << path;
      continue;
    }
    const std::string& fmt = r["format"];
    const RecordFormat expected_format = fmt.rfind("PEER_AT2", 0) == 0 ? RecordFormat::PeerAt2
                                         : fmt == "BBP_4COL"           ? RecordFormat::Bbp
                                         : fmt == "USGS_SMC_V2"        ? RecordFormat::UsgsSmc
                                                                       : RecordFormat::Auto;
    EXPECT_EQ(detect_format(path), expected_format);
    EXPECT_EQ(c->file, path);
    EXPECT_EQ(c->vertical, want_vertical);
    EXPECT_EQ(c->accel.size(), std::stoul(r["npts"]));
    const double dt = std::stod(r["dt_s"]);
    EXPECT_NEAR(c->dt, dt, 1e-6 * dt);
    const double pga = peak_abs(c->accel) / kGravity;
    const double pga_manifest = std::stod(r["pga_g"]);
    EXPECT_NEAR(pga, pga_manifest, std::max(1e-3 * pga_manifest, 0.00006));
    for (double v : c->accel) ASSERT_TRUE(std::isfinite(v));

    if (expected_format == RecordFormat::Bbp) {
      // manifest station names for BBP are descriptive; they quote the BBP id we read
      EXPECT_TRUE(r["station"].find("BBP id " + c->station + ")") != std::string::npos ||
                  r["station"].find("BBP id " + c->station + ";") != std::string::npos)
          << c->station << " vs " << r["station"];
    } else {
      EXPECT_EQ(c->station, r["station"]);
      EXPECT_EQ(c->t0, 0.0);
    }

    // NPTS/DT cross-checked against an independent reading of the header
    if (expected_format == RecordFormat::PeerAt2 || expected_format == RecordFormat::UsgsSmc) {
      std::string eol;
      const auto lines = split_lines_keep(read_text(path), &eol);
      ASSERT_GE(lines.size(), 27u);
      long npts = -1;
      double hdr_dt = -1;
      if (expected_format == RecordFormat::PeerAt2) {
        std::smatch m;
        static const std::regex re_n(R"(NPTS\s*=\s*(\d+))"), re_d(R"(DT\s*=\s*([0-9.Ee+-]+))");
        if (std::regex_search(lines[3], m, re_n)) {
          npts = std::stol(m[1]);
          ASSERT_TRUE(std::regex_search(lines[3], m, re_d));
          hdr_dt = std::stod(m[1]);
        } else {
          std::istringstream ss(lines[3]);
          ss >> npts >> hdr_dt;
          EXPECT_NE(lines[3].find("NPTS, DT"), std::string::npos);
        }
      } else {
        npts = std::stol(lines[13].substr(0, 10));           // integer #17
        hdr_dt = 1.0 / std::stod(lines[17].substr(15, 15));  // 1 / real #2
      }
      EXPECT_EQ(c->accel.size(), static_cast<std::size_t>(npts));
      EXPECT_NEAR(c->dt, hdr_dt, 1e-12);
    }
    ++checked;
  }
  EXPECT_EQ(checked, rows.size());
}

TEST(RecordReaderRealData, QuirksOfParticularFiles) {
  SKIP_WITHOUT_RECORDS(dir);
  // RSN960 LOS270 holds NPTS+1 values (a trailing .0 pad): exactly NPTS are read
  const auto los = read_record(dir + "/northridge_1994/RSN960_NORTHR_LOS270.AT2").at(0);
  EXPECT_EQ(los.accel.size(), 1999u);
  EXPECT_NEAR(los.accel.back(), .9772475E-03 * kGravity, 1e-12);

  // DWN verticals are stored positive up: sign flipped relative to the file
  const auto cpe = read_record(dir + "/imperial_valley_1979/RSN164_IMPVALL.H_H-CPEDWN.AT2").at(0);
  EXPECT_TRUE(cpe.vertical);
  EXPECT_EQ(cpe.label, "DWN");
  EXPECT_NEAR(cpe.accel[0], -.1246943E-02 * kGravity, 1e-12);
  // UP verticals are not
  const auto rin = read_record(dir + "/northridge_1994/RinaldiUP.AT2").at(0);
  EXPECT_TRUE(rin.vertical);
  EXPECT_NEAR(rin.accel[0], -.8777599E-05 * kGravity, 1e-12);
  EXPECT_EQ(rin.event, "Northridge-01");

  // BBP start times are kept (t0 = first time value)
  const auto b5295 = read_record(dir + "/landers_1992/5295.bbp");
  ASSERT_EQ(b5295.size(), 3u);
  EXPECT_NEAR(b5295[0].t0, 0.0300026, 1e-12);
  EXPECT_NEAR(b5295[0].dt, 0.005, 1e-9);
  EXPECT_EQ(b5295[0].event, "1992 Landers EQ");
  const auto ce12630 = read_record(dir + "/landers_1992/ce12630.bbp");
  EXPECT_DOUBLE_EQ(ce12630[0].t0, 8.8);
  EXPECT_EQ(ce12630[2].label, "U-D");
  EXPECT_TRUE(ce12630[2].vertical);

  // SMC: 6001 values, 200 samples/s, vertical "up"
  const auto smc_up = read_record(dir + "/loma_prieta_1989/0111b.smc").at(0);
  EXPECT_TRUE(smc_up.vertical);
  EXPECT_EQ(smc_up.event, "Loma Prieta, CA");
  EXPECT_DOUBLE_EQ(smc_up.dt, 0.005);
}

TEST(RecordReaderRealData, CorruptedCopiesAreRejected) {
  SKIP_WITHOUT_RECORDS(dir);
  TempDir tmp;
  std::string eol;

  // AT2 (1999 header, NPTS 7802) with its last three lines (12 values) removed
  {
    auto lines = split_lines_keep(read_text(dir + "/imperial_valley_1979/H-E12140.at2"), &eol);
    ASSERT_GT(lines.size(), 10u);
    lines.resize(lines.size() - 3);
    const auto p = tmp.write("H-E12140.at2", join_lines(lines, eol));
    expect_record_error(p, lines.size(), {"expected 7802 values (NPTS), found 7790"});
  }
  // CRLF NGA file with garbage in the NPTS line
  {
    auto lines = split_lines_keep(read_text(dir + "/northridge_1994/RSN960_NORTHR_LOS270.AT2"), &eol);
    ASSERT_EQ(eol, "\r\n");
    lines[3] = "NPTS=   #&!?, DT=   .0100 SEC";
    expect_record_error(tmp.write("RSN960_garbage.AT2", join_lines(lines, eol)), 4, {"bad header", "NPTS"});
  }
  // a 1.2.3 token and a NaN in real AT2 data
  {
    auto lines = split_lines_keep(read_text(dir + "/borrego_mountain_1968/RSN36_BORREGO_A-ELC180.AT2"), &eol);
    auto replace_first_token = [](std::string line, const std::string& tok) {
      const std::size_t b = line.find_first_not_of(' ');
      const std::size_t e = line.find(' ', b);
      return line.substr(0, b) + tok + line.substr(e);
    };
    auto bad = lines;
    bad[99] = replace_first_token(bad[99], "1.2.3");
    expect_record_error(tmp.write("RSN36_123.AT2", join_lines(bad, eol)), 100, {"non-numeric value '1.2.3'"});
    bad = lines;
    bad[199] = replace_first_token(bad[199], "NaN");
    expect_record_error(tmp.write("RSN36_nan.AT2", join_lines(bad, eol)), 200, {"non-finite value 'NaN'"});
  }
  // SMC with one data line missing
  {
    auto lines = split_lines_keep(read_text(dir + "/loma_prieta_1989/0111a.smc"), &eol);
    lines.erase(lines.begin() + 400);
    const auto p = tmp.write("0111a.smc", join_lines(lines, eol));
    expect_record_error(p, lines.size(), {"expected 6001 values (NPTS), found 5993"});
  }
  // BBP with one row missing -> non-uniform time step at the row after the gap
  {
    auto lines = split_lines_keep(read_text(dir + "/landers_1992/ce12025.bbp"), &eol);
    lines.erase(lines.begin() + 1000);
    expect_record_error(tmp.write("ce12025.bbp", join_lines(lines, eol)), 1001, {"non-uniform time step"});
  }
  // the same file turned into a 3-column CSV with a time jump
  {
    auto lines = split_lines_keep(read_text(dir + "/landers_1992/ce12025.bbp"), &eol);
    std::string csv = "time_s,accel_h,accel_v\n";
    std::size_t row = 0;
    for (const auto& l : lines) {
      if (l.empty() || l[0] == '#') continue;
      std::istringstream ss(l);
      std::string t, ns, ew, ud;
      ss >> t >> ns >> ew >> ud;
      if (++row == 500) t = "9.999";
      csv += t + "," + ns + "," + ud + "\n";
    }
    expect_record_error(tmp.write("ce12025.csv", csv), 501, {"non-uniform time step"});
  }
}
