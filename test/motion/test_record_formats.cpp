// Tests of the miniSEED, COSMOS V2 and K-NET readers (src/motion/miniseed_reader.cpp,
// cosmos_reader.cpp, knet_reader.cpp) on files made from the shared real records (the writers are
// test/support/record_writers.cpp, which the fuzzer's seeds use too):
//  * miniSEED: written here with libmseed itself (msr_pack: steim1, steim2, int32, float32,
//    float64; three channels interleaved; 512- and 4096-byte records) from the Rinaldi AT2
//    components, read back: float64 exact, counts within the integer quantisation 0.5 / gain.
//  * COSMOS V2 and K-NET: written here after the published format descriptions (COSMOS Strong
//    Motion Data Format v1.20; NIED "About K-NET ASCII format"), each with real-world quirks
//    (touching fixed-width fields, Fortran D exponents, trailing blanks, CRLF, KiK-net channel
//    numbers, the logger's count offset), read back and compared with the AT2 samples within the
//    precision of the format.
//  * Truncated, wrong-scale and mixed-rate files: the error names the file and the line (miniSEED:
//    the record and byte offset), asserted on the message text.
// Skipped with a notice when the records directory is absent.

#include <gtest/gtest.h>
#include <libmseed.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "rocking_monitor/motion/sensor_frame.hpp"
#include "rocking_monitor/motion/station.hpp"
#include "record_writers.hpp"
#include "temp_root.hpp"
#include "test_helpers.hpp"

#ifndef ROCKING_RECORDS_DIR
#define ROCKING_RECORDS_DIR "/work/shared/records"
#endif

namespace fs = std::filesystem;
namespace rm = rocking_monitor::core;
namespace rt = rocking_monitor::core::testing;
// The format writers, shared with the fuzzer's seeds (test/support/record_writers.hpp).
using rt::CosmosChannel;
using rt::KnetFile;
using rt::cosmos_channel;
using rt::counts;
using rt::fortran_e;
using rt::knet_file;
using rt::pack_channel;

namespace {

const rm::testing::TempRoot& kTemp = rm::testing::TempRoot::registered("rocking_formats_test_");

fs::path scratch(const std::string& test) {
  const fs::path p = kTemp.path() / test;
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::string records_dir() {
  const std::string dir = ROCKING_RECORDS_DIR;
  return fs::is_regular_file(fs::path(dir) / "northridge_1994" / "Rinaldi228.AT2") ? dir : "";
}

#define SKIP_WITHOUT_RECORDS(dir)                                                                           \
  const std::string dir = records_dir();                                                                    \
  if (dir.empty()) {                                                                                        \
    GTEST_SKIP() << "records directory not found: " << ROCKING_RECORDS_DIR << " (real-data tests skipped)"; \
  }

/// The Rinaldi Receiving Sta components (Northridge 1994, 100 Hz, 1991 samples): 228, 318, UP.
struct Rinaldi {
  rm::Component h228, h318, up;
};
Rinaldi rinaldi(const std::string& dir) {
  const std::string r = dir + "/northridge_1994/";
  return {rm::read_record(r + "Rinaldi228.AT2").at(0), rm::read_record(r + "Rinaldi318.AT2").at(0),
          rm::read_record(r + "RinaldiUP.AT2").at(0)};
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
void write_file(const fs::path& p, const std::string& s) {
  std::ofstream out(p, std::ios::binary);
  out << s;
}

/// The error message of reading `path`, or "" when it reads.
std::string read_error(const std::string& path, const rm::ReadOptions& options = {}) {
  try {
    rm::read_record(path, options);
  } catch (const rm::RecordError& e) {
    return e.what();
  }
  return "";
}

// ------------------------------------------------------------------ miniSEED with libmseed

/// Writes the channels' records interleaved (one record of each in turn), as a recorder does.
void write_interleaved(const fs::path& p, const std::vector<std::vector<std::string>>& channels) {
  write_file(p, rt::interleave(channels));
}

const hptime_t kStart = rt::kRinaldiStart;
const double kGain = rt::logger_gain();

}  // namespace

// =================================================================== miniSEED

TEST(RecordFormatsMiniSeed, Steim2ThreeChannelsInterleavedEqualTheAt2WithinOneCount) {
  SKIP_WITHOUT_RECORDS(dir);
  const Rinaldi r = rinaldi(dir);
  const fs::path d = scratch("steim2");
  // channel 1 at 228 deg, channel 2 at 318 deg (90 clockwise of 1), Z up; the vertical record is a
  // different length (4096 bytes) from the horizontals (512).
  write_interleaved(d / "rrs.mseed", {pack_channel("HNZ", 100.0, kStart, counts(r.up, kGain), DE_STEIM2, 4096),
                                      pack_channel("HN2", 100.0, kStart, counts(r.h318, kGain), DE_STEIM2, 512),
                                      pack_channel("HN1", 100.0, kStart, counts(r.h228, kGain), DE_STEIM2, 512)});
  EXPECT_EQ(rm::detect_format((d / "rrs.mseed").string()), rm::RecordFormat::MiniSeed);
  rm::ReadOptions o;
  o.gain_counts_per_mps2 = kGain;
  o.sensor_azimuth_deg = 228.0;
  const std::vector<rm::Component> comps = rm::read_record((d / "rrs.mseed").string(), o);
  ASSERT_EQ(comps.size(), 3u);
  // N/1, E/2, Z whatever the file order
  EXPECT_EQ(comps[0].channel, "HN1");
  EXPECT_EQ(comps[0].label, "228");
  EXPECT_EQ(comps[1].label, "318");
  EXPECT_EQ(comps[2].label, "UP");
  EXPECT_TRUE(comps[2].vertical);
  EXPECT_EQ(comps[0].station, "XX.RRS");
  EXPECT_EQ(comps[0].event, "1994-01-17T12:31:01.000000Z");
  const rm::Component* ref[3] = {&r.h228, &r.h318, &r.up};
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(comps[k].channel);
    EXPECT_DOUBLE_EQ(comps[k].dt, 0.01);
    ASSERT_EQ(comps[k].accel.size(), ref[k]->accel.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < comps[k].accel.size(); ++i) {
      // the counts came back exactly: a sample is counts / gain
      EXPECT_EQ(comps[k].accel[i], std::llround(ref[k]->accel[i] * kGain) / kGain);
      worst = std::max(worst, std::abs(comps[k].accel[i] - ref[k]->accel[i]));
    }
    EXPECT_LE(worst, 0.5 / kGain * (1 + 1e-9));
  }
  // As a station it orders like the AT2 station: 318 first (228 is 90 deg counter-clockwise of it).
  const rm::StationRecord st = rm::load_station(rm::station_from_files({(d / "rrs.mseed").string()}, o), o);
  ASSERT_EQ(st.horizontals.size(), 2u);
  EXPECT_EQ(st.horizontals[0].label, "318");
  EXPECT_EQ(st.horizontals[1].label, "228");
  ASSERT_TRUE(st.vertical.has_value());
}

TEST(RecordFormatsMiniSeed, FloatEncodingsAndSteim1Int32) {
  SKIP_WITHOUT_RECORDS(dir);
  const Rinaldi r = rinaldi(dir);
  const fs::path d = scratch("float");
  rm::ReadOptions o;
  o.gain_counts_per_mps2 = 1.0;  // samples written in m/s^2
  write_interleaved(d / "f64.mseed", {pack_channel("HNE", 100.0, kStart, r.h228.accel, DE_FLOAT64, 512)});
  const rm::Component f64 = rm::read_record((d / "f64.mseed").string(), o).at(0);
  EXPECT_EQ(f64.label, "090");         // E: the code says east
  EXPECT_EQ(f64.accel, r.h228.accel);  // exact
  write_interleaved(d / "f32.mseed", {pack_channel("ENN", 100.0, kStart, r.h228.accel, DE_FLOAT32, 512)});
  const rm::Component f32 = rm::read_record((d / "f32.mseed").string(), o).at(0);
  EXPECT_EQ(f32.label, "000");
  ASSERT_EQ(f32.accel.size(), r.h228.accel.size());
  for (std::size_t i = 0; i < f32.accel.size(); ++i) {
    EXPECT_EQ(f32.accel[i], static_cast<double>(static_cast<float>(r.h228.accel[i])));
  }
  for (int enc : {DE_STEIM1, DE_INT32}) {
    const std::string name = "i" + std::to_string(enc) + ".mseed";
    write_interleaved(d / name, {pack_channel("HLZ", 100.0, kStart, counts(r.up, kGain), enc, 512)});
    rm::ReadOptions g;
    g.gain_counts_per_mps2 = kGain;
    const rm::Component z = rm::read_record((d / name).string(), g).at(0);
    ASSERT_EQ(z.accel.size(), r.up.accel.size());
    for (std::size_t i = 0; i < z.accel.size(); ++i) EXPECT_EQ(z.accel[i], std::llround(r.up.accel[i] * kGain) / kGain);
  }
}

TEST(RecordFormatsMiniSeed, GainAndAzimuthFromAChannelTableBesideTheFile) {
  SKIP_WITHOUT_RECORDS(dir);
  const Rinaldi r = rinaldi(dir);
  const fs::path d = scratch("table");
  write_interleaved(d / "rrs.mseed", {pack_channel("HN1", 100.0, kStart, counts(r.h228, kGain), DE_STEIM2, 512),
                                      pack_channel("HN2", 100.0, kStart, counts(r.h318, 2 * kGain), DE_STEIM2, 512)});
  const std::string f = (d / "rrs.mseed").string();
  // Refuses to guess, and says which is missing.
  EXPECT_NE(read_error(f).find("rrs.mseed: channel XX.RRS..HN1: no gain (counts per m/s^2): give --gain or "
                               "gain_counts_per_mps2 in a channel table (no CHANNELS.csv beside the file)"),
            std::string::npos)
      << read_error(f);
  rm::ReadOptions g;
  g.gain_counts_per_mps2 = kGain;
  EXPECT_NE(read_error(f, g).find("channel XX.RRS..HN1: the sensor's azimuth is unknown"), std::string::npos)
      << read_error(f, g);
  write_file(d / "CHANNELS.csv",
             "network,station,location,channel,azimuth_deg,gain_counts_per_mps2\n"
             "XX,RRS,--,HN1,228," +
                 std::to_string(kGain) +
                 "\n"
                 "XX,RRS,,HN2,318," +
                 std::to_string(2 * kGain) + "\n");
  const std::vector<rm::Component> c = rm::read_record(f);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].label, "228");
  EXPECT_EQ(c[1].label, "318");
  const double gain_text = std::stod(std::to_string(kGain));
  for (std::size_t i = 0; i < c[1].accel.size(); ++i) {
    EXPECT_NEAR(c[0].accel[i], r.h228.accel[i], 0.51 / gain_text);
    EXPECT_NEAR(c[1].accel[i], r.h318.accel[i], 0.51 / (2 * gain_text));
  }
  // A bad table names its line.
  write_file(d / "CHANNELS.csv",
             "network,station,location,channel,azimuth_deg,gain_counts_per_mps2\nXX,RRS,,HN1,228,-5\n");
  EXPECT_NE(read_error(f).find("CHANNELS.csv:2: gain_counts_per_mps2 '-5' is not positive"), std::string::npos)
      << read_error(f);
}

TEST(RecordFormatsMiniSeed, GapMixedRateNonAccelerometerAndTruncationAreNamedErrors) {
  SKIP_WITHOUT_RECORDS(dir);
  const Rinaldi r = rinaldi(dir);
  const fs::path d = scratch("errors");
  rm::ReadOptions o;
  o.gain_counts_per_mps2 = kGain;
  const std::vector<double> z = counts(r.up, kGain);
  const std::vector<double> first(z.begin(), z.begin() + 1000), second(z.begin() + 1000, z.end());
  // gap: the second half starts 1 s late
  std::vector<std::string> recs = pack_channel("HNZ", 100.0, kStart, first, DE_STEIM2, 512);
  const std::vector<std::string> late =
      pack_channel("HNZ", 100.0, kStart + MS_EPOCH2HPTIME(11), second, DE_STEIM2, 512);
  const std::size_t first_late = recs.size() + 1;
  recs.insert(recs.end(), late.begin(), late.end());
  write_interleaved(d / "gap.mseed", {recs});
  const std::string gap = read_error((d / "gap.mseed").string(), o);
  EXPECT_NE(gap.find("gap.mseed: record " + std::to_string(first_late) + " at byte " +
                     std::to_string(512 * (first_late - 1)) +
                     ": channel XX.RRS..HNZ: gap of 1.000000 s at 1994-01-17T12:31:11.000000Z"),
            std::string::npos)
      << gap;
  // the same records, overlapping by 2 s
  recs = pack_channel("HNZ", 100.0, kStart, first, DE_STEIM2, 512);
  const std::vector<std::string> early =
      pack_channel("HNZ", 100.0, kStart + MS_EPOCH2HPTIME(8), second, DE_STEIM2, 512);
  recs.insert(recs.end(), early.begin(), early.end());
  write_interleaved(d / "overlap.mseed", {recs});
  EXPECT_NE(read_error((d / "overlap.mseed").string(), o).find(": channel XX.RRS..HNZ: overlap of "), std::string::npos)
      << read_error((d / "overlap.mseed").string(), o);
  EXPECT_NE(read_error((d / "overlap.mseed").string(), o).find(" s at 1994-01-17T12:31:09.000000Z (records overlap"),
            std::string::npos);
  // mixed rates
  write_interleaved(d / "mixed.mseed", {pack_channel("HNE", 100.0, kStart, counts(r.h228, kGain), DE_STEIM2, 512),
                                        pack_channel("HNZ", 200.0, kStart, z, DE_STEIM2, 512)});
  EXPECT_NE(read_error((d / "mixed.mseed").string(), o)
                .find("mixed sample rates: XX.RRS..HNE 100.000000 Hz, XX.RRS..HNZ 200.000000 Hz"),
            std::string::npos)
      << read_error((d / "mixed.mseed").string(), o);
  // a velocity channel
  write_interleaved(d / "hh.mseed", {pack_channel("HHZ", 100.0, kStart, z, DE_STEIM2, 512)});
  EXPECT_NE(read_error((d / "hh.mseed").string(), o)
                .find("hh.mseed: record 1 at byte 0: channel HHZ is not an accelerometer (instrument code H"),
            std::string::npos)
      << read_error((d / "hh.mseed").string(), o);
  // an unknown encoding (blockette 1000 byte 4, at byte 52 of the record) in record 3
  std::string enc = read_file(d / "gap.mseed");
  enc[2 * 512 + 52] = static_cast<char>(99);
  write_file(d / "encoding.mseed", enc);
  const std::string encoding = read_error((d / "encoding.mseed").string(), o);
  EXPECT_NE(encoding.find("encoding.mseed: record 3 at byte 1024: "), std::string::npos) << encoding;
  // steim2 frames that fail libmseed's integrity check (the last-sample constant of record 2)
  std::string frames = read_file(d / "gap.mseed");
  frames[512 + 64 + 8] = static_cast<char>(frames[512 + 64 + 8] ^ 0x40);
  write_file(d / "integrity.mseed", frames);
  const std::string integrity = read_error((d / "integrity.mseed").string(), o);
  EXPECT_NE(integrity.find("integrity.mseed: record 2 at byte 512: libmseed: "), std::string::npos) << integrity;
  // truncated in the middle of its last record
  write_interleaved(d / "whole.mseed", {pack_channel("HNZ", 100.0, kStart, z, DE_STEIM2, 512)});
  const std::string whole = read_file(d / "whole.mseed");
  const std::size_t n_records = whole.size() / 512;
  write_file(d / "cut.mseed", whole.substr(0, whole.size() - 300));
  const std::string cut = read_error((d / "cut.mseed").string(), o);
  EXPECT_NE(cut.find("cut.mseed: record " + std::to_string(n_records) + " at byte " +
                     std::to_string(512 * (n_records - 1)) + ": not a valid miniSEED record"),
            std::string::npos)
      << cut;
}

// =================================================================== COSMOS V2

namespace {

void expect_within_e13_6(const rm::Component& got, const rm::Component& want, double sign = 1.0) {
  ASSERT_EQ(got.accel.size(), want.accel.size());
  for (std::size_t i = 0; i < got.accel.size(); ++i) {
    // 6 significant digits of a cm/s^2 value: half a unit in the 6th digit, relative 5e-6
    const double w = sign * want.accel[i];
    ASSERT_NEAR(got.accel[i], w, 5e-6 * std::abs(w) + 1e-15) << "sample " << i;
  }
}

}  // namespace

TEST(RecordFormatsCosmos, FortranFieldsMatchGfortranAndTouch) {
  EXPECT_EQ(fortran_e(-12.3456789, 13, 6), "-0.123457E+02");
  EXPECT_EQ(fortran_e(0.00123456789, 13, 6), " 0.123457E-02");
  EXPECT_EQ(fortran_e(0.01, 16, 7, 'D'), "   0.1000000D-01");
  EXPECT_EQ(fortran_e(-0.9999999, 13, 6), "-0.100000E+01");
}

TEST(RecordFormatsCosmos, ThreeChannelFileWithCrlfEqualsTheAt2) {
  SKIP_WITHOUT_RECORDS(dir);
  const Rinaldi r = rinaldi(dir);
  const fs::path d = scratch("cosmos3");
  const std::string eol = "\r\n";
  write_file(d / "rrs.v2", cosmos_channel({&r.h228, 228, 0.01}, 1, eol) + cosmos_channel({&r.h318, 318, 0.01}, 2, eol) +
                               cosmos_channel({&r.up, 400, 0.01}, 3, eol));
  const std::string f = (d / "rrs.v2").string();
  EXPECT_EQ(rm::detect_format(f), rm::RecordFormat::CosmosV2);
  const std::vector<rm::Component> c = rm::read_record(f);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].label, "228");
  EXPECT_EQ(c[1].label, "318");
  EXPECT_EQ(c[2].label, "UP");
  EXPECT_TRUE(c[2].vertical);
  EXPECT_EQ(c[0].station, "Rinaldi Receiving Sta");
  EXPECT_DOUBLE_EQ(c[0].dt, 0.01);
  expect_within_e13_6(c[0], r.h228);
  expect_within_e13_6(c[1], r.h318);
  expect_within_e13_6(c[2], r.up);
}

TEST(RecordFormatsCosmos, OneChannelPerFileDExponentsDownwardVertical) {
  SKIP_WITHOUT_RECORDS(dir);
  const Rinaldi r = rinaldi(dir);
  const fs::path d = scratch("cosmos1");
  CosmosChannel ch{&r.h318, 360 - 42, 0.01};
  ch.real_exp = 'D';
  ch.units = "cm/sec/sec";
  write_file(d / "CHAN2.V2", cosmos_channel(ch, 2, "\n"));
  const rm::Component c = rm::read_record((d / "CHAN2.V2").string()).at(0);
  EXPECT_EQ(c.label, "318");
  expect_within_e13_6(c, r.h318);
  // orientation 500: the sensor's positive direction is down; stored positive up
  write_file(d / "CHAN3.V2", cosmos_channel({&r.up, 500, 0.01, "g(02)"}, 3, "\n"));
  rm::Component g = rm::read_record((d / "CHAN3.V2").string()).at(0);
  EXPECT_EQ(g.label, "DOWN");
  // written as cm/s^2 numbers but declared g: every value is g/0.01 times the cm/s^2 reading
  for (double& a : g.accel) a *= 0.01 / rm::kGravity;
  expect_within_e13_6(g, r.up, -1.0);
}

TEST(RecordFormatsCosmos, TruncatedWrongUnitsAndMixedRateNameTheLine) {
  SKIP_WITHOUT_RECORDS(dir);
  const Rinaldi r = rinaldi(dir);
  const fs::path d = scratch("cosmos_err");
  const std::string good = cosmos_channel({&r.h228, 228, 0.01}, 1, "\n");
  // 13 text + 1 + 10 int + 1 + 20 real + 2 comment + 1 data header = 48 lines, data from line 49;
  // 1991 values in lines of 6: 332 lines (49..380).
  std::string cut = good.substr(0, good.find("       6 velocity"));
  for (int k = 0; k < 3; ++k) cut = cut.substr(0, cut.rfind('\n', cut.size() - 2) + 1);  // drop 3 lines
  write_file(d / "cut.v2", cut);
  EXPECT_NE(read_error((d / "cut.v2").string()).find("cut.v2:377: expected 1991 values, found 1974 (file ends early)"),
            std::string::npos)
      << read_error((d / "cut.v2").string());
  write_file(d / "counts.v2", cosmos_channel({&r.h228, 228, 0.01, "counts(50)"}, 1, "\n"));
  EXPECT_NE(read_error((d / "counts.v2").string()).find("counts.v2:48: unknown acceleration units 'counts'"),
            std::string::npos)
      << read_error((d / "counts.v2").string());
  const std::string second = cosmos_channel({&r.h318, 318, 0.02}, 2, "\n");
  write_file(d / "mixed.v2", good + second);
  const std::size_t lines_first = static_cast<std::size_t>(std::count(good.begin(), good.end(), '\n'));
  // the second channel's real-header line: its 13 text + 1 + 10 integer lines after the first channel
  EXPECT_NE(read_error((d / "mixed.v2").string())
                .find("mixed.v2:" + std::to_string(lines_first + 25) +
                      ": mixed sample rates: channel 1 has dt = 0.010000 s, channel 2 dt = 0.020000 s"),
            std::string::npos)
      << read_error((d / "mixed.v2").string());
  // touching fields that are not numbers
  std::string bad = good;
  const std::size_t p = bad.find("E", bad.find("Format=(6E13.6)") + 20);
  bad[p] = 'X';
  write_file(d / "bad.v2", bad);
  EXPECT_NE(read_error((d / "bad.v2").string()).find("bad.v2:49: non-numeric value"), std::string::npos)
      << read_error((d / "bad.v2").string());
}

// =================================================================== K-NET / KiK-net

namespace {

/// The AT2 samples with their mean removed (what the K-NET reader must return, to a count).
void expect_knet_equals(const rm::Component& got, const rm::Component& at2, double gal_per_count) {
  ASSERT_EQ(got.accel.size(), at2.accel.size());
  const double mean = std::accumulate(at2.accel.begin(), at2.accel.end(), 0.0) / static_cast<double>(at2.accel.size());
  // rounding to a count (half a count) plus the mean of those roundings (at most half a count)
  const double tol = gal_per_count * 0.01 * (1.0 + 1e-9);
  for (std::size_t i = 0; i < got.accel.size(); ++i)
    ASSERT_NEAR(got.accel[i], at2.accel[i] - mean, tol) << "sample " << i;
}

}  // namespace

TEST(RecordFormatsKnet, ThreeFilesOneStationOffsetRemoved) {
  SKIP_WITHOUT_RECORDS(dir);
  const Rinaldi r = rinaldi(dir);
  const fs::path d = scratch("knet") / "northridge_knet";
  fs::create_directories(d);
  const KnetFile ns = knet_file(r.h318, "N-S", 8009, "\n", true);
  write_file(d / "RRS0019401171231.NS", ns.text);
  write_file(d / "RRS0019401171231.EW", knet_file(r.h228, "E-W", -2471, "\r\n", false).text);
  write_file(d / "RRS0019401171231.UD", knet_file(r.up, "U-D", 0, "\n", false).text);
  const std::string f = (d / "RRS0019401171231.NS").string();
  EXPECT_EQ(rm::detect_format(f), rm::RecordFormat::Knet);
  const rm::Component c = rm::read_record(f).at(0);
  EXPECT_EQ(c.label, "N");
  EXPECT_EQ(c.station, "RRS001");
  EXPECT_DOUBLE_EQ(c.dt, 0.01);
  expect_knet_equals(c, r.h318, ns.gal_per_count);
  expect_knet_equals(rm::read_record((d / "RRS0019401171231.EW").string()).at(0), r.h228, ns.gal_per_count);
  const rm::Component up = rm::read_record((d / "RRS0019401171231.UD").string()).at(0);
  EXPECT_TRUE(up.vertical);
  expect_knet_equals(up, r.up, ns.gal_per_count);
  // grouped by name into one station: E then N (N is 90 deg counter-clockwise of E), and up
  const rm::StationListing listing = rm::list_stations(d.parent_path().string());
  ASSERT_EQ(listing.stations.size(), 1u);
  EXPECT_EQ(listing.stations[0].station, "RRS001");
  const rm::StationRecord st = rm::load_station(listing.stations[0]);
  ASSERT_EQ(st.horizontals.size(), 2u);
  EXPECT_EQ(st.horizontals[0].label, "E");
  EXPECT_EQ(st.horizontals[1].label, "N");
  EXPECT_TRUE(st.vertical.has_value());
}

TEST(RecordFormatsKnet, KiknetChannelNumbersMakeTwoStations) {
  SKIP_WITHOUT_RECORDS(dir);
  const Rinaldi r = rinaldi(dir);
  const fs::path d = scratch("kiknet") / "ev";
  fs::create_directories(d);
  write_file(d / "RRSH019401171231.NS1", knet_file(r.h318, "1", -2466, "\n", true).text);
  write_file(d / "RRSH019401171231.NS2", knet_file(r.h318, "4", 12, "\n", true).text);
  write_file(d / "RRSH019401171231.UD2", knet_file(r.up, "6", 12, "\n", true).text);
  const rm::StationListing listing = rm::list_stations(d.parent_path().string());
  ASSERT_EQ(listing.stations.size(), 2u);
  EXPECT_EQ(listing.stations[0].station, "RRS001 borehole");
  EXPECT_EQ(listing.stations[1].station, "RRS001 surface");
  EXPECT_EQ(listing.stations[1].component_count(), 2u);
  EXPECT_EQ(rm::read_record((d / "RRSH019401171231.UD2").string()).at(0).label, "UP");
}

TEST(RecordFormatsKnet, TruncatedWrongScaleAndMixedRate) {
  SKIP_WITHOUT_RECORDS(dir);
  const Rinaldi r = rinaldi(dir);
  const fs::path d = scratch("knet_err");
  const KnetFile k = knet_file(r.h318, "N-S", 8009, "\n", false);
  // cut before the peak: 17 header lines, then the first 40 data lines
  std::size_t pos = 0;
  for (int i = 0; i < 17 + 40; ++i) pos = k.text.find('\n', pos) + 1;
  write_file(d / "cut.NS", k.text.substr(0, pos));
  EXPECT_NE(read_error((d / "cut.NS").string()).find("cut.NS:57: the data's peak"), std::string::npos)
      << read_error((d / "cut.NS").string());
  EXPECT_NE(read_error((d / "cut.NS").string()).find("truncated file or wrong scale factor"), std::string::npos);
  // a scale factor in other units, and one that disagrees with Max. Acc.
  write_file(d / "cm.NS", knet_file(r.h318, "N-S", 0, "\n", false, "3920(cm)/6182761").text);
  EXPECT_NE(read_error((d / "cm.NS").string()).find("cm.NS:14: bad scale factor '3920(cm)/6182761'"), std::string::npos)
      << read_error((d / "cm.NS").string());
  std::string twice = k.text;
  twice.replace(twice.find("3920(gal)/6182761"), 17, "7840(gal)/6182761");
  write_file(d / "twice.NS", twice);
  EXPECT_NE(read_error((d / "twice.NS").string()).find("differs from Max. Acc."), std::string::npos)
      << read_error((d / "twice.NS").string());
  // a line cut short in the middle of the data
  std::string hole = k.text;
  const std::size_t l30 = [&] {
    std::size_t q = 0;
    for (int i = 0; i < 17 + 29; ++i) q = hole.find('\n', q) + 1;
    return q;
  }();
  hole.erase(l30, 18);  // two counts of line 47
  write_file(d / "hole.NS", hole);
  EXPECT_NE(
      read_error((d / "hole.NS").string()).find("hole.NS:47: only the last data line may hold fewer than 8 values"),
      std::string::npos)
      << read_error((d / "hole.NS").string());
  // mixed rates within a station: 100 Hz N-S, 200 Hz U-D
  const fs::path s = d / "station";
  fs::create_directories(s);
  write_file(s / "RRS0019401171231.NS", k.text);
  std::string fast = knet_file(r.up, "U-D", 0, "\n", false).text;
  fast.replace(fast.find("100Hz"), 5, "200Hz");
  write_file(s / "RRS0019401171231.UD", fast);
  std::string err;
  try {
    rm::to_sensor_frame(rm::load_station(
        rm::station_from_files({(s / "RRS0019401171231.NS").string(), (s / "RRS0019401171231.UD").string()})));
  } catch (const rm::RecordError& e) {
    err = e.what();
  }
  EXPECT_NE(err.find("RRS0019401171231.UD"), std::string::npos) << err;
  EXPECT_NE(err.find("different sample intervals (0.01 s and 0.005 s)"), std::string::npos) << err;
}

// =================================================================== the tools accept them

#ifdef ROCKING_SIM_EXE
TEST(RecordFormatsTools, RockingSimOnMiniSeedEqualsTheAt2Run) {
  SKIP_WITHOUT_RECORDS(dir);
  const Rinaldi r = rinaldi(dir);
  const fs::path d = scratch("sim");
  // float64 m/s^2 (gain 1): the same samples, so the same run to the bit
  write_interleaved(d / "rrs.mseed", {pack_channel("HN1", 100.0, kStart, r.h228.accel, DE_FLOAT64, 512),
                                      pack_channel("HNZ", 100.0, kStart, r.up.accel, DE_FLOAT64, 512)});
  const std::string body = " --width 0.3 --cg-height 0.6 --eccentricity 0.45 --fidelity rocking --json";
  const auto at2 = rm::testing::run_command(std::string(ROCKING_SIM_EXE) + " --record " + dir +
                                            "/northridge_1994/Rinaldi228.AT2 --vertical " + dir +
                                            "/northridge_1994/RinaldiUP.AT2" + body);
  const auto ms = rm::testing::run_command(std::string(ROCKING_SIM_EXE) + " --record " + (d / "rrs.mseed").string() +
                                           " --gain 1 --sensor-azimuth 228" + body);
  ASSERT_EQ(at2.status, 0) << at2.out;
  ASSERT_EQ(ms.status, 0) << ms.out;
  const auto a = nlohmann::json::parse(at2.out);
  const auto b = nlohmann::json::parse(ms.out);
  for (const char* key : {"overturned", "max_rotation_ratio", "impacts", "uplift_time_s", "overturn_time_s", "steps"}) {
    EXPECT_EQ(a[key], b[key]) << key;
  }
  EXPECT_EQ(a["record"]["pga_mps2"], b["record"]["pga_mps2"]);
  // without a gain it refuses, naming what is missing
  const auto none = rm::testing::run_command(std::string(ROCKING_SIM_EXE) + " --record " + (d / "rrs.mseed").string() +
                                             body + " 2>&1");
  EXPECT_NE(none.status, 0);
  EXPECT_NE(none.out.find("no gain (counts per m/s^2)"), std::string::npos) << none.out;
}
#endif
