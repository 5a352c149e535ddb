// record_to_bag end to end: the bags it writes are read back with rosbag::View and compared, sample by
// sample and stamp by stamp, with the record read by the core reader. No ROS master needed.
//
//  * RecordToBag.OneSinePulseCsvRoundTrip: every sample and stamp, REP 145 fields, AccelStamped.
//  * RecordToBag.ThreeComponentStationsRoundTrip: real 2H+V stations (Rinaldi, Cerro Prieto with a DWN
//    vertical), z - g == vertical, --azimuth against core::rotate, --start-time with decimals.
//  * RecordToBag.CommittedSyntheticBagsAreWhatTheReadmeSays: bags/synthetic_*.bag content, sizes, and
//    that regenerating them gives the same messages.
//  * RecordToBag.AllModeWritesOneBagPerStationAndAnIndex, RecordToBag.BadInputGivesOneErrorLine.

#include <gtest/gtest.h>

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <geometry_msgs/AccelStamped.h>
#include <sensor_msgs/Imu.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "rocking_monitor/motion/sensor_frame.hpp"
#include "rocking_monitor/motion/station.hpp"
#include "rocking_monitor/ros/ground_motion_source.hpp"

#include "test_helpers.hpp"

namespace {

namespace fs = std::filesystem;
namespace core = rocking_monitor::core;
namespace rec = rocking_monitor::records;
using core::kGravity;

const std::string kSource = ROCKING_SOURCE_DIR;
const std::string kRecords = ROCKING_RECORDS_DIR;
const std::string kPulseCsv = kSource + "/bags/one_sine_pulse.csv";
constexpr std::int64_t kDefaultStartNs = 1'000'000'000LL * 1'000'000'000LL;

struct ToolRun {
  int status = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

ToolRun run_tool(const std::string& args) {
  static std::atomic<int> counter{0};
  const fs::path err_file = fs::temp_directory_path() / ("record_to_bag_err_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  const std::string cmd = std::string(RECORD_TO_BAG_EXE) + " " + args + " 2>" + err_file.string();
  const rocking_monitor::core::testing::CommandResult c = rocking_monitor::core::testing::run_command(cmd);
  ToolRun r;
  r.status = c.status;
  r.out = c.out;
  std::ifstream in(err_file);
  std::ostringstream ss;
  ss << in.rdbuf();
  r.err = ss.str();
  fs::remove(err_file);
  return r;
}

class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = fs::temp_directory_path() / ("record_to_bag_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }
  std::string str() const { return path_.string(); }

 private:
  fs::path path_;
};

struct BagContent {
  std::vector<sensor_msgs::Imu> imu;
  std::vector<ros::Time> imu_bag_time;
  std::vector<geometry_msgs::AccelStamped> accel;
  std::vector<std::string> topics;
};

BagContent read_bag(const std::string& path, const std::string& imu_topic = "/ground/imu", const std::string& accel_topic = "/ground/accel") {
  BagContent c;
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  rosbag::View view(bag);
  for (const rosbag::ConnectionInfo* info : view.getConnections()) c.topics.push_back(info->topic);
  for (const rosbag::MessageInstance& m : view) {
    if (m.getTopic() == imu_topic) {
      auto msg = m.instantiate<sensor_msgs::Imu>();
      if (msg) {
        c.imu.push_back(*msg);
        c.imu_bag_time.push_back(m.getTime());
      }
    } else if (m.getTopic() == accel_topic) {
      auto msg = m.instantiate<geometry_msgs::AccelStamped>();
      if (msg) c.accel.push_back(*msg);
    }
  }
  return c;
}

/// REP 145 fields of an accelerometer-only Imu.
void expect_rep145(const sensor_msgs::Imu& m, double variance, const std::string& frame) {
  EXPECT_EQ(m.header.frame_id, frame);
  EXPECT_EQ(m.orientation_covariance[0], -1.0);
  EXPECT_EQ(m.angular_velocity_covariance[0], -1.0);
  EXPECT_EQ(m.orientation.x, 0.0);
  EXPECT_EQ(m.orientation.w, 0.0);
  EXPECT_EQ(m.angular_velocity.x, 0.0);
  EXPECT_EQ(m.angular_velocity.y, 0.0);
  EXPECT_EQ(m.angular_velocity.z, 0.0);
  for (int k = 0; k < 9; ++k) {
    const double expected = (k == 0 || k == 4 || k == 8) ? variance : 0.0;
    EXPECT_DOUBLE_EQ(m.linear_acceleration_covariance[k], expected) << k;
  }
}

bool records_available() { return fs::exists(fs::path(kRecords) / "MANIFEST.csv"); }

#define SKIP_WITHOUT_RECORDS()                                                                     \
  do {                                                                                             \
    if (!records_available()) {                                                                    \
      std::cout << "NOTICE: records directory " << kRecords << " not found; skipping" << std::endl; \
      GTEST_SKIP() << "records directory " << kRecords << " not found";                           \
    }                                                                                              \
  } while (0)

// ------------------------------------------------------------------ tests

TEST(RecordToBag, OneSinePulseCsvRoundTrip) {
  TempDir dir;
  const std::string bag = dir / "pulse.bag";
  const ToolRun r = run_tool("--file " + kPulseCsv + " --out " + bag + " --accel-topic /ground/accel --noise-density 1e-3");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");  // no notes for a clean single-column CSV
  EXPECT_NE(r.out.find("1601 samples at 200 Hz (8 s)"), std::string::npos) << r.out;

  const std::vector<core::Component> comps = core::read_record(kPulseCsv);
  ASSERT_EQ(comps.size(), 1u);
  const core::Component& h = comps[0];
  const BagContent c = read_bag(bag);
  ASSERT_EQ(c.imu.size(), h.accel.size());
  ASSERT_EQ(c.accel.size(), h.accel.size());
  const double variance = 1e-3 * 1e-3 * 200.0 / 2.0;  // n^2 fs/2
  for (std::size_t i = 0; i < h.accel.size(); ++i) {
    SCOPED_TRACE(i);
    const sensor_msgs::Imu& m = c.imu[i];
    // stamp = 1e9 s + t_i, exactly; bag time = stamp (rosbag play --clock replays exactly)
    const std::int64_t t_ns = static_cast<std::int64_t>(std::llround((h.t0 + h.dt * static_cast<double>(i)) * 1e9));
    ASSERT_EQ(static_cast<std::int64_t>(m.header.stamp.toNSec()), kDefaultStartNs + t_ns);
    ASSERT_EQ(c.imu_bag_time[i], m.header.stamp);
    ASSERT_EQ(m.header.seq, 0u);
    ASSERT_EQ(m.linear_acceleration.x, h.accel[i]);
    ASSERT_EQ(m.linear_acceleration.y, 0.0);
    ASSERT_EQ(m.linear_acceleration.z, kGravity);  // no vertical: at rest the sensor reads +g on z
    ASSERT_EQ(c.accel[i].header.stamp, m.header.stamp);
    ASSERT_EQ(c.accel[i].accel.linear.x, h.accel[i]);
    ASSERT_EQ(c.accel[i].accel.linear.z, 0.0);  // gravity excluded
    if (i % 400 == 0) expect_rep145(m, variance, "accelerometer");
  }
  // sample 0.15 s is the crest of 4.0 sin(2 pi t / 0.6) as printed in the CSV
  EXPECT_EQ(c.imu[30].linear_acceleration.x, 4.0);
  EXPECT_EQ(c.imu.back().header.stamp.toNSec(), static_cast<std::uint64_t>(kDefaultStartNs + 8'000'000'000LL));
}

TEST(RecordToBag, ThreeComponentStationsRoundTrip) {
  SKIP_WITHOUT_RECORDS();
  TempDir dir;
  const core::StationListing listing = core::list_stations(kRecords);
  for (const char* name : {"northridge_1994/rinaldi_receiving_sta", "imperial_valley_1979/cerro_prieto", "landers_1992/lucerne_bbp_id_luc"}) {
    SCOPED_TRACE(name);
    const std::string bag = dir / "station.bag";
    const ToolRun r = run_tool("--station " + std::string(name) + " --records-dir " + kRecords + " --out " + bag +
                           " --frame-id ground_sensor --topic /quake/imu --start-time 1234.000000250");
    ASSERT_EQ(r.status, 0) << r.err;
    const core::StationRecord st = core::load_station(core::find_station(listing, name));
    ASSERT_EQ(st.horizontals.size(), 2u);
    ASSERT_TRUE(st.vertical.has_value());
    const BagContent c = read_bag(bag, "/quake/imu");
    ASSERT_EQ(c.topics, std::vector<std::string>{"/quake/imu"});
    ASSERT_EQ(c.imu.size(), st.vertical->accel.size());
    const double variance = rec::kDefaultNoiseDensity * rec::kDefaultNoiseDensity / (2.0 * st.vertical->dt);
    expect_rep145(c.imu.front(), variance, "ground_sensor");
    for (std::size_t i = 0; i < c.imu.size(); ++i) {
      SCOPED_TRACE(i);
      const sensor_msgs::Imu& m = c.imu[i];
      const std::int64_t t_ns = static_cast<std::int64_t>(std::llround((st.vertical->t0 + st.vertical->dt * static_cast<double>(i)) * 1e9));
      ASSERT_EQ(static_cast<std::int64_t>(m.header.stamp.toNSec()), 1234'000'000'250LL + t_ns);
      ASSERT_EQ(m.linear_acceleration.x, st.horizontals[0].accel[i]);
      ASSERT_EQ(m.linear_acceleration.y, st.horizontals[1].accel[i]);
      // gravity round trip: z = a_up + g, and z - g gives the vertical back (to the rounding of the sum)
      ASSERT_EQ(m.linear_acceleration.z, st.vertical->accel[i] + kGravity);
      ASSERT_NEAR(m.linear_acceleration.z - kGravity, st.vertical->accel[i], 4e-15);
    }
    if (std::string(name) == "imperial_valley_1979/cerro_prieto") {
      // DWN vertical: the file is positive down; the bag is positive up (z = g - a_down)
      const std::vector<core::Component> raw = core::read_record(st.vertical->file);
      EXPECT_EQ(c.imu[1000].linear_acceleration.z, raw[0].accel[1000] + kGravity);
      EXPECT_EQ(st.vertical->label, "DWN");
    }
    // --azimuth: the horizontals rotated exactly as core::rotate does
    const ToolRun r2 = run_tool("--station " + std::string(name) + " --records-dir " + kRecords + " --out " + bag + " --azimuth 30");
    ASSERT_EQ(r2.status, 0) << r2.err;
    const core::RotatedPair p = core::rotate(st.horizontals[0], st.horizontals[1], 30.0);
    const BagContent c2 = read_bag(bag);
    ASSERT_EQ(c2.imu.size(), p.along.accel.size());
    for (std::size_t i = 0; i < c2.imu.size(); ++i) {
      ASSERT_EQ(c2.imu[i].linear_acceleration.x, p.along.accel[i]) << i;
      ASSERT_EQ(c2.imu[i].linear_acceleration.y, p.left.accel[i]) << i;
    }
  }
}

TEST(RecordToBag, LengthMismatchIsPaddedAndReported) {
  SKIP_WITHOUT_RECORDS();
  TempDir dir;
  // El Centro Array #10: 050 has 7411 samples, 320 has 7403.
  const std::string bag = dir / "e10.bag";
  ToolRun r = run_tool("--station 'imperial_valley_1979/el_centro_array_10' --records-dir " + kRecords + " --out " + bag);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("record_to_bag: note: padded RSN173_IMPVALL.H_H-E10320.AT2 [320] with 8 zero samples"), std::string::npos) << r.err;
  EXPECT_EQ(read_bag(bag).imu.size(), 7411u);
  r = run_tool("--station 'imperial_valley_1979/el_centro_array_10' --records-dir " + kRecords + " --out " + bag + " --length-mismatch truncate");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("dropped the last 8"), std::string::npos) << r.err;
  EXPECT_EQ(read_bag(bag).imu.size(), 7403u);
  r = run_tool("--station 'imperial_valley_1979/el_centro_array_10' --records-dir " + kRecords + " --out " + dir / "x.bag" +
               " --length-mismatch error");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("RSN173_IMPVALL.H_H-E10320.AT2 [320] and RSN173_IMPVALL.H_H-E10050.AT2 [50]: different lengths (7403 and 7411"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "x.bag"));
  EXPECT_FALSE(fs::exists(dir / "x.bag.partial"));
}

TEST(RecordToBag, CommittedSyntheticBagsAreWhatTheReadmeSays) {
  // one-sine pulse: the CSV's samples exactly
  const std::string pulse_bag = kSource + "/bags/synthetic_one_sine_pulse.bag";
  const std::string ricker_bag = kSource + "/bags/synthetic_ricker.bag";
  const std::string noise_bag = kSource + "/bags/synthetic_quiet_noise.bag";
  for (const std::string& b : {pulse_bag, ricker_bag, noise_bag}) {
    ASSERT_TRUE(fs::exists(b)) << b;
    EXPECT_LT(fs::file_size(b), 1'000'000u) << b;
  }
  const core::Component pulse = core::read_record(kPulseCsv).at(0);
  const BagContent p = read_bag(pulse_bag);
  ASSERT_EQ(p.imu.size(), 1601u);
  for (std::size_t i = 0; i < p.imu.size(); ++i) {
    ASSERT_EQ(p.imu[i].linear_acceleration.x, pulse.accel[i]) << i;
    ASSERT_EQ(p.imu[i].linear_acceleration.z, kGravity) << i;
    ASSERT_EQ(p.imu[i].header.stamp.toNSec(), static_cast<std::uint64_t>(kDefaultStartNs + 5'000'000LL * static_cast<std::int64_t>(i)));
  }

  // Ricker: peak 3.0 m/s^2 at 2.0 s, 1.5 Hz, 200 Hz for 10 s on x; nothing on y, z = g
  const BagContent rk = read_bag(ricker_bag);
  ASSERT_EQ(rk.imu.size(), 2001u);
  double peak = 0.0;
  std::size_t at = 0;
  double trough = 0.0;
  for (std::size_t i = 0; i < rk.imu.size(); ++i) {
    const double x = rk.imu[i].linear_acceleration.x;
    if (x > peak) {
      peak = x;
      at = i;
    }
    trough = std::min(trough, x);
    ASSERT_EQ(rk.imu[i].linear_acceleration.y, 0.0);
    ASSERT_EQ(rk.imu[i].linear_acceleration.z, kGravity);
  }
  EXPECT_EQ(peak, 3.0);
  EXPECT_EQ(at, 400u);
  EXPECT_NEAR(trough, -2.0 * 3.0 * std::exp(-1.5), 2e-3);  // side lobes -0.446 peak (sampled at 5 ms)

  // Quiet building: 0.005 m/s^2 RMS on each axis, zero mean, 30 s at 200 Hz
  const BagContent q = read_bag(noise_bag);
  ASSERT_EQ(q.imu.size(), 6001u);
  EXPECT_EQ(q.imu.back().header.stamp.toNSec() - q.imu.front().header.stamp.toNSec(), 30'000'000'000ULL);
  std::array<double, 3> sum{}, sum2{};
  for (const auto& m : q.imu) {
    const std::array<double, 3> a = {m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z - kGravity};
    for (int k = 0; k < 3; ++k) {
      sum[k] += a[k];
      sum2[k] += a[k] * a[k];
    }
  }
  const double n = static_cast<double>(q.imu.size());
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(sum[k] / n, 0.0, 4.0 * 0.005 / std::sqrt(n)) << k;
    EXPECT_NEAR(std::sqrt(sum2[k] / n), 0.005, 0.005 * 0.04) << k;  // 4 % ~ 4.4 standard errors of an RMS over 6001 samples
  }

  // Regenerating them (as bags/README.md says) gives the same messages.
  TempDir dir;
  const std::vector<std::pair<std::string, std::string>> how = {
      {"--file " + kPulseCsv, pulse_bag},
      {"--synthetic " + kSource + "/bags/synthetic_ricker.yaml", ricker_bag},
      {"--synthetic " + kSource + "/bags/synthetic_quiet_noise.yaml", noise_bag}};
  for (const auto& [args, committed] : how) {
    const std::string fresh = dir / "fresh.bag";
    const ToolRun r = run_tool(args + " --out " + fresh + " --compression bz2");
    ASSERT_EQ(r.status, 0) << r.err;
    const BagContent a = read_bag(fresh);
    const BagContent b = read_bag(committed);
    ASSERT_EQ(a.imu.size(), b.imu.size()) << committed;
    for (std::size_t i = 0; i < a.imu.size(); ++i) {
      ASSERT_EQ(a.imu[i].header.stamp, b.imu[i].header.stamp) << committed << " " << i;
      ASSERT_EQ(a.imu[i].linear_acceleration.x, b.imu[i].linear_acceleration.x) << committed << " " << i;
      ASSERT_EQ(a.imu[i].linear_acceleration.y, b.imu[i].linear_acceleration.y) << committed << " " << i;
      ASSERT_EQ(a.imu[i].linear_acceleration.z, b.imu[i].linear_acceleration.z) << committed << " " << i;
      ASSERT_EQ(a.imu[i].linear_acceleration_covariance, b.imu[i].linear_acceleration_covariance) << committed;
    }
  }
}

TEST(RecordToBag, AllModeWritesOneBagPerStationAndAnIndex) {
  SKIP_WITHOUT_RECORDS();
  TempDir dir;
  // A small records directory without a manifest: Rinaldi (3 files), Takatori (2), Taft (1).
  const std::string recs = dir / "records";
  fs::create_directories(recs + "/northridge_1994");
  fs::create_directories(recs + "/kobe_1995");
  fs::create_directories(recs + "/kern_county_1952");
  for (const char* f : {"northridge_1994/Rinaldi228.AT2", "northridge_1994/Rinaldi318.AT2", "northridge_1994/RinaldiUP.AT2",
                        "kobe_1995/RSN1120_KOBE_TAK000.AT2", "kobe_1995/RSN1120_KOBE_TAK090.AT2", "kern_county_1952/RSN15_KERN_TAF021.AT2"}) {
    fs::copy_file(kRecords + "/" + f, recs + "/" + f);
  }
  const std::string out = dir / "bags";
  const ToolRun r = run_tool("--all --records-dir " + recs + " --out-dir " + out + " --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("wrote 2 bags"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1 stations with fewer than 2 components skipped, 0 failed"), std::string::npos) << r.out;
  ASSERT_TRUE(fs::exists(out + "/northridge_1994__rinaldi.bag"));
  ASSERT_TRUE(fs::exists(out + "/kobe_1995__rsn1120_tak.bag") || fs::exists(out + "/kobe_1995__tak.bag")) << r.out;
  std::ifstream index(out + "/index.csv");
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(index, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].rfind("bag,station_id,event,station,samples,rate_hz,duration_s,x_azimuth_deg,x,y,z,notes", 0), 0u);
  const BagContent c = read_bag(out + "/northridge_1994__rinaldi.bag");
  EXPECT_EQ(c.imu.size(), 1991u);
  // (318, 228, up) is the right-handed order: x = 318, y = 228 = 318 - 90
  const core::Component h318 = core::read_record(kRecords + "/northridge_1994/Rinaldi318.AT2").at(0);
  EXPECT_EQ(c.imu[500].linear_acceleration.x, h318.accel[500]);
}

TEST(RecordToBag, BadInputGivesOneErrorLine) {
  TempDir dir;
  const std::string bad_csv = dir / "bad.csv";
  std::ofstream(bad_csv) << "time_s,accel\n0.00,0.1\n0.01,abc\n0.02,0.3\n";
  const std::string out = " --out " + dir / "x.bag";
  struct Case {
    std::string args;
    std::string part;
  };
  const std::vector<Case> cases = {
      {"--file " + dir / "missing.AT2" + out, dir / "missing.AT2" + ": cannot open file"},
      {"--file " + bad_csv + out, bad_csv + ":3: non-numeric value 'abc'"},
      {"--file " + kPulseCsv + out + " --azimuth abc", "--azimuth"},
      {"--file " + kPulseCsv + out + " --azimuth 45", "an azimuth needs two horizontal components, the station has 1"},
      {"--file " + kPulseCsv + out + " --start-time -5", "--start-time"},
      {"--file " + kPulseCsv + out + " --start-time 1.5e9", "--start-time: '1.5e9' is not a time in seconds"},
      {"--file " + kPulseCsv + out + " --noise-density -1", "--noise-density"},
      {"--file " + kPulseCsv + out + " --length-mismatch chop", "--length-mismatch"},
      {"--file " + kPulseCsv, "--out: required"},
      {"--file " + kPulseCsv + " --station X" + out, "Exactly 1 option from [--file,--station,--synthetic,--list,--all] is required and 2 were given"},
      {out, "Exactly 1 option from [--file,--station,--synthetic,--list,--all] is required"},
      {"--station X --records-dir " + dir / "none" + out, dir / "none" + ": not a directory (records directory)"},
      {"--file " + kPulseCsv + out + " --frame-id ''", "--frame-id: must not be empty"},
      {"--synthetic " + dir / "nope.yaml" + out, dir / "nope.yaml: cannot open file"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    const ToolRun r = run_tool(c.args);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("record_to_bag: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.part), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "x.bag"));
  }
  // A malformed synthetic spec names the YAML line.
  const std::string spec = dir / "spec.yaml";
  std::ofstream(spec) << "rate_hz: 100\nduration_s: 1\nx:\n  - ricker: {peak_mps2: 1, frequency_hz: 2}\n  - rickr: {}\n";
  ToolRun r = run_tool("--synthetic " + spec + out);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find(spec + ":4: ricker needs 'center_s'"), std::string::npos) << r.err;
  std::ofstream(spec) << "rate_hz: 100\nduration_s: 1\nx:\n  - rickr: {}\n";
  r = run_tool("--synthetic " + spec + out);
  EXPECT_NE(r.err.find(spec + ":4: unknown term 'rickr'"), std::string::npos) << r.err;
  std::ofstream(spec) << "rate_hz: 100\nduration: 1\n";
  r = run_tool("--synthetic " + spec + out);
  EXPECT_NE(r.err.find(spec + ":2: unknown key 'duration'"), std::string::npos) << r.err;
  if (records_available()) {
    r = run_tool("--station Atlantis --records-dir " + kRecords + out);
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("no station matches 'Atlantis'"), std::string::npos) << r.err;
  }
}

TEST(RecordToBag, TimeParsingIsExactToTheNanosecond) {
  EXPECT_EQ(rec::parse_time_ns("1000000000"), kDefaultStartNs);
  EXPECT_EQ(rec::parse_time_ns("1234.5"), 1'234'500'000'000LL);
  EXPECT_EQ(rec::parse_time_ns("4294967295.999999999"), 4'294'967'295'999'999'999LL);
  for (const char* bad : {"", "-1", "1e9", "1.", ".5", "1.0000000001", "4294967296", "12a"}) {
    EXPECT_THROW(rec::parse_time_ns(bad), std::invalid_argument) << bad;
  }
  EXPECT_DOUBLE_EQ(rec::accel_variance(2.5e-4, 0.005), 2.5e-4 * 2.5e-4 * 100.0);
}

}  // namespace
