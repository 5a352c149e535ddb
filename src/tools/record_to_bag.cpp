// record_to_bag: strong-motion record (or station, or synthetic spec) -> rosbag of sensor_msgs/Imu as a
// real accelerometer bolted to the ground publishes them (REP 145), optionally with
// geometry_msgs/AccelStamped of the ground acceleration. See docs/records.md.
//
// Frame (REP 103): x = first horizontal of the station, or the ground acceleration along --azimuth
// (degrees clockwise from north); y = 90 deg counter-clockwise of x seen from above; z = up.
// linear_acceleration = specific force: (a_x, a_y, a_up + 9.80665) m/s^2.
// Stamps: --start-time + record time, to the nanosecond; the bag time of each message equals its
// header stamp, so `rosbag play --clock` replays the record exactly.

#include <CLI/CLI.hpp>
#include <rosbag/bag.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/csv/csv_writer.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "rocking_monitor/motion/sensor_frame.hpp"
#include "rocking_monitor/motion/station.hpp"
#include "rocking_monitor/ros/ground_motion_source.hpp"
#include "command_line.hpp"

namespace fs = std::filesystem;
namespace core = rocking_monitor::core;
namespace rec = rocking_monitor::records;

namespace {

constexpr const char* kProgram = "record_to_bag";

struct BagOptions {
  std::string topic = rec::kDefaultImuTopic;
  std::string accel_topic;  // empty: no AccelStamped
  std::string frame_id = rec::kDefaultFrameId;
  std::int64_t start_ns = rec::kDefaultStartTimeNs;
  double noise_density = rec::kDefaultNoiseDensity;
  rosbag::compression::CompressionType compression = rosbag::compression::LZ4;
};

struct BagStats {
  std::size_t messages = 0;
  std::uintmax_t bytes = 0;
};

/// Writes the bag to "<out>.partial" and renames it at the end, so a failure never leaves a
/// truncated bag under the final name.
BagStats write_bag(const core::SensorFrameMotion& m, const std::string& out, const BagOptions& o) {
  if (m.size() == 0) throw std::runtime_error(out + ": nothing to write (no samples)");
  const std::int64_t first = o.start_ns + m.time_ns(0);
  const std::int64_t last = o.start_ns + m.time_ns(m.size() - 1);
  if (first <= 0) throw std::invalid_argument("--start-time: the first stamp would be <= 0 s (record starts at t0 = " + std::to_string(m.t0) + " s)");
  if (last / 1'000'000'000LL > 4294967295LL) throw std::invalid_argument("--start-time: the last stamp is beyond the range of ros::Time");
  const double variance = rec::accel_variance(o.noise_density, m.dt);
  const std::string tmp = out + ".partial";
  BagStats stats;
  try {
    rosbag::Bag bag;
    bag.open(tmp, rosbag::bagmode::Write);
    bag.setCompression(o.compression);
    for (std::size_t i = 0; i < m.size(); ++i) {
      const core::AccelerometerSample s = m.sample(i);
      ros::Time stamp;
      stamp.fromNSec(static_cast<std::uint64_t>(o.start_ns + s.time_ns));
      bag.write(o.topic, stamp, rec::make_imu_message(s, stamp, o.frame_id, variance));
      ++stats.messages;
      if (!o.accel_topic.empty()) {
        bag.write(o.accel_topic, stamp, rec::make_accel_message(s, stamp, o.frame_id));
        ++stats.messages;
      }
    }
    bag.close();
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, out);
  stats.bytes = fs::file_size(out);
  return stats;
}

void print_notes(const core::SensorFrameMotion& m, const std::string& prefix = "") {
  for (const std::string& n : m.notes) std::cerr << kProgram << ": note: " << prefix << n << "\n";
}

void write_csv(const core::SensorFrameMotion& m, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing (--csv-out)");
  out << "# ground acceleration on the sensor axes (gravity excluded), m/s^2; " << rec::describe(m) << "\n";
  out << "time_s,x_mps2,y_mps2,z_mps2\n";
  char line[160];
  for (std::size_t i = 0; i < m.size(); ++i) {
    std::snprintf(line, sizeof line, "%.9f,%.17g,%.17g,%.17g\n", static_cast<double>(m.time_ns(i)) * 1e-9, m.ground[0][i],
                  m.ground[1][i], m.ground[2][i]);
    out << line;
  }
  if (!out) throw std::runtime_error(path + ": write failed (--csv-out)");
}

int list_mode(const std::string& dir) {
  const core::StationListing l = core::list_stations(dir);
  std::printf("# %zu stations in %s (%s)\n# id | H | V | station | files\n", l.stations.size(), dir.c_str(),
              l.source == core::StationSource::Manifest ? "MANIFEST.csv" : "grouped by file name");
  for (const core::StationInfo& s : l.stations) {
    std::string files;
    for (const auto* list : {&s.horizontals, &s.verticals}) {
      for (const core::StationComponent& c : *list) files += (files.empty() ? "" : " ") + fs::path(c.file).filename().string() + "[" + c.label + "]";
    }
    std::printf("%s | %zu | %zu | %s | %s\n", s.id.c_str(), s.horizontals.size(), s.verticals.size(), s.station.c_str(), files.c_str());
  }
  return 0;
}

int all_mode(const rec::SourceSpec& base, const std::string& out_dir, std::size_t min_components, const BagOptions& bo, bool quiet) {
  const auto t_start = std::chrono::steady_clock::now();
  const core::StationListing l = core::list_stations(base.records_dir);
  fs::create_directories(out_dir);
  const std::string index_path = (fs::path(out_dir) / "index.csv").string();
  std::ofstream index(index_path);
  if (!index) throw std::runtime_error(index_path + ": cannot open for writing");
  index << "bag,station_id,event,station,samples,rate_hz,duration_s,x_azimuth_deg,x,y,z,notes\n";
  core::csv::Writer index_row(index);
  std::size_t bags = 0;
  std::size_t skipped = 0;
  std::size_t failed = 0;
  std::size_t messages = 0;
  std::uintmax_t bytes = 0;
  for (const core::StationInfo& s : l.stations) {
    if (s.component_count() < min_components) {
      ++skipped;
      continue;
    }
    const std::string bag_name = s.id.substr(0, s.id.find('/')) + "__" + s.id.substr(s.id.find('/') + 1) + ".bag";
    const std::string out = (fs::path(out_dir) / bag_name).string();
    try {
      const core::StationRecord r = core::load_station(s, base.read);
      const core::SensorFrameMotion m = core::to_sensor_frame(r, base.frame);
      const BagStats st = write_bag(m, out, bo);
      ++bags;
      messages += st.messages;
      bytes += st.bytes;
      std::string notes;
      for (const std::string& n : m.notes) notes += (notes.empty() ? "" : " | ") + n;
      index_row.text(bag_name).text(s.id).text(s.event).text(s.station).value(std::to_string(m.size()));
      index_row.number("%.6g", 1.0 / m.dt).number("%.6g", m.duration());
      index_row.value(m.x_azimuth_deg ? core::format_azimuth_label(*m.x_azimuth_deg) : std::string());
      index_row.text(m.source[0]).text(m.source[1]).text(m.source[2]).text(notes);
      index_row.end_row();
      if (!quiet) {
        std::printf("%s: %s\n", bag_name.c_str(), rec::describe(m).c_str());
        print_notes(m, bag_name + ": ");
      }
    } catch (const std::exception& e) {
      ++failed;
      std::cerr << kProgram << ": error: " << s.id << ": " << e.what() << "\n";
    }
  }
  index.close();
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  std::printf("wrote %zu bags (%zu messages, %.1f MB) and index.csv to %s in %.1f s; %zu stations with fewer than %zu components "
              "skipped, %zu failed\n",
              bags, messages, static_cast<double>(bytes) / 1e6, out_dir.c_str(), secs, skipped, min_components, failed);
  return failed == 0 ? 0 : 2;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "record_to_bag: convert a strong-motion record, a station of a records directory or a synthetic spec into a rosbag of "
      "sensor_msgs/Imu (REP 145: m/s^2, specific force with +9.80665 on z, no orientation, no gyro). Frame: x = first "
      "horizontal or --azimuth, y = 90 deg counter-clockwise of x seen from above, z = up."};
  std::vector<std::string> files;
  std::string records_dir = rec::default_records_dir();
  std::string station, synthetic, out, out_dir, units_text, csv_out;
  std::string length_text = "pad";
  std::string compression_text = "lz4";
  std::string start_text = "1000000000";
  std::optional<double> azimuth;
  double scale = 1.0;
  std::size_t min_components = 2;
  bool list = false;
  bool all = false;
  bool quiet = false;
  BagOptions bo;

  auto* src = app.add_option_group("source", "exactly one of these");
  src->add_option("--file", files,
                  "Record file(s) forming one station, up to 3 (--file h1 --file h2 --file up): PEER .AT2, SCEC .bbp (3 components), "
                  "USGS .smc, CSV 'time_s,accel[,accel_v]'");
  src->add_option("--station", station, "Station of --records-dir: id (see --list), name, file name or a unique part of it");
  src->add_option("--synthetic", synthetic, "Synthetic-motion YAML spec (bags/synthetic_*.yaml; format in docs/records.md)");
  src->add_flag("--list", list, "List the stations of --records-dir and exit");
  src->add_flag("--all", all, "One bag per station of --records-dir with >= --min-components components, into --out-dir, plus index.csv");
  src->require_option(1);
  app.add_option("--records-dir", records_dir,
                 "Records directory (MANIFEST.csv, or files grouped by name); default: the build's ROCKING_RECORDS_DIR (" +
                     records_dir + ")");
  app.add_option("-o,--out", out, "Output bag (single source)");
  app.add_option("--out-dir", out_dir, "Output directory (--all)");
  app.add_option("--min-components", min_components, "--all: skip stations with fewer components (default 2)")
      ->check(CLI::Range(1, 3));
  app.add_option("--azimuth", azimuth,
                 "Azimuth of the sensor x axis, degrees clockwise from north (needs two horizontals); default: x = first horizontal "
                 "as recorded (ordered so that the second is 90 deg to its left, e.g. E then N)");
  app.add_option("--units", units_text, "Units of CSV records: g | m/s2 | cm/s2 (default m/s2)")
      ->check(CLI::IsMember({"g", "m/s2", "cm/s2"}));
  rec::SourceSpec spec;
  rocking_monitor::tools::add_miniseed_options(app, spec.read);
  app.add_option("--scale", scale, "Multiply the ground acceleration (not gravity) by S (default 1)");
  app.add_option("--length-mismatch", length_text,
                 "Components of unequal length: pad (zeros = ground at rest, default) | truncate | error; changes are reported")
      ->check(CLI::IsMember({"pad", "truncate", "error"}));
  app.add_option("--topic", bo.topic, "Imu topic (default /ground/imu)");
  app.add_option("--accel-topic", bo.accel_topic, "Also write geometry_msgs/AccelStamped of the ground acceleration (gravity excluded) here; default: off");
  app.add_option("--frame-id", bo.frame_id, "header.frame_id (default accelerometer)");
  app.add_option("--start-time", start_text,
                 "Stamp of record time 0, s since the epoch, up to 9 decimals (default 1000000000 = 2001-09-09T01:46:40Z)");
  app.add_option("--noise-density", bo.noise_density,
                 "Accelerometer noise density, (m/s^2)/sqrt(Hz), for linear_acceleration_covariance = n^2 fs/2 on the diagonal "
                 "(default 2.5e-4 = 25 ug/sqrt(Hz)); no noise is added to the data")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--compression", compression_text, "Bag compression: none | lz4 (default) | bz2")
      ->check(CLI::IsMember({"none", "lz4", "bz2"}));
  app.add_option("--csv-out", csv_out, "Also write the ground acceleration on the sensor axes as CSV (time_s,x,y,z in m/s^2)");
  app.add_flag("-q,--quiet", quiet, "Print only errors and notes");
  if (const auto status = rocking_monitor::tools::parse_command_line(app, argc, argv, kProgram)) return *status;

  try {
    spec.files = files;
    spec.station = station;
    spec.records_dir = records_dir;
    spec.synthetic = synthetic;
    if (units_text == "g") spec.read.csv_units = core::AccelUnits::G;
    if (units_text == "cm/s2") spec.read.csv_units = core::AccelUnits::CentimetersPerSecond2;
    rocking_monitor::tools::miniseed_options_given(spec.read);  // checks the azimuth
    spec.frame.azimuth_deg = azimuth;
    if (azimuth && !std::isfinite(*azimuth)) throw std::invalid_argument("--azimuth: must be finite");
    if (!std::isfinite(scale)) throw std::invalid_argument("--scale: must be finite");
    spec.frame.scale = scale;
    spec.frame.length_mismatch = core::parse_length_mismatch(length_text);
    try {
      bo.start_ns = rec::parse_time_ns(start_text);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--start-time: ") + e.what());
    }
    if (compression_text == "none") bo.compression = rosbag::compression::Uncompressed;
    if (compression_text == "bz2") bo.compression = rosbag::compression::BZ2;
    if (bo.topic.empty() || bo.topic == bo.accel_topic) throw std::invalid_argument("--topic: must be non-empty and differ from --accel-topic");
    if (bo.frame_id.empty()) throw std::invalid_argument("--frame-id: must not be empty");

    if ((list || all || !station.empty()) && records_dir.empty()) {  // only when built without a default
      throw std::invalid_argument(std::string(list ? "--list" : all ? "--all" : "--station") + " needs --records-dir");
    }
    if (list) return list_mode(records_dir);
    if (all) {
      if (out_dir.empty()) throw std::invalid_argument("--all needs --out-dir");
      if (!out.empty() || !csv_out.empty()) throw std::invalid_argument("--all writes to --out-dir; --out and --csv-out are for one source");
      return all_mode(spec, out_dir, min_components, bo, quiet);
    }
    if (out.empty()) throw std::invalid_argument("--out: required (the bag to write)");
    if (!out_dir.empty()) throw std::invalid_argument("--out-dir is for --all; use --out");

    const core::SensorFrameMotion m = rec::load_ground_motion(spec);
    if (!csv_out.empty()) write_csv(m, csv_out);
    const BagStats st = write_bag(m, out, bo);
    print_notes(m);
    if (!quiet) {
      std::printf("wrote %s: %zu messages, %.3f MB; %s\n", out.c_str(), st.messages, static_cast<double>(st.bytes) / 1e6,
                  rec::describe(m).c_str());
    }
    return 0;
  } catch (const std::exception& e) {
    std::string what = e.what();
    for (char& c : what) c = c == '\n' ? ' ' : c;  // one line, whatever the source of the message
    std::cerr << kProgram << ": error: " << what << "\n";
    return 2;
  }
}
