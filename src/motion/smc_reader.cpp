// USGS SMC V2 records: text header, fixed-width integer and real header blocks (8 x 10 and 5 x 15
// columns), then the acceleration in cm/s^2 in 8 columns of 10.
#include "record_reader_internal.hpp"

#include <algorithm>
#include <cctype>
#include <string_view>
#include <utility>

namespace rocking_monitor::core::record_io {

namespace {

// ------------------------------------------------------------------ USGS SMC V2

constexpr long long kSmcMissingInt = -32768;

/// Splits a fixed-width line into `count` fields of `width` characters. Returns false when the
/// line is longer than count*width (ignoring trailing blanks).
bool fixed_fields(std::string_view line, std::size_t width, std::size_t count, std::vector<std::string_view>& out) {
  std::size_t len = line.size();
  while (len > 0 && is_space(line[len - 1])) --len;
  line = line.substr(0, len);
  out.clear();
  if (len > width * count) return false;
  for (std::size_t p = 0; p < len; p += width) out.push_back(trim(line.substr(p, width)));
  return true;
}

}  // namespace

std::vector<Component> read_smc(const std::string& path, std::string_view data) {
  const std::vector<Line> lines = split_lines(data);
  if (lines.empty()) fail(path, 0, "empty file");
  const std::string l1 = upper(trim(lines[0].text));
  if (l1.empty() || l1[0] != '2' || l1.find("CORRECTED ACCELEROGRAM") == std::string::npos ||
      l1.find("UNCORRECTED") != std::string::npos) {
    fail(path, 1,
         "unsupported SMC file type " + in_quotes(trim(lines[0].text)) + " (only '2 CORRECTED ACCELEROGRAM' is supported)");
  }
  constexpr std::size_t kText = 11, kIntLines = 6, kRealLines = 10;
  constexpr std::size_t kHeader = kText + kIntLines + kRealLines;
  if (lines.size() < kHeader) {
    fail(path, lines.size(),
         "bad header: an SMC file needs 27 header lines (11 text, 6 integer, 10 real), found " +
             std::to_string(lines.size()));
  }

  std::vector<std::string_view> f;
  std::vector<long long> ints;
  for (std::size_t k = 0; k < kIntLines; ++k) {
    const Line& ln = lines[kText + k];
    if (!fixed_fields(ln.text, 10, 8, f) || f.size() != 8) {
      fail(path, ln.number, "bad header: expected 8 integers in 10-character fields, found " + in_quotes(trim(ln.text)));
    }
    for (std::size_t j = 0; j < 8; ++j) {
      long long v = 0;
      if (!parse_integer(f[j], v)) {
        fail(path, ln.number, "bad header: integer field " + std::to_string(k * 8 + j + 1) + " is " + in_quotes(f[j]));
      }
      ints.push_back(v);
    }
  }
  std::vector<double> reals;
  for (std::size_t k = 0; k < kRealLines; ++k) {
    const Line& ln = lines[kText + kIntLines + k];
    if (!fixed_fields(ln.text, 15, 5, f) || f.size() != 5) {
      fail(path, ln.number, "bad header: expected 5 reals in 15-character fields, found " + in_quotes(trim(ln.text)));
    }
    for (std::size_t j = 0; j < 5; ++j) {
      double v = 0.0;
      if (parse_number(f[j], v) != NumStatus::Ok) {
        fail(path, ln.number, "bad header: real field " + std::to_string(k * 5 + j + 1) + " is " + in_quotes(f[j]));
      }
      reals.push_back(v);
    }
  }
  const long long n_comments = ints[15];  // integer #16
  const long long npts = ints[16];        // integer #17
  const double sps = reals[1];            // real #2
  const std::size_t int16_line = lines[kText + 1].number;
  const std::size_t int17_line = lines[kText + 2].number;
  const std::size_t real2_line = lines[kText + kIntLines].number;
  if (n_comments == kSmcMissingInt || n_comments < 0) {
    fail(path, int16_line, "bad header: missing number of comment lines (integer #16)");
  }
  if (npts == kSmcMissingInt) fail(path, int17_line, "bad header: missing NPTS (integer #17)");
  if (npts < 0) fail(path, int17_line, "bad header: negative NPTS " + std::to_string(npts));
  if (npts == 0) fail(path, int17_line, "empty data: NPTS = 0");
  if (sps >= 1e38) fail(path, real2_line, "bad header: missing sampling rate (real #2)");
  if (!(sps > 0.0)) fail(path, real2_line, "non-positive sampling rate (real #2) " + std::to_string(sps));

  Component c;
  c.file = path;
  c.dt = 1.0 / sps;
  c.t0 = 0.0;
  // line 4: "     1989  10  18    0004 Loma Prieta, CA": the event follows the date/time numbers
  {
    std::string_view s = lines[3].text;
    std::size_t i = 0;
    while (true) {
      while (i < s.size() && is_space(s[i])) ++i;
      std::size_t j = i;
      while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
      if (j == i || (j < s.size() && !is_space(s[j]))) break;
      i = j;
    }
    c.event = std::string(trim(s.substr(std::min(i, s.size()))));
  }
  // line 6: "station = <name> component= <azimuth|up>"
  {
    const std::string_view s = lines[5].text;
    const std::string l = lower(s);
    const std::size_t st = l.find("station");
    const std::size_t co = l.find("component");
    if (co != std::string::npos) {
      std::size_t eq = l.find('=', co);
      if (eq != std::string::npos) c.label = std::string(trim(s.substr(eq + 1)));
      if (st != std::string::npos && st < co) {
        const std::size_t seq = l.find('=', st);
        if (seq != std::string::npos && seq < co) c.station = std::string(trim(s.substr(seq + 1, co - seq - 1)));
      }
    }
  }
  c.vertical = label_is_vertical(c.label);
  const double scale = label_is_positive_down(c.label) ? -0.01 : 0.01;  // cm/s^2 -> m/s^2, positive up

  // comment lines
  std::size_t li = kHeader;
  for (long long k = 0; k < n_comments; ++k, ++li) {
    if (li >= lines.size()) {
      fail(path, lines.back().number,
           "file ends inside the comment block (integer #16 says " + std::to_string(n_comments) + " comment lines)");
    }
    const std::string_view t = lines[li].text;
    if (t.empty() || t[0] != '|') {
      fail(path, lines[li].number,
           "expected comment line " + std::to_string(k + 1) + " of " + std::to_string(n_comments) +
               " starting with '|', found " + in_quotes(trim(t)));
    }
  }

  // data: 8 values per line in 10-character fields (neighbouring values may touch)
  const auto want = static_cast<std::size_t>(npts);
  c.accel.reserve(std::min<std::size_t>(want, data.size() / 8 + 1));
  std::size_t last_data_line = li > 0 ? lines[li - 1].number : 1;
  // A data line with fewer than 8 values, or a blank line, is only allowed at the end.
  std::size_t short_line = 0;
  std::string short_problem;
  for (; li < lines.size() && c.accel.size() < want; ++li) {
    const Line& ln = lines[li];
    if (!fixed_fields(ln.text, 10, 8, f)) {
      fail(path, ln.number, "data line longer than 8 fields of 10 characters: " + in_quotes(trim(ln.text)));
    }
    if (f.empty()) {  // blank line: fine only at the end of the file
      if (short_line == 0) {
        short_line = ln.number;
        short_problem = "blank line inside the data";
      }
      continue;
    }
    if (short_line != 0) fail(path, short_line, short_problem);
    if (!ln.text.empty() && ln.text[0] == '|') {
      fail(path, ln.number, "unexpected comment line in the data (integer #16 says " + std::to_string(n_comments) +
                                " comment lines)");
    }
    for (std::size_t j = 0; j < f.size() && c.accel.size() < want; ++j) {
      if (f[j].empty()) {
        fail(path, ln.number, "empty 10-character field " + std::to_string(j + 1) + " in the data");
      }
      c.accel.push_back(scaled_or_fail(number_or_fail(f[j], path, ln.number), scale, path, ln.number));
    }
    last_data_line = ln.number;
    if (f.size() < 8 && c.accel.size() < want) {
      short_line = ln.number;
      short_problem = "short data line (" + std::to_string(f.size()) + " of 8 values) before the end of the data";
    }
  }
  return npts_checked(std::move(c), want, path, last_data_line);
}

}  // namespace rocking_monitor::core::record_io
