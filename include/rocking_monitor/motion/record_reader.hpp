#pragma once

#include <optional>
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

enum class RecordFormat { Auto, PeerAt2, Bbp, UsgsSmc, Csv, MiniSeed, CosmosV2, Knet };

/// Units of plain CSV/whitespace files (the other formats carry their own units).
enum class AccelUnits { MetersPerSecond2, G, CentimetersPerSecond2 };

struct ReadOptions {
  RecordFormat format = RecordFormat::Auto;
  AccelUnits csv_units = AccelUnits::MetersPerSecond2;
  /// miniSEED only (the text formats carry their own units): sensitivity of every channel, counts
  /// per m/s^2 (a sample is divided by it). Float data already in m/s^2: 1. Unset: from the channel
  /// table; neither: an error naming the channel (never guessed).
  std::optional<double> gain_counts_per_mps2;
  /// miniSEED only: azimuth of the sensor's first horizontal (channel N or 1), degrees clockwise
  /// from north; the second (E or 2) is 90 deg clockwise of it. Unset: N = 0 and E = 90 as the SEED
  /// codes say, 1/2 from the channel table, else an error (never guessed).
  std::optional<double> sensor_azimuth_deg;
  /// miniSEED only: a channel table (CSV: network,station,location,channel,azimuth_deg,
  /// gain_counts_per_mps2; docs/records.md). Empty: `CHANNELS.csv` next to the record, if it exists.
  /// Values given above win over the table's.
  std::string channel_table;
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
///  - miniSEED 2 (libmseed; steim1/2, int16/32, float32/64): one component per accelerometer
///    channel (HN?, HL?, HG?, EN?, BN?, ...; Z positive up), counts / gain -> m/s^2; a gap, overlap
///    or rate change inside a channel, or channels of different rates or start samples, is an error
///    naming the channel, the time and the record. Errors name "<file>: record <n> at byte <offset>".
///  - COSMOS V2 (corrected acceleration): one component per channel block, units from the data
///    header line, values in the Fortran format it gives.
///  - K-NET / KiK-net ASCII: one component (counts x scale factor, gal -> m/s^2, mean removed).
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
