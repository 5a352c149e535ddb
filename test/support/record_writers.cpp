#include "record_writers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>

#include "rocking_monitor/constants.hpp"

namespace rocking_monitor::core::testing {

// ------------------------------------------------------------------ miniSEED

double logger_gain() { return 8388608.0 / (2.0 * kGravity); }

namespace {
void collect_record(char* record, int reclen, void* handler_data) {
  static_cast<std::vector<std::string>*>(handler_data)->emplace_back(record, static_cast<std::size_t>(reclen));
}
}  // namespace

std::vector<std::string> pack_channel(const std::string& chan, double rate, hptime_t start,
                                      const std::vector<double>& values, int encoding, int reclen,
                                      const std::string& sta) {
  std::vector<int32_t> ints;
  std::vector<float> floats;
  std::vector<double> doubles;
  MSRecord* msr = msr_init(nullptr);
  std::snprintf(msr->network, sizeof msr->network, "XX");
  std::snprintf(msr->station, sizeof msr->station, "%s", sta.c_str());
  msr->location[0] = '\0';
  std::snprintf(msr->channel, sizeof msr->channel, "%s", chan.c_str());
  msr->dataquality = 'D';
  msr->starttime = start;
  msr->samprate = rate;
  msr->reclen = reclen;
  msr->byteorder = 1;
  msr->encoding = static_cast<int8_t>(encoding);
  msr->numsamples = static_cast<int64_t>(values.size());
  if (encoding == DE_FLOAT32) {
    for (double v : values) floats.push_back(static_cast<float>(v));
    msr->datasamples = floats.data();
    msr->sampletype = 'f';
  } else if (encoding == DE_FLOAT64) {
    doubles = values;
    msr->datasamples = doubles.data();
    msr->sampletype = 'd';
  } else {
    for (double v : values) ints.push_back(static_cast<int32_t>(std::llround(v)));
    msr->datasamples = ints.data();
    msr->sampletype = 'i';
  }
  std::vector<std::string> records;
  int64_t packed = 0;
  const int n = msr_pack(msr, collect_record, &records, &packed, 1, 0);
  msr->datasamples = nullptr;  // ours, not libmseed's
  msr_free(&msr);
  if (n <= 0 || packed != static_cast<int64_t>(values.size())) {
    throw std::runtime_error("pack_channel " + chan + ": libmseed packed " + std::to_string(packed) + " of " +
                             std::to_string(values.size()) + " samples in " + std::to_string(n) + " records");
  }
  return records;
}

std::string interleave(const std::vector<std::vector<std::string>>& channels) {
  std::string out;
  for (std::size_t k = 0;; ++k) {
    bool any = false;
    for (const auto& c : channels) {
      if (k < c.size()) {
        out += c[k];
        any = true;
      }
    }
    if (!any) break;
  }
  return out;
}

std::vector<double> counts(const Component& c, double gain) {
  std::vector<double> out;
  for (double a : c.accel) out.push_back(static_cast<double>(std::llround(a * gain)));
  return out;
}

// ------------------------------------------------------------------ COSMOS V2

std::string fortran_e(double v, int w, int d, char exp) {
  int e = 0;
  double m = 0.0;
  if (v != 0.0) {
    e = static_cast<int>(std::floor(std::log10(std::abs(v)))) + 1;
    m = v / std::pow(10.0, e);
    const double scale = std::pow(10.0, d);
    if (std::abs(std::round(m * scale)) >= scale) {
      m /= 10.0;
      ++e;
    }
  }
  char mant[64];
  std::snprintf(mant, sizeof mant, "%.*f", d, m);
  char expo[16];
  std::snprintf(expo, sizeof expo, "%c%c%02d", exp, e < 0 ? '-' : '+', std::abs(e));
  std::string s = std::string(mant) + expo;
  if (static_cast<int>(s.size()) > w) {
    const std::size_t z = s.find("0.");
    if (z != std::string::npos) s.erase(z, 1);
  }
  return std::string(static_cast<std::size_t>(std::max(0, w - static_cast<int>(s.size()))), ' ') + s;
}

namespace {
/// Values in lines of `per_line` fields (with `quirks`, trailing blanks on every other line).
std::string fixed_lines(const std::vector<std::string>& fields, std::size_t per_line, const std::string& eol,
                        bool quirks) {
  std::string out;
  for (std::size_t i = 0; i < fields.size(); i += per_line) {
    for (std::size_t k = i; k < std::min(fields.size(), i + per_line); ++k) out += fields[k];
    if (quirks && (i / per_line) % 2 == 1) out += "   ";
    out += eol;
  }
  return out;
}
}  // namespace

std::string cosmos_channel(const CosmosChannel& ch, int number, const std::string& eol) {
  std::string s;
  s += "Corrected acceleration  (Format v01.20 with 13 text lines) Src: made from a PEER AT2" + eol;
  s += "Northridge earthquake                Jan 17, 1994 12:31 PST" + eol;
  s += "Hypocenter: 34.213   -118.537   H= 18km(SCSN)  ML=6.6  Mw=6.7" + eol;
  s += "Origin: 01/17/1994, 12:30:55.4 UT (SCSN)" + eol;
  s += "Rinaldi Receiving Sta" + eol;
  for (int k = 6; k <= 13; ++k) s += "text line " + std::to_string(k) + eol;
  s += " 100 Integer-header values follow on  10 lines, Format= (10I8)" + eol;
  std::vector<std::string> ints(100, "    -999");
  auto put_int = [&](int index1, int v) {
    char b[16];
    std::snprintf(b, sizeof b, "%8d", v);
    ints[static_cast<std::size_t>(index1 - 1)] = b;
  };
  put_int(1, 2);
  put_int(2, 1);
  put_int(3, 4);
  put_int(10, number);
  put_int(54, ch.orientation);
  s += fixed_lines(ints, 10, eol, ch.quirks);
  s += std::string(" 100 Real-header values follow on  20 lines, Format= (5") + ch.real_exp + "16.7)" + eol;
  std::vector<double> reals(100, -999.0);
  reals[33] = ch.dt;
  reals[61] = ch.dt * 1000.0;
  std::vector<std::string> rf;
  for (double v : reals) rf.push_back(fortran_e(v, 16, 7, ch.real_exp));
  s += fixed_lines(rf, 5, eol, ch.quirks);
  s += "   1 Comment line(s) follow, each starting with a \"|\":" + eol;
  s += "| Sensor: FBA-23" + eol;
  const std::size_t n = ch.comp->accel.size();
  char hdr[160];
  std::snprintf(hdr, sizeof hdr, "%8zu acceleration pts, approx %4d secs, units=%s, Format=(6E13.6)", n,
                static_cast<int>(std::lround(static_cast<double>(n) * ch.dt)), ch.units.c_str());
  s += hdr + eol;
  std::vector<std::string> df;
  for (double a : ch.comp->accel) df.push_back(fortran_e(a * 100.0, 13, 6));  // cm/s^2
  s += fixed_lines(df, 6, eol, ch.quirks);
  if (ch.quirks) {
    s += "       6 velocity     pts, approx    0 secs, units=cm/sec (05), Format=(6E13.6)" + eol;
    s += fixed_lines(std::vector<std::string>(6, fortran_e(-1.5, 13, 6)), 6, eol, ch.quirks);
  }
  s += "End-of-data for Chan  " + std::to_string(number) + " acceleration" + eol;
  return s;
}

// ------------------------------------------------------------------ K-NET / KiK-net

KnetFile knet_file(const Component& c, const std::string& dir_field, long long offset, const std::string& eol,
                   bool old_names, const std::string& scale, bool trailing_blanks) {
  KnetFile k;
  k.gal_per_count = 3920.0 / 6182761.0;
  for (double a : c.accel) k.counts.push_back(std::llround(a * 100.0 / k.gal_per_count) + offset);
  const double mean =
      std::accumulate(k.counts.begin(), k.counts.end(), 0.0L) / static_cast<long double>(k.counts.size());
  double peak = 0.0;
  for (long long x : k.counts) peak = std::max(peak, std::abs((static_cast<double>(x) - mean) * k.gal_per_count));
  char peak_text[32];
  std::snprintf(peak_text, sizeof peak_text, "%.3f", peak);
  auto line = [&](const std::string& name, const std::string& value) {
    std::string n = name;
    n.resize(18, ' ');
    k.text += n + value + eol;
  };
  line("Origin Time", "1994/01/17 12:30:55");
  line("Lat.", "34.213");
  line(old_names ? "Long." : "Lon.", "-118.537");
  line("Depth. (km)", "18");
  line("Mag.", "6.7");
  line("Station Code", "RRS001");
  line("Station Lat.", "34.281");
  line(old_names ? "Station Long." : "Station Lon.", "-118.479");
  line("Station Height(m)", "282");
  line("Record Time", "1994/01/17 12:31:10");
  line("Sampling Freq(Hz)", "100Hz");
  line("Duration Time(s)", "20");
  line("Dir.", dir_field);
  line("Scale Factor", scale);
  line(old_names ? "Max. Acc. (gal)" : "Max Acc. (gal)", peak_text);
  line("Last Correction", "1994/01/17 12:30:55");
  line("Memo.", "");
  for (std::size_t i = 0; i < k.counts.size(); i += 8) {
    for (std::size_t j = i; j < std::min(k.counts.size(), i + 8); ++j) {
      char b[16];
      std::snprintf(b, sizeof b, "%9lld", k.counts[j]);
      k.text += b;
    }
    if (trailing_blanks && (i / 8) % 3 == 2) k.text += "  ";
    k.text += eol;
  }
  return k;
}

}  // namespace rocking_monitor::core::testing
