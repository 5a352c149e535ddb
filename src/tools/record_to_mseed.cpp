// record_to_mseed: a strong-motion record (a station's two horizontals and vertical, any format the
// record reader takes) -> miniSEED 2 as a strong-motion recorder would write it: int32 counts
// through a gain, steim2 (default), three channels interleaved in the order a recorder sends them
// (by the end time of each record). Optionally also the dequantised samples, in the station frame
// exactly as seedlink_bridge computes them, as table records (time_s,accel m/s^2) for rocking_sim.
//
// Channels: --orientation NE writes <band>N / <band>E / <band>Z (the record rotated to north and
// east); --orientation 12 writes <band>1 / <band>2 / <band>Z with 1 along --azimuth (default: the
// first horizontal as recorded) and 2 at 90 deg clockwise of it (SEED convention).

// Thin command-line layer: the flags (record_to_mseed_options.*) parsed, then the one job
// (record_to_mseed_run.cpp).

#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

#include "command_line.hpp"
#include "record_to_mseed_options.hpp"

namespace r2m = rocking_monitor::tools::record_to_mseed;

int main(int argc, char** argv) {
  CLI::App app{
      "record_to_mseed: write a strong-motion record (two horizontals and a vertical) as miniSEED 2 records of int32 counts, "
      "as a strong-motion recorder streams them over SeedLink (three channels interleaved by record end time)."};
  r2m::Options options;
  r2m::add_options(app, options);
  if (const auto status = rocking_monitor::tools::parse_command_line(app, argc, argv, r2m::kProgram)) return *status;

  try {
    r2m::run(options);
    return 0;
  } catch (const std::exception& e) {
    std::string what = e.what();
    for (char& c : what) c = c == '\n' ? ' ' : c;
    std::cerr << r2m::kProgram << ": error: " << what << "\n";
    return 2;
  }
}
