// record_to_bag: strong-motion record (or station, or synthetic spec) -> rosbag of sensor_msgs/Imu as a
// real accelerometer bolted to the ground publishes them (REP 145), optionally with
// geometry_msgs/AccelStamped of the ground acceleration. See docs/records.md.
//
// Frame (REP 103): x = first horizontal of the station, or the ground acceleration along --azimuth
// (degrees clockwise from north); y = 90 deg counter-clockwise of x seen from above; z = up.
// linear_acceleration = specific force: (a_x, a_y, a_up + 9.80665) m/s^2.
// Stamps: --start-time + record time, to the nanosecond; the bag time of each message equals its
// header stamp, so `rosbag play --clock` replays the record exactly.

// Thin command-line layer: the flags (record_to_bag_options.*) parsed and settled, then one job: --list
// or --all (record_to_bag_directory.cpp) or one source to one bag (here), written by
// record_to_bag_writing.*.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>

#include "command_line.hpp"
#include "record_to_bag_jobs.hpp"
#include "record_to_bag_options.hpp"

namespace r2b = rocking_monitor::tools::record_to_bag;

namespace {

/// --file, --station or --synthetic: one bag (and --csv-out).
int one_source(const r2b::Options& o) {
  if (o.out.empty()) throw std::invalid_argument("--out: required (the bag to write)");
  if (!o.out_dir.empty()) throw std::invalid_argument("--out-dir is for --all; use --out");
  const r2b::core::SensorFrameMotion m = r2b::rec::load_ground_motion(o.spec);
  if (!o.csv_out.empty()) r2b::write_csv(m, o.csv_out);
  const r2b::BagStats st = r2b::write_bag(m, o.out, o.bo);
  r2b::print_notes(m);
  if (!o.quiet) {
    std::printf("wrote %s: %zu messages, %.3f MB; %s\n", o.out.c_str(), st.messages, static_cast<double>(st.bytes) / 1e6,
                r2b::rec::describe(m).c_str());
  }
  return 0;
}

/// The job the source flags choose.
int run(const r2b::Options& o) {
  if ((o.list || o.all || !o.station.empty()) && o.records_dir.empty()) {  // only when built without a default
    throw std::invalid_argument(std::string(o.list ? "--list" : o.all ? "--all" : "--station") + " needs --records-dir");
  }
  if (o.list) return r2b::list_mode(o.records_dir);
  if (o.all) {
    if (o.out_dir.empty()) throw std::invalid_argument("--all needs --out-dir");
    if (!o.out.empty() || !o.csv_out.empty()) throw std::invalid_argument("--all writes to --out-dir; --out and --csv-out are for one source");
    return r2b::all_mode(o.spec, o.out_dir, o.min_components, o.bo, o.quiet);
  }
  return one_source(o);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "record_to_bag: convert a strong-motion record, a station of a records directory or a synthetic spec into a rosbag of "
      "sensor_msgs/Imu (REP 145: m/s^2, specific force with +9.80665 on z, no orientation, no gyro). Frame: x = first "
      "horizontal or --azimuth, y = 90 deg counter-clockwise of x seen from above, z = up."};
  r2b::Options options;
  r2b::add_options(app, options);
  if (const auto status = rocking_monitor::tools::parse_command_line(app, argc, argv, r2b::kProgram)) return *status;

  try {
    r2b::settle(options);
    return run(options);
  } catch (const std::exception& e) {
    std::string what = e.what();
    for (char& c : what) c = c == '\n' ? ' ' : c;  // one line, whatever the source of the message
    std::cerr << r2b::kProgram << ": error: " << what << "\n";
    return 2;
  }
}
