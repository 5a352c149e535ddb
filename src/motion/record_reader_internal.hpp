#pragma once

// Private to the record readers (src/motion/*_reader.cpp, record_*.cpp): what the formats share.
// Not installed and not part of the public API (include/rocking_monitor/motion/record_reader.hpp).

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rocking_monitor/motion/record_reader.hpp"

namespace rocking_monitor::core::record_io {

// ------------------------------------------------------------------ errors (record_text.cpp)

/// Arbitrary file text made safe for a one-line message (control/non-ASCII bytes escaped, long
/// text shortened).
std::string printable(std::string_view s, std::size_t max_len = 60);
/// printable(s) in single quotes.
std::string in_quotes(std::string_view s);
/// Throws RecordError "<path>:<line>: <problem>" (line == 0: "<path>: <problem>").
[[noreturn]] void fail(const std::string& path, std::size_t line, const std::string& problem);

// ------------------------------------------------------------------ files and lines (record_text.cpp)

std::string read_whole_file(const std::string& path);
/// At most max_bytes of the file; *whole says whether that was all of it.
std::string read_file_head(const std::string& path, std::size_t max_bytes, bool* whole);

struct Line {
  std::string_view text;  ///< without the line terminator
  std::size_t number;     ///< 1-based
};
/// Splits on LF, CRLF or a lone CR. A leading UTF-8 BOM is skipped.
std::vector<Line> split_lines(std::string_view data);

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }
std::string_view trim(std::string_view s);
bool is_blank(std::string_view s);
std::string upper(std::string_view s);
std::string lower(std::string_view s);

/// Calls f(token) for each white-space separated token of the line.
template <typename F>
void for_each_ws_token(std::string_view line, F&& f) {
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (i < n) {
    while (i < n && is_space(line[i])) ++i;
    if (i >= n) break;
    std::size_t j = i;
    while (j < n && !is_space(line[j])) ++j;
    f(line.substr(i, j - i));
    i = j;
  }
}
std::vector<std::string_view> ws_tokens(std::string_view line);
/// Numeric table row: tokens separated by one comma (spaces around allowed) or by white space.
bool csv_tokens(std::string_view line, std::vector<std::string_view>& out, std::size_t* bad_column);
std::string file_extension_lower(const std::string& path);
std::string file_stem(const std::string& path);

/// The one component of an AT2/SMC file once it holds `want` (NPTS) values; fewer is an error
/// naming the last data line.
std::vector<Component> npts_checked(Component c, std::size_t want, const std::string& path,
                                    std::size_t last_data_line);

// ------------------------------------------------------------------ numbers (record_numbers.cpp)

enum class NumStatus { Ok, NonNumeric, NonFinite };
bool is_nonfinite_word(std::string_view t);
NumStatus parse_number(std::string_view tok, double& out);
/// The number, or RecordError naming path, line and the token.
double number_or_fail(std::string_view tok, const std::string& path, std::size_t line);
/// value * scale (a unit conversion to m/s^2), or RecordError naming path and line when the product
/// overflows to infinity although the value itself was finite (1e308 g, say).
double scaled_or_fail(double value, double scale, const std::string& path, std::size_t line);
bool is_number(std::string_view tok);
bool parse_integer(std::string_view tok, long long& out);
/// One unit in the last printed digit of a number token (its rounding allowance).
double printed_resolution(std::string_view tok);

// ------------------------------------------------------------------ time columns (record_time_columns.cpp)

struct TimeSample {
  double t;
  double res;  // rounding allowance of the printed value
  std::size_t line;
};
/// Checks that the time column is uniform and returns dt.
double check_uniform_time(const std::string& path, const std::vector<TimeSample>& ts);

// ------------------------------------------------------------------ labels (record_reader.cpp)

/// Upper case, trimmed, without a leading '-' / '_'.
std::string normalised_label(const std::string& label);

// ------------------------------------------------------------------ Fortran fixed-width data (fortran_format.cpp)

/// A Fortran edit descriptor for numbers as COSMOS headers give it: "(8F10.5)", "(5E16.7)",
/// "(10I8)", "(1P6E13.5)": `per_line` fields of `width` characters each.
struct FortranFormat {
  std::size_t per_line = 0;
  std::size_t width = 0;
  char kind = 'F';  ///< F, E, D, G or I
};
/// Parses the text between and including the parentheses; false when it is not one of the forms above.
bool parse_fortran_format(std::string_view text, FortranFormat& out);
/// Reads `count` numbers laid out in `format` from lines[first...]: fields are cut by column, so
/// touching fields ("-0.12E+01-0.23E+01") are two numbers; trailing blanks are ignored; a blank or
/// malformed field, a line longer than the format allows or too few lines is an error naming the line.
/// Returns the index of the line after the last one used.
std::size_t read_fortran_values(const std::vector<Line>& lines, std::size_t first, std::size_t count,
                                const FortranFormat& format, const std::string& path, std::vector<double>& out);

// ------------------------------------------------------------------ SEED channel codes (seed_channel.cpp)

/// What a SEED channel code ("HNE", "HN1", "ENZ") says about a component.
struct SeedChannel {
  bool vertical = false;     ///< Z or 3: positive up (SEED dip -90)
  int horizontal_index = 0;  ///< 0: N or 1 (the sensor's first horizontal), 1: E or 2
  bool geographic = false;   ///< N/E: the code itself says north/east
};
/// Classifies a channel code; throws RecordError "<where>: ..." when it is not a 3-character
/// accelerometer code (instrument N, or L/G as older strong-motion networks used) with orientation
/// Z, N, E, 1, 2 or 3.
SeedChannel classify_seed_channel(const std::string& channel, const std::string& where);

// ------------------------------------------------------------------ channel tables (channel_table.cpp)

/// One row of a channel table (CSV: network,station,location,channel,azimuth_deg,gain_counts_per_mps2).
struct ChannelTableRow {
  std::string network, station, location, channel;
  std::optional<double> azimuth_deg;           ///< degrees clockwise from north
  std::optional<double> gain_counts_per_mps2;  ///< counts per m/s^2
  std::size_t line = 0;
};
struct ChannelTable {
  std::string path;  ///< empty: no table
  std::vector<ChannelTableRow> rows;
  /// The row of a channel ("--" and "" are the same empty location), or nullptr.
  const ChannelTableRow* find(const std::string& net, const std::string& sta, const std::string& loc,
                              const std::string& cha) const;
};
/// Reads a channel table; errors name the table's file and line.
ChannelTable read_channel_table(const std::string& path);
/// options.channel_table, else CHANNELS.csv in the record's directory when it exists, else no table.
ChannelTable channel_table_for(const std::string& record_path, const ReadOptions& options);

// ------------------------------------------------------------------ one reader per format

std::vector<Component> read_at2(const std::string& path, std::string_view data);
std::vector<Component> read_bbp(const std::string& path, std::string_view data);
std::vector<Component> read_smc(const std::string& path, std::string_view data);
std::vector<Component> read_csv(const std::string& path, std::string_view data, AccelUnits units);
std::vector<Component> read_miniseed(const std::string& path, const ReadOptions& options);  // miniseed_reader.cpp
std::vector<Component> read_cosmos(const std::string& path, std::string_view data);          // cosmos_reader.cpp
std::vector<Component> read_knet(const std::string& path, std::string_view data);            // knet_reader.cpp
/// True when the bytes start with a miniSEED 2 record (libmseed's ms_detect).
bool looks_like_miniseed(std::string_view head);
RecordFormat detect_from_content(std::string_view head, bool whole_file, const std::string& path);

}  // namespace rocking_monitor::core::record_io
