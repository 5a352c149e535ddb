#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "rocking_monitor/motion/component.hpp"

namespace rocking_monitor::core {

/// Thrown for any unreadable or malformed record. what() is one line: "<file>:<line>: <problem>"
/// (line omitted when the problem is not tied to a line, e.g. a missing file).
class RecordError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class RecordFormat { Auto, PeerAt2, Bbp, UsgsSmc, Csv };

/// Units of plain CSV/whitespace files (the other formats carry their own units).
enum class AccelUnits { MetersPerSecond2, G, CentimetersPerSecond2 };

struct ReadOptions {
  RecordFormat format = RecordFormat::Auto;
  AccelUnits csv_units = AccelUnits::MetersPerSecond2;
};

/// Detects the format from the file's content (first lines), falling back to the extension.
/// Returns RecordFormat::Auto when neither identifies it; throws RecordError if the file cannot be read.
RecordFormat detect_format(const std::string& path);

/// Reads every component a file holds, converted to SI:
///  - PEER .AT2: one component (g -> m/s^2), all header variants, exactly NPTS values.
///  - SCEC BBP 4-column: three components N-S, E-W, U-D (cm/s^2 -> m/s^2).
///  - USGS SMC V2: one component (cm/s^2 -> m/s^2).
///  - CSV/whitespace: rows "time_s accel" or "time_s accel_h accel_v" (one header line allowed);
///    returns the horizontal and, with three columns, the vertical. The time column must be uniform.
/// Throws RecordError naming file and line on any problem; never truncates silently.
std::vector<Component> read_record(const std::string& path, const ReadOptions& options = {});

const char* to_string(RecordFormat format);

/// True when a component label names a vertical channel: UP, DWN, DOWN, U-D, V, Z, ...
/// (case-insensitive, a leading '-' as in PEER file names is ignored).
bool label_is_vertical(const std::string& label);

/// True when the label says the channel is positive downward (PEER "DWN", SMC "down"). Readers
/// multiply such components by -1, so every stored vertical is positive up (label kept as written).
bool label_is_positive_down(const std::string& label);

}  // namespace rocking_monitor::core
