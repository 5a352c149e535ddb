#pragma once

// One voice for every executable's command-line errors: "<program>: error: <what>" on one line and
// exit status 2, the same as the tools' own input errors; --help still prints CLI11's help.

#include <CLI/CLI.hpp>

#include <cmath>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rocking_monitor/motion/record_reader.hpp"

namespace rocking_monitor::tools {

/// Parses the command line. Returns the status main() should exit with (help printed: 0; a parse
/// error: 2, after one prefixed line on stderr), or nothing when the program should go on.
inline std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv, const std::string& program) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --help-all, --version: CLI11 prints them
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // CLI11 checks required options before unknown ones; a mistyped flag is the better first
    // message ("--recrod" rather than "--record is required").
    const std::vector<std::string> unknown = app.remaining();
    std::string what = e.what();
    if (!unknown.empty() && dynamic_cast<const CLI::ExtrasError*>(&e) == nullptr) {
      what = "unknown argument" + std::string(unknown.size() > 1 ? "s" : "") + ":";
      for (const std::string& u : unknown) what += " " + u;
    }
    std::cerr << program << ": error: " << what << " (see " << program << " --help)\n";
    return 2;
  }
  return std::nullopt;
}

/// The miniSEED options of the record tools (--gain, --sensor-azimuth, --channel-table), bound to `read`.
inline void add_miniseed_options(CLI::App& app, core::ReadOptions& read) {
  app.add_option("--gain", read.gain_counts_per_mps2,
                 "miniSEED: sensitivity of every channel, counts per m/s^2 (float data in m/s^2: 1)")
      ->check(CLI::PositiveNumber);
  app.add_option("--sensor-azimuth", read.sensor_azimuth_deg,
                 "miniSEED: azimuth of the sensor's channel N/1, degrees clockwise from north (E/2 is 90 deg "
                 "clockwise of it)");
  app.add_option("--channel-table", read.channel_table,
                 "miniSEED: CSV network,station,location,channel,azimuth_deg,gain_counts_per_mps2 (default: "
                 "CHANNELS.csv beside the record)");
}

/// Whether any of them was given; throws for a non-finite azimuth.
inline bool miniseed_options_given(const core::ReadOptions& read) {
  if (read.sensor_azimuth_deg && !std::isfinite(*read.sensor_azimuth_deg))
    throw std::invalid_argument("--sensor-azimuth: must be finite");
  return read.gain_counts_per_mps2 || read.sensor_azimuth_deg || !read.channel_table.empty();
}

}  // namespace rocking_monitor::tools
