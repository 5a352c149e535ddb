// record_to_mseed's flags: one table in --help's order.
#include "record_to_mseed_options.hpp"

namespace rocking_monitor::tools::record_to_mseed {

void add_options(CLI::App& app, Options& o) {
  app.add_option("--file", o.files, "Record files of one station: two horizontals and a vertical (any format rocking_sim reads)")
      ->required();
  app.add_option("-o,--out", o.out, "Output miniSEED file")->required();
  app.add_option("--gain", o.gain, "Counts per m/s^2 (the sensitivity the bridge is given as ~gain), e.g. 427000")->required();
  app.add_option("--network", o.network, "SEED network code, 1-2 characters (default XX)");
  app.add_option("--station", o.station, "SEED station code, 1-5 characters (default REC)");
  app.add_option("--location", o.location, "SEED location code, 0-2 characters (default empty)");
  app.add_option("--band", o.band, "Band and instrument code of the channels (default HN: high rate, accelerometer)");
  app.add_option("--orientation", o.orientation, "NE: channels N, E, Z (rotated to north/east) | 12: channels 1, 2, Z, 1 along --azimuth")
      ->check(CLI::IsMember({"NE", "12"}));
  app.add_option("--azimuth", o.azimuth, "--orientation 12: azimuth of channel 1, degrees clockwise from north (default: the first "
                                       "horizontal as recorded)");
  app.add_option("--start-time", o.start_text, "Data time of the first sample, s since the epoch (default 1000000000)");
  app.add_option("--encoding", o.encoding_text, "steim2 (default) | steim1 | int32")->check(CLI::IsMember({"steim2", "steim1", "int32"}));
  app.add_option("--record-length", o.record_length, "Record length, bytes: 512 (SeedLink's) or 4096 (files), any power of two 256..8192");
  app.add_option("--max-samples", o.max_samples, "At most this many samples per record (0: as many as fit); shorter records = lower latency");
  app.add_option("--table-out", o.table_out,
                 "Also write PREFIX_east.csv, PREFIX_north.csv, PREFIX_up.csv: the dequantised samples in the station frame "
                 "(x east, y north, z up), m/s^2, exactly as seedlink_bridge publishes them");
  app.add_flag("-q,--quiet", o.quiet, "Print only errors");
}

}  // namespace rocking_monitor::tools::record_to_mseed
