// record_to_mseed's job: the station's record in the sensor frame, its counts through the gain, packed
// into miniSEED records interleaved as a recorder sends them, written; the dequantised tables.
#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "record_to_mseed_options.hpp"
#include "rocking_monitor/feeds/mseed_record.hpp"
#include "rocking_monitor/feeds/mseed_writer.hpp"
#include "rocking_monitor/feeds/seed_channels.hpp"
#include "rocking_monitor/motion/sensor_frame.hpp"
#include "rocking_monitor/motion/station.hpp"

namespace core = rocking_monitor::core;
namespace feeds = rocking_monitor::feeds;

namespace rocking_monitor::tools::record_to_mseed {

namespace {

std::int64_t parse_time_us(const std::string& text) {
  char* end = nullptr;
  const double s = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(s) || s < 0.0 || s > 4e9)
    throw std::invalid_argument("--start-time '" + text + "': expected seconds since the epoch (e.g. 1000000000.5)");
  return std::llround(s * 1e6);
}

std::int32_t to_counts(double v, double gain, const std::string& channel, std::size_t i) {
  const double c = std::nearbyint(v * gain);
  // Steim2 differences hold 30 bits: keep counts well inside int32 so any difference fits too.
  if (!(std::fabs(c) < 536870911.0))
    throw std::invalid_argument(channel + " sample " + std::to_string(i) + ": " + std::to_string(v) + " m/s^2 x gain " +
                                std::to_string(gain) + " = " + std::to_string(c) + " counts, beyond +-2^29 (lower --gain)");
  return static_cast<std::int32_t>(c);
}

void write_table(const std::string& path, const std::vector<double>& values, double dt, const std::string& what) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing (--table-out)");
  out << "# " << what << ", m/s^2: the miniSEED counts / gain in the station frame, as seedlink_bridge publishes them\n";
  out << "time_s,accel_mps2\n";
  char line[96];
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::snprintf(line, sizeof line, "%.9f,%.17g\n", static_cast<double>(i) * dt, values[i]);
    out << line;
  }
  if (!out) throw std::runtime_error(path + ": write failed (--table-out)");
}

/// The flags checked together, before any file is read.
void check_options(const Options& o) {
  if (o.files.size() != 3) throw std::invalid_argument("--file: give the station's three components (two horizontals, a vertical)");
  if (!(*o.gain > 0.0) || !std::isfinite(*o.gain)) throw std::invalid_argument("--gain: must be finite and > 0 (counts per m/s^2)");
  if (o.band.size() != 2) throw std::invalid_argument("--band '" + o.band + "': two characters (band and instrument code, e.g. HN)");
  if (o.orientation == "NE" && o.azimuth) throw std::invalid_argument("--azimuth is for --orientation 12 (N/E channels point north/east)");
}

/// The station's three components in the sensor frame: x east and y north (NE), or x along channel 1.
struct StationMotion {
  core::SensorFrameMotion m;
  bool numbered = false;  ///< --orientation 12
  double az1 = 0.0;       ///< channel 1's azimuth, deg (12)
  double rate = 0.0;      ///< Hz
};

StationMotion station_motion(const Options& o) {
  core::SensorFrameOptions fo;
  fo.length_mismatch = core::LengthMismatch::Error;
  if (o.orientation == "NE") fo.azimuth_deg = 90.0;  // x east, y (90 deg counter-clockwise of x) north
  else fo.azimuth_deg = o.azimuth;
  const core::StationRecord rec = core::load_station(core::station_from_files(o.files));
  StationMotion s{core::to_sensor_frame(rec, fo)};
  const core::SensorFrameMotion& m = s.m;
  if (!m.recorded[0] || !m.recorded[1] || !m.recorded[2])
    throw std::invalid_argument("--file: the station needs two horizontals and a vertical");
  s.numbered = o.orientation == "12";
  if (s.numbered && !m.x_azimuth_deg)
    throw std::invalid_argument("--orientation 12: the azimuth of the first horizontal is unknown; give --azimuth");
  s.az1 = s.numbered ? *m.x_azimuth_deg : 0.0;
  s.rate = 1.0 / m.dt;
  return s;
}

/// Slots H1 (N or 1), H2 (E or 2), Z with their counts. y is 90 deg counter-clockwise of x; 2 is 90 deg
/// clockwise of 1.
std::array<feeds::ChannelSeries, 3> channel_series(const Options& o, const StationMotion& s, std::int64_t start_us,
                                                   const std::array<std::string, 3>& chans) {
  std::array<feeds::ChannelSeries, 3> series;
  for (int c = 0; c < 3; ++c) {
    series[c].network = o.network;
    series[c].station = o.station;
    series[c].location = o.location;
    series[c].channel = chans[c];
    series[c].start_us = start_us;
    series[c].sample_rate = s.rate;
  }
  const core::SensorFrameMotion& m = s.m;
  for (std::size_t i = 0; i < m.size(); ++i) {
    const double h1 = s.numbered ? m.ground[0][i] : m.ground[1][i];
    const double h2 = s.numbered ? -m.ground[1][i] : m.ground[0][i];
    series[0].counts.push_back(to_counts(h1, *o.gain, chans[0], i));
    series[1].counts.push_back(to_counts(h2, *o.gain, chans[1], i));
    series[2].counts.push_back(to_counts(m.ground[2][i], *o.gain, chans[2], i));
  }
  return series;
}

/// The three channels' records, each read back, in the order a recorder sends them (record end time).
struct Packed {
  struct Rec {
    std::int64_t end_us;
    int channel;
    std::string bytes;
  };
  std::vector<Rec> all;
  std::size_t min_n = SIZE_MAX, max_n = 0;  ///< samples per record
};

Packed pack_interleaved(const Options& o, const std::array<feeds::ChannelSeries, 3>& series, double rate) {
  feeds::PackOptions po;
  po.encoding = o.encoding_text == "steim2" ? 11 : o.encoding_text == "steim1" ? 10 : 3;
  po.record_length = o.record_length;
  po.max_samples = o.max_samples;
  Packed p;
  feeds::MseedDecoder decoder;
  feeds::DecodedRecord d;
  for (int c = 0; c < 3; ++c) {
    for (std::string& r : feeds::pack_channel(series[c], po)) {
      if (decoder.decode(r.data(), r.size(), d) != feeds::MseedDecoder::Result::Ok)
        throw std::runtime_error("libmseed wrote a record it cannot read back: " + decoder.error());
      p.min_n = std::min(p.min_n, d.samples.size());
      p.max_n = std::max(p.max_n, d.samples.size());
      p.all.push_back({d.start_us + std::llround(static_cast<double>(d.samples.size()) * 1e6 / rate), c, std::move(r)});
    }
  }
  std::stable_sort(p.all.begin(), p.all.end(), [](const Packed::Rec& a, const Packed::Rec& b) {
    return a.end_us != b.end_us ? a.end_us < b.end_us : a.channel < b.channel;
  });
  return p;
}

void write_mseed(const std::string& out, const Packed& p) {
  std::ofstream f(out, std::ios::binary);
  if (!f) throw std::runtime_error(out + ": cannot open for writing");
  for (const Packed::Rec& r : p.all) f.write(r.bytes.data(), static_cast<std::streamsize>(r.bytes.size()));
  if (!f) throw std::runtime_error(out + ": write failed");
}

/// --table-out: the counts dequantised in the station frame, as seedlink_bridge publishes them.
void write_tables(const Options& o, const std::array<feeds::ChannelSeries, 3>& series, const StationMotion& s) {
  const feeds::StationFrame frame(*o.gain, s.az1);
  std::array<std::vector<double>, 3> enu;
  for (std::size_t i = 0; i < s.m.size(); ++i) {
    const auto v = frame.to_enu(series[0].counts[i], series[1].counts[i], series[2].counts[i]);
    for (int k = 0; k < 3; ++k) enu[k].push_back(v[k]);
  }
  write_table(o.table_out + "_east.csv", enu[0], s.m.dt, "east");
  write_table(o.table_out + "_north.csv", enu[1], s.m.dt, "north");
  write_table(o.table_out + "_up.csv", enu[2], s.m.dt, "up");
}

void print_summary(const Options& o, const Packed& p, const std::array<std::string, 3>& chans, const StationMotion& s,
                   std::int64_t start_us) {
  std::printf("wrote %s: %zu records of %d bytes (%s), %zu to %zu samples each; channels %s.%s.%s.{%s,%s,%s}, %zu samples at "
              "%.6g Hz from %.6f s",
              o.out.c_str(), p.all.size(), o.record_length, o.encoding_text.c_str(), p.min_n, p.max_n, o.network.c_str(),
              o.station.c_str(), o.location.c_str(), chans[0].c_str(), chans[1].c_str(), chans[2].c_str(), s.m.size(), s.rate,
              static_cast<double>(start_us) * 1e-6);
  if (s.numbered) std::printf("; channel 1 at azimuth %.6g deg (give it as the bridge's ~azimuth)", s.az1);
  std::printf("\n");
}

}  // namespace

void run(const Options& o) {
  check_options(o);
  const std::int64_t start_us = parse_time_us(o.start_text);
  const StationMotion s = station_motion(o);
  const std::array<std::string, 3> chans = {o.band + (s.numbered ? "1" : "N"), o.band + (s.numbered ? "2" : "E"),
                                            o.band + "Z"};
  const std::array<feeds::ChannelSeries, 3> series = channel_series(o, s, start_us, chans);
  const Packed p = pack_interleaved(o, series, s.rate);
  write_mseed(o.out, p);
  if (!o.table_out.empty()) write_tables(o, series, s);
  if (!o.quiet) print_summary(o, p, chans, s, start_us);
}

}  // namespace rocking_monitor::tools::record_to_mseed
