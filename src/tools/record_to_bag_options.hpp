#pragma once
// record_to_bag's command line: every flag's value in one struct, the table that declares them, and the
// flags settled into what the jobs take (the source, the frame, the bag's options).

#include <CLI/CLI.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "record_to_bag_writing.hpp"

namespace rocking_monitor::tools::record_to_bag {

/// Every flag's value as parsed; the defaults are those --help states.
struct Options {
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
  BagOptions bo;        ///< --topic, --accel-topic, --frame-id, --noise-density; settle(): --start-time, --compression
  rec::SourceSpec spec;  ///< the miniSEED options; settle(): the source and its frame
};

/// Declares every flag on `app`, bound to `o`, in --help's order.
void add_options(CLI::App& app, Options& o);

/// The flags checked and settled into o.spec and o.bo; throws std::invalid_argument naming the flag.
void settle(Options& o);

}  // namespace rocking_monitor::tools::record_to_bag
