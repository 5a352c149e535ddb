#include "seed_records.hpp"

#include <libmseed.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/motion/record_reader.hpp"

namespace rocking_monitor::fuzz {
namespace {

namespace rm = rocking_monitor::core;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot read fuzz seed");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Seed file_seed(const std::string& path) {
  return {path.substr(path.find_last_of('/') + 1), slurp(path)};
}

// A 24-bit logger with a +-2 g sensor: 2^23 counts / (2 g).
const double kGain = 8388608.0 / (2.0 * core::kGravity);

void collect_record(char* record, int reclen, void* handler_data) {
  static_cast<std::string*>(handler_data)->append(record, static_cast<std::size_t>(reclen));
}

/// One steim2 channel in 512-byte records, packed by libmseed.
std::string miniseed(const rm::Component& c, const char* chan) {
  std::vector<int32_t> ints;
  for (double a : c.accel) ints.push_back(static_cast<int32_t>(std::llround(a * kGain)));
  MSRecord* msr = msr_init(nullptr);
  std::snprintf(msr->network, sizeof msr->network, "XX");
  std::snprintf(msr->station, sizeof msr->station, "RRS");
  std::snprintf(msr->channel, sizeof msr->channel, "%s", chan);
  msr->dataquality = 'D';
  msr->starttime = MS_EPOCH2HPTIME(758809861);  // 1994-01-17T12:31:01Z
  msr->samprate = 1.0 / c.dt;
  msr->reclen = 512;
  msr->byteorder = 1;
  msr->encoding = DE_STEIM2;
  msr->numsamples = static_cast<int64_t>(ints.size());
  msr->datasamples = ints.data();
  msr->sampletype = 'i';
  std::string out;
  int64_t packed = 0;
  msr_pack(msr, collect_record, &out, &packed, 1, 0);
  msr->datasamples = nullptr;  // ours, not libmseed's
  msr_free(&msr);
  return out;
}

/// Fortran Ew.d: "-0.123457E+01" (leading 0 dropped when it would not fit).
std::string fortran_e(double v, int w, int d) {
  int e = 0;
  double m = 0.0;
  if (v != 0.0) {
    e = static_cast<int>(std::floor(std::log10(std::abs(v)))) + 1;
    m = v / std::pow(10.0, e);
    if (std::abs(std::round(m * std::pow(10.0, d))) >= std::pow(10.0, d)) {
      m /= 10.0;
      ++e;
    }
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*fE%c%02d", d, m, e < 0 ? '-' : '+', std::abs(e));
  std::string s = buf;
  if (static_cast<int>(s.size()) > w) s.erase(s.find("0."), 1);
  return std::string(static_cast<std::size_t>(std::max(0, w - static_cast<int>(s.size()))), ' ') + s;
}

std::string fixed_lines(const std::vector<std::string>& fields, std::size_t per_line) {
  std::string out;
  for (std::size_t i = 0; i < fields.size(); i += per_line) {
    for (std::size_t k = i; k < std::min(fields.size(), i + per_line); ++k) out += fields[k];
    out += "\n";
  }
  return out;
}

/// One COSMOS V2 channel (v1.20 layout, as test_record_formats.cpp writes it).
std::string cosmos(const rm::Component& c) {
  std::string s = "Corrected acceleration  (Format v01.20 with 13 text lines) Src: made from a PEER AT2\n";
  s += "Northridge earthquake                Jan 17, 1994 12:31 PST\n";
  s += "Hypocenter: 34.213   -118.537   H= 18km(SCSN)  ML=6.6  Mw=6.7\n";
  s += "Origin: 01/17/1994, 12:30:55.4 UT (SCSN)\n";
  s += "Rinaldi Receiving Sta\n";
  for (int k = 6; k <= 13; ++k) s += "text line " + std::to_string(k) + "\n";
  s += " 100 Integer-header values follow on  10 lines, Format= (10I8)\n";
  std::vector<std::string> ints(100, "    -999");
  const auto put = [&](int i1, int v) {
    char b[16];
    std::snprintf(b, sizeof b, "%8d", v);
    ints[static_cast<std::size_t>(i1 - 1)] = b;
  };
  put(1, 2);
  put(2, 1);
  put(3, 4);
  put(10, 1);
  put(54, 228);
  s += fixed_lines(ints, 10);
  s += " 100 Real-header values follow on  20 lines, Format= (5E16.7)\n";
  std::vector<double> reals(100, -999.0);
  reals[33] = c.dt;
  reals[61] = c.dt * 1000.0;
  std::vector<std::string> rf;
  for (double v : reals) rf.push_back(fortran_e(v, 16, 7));
  s += fixed_lines(rf, 5);
  s += "   1 Comment line(s) follow, each starting with a \"|\":\n| Sensor: FBA-23\n";
  char hdr[160];
  std::snprintf(hdr, sizeof hdr, "%8zu acceleration pts, approx %4d secs, units=cm/sec2(04), Format=(6E13.6)",
                c.accel.size(), static_cast<int>(std::lround(static_cast<double>(c.accel.size()) * c.dt)));
  s += std::string(hdr) + "\n";
  std::vector<std::string> df;
  for (double a : c.accel) df.push_back(fortran_e(a * 100.0, 13, 6));
  s += fixed_lines(df, 6);
  s += "End-of-data for Chan  1 acceleration\n";
  return s;
}

/// One K-NET ASCII file (17 header lines, counts 8 per line).
std::string knet(const rm::Component& c) {
  const double gal_per_count = 3920.0 / 6182761.0;
  std::vector<long long> counts;
  for (double a : c.accel) counts.push_back(std::llround(a * 100.0 / gal_per_count) + 8009);
  long double sum = 0.0L;
  for (long long x : counts) sum += static_cast<long double>(x);
  const double mean = static_cast<double>(sum / static_cast<long double>(counts.size()));
  double peak = 0.0;  // Max. Acc. as NIED defines it: of the record with its mean removed
  for (long long x : counts) peak = std::max(peak, std::abs((static_cast<double>(x) - mean) * gal_per_count));
  char peak_text[32];
  std::snprintf(peak_text, sizeof peak_text, "%.3f", peak);
  std::string t;
  const auto line = [&](std::string name, const std::string& value) {
    name.resize(18, ' ');
    t += name + value + "\n";
  };
  line("Origin Time", "1994/01/17 12:30:55");
  line("Lat.", "34.213");
  line("Long.", "-118.537");
  line("Depth. (km)", "18");
  line("Mag.", "6.7");
  line("Station Code", "RRS001");
  line("Station Lat.", "34.281");
  line("Station Long.", "-118.479");
  line("Station Height(m)", "282");
  line("Record Time", "1994/01/17 12:31:10");
  line("Sampling Freq(Hz)", "100Hz");
  line("Duration Time(s)", "20");
  line("Dir.", "E-W");
  line("Scale Factor", "3920(gal)/6182761");
  line("Max. Acc. (gal)", peak_text);
  line("Last Correction", "1994/01/17 12:30:55");
  line("Memo.", "");
  for (std::size_t i = 0; i < counts.size(); i += 8) {
    for (std::size_t j = i; j < std::min(counts.size(), i + 8); ++j) {
      char b[16];
      std::snprintf(b, sizeof b, "%9lld", counts[j]);
      t += b;
    }
    t += "\n";
  }
  return t;
}

std::string csv(const rm::Component& c) {
  std::string s = "time_s,accel_mps2\n";
  char b[64];
  for (std::size_t i = 0; i < c.accel.size(); ++i) {
    std::snprintf(b, sizeof b, "%.3f,%.9g\n", static_cast<double>(i) * c.dt, c.accel[i]);
    s += b;
  }
  return s;
}

}  // namespace

double miniseed_gain() { return kGain; }

std::vector<Target> make_targets(const std::string& records_dir, const std::string& config_dir) {
  const std::string r = records_dir + "/";
  const rm::Component h228 = rm::read_record(r + "northridge_1994/Rinaldi228.AT2").at(0);
  std::vector<Target> t;
  t.push_back({"at2", false,
               {file_seed(r + "northridge_1994/Rinaldi228.AT2"), file_seed(r + "northridge_1994/RinaldiUP.AT2"),
                file_seed(r + "imperial_valley_1979/H-E01140.at2")}});
  t.push_back({"bbp", false, {file_seed(r + "northridge_1994/s01.bbp")}});
  t.push_back({"smc", false, {file_seed(r + "loma_prieta_1989/0111a.smc")}});
  t.push_back({"csv", false, {{"rinaldi228.csv", csv(h228)}}});
  t.push_back({"miniseed", true, {{"rrs.mseed", miniseed(h228, "HNE")}}});
  t.push_back({"cosmos", false, {{"rrs.v2", cosmos(h228)}}});
  t.push_back({"knet", false, {{"RRS0019401171231.EW", knet(h228)}}});
  const std::vector<Seed> catalogues = {file_seed(config_dir + "/catalogue_example.yaml"),
                                        file_seed(config_dir + "/catalogue_uncertain_example.yaml")};  // config/monitor.yaml holds no catalogue
  t.push_back({"catalogue", false, catalogues});
  t.push_back({"catalogue_items", false, catalogues});
  return t;
}

}  // namespace rocking_monitor::fuzz
