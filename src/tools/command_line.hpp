#pragma once

// One voice for every executable's command-line errors: "<program>: error: <what>" on one line and
// exit status 2, the same as the tools' own input errors; --help still prints CLI11's help.

#include <CLI/CLI.hpp>

#include <iostream>
#include <optional>
#include <string>
#include <vector>

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

}  // namespace rocking_monitor::tools
