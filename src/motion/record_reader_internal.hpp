#pragma once

// Private to the record readers (src/motion/*_reader.cpp, record_*.cpp): what the formats share.
// Not installed and not part of the public API (include/rocking_monitor/motion/record_reader.hpp).

#include <cstddef>
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
std::string quoted(std::string_view s);
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

// ------------------------------------------------------------------ one reader per format

std::vector<Component> read_at2(const std::string& path, std::string_view data);
std::vector<Component> read_bbp(const std::string& path, std::string_view data);
std::vector<Component> read_smc(const std::string& path, std::string_view data);
std::vector<Component> read_csv(const std::string& path, std::string_view data, AccelUnits units);
RecordFormat detect_from_content(std::string_view head, bool whole_file, const std::string& path);

}  // namespace rocking_monitor::core::record_io
