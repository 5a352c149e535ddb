// record_to_bag's flags: one table in --help's order, and settling them.
#include "record_to_bag_options.hpp"

#include <cmath>
#include <stdexcept>

#include "command_line.hpp"

namespace rocking_monitor::tools::record_to_bag {

void add_options(CLI::App& app, Options& o) {
  auto* src = app.add_option_group("source", "exactly one of these");
  src->add_option("--file", o.files,
                  "Record file(s) forming one station, up to 3 (--file h1 --file h2 --file up): PEER .AT2, SCEC .bbp (3 components), "
                  "USGS .smc, CSV 'time_s,accel[,accel_v]'");
  src->add_option("--station", o.station, "Station of --records-dir: id (see --list), name, file name or a unique part of it");
  src->add_option("--synthetic", o.synthetic, "Synthetic-motion YAML spec (bags/synthetic_*.yaml; format in docs/records.md)");
  src->add_flag("--list", o.list, "List the stations of --records-dir and exit");
  src->add_flag("--all", o.all, "One bag per station of --records-dir with >= --min-components components, into --out-dir, plus index.csv");
  src->require_option(1);
  app.add_option("--records-dir", o.records_dir,
                 "Records directory (MANIFEST.csv, or files grouped by name); default: the build's ROCKING_RECORDS_DIR (" +
                     o.records_dir + ")");
  app.add_option("-o,--out", o.out, "Output bag (single source)");
  app.add_option("--out-dir", o.out_dir, "Output directory (--all)");
  app.add_option("--min-components", o.min_components, "--all: skip stations with fewer components (default 2)")
      ->check(CLI::Range(1, 3));
  app.add_option("--azimuth", o.azimuth,
                 "Azimuth of the sensor x axis, degrees clockwise from north (needs two horizontals); default: x = first horizontal "
                 "as recorded (ordered so that the second is 90 deg to its left, e.g. E then N)");
  app.add_option("--units", o.units_text, "Units of CSV records: g | m/s2 | cm/s2 (default m/s2)")
      ->check(CLI::IsMember({"g", "m/s2", "cm/s2"}));
  rocking_monitor::tools::add_miniseed_options(app, o.spec.read);
  app.add_option("--scale", o.scale, "Multiply the ground acceleration (not gravity) by S (default 1)");
  app.add_option("--length-mismatch", o.length_text,
                 "Components of unequal length: pad (zeros = ground at rest, default) | truncate | error; changes are reported")
      ->check(CLI::IsMember({"pad", "truncate", "error"}));
  app.add_option("--topic", o.bo.topic, "Imu topic (default /ground/imu)");
  app.add_option("--accel-topic", o.bo.accel_topic, "Also write geometry_msgs/AccelStamped of the ground acceleration (gravity excluded) here; default: off");
  app.add_option("--frame-id", o.bo.frame_id, "header.frame_id (default accelerometer)");
  app.add_option("--start-time", o.start_text,
                 "Stamp of record time 0, s since the epoch, up to 9 decimals (default 1000000000 = 2001-09-09T01:46:40Z)");
  app.add_option("--noise-density", o.bo.noise_density,
                 "Accelerometer noise density, (m/s^2)/sqrt(Hz), for linear_acceleration_covariance = n^2 fs/2 on the diagonal "
                 "(default 2.5e-4 = 25 ug/sqrt(Hz)); no noise is added to the data")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--compression", o.compression_text, "Bag compression: none | lz4 (default) | bz2")
      ->check(CLI::IsMember({"none", "lz4", "bz2"}));
  app.add_option("--csv-out", o.csv_out, "Also write the ground acceleration on the sensor axes as CSV (time_s,x,y,z in m/s^2)");
  app.add_flag("-q,--quiet", o.quiet, "Print only errors and notes");
}

void settle(Options& o) {
  o.spec.files = o.files;
  o.spec.station = o.station;
  o.spec.records_dir = o.records_dir;
  o.spec.synthetic = o.synthetic;
  if (o.units_text == "g") o.spec.read.csv_units = core::AccelUnits::G;
  if (o.units_text == "cm/s2") o.spec.read.csv_units = core::AccelUnits::CentimetersPerSecond2;
  rocking_monitor::tools::miniseed_options_given(o.spec.read);  // checks the o.azimuth
  o.spec.frame.azimuth_deg = o.azimuth;
  if (o.azimuth && !std::isfinite(*o.azimuth)) throw std::invalid_argument("--azimuth: must be finite");
  if (!std::isfinite(o.scale)) throw std::invalid_argument("--scale: must be finite");
  o.spec.frame.scale = o.scale;
  o.spec.frame.length_mismatch = core::parse_length_mismatch(o.length_text);
  try {
    o.bo.start_ns = rec::parse_time_ns(o.start_text);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("--start-time: ") + e.what());
  }
  if (o.compression_text == "none") o.bo.compression = rosbag::compression::Uncompressed;
  if (o.compression_text == "bz2") o.bo.compression = rosbag::compression::BZ2;
  if (o.bo.topic.empty() || o.bo.topic == o.bo.accel_topic) throw std::invalid_argument("--topic: must be non-empty and differ from --accel-topic");
  if (o.bo.frame_id.empty()) throw std::invalid_argument("--frame-id: must not be empty");
}

}  // namespace rocking_monitor::tools::record_to_bag
