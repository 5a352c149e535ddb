#pragma once
// record_to_mseed's command line: every flag's value in one struct, the table that declares them, and
// the one job they run (src/tools/record_to_mseed_run.cpp).

#include <CLI/CLI.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace rocking_monitor::tools::record_to_mseed {

constexpr const char* kProgram = "record_to_mseed";

/// Every flag's value as parsed; the defaults are those --help states.
struct Options {
  std::vector<std::string> files;
  std::string out, table_out, network = "XX", station = "REC", location, band = "HN", orientation = "NE",
      encoding_text = "steim2";
  std::string start_text = "1000000000";
  std::optional<double> gain, azimuth;
  int record_length = 512;
  std::size_t max_samples = 0;
  bool quiet = false;
};

/// Declares every flag on `app`, bound to `o`, in --help's order.
void add_options(CLI::App& app, Options& o);

/// The record files -> the miniSEED file (and --table-out's tables), the summary line unless --quiet.
/// Throws std::exception naming the flag or file at fault.
void run(const Options& o);

}  // namespace rocking_monitor::tools::record_to_mseed
