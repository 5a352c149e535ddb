// record_to_mseed: a strong-motion record (a station's two horizontals and vertical, any format the
// record reader takes) -> miniSEED 2 as a strong-motion recorder would write it: int32 counts
// through a gain, steim2 (default), three channels interleaved in the order a recorder sends them
// (by the end time of each record). Optionally also the dequantised samples, in the station frame
// exactly as seedlink_bridge computes them, as table records (time_s,accel m/s^2) for rocking_sim.
//
// Channels: --orientation NE writes <band>N / <band>E / <band>Z (the record rotated to north and
// east); --orientation 12 writes <band>1 / <band>2 / <band>Z with 1 along --azimuth (default: the
// first horizontal as recorded) and 2 at 90 deg clockwise of it (SEED convention).

#include <CLI/CLI.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "rocking_monitor/feeds/mseed_record.hpp"
#include "rocking_monitor/feeds/mseed_writer.hpp"
#include "rocking_monitor/feeds/seed_channels.hpp"
#include "rocking_monitor/motion/sensor_frame.hpp"
#include "rocking_monitor/motion/station.hpp"
#include "command_line.hpp"

namespace core = rocking_monitor::core;
namespace feeds = rocking_monitor::feeds;

namespace {

constexpr const char* kProgram = "record_to_mseed";

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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "record_to_mseed: write a strong-motion record (two horizontals and a vertical) as miniSEED 2 records of int32 counts, "
      "as a strong-motion recorder streams them over SeedLink (three channels interleaved by record end time)."};
  std::vector<std::string> files;
  std::string out, table_out, network = "XX", station = "REC", location, band = "HN", orientation = "NE", encoding_text = "steim2";
  std::string start_text = "1000000000";
  std::optional<double> gain, azimuth;
  int record_length = 512;
  std::size_t max_samples = 0;
  bool quiet = false;
  app.add_option("--file", files, "Record files of one station: two horizontals and a vertical (any format rocking_sim reads)")
      ->required();
  app.add_option("-o,--out", out, "Output miniSEED file")->required();
  app.add_option("--gain", gain, "Counts per m/s^2 (the sensitivity the bridge is given as ~gain), e.g. 427000")->required();
  app.add_option("--network", network, "SEED network code, 1-2 characters (default XX)");
  app.add_option("--station", station, "SEED station code, 1-5 characters (default REC)");
  app.add_option("--location", location, "SEED location code, 0-2 characters (default empty)");
  app.add_option("--band", band, "Band and instrument code of the channels (default HN: high rate, accelerometer)");
  app.add_option("--orientation", orientation, "NE: channels N, E, Z (rotated to north/east) | 12: channels 1, 2, Z, 1 along --azimuth")
      ->check(CLI::IsMember({"NE", "12"}));
  app.add_option("--azimuth", azimuth, "--orientation 12: azimuth of channel 1, degrees clockwise from north (default: the first "
                                       "horizontal as recorded)");
  app.add_option("--start-time", start_text, "Data time of the first sample, s since the epoch (default 1000000000)");
  app.add_option("--encoding", encoding_text, "steim2 (default) | steim1 | int32")->check(CLI::IsMember({"steim2", "steim1", "int32"}));
  app.add_option("--record-length", record_length, "Record length, bytes: 512 (SeedLink's) or 4096 (files), any power of two 256..8192");
  app.add_option("--max-samples", max_samples, "At most this many samples per record (0: as many as fit); shorter records = lower latency");
  app.add_option("--table-out", table_out,
                 "Also write PREFIX_east.csv, PREFIX_north.csv, PREFIX_up.csv: the dequantised samples in the station frame "
                 "(x east, y north, z up), m/s^2, exactly as seedlink_bridge publishes them");
  app.add_flag("-q,--quiet", quiet, "Print only errors");
  if (const auto status = rocking_monitor::tools::parse_command_line(app, argc, argv, kProgram)) return *status;

  try {
    if (files.size() != 3) throw std::invalid_argument("--file: give the station's three components (two horizontals, a vertical)");
    if (!(*gain > 0.0) || !std::isfinite(*gain)) throw std::invalid_argument("--gain: must be finite and > 0 (counts per m/s^2)");
    if (band.size() != 2) throw std::invalid_argument("--band '" + band + "': two characters (band and instrument code, e.g. HN)");
    if (orientation == "NE" && azimuth) throw std::invalid_argument("--azimuth is for --orientation 12 (N/E channels point north/east)");
    const std::int64_t start_us = parse_time_us(start_text);
    core::SensorFrameOptions fo;
    fo.length_mismatch = core::LengthMismatch::Error;
    if (orientation == "NE") fo.azimuth_deg = 90.0;  // x east, y (90 deg counter-clockwise of x) north
    else fo.azimuth_deg = azimuth;
    const core::StationRecord rec = core::load_station(core::station_from_files(files));
    const core::SensorFrameMotion m = core::to_sensor_frame(rec, fo);
    if (!m.recorded[0] || !m.recorded[1] || !m.recorded[2])
      throw std::invalid_argument("--file: the station needs two horizontals and a vertical");
    const bool numbered = orientation == "12";
    if (numbered && !m.x_azimuth_deg)
      throw std::invalid_argument("--orientation 12: the azimuth of the first horizontal is unknown; give --azimuth");
    const double az1 = numbered ? *m.x_azimuth_deg : 0.0;
    const double rate = 1.0 / m.dt;

    // Slots H1 (N or 1), H2 (E or 2), Z. y is 90 deg counter-clockwise of x; 2 is 90 deg clockwise of 1.
    const std::array<std::string, 3> chans = {band + (numbered ? "1" : "N"), band + (numbered ? "2" : "E"), band + "Z"};
    std::array<feeds::ChannelSeries, 3> series;
    for (int c = 0; c < 3; ++c) {
      series[c].network = network;
      series[c].station = station;
      series[c].location = location;
      series[c].channel = chans[c];
      series[c].start_us = start_us;
      series[c].sample_rate = rate;
    }
    for (std::size_t i = 0; i < m.size(); ++i) {
      const double h1 = numbered ? m.ground[0][i] : m.ground[1][i];
      const double h2 = numbered ? -m.ground[1][i] : m.ground[0][i];
      series[0].counts.push_back(to_counts(h1, *gain, chans[0], i));
      series[1].counts.push_back(to_counts(h2, *gain, chans[1], i));
      series[2].counts.push_back(to_counts(m.ground[2][i], *gain, chans[2], i));
    }
    feeds::PackOptions po;
    po.encoding = encoding_text == "steim2" ? 11 : encoding_text == "steim1" ? 10 : 3;
    po.record_length = record_length;
    po.max_samples = max_samples;
    struct Rec {
      std::int64_t end_us;
      int channel;
      std::string bytes;
    };
    std::vector<Rec> all;
    feeds::MseedDecoder decoder;
    feeds::DecodedRecord d;
    std::size_t min_n = SIZE_MAX, max_n = 0;
    for (int c = 0; c < 3; ++c) {
      for (std::string& r : feeds::pack_channel(series[c], po)) {
        if (decoder.decode(r.data(), r.size(), d) != feeds::MseedDecoder::Result::Ok)
          throw std::runtime_error("libmseed wrote a record it cannot read back: " + decoder.error());
        min_n = std::min(min_n, d.samples.size());
        max_n = std::max(max_n, d.samples.size());
        all.push_back({d.start_us + std::llround(static_cast<double>(d.samples.size()) * 1e6 / rate), c, std::move(r)});
      }
    }
    std::stable_sort(all.begin(), all.end(), [](const Rec& a, const Rec& b) {
      return a.end_us != b.end_us ? a.end_us < b.end_us : a.channel < b.channel;
    });
    {
      std::ofstream f(out, std::ios::binary);
      if (!f) throw std::runtime_error(out + ": cannot open for writing");
      for (const Rec& r : all) f.write(r.bytes.data(), static_cast<std::streamsize>(r.bytes.size()));
      if (!f) throw std::runtime_error(out + ": write failed");
    }
    if (!table_out.empty()) {
      const feeds::StationFrame frame(*gain, az1);
      std::array<std::vector<double>, 3> enu;
      for (std::size_t i = 0; i < m.size(); ++i) {
        const auto v = frame.to_enu(series[0].counts[i], series[1].counts[i], series[2].counts[i]);
        for (int k = 0; k < 3; ++k) enu[k].push_back(v[k]);
      }
      write_table(table_out + "_east.csv", enu[0], m.dt, "east");
      write_table(table_out + "_north.csv", enu[1], m.dt, "north");
      write_table(table_out + "_up.csv", enu[2], m.dt, "up");
    }
    if (!quiet) {
      std::printf("wrote %s: %zu records of %d bytes (%s), %zu to %zu samples each; channels %s.%s.%s.{%s,%s,%s}, %zu samples at "
                  "%.6g Hz from %.6f s",
                  out.c_str(), all.size(), record_length, encoding_text.c_str(), min_n, max_n, network.c_str(), station.c_str(),
                  location.c_str(), chans[0].c_str(), chans[1].c_str(), chans[2].c_str(), m.size(), rate,
                  static_cast<double>(start_us) * 1e-6);
      if (numbered) std::printf("; channel 1 at azimuth %.6g deg (give it as the bridge's ~azimuth)", az1);
      std::printf("\n");
    }
    return 0;
  } catch (const std::exception& e) {
    std::string what = e.what();
    for (char& c : what) c = c == '\n' ? ' ' : c;
    std::cerr << kProgram << ": error: " << what << "\n";
    return 2;
  }
}
