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

constexpr std::size_t kSmcText = 11, kSmcIntLines = 6, kSmcRealLines = 10;
constexpr std::size_t kSmcHeader = kSmcText + kSmcIntLines + kSmcRealLines;

// Line 1 names the file type: only corrected accelerograms (V2) carry acceleration in cm/s^2.
void check_smc_type(const std::string& path, const std::vector<Line>& lines) {
  if (lines.empty()) fail(path, 0, "empty file");
  const std::string l1 = upper(trim(lines[0].text));
  if (l1.empty() || l1[0] != '2' || l1.find("CORRECTED ACCELEROGRAM") == std::string::npos ||
      l1.find("UNCORRECTED") != std::string::npos) {
    fail(path, 1,
         "unsupported SMC file type " + in_quotes(trim(lines[0].text)) + " (only '2 CORRECTED ACCELEROGRAM' is supported)");
  }
  if (lines.size() < kSmcHeader) {
    fail(path, lines.size(),
         "bad header: an SMC file needs 27 header lines (11 text, 6 integer, 10 real), found " +
             std::to_string(lines.size()));
  }
}

// The integer header block: 6 lines of 8 integers in 10-character fields.
std::vector<long long> smc_integers(const std::string& path, const std::vector<Line>& lines) {
  std::vector<std::string_view> f;
  std::vector<long long> ints;
  for (std::size_t k = 0; k < kSmcIntLines; ++k) {
    const Line& ln = lines[kSmcText + k];
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
  return ints;
}

// The real header block: 10 lines of 5 reals in 15-character fields.
std::vector<double> smc_reals(const std::string& path, const std::vector<Line>& lines) {
  std::vector<std::string_view> f;
  std::vector<double> reals;
  for (std::size_t k = 0; k < kSmcRealLines; ++k) {
    const Line& ln = lines[kSmcText + kSmcIntLines + k];
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
  return reals;
}

// What the reader needs of the numeric header, checked.
struct SmcHeader {
  long long n_comments = 0;  // integer #16
  long long npts = 0;        // integer #17
  double sps = 0.0;          // real #2
};

SmcHeader smc_header(const std::string& path, const std::vector<Line>& lines) {
  const std::vector<long long> ints = smc_integers(path, lines);
  const std::vector<double> reals = smc_reals(path, lines);
  SmcHeader h;
  h.n_comments = ints[15];
  h.npts = ints[16];
  h.sps = reals[1];
  const std::size_t int16_line = lines[kSmcText + 1].number;
  const std::size_t int17_line = lines[kSmcText + 2].number;
  const std::size_t real2_line = lines[kSmcText + kSmcIntLines].number;
  if (h.n_comments == kSmcMissingInt || h.n_comments < 0) {
    fail(path, int16_line, "bad header: missing number of comment lines (integer #16)");
  }
  if (h.npts == kSmcMissingInt) fail(path, int17_line, "bad header: missing NPTS (integer #17)");
  if (h.npts < 0) fail(path, int17_line, "bad header: negative NPTS " + std::to_string(h.npts));
  if (h.npts == 0) fail(path, int17_line, "empty data: NPTS = 0");
  if (h.sps >= 1e38) fail(path, real2_line, "bad header: missing sampling rate (real #2)");
  if (!(h.sps > 0.0)) fail(path, real2_line, "non-positive sampling rate (real #2) " + std::to_string(h.sps));
  return h;
}

// line 4: "     1989  10  18    0004 Loma Prieta, CA": the event follows the date/time numbers
std::string smc_event(std::string_view s) {
  std::size_t i = 0;
  while (true) {
    while (i < s.size() && is_space(s[i])) ++i;
    std::size_t j = i;
    while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
    if (j == i || (j < s.size() && !is_space(s[j]))) break;
    i = j;
  }
  return std::string(trim(s.substr(std::min(i, s.size()))));
}

// line 6: "station = <name> component= <azimuth|up>"
void smc_station_and_component(std::string_view s, Component& c) {
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

// The comment block after the header: each line starts with '|'. Returns the first data line's index.
std::size_t skip_smc_comments(const std::string& path, const std::vector<Line>& lines, long long n_comments) {
  std::size_t li = kSmcHeader;
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
  return li;
}

// data from line `li`: 8 values per line in 10-character fields (neighbouring values may touch), up
// to `want` values scaled into c.accel. Returns the last data line's number.
std::size_t read_smc_samples(const std::string& path, const std::vector<Line>& lines, std::size_t li,
                             std::size_t want, long long n_comments, double scale, Component& c) {
  std::vector<std::string_view> f;
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
  return last_data_line;
}

}  // namespace

std::vector<Component> read_smc(const std::string& path, std::string_view data) {
  const std::vector<Line> lines = split_lines(data);
  check_smc_type(path, lines);
  const SmcHeader h = smc_header(path, lines);
  Component c;
  c.file = path;
  c.dt = 1.0 / h.sps;
  c.t0 = 0.0;
  c.event = smc_event(lines[3].text);
  smc_station_and_component(lines[5].text, c);
  c.vertical = label_is_vertical(c.label);
  const double scale = label_is_positive_down(c.label) ? -0.01 : 0.01;  // cm/s^2 -> m/s^2, positive up
  const std::size_t li = skip_smc_comments(path, lines, h.n_comments);
  const auto want = static_cast<std::size_t>(h.npts);
  c.accel.reserve(std::min<std::size_t>(want, data.size() / 8 + 1));
  const std::size_t last_data_line = read_smc_samples(path, lines, li, want, h.n_comments, scale, c);
  return npts_checked(std::move(c), want, path, last_data_line);
}

}  // namespace rocking_monitor::core::record_io
