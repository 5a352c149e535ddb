// COSMOS V2 records (COSMOS Strong Motion Data Format v1.20): per channel a text header (its line 1
// says "Corrected acceleration ... with <n> text lines"), "<n> Integer-header values follow on <l>
// lines, Format= (10I8)", "<n> Real-header values follow on <l> lines, Format= (...)", "<n> Comment
// line(s) follow", then data blocks "<npts> acceleration pts, approx <s> secs, units=cm/sec2(04),
// Format=(8F10.5)" (a V2 file may add velocity and displacement blocks: skipped), "End-of-data ...".
// A file holds one channel or several, one after the other.
//  * dt: real header #34 (s), else #62 (ms).
//  * orientation: integer header #54: 1-360 = azimuth of the positive direction (360 = north),
//    400 = up, 500 = down (flipped to positive up like every vertical).
//  * units: the data header's "units=" text (cm/sec2, cm/s/s, m/sec2, mm/sec2, g, gal); anything
//    else is an error, never a guess.
#include <cctype>
#include <cmath>

#include "record_reader_internal.hpp"
#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/motion/station.hpp"

namespace rocking_monitor::core::record_io {

namespace {

constexpr double kCosmosUndefined = -999.0;

/// "<n> <words...> Format= (...)" -> n, the words (upper case) and the format text.
bool split_block_header(std::string_view line, long long& n, std::string& words, std::string& format_text) {
  const std::string_view t = trim(line);
  std::size_t i = 0;
  while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i;
  if (i == 0 || !parse_integer(t.substr(0, i), n)) return false;
  const std::string up = upper(t);
  const std::size_t f = up.find("FORMAT");
  const std::size_t open = up.find('(', f == std::string::npos ? 0 : f);
  const std::size_t close = up.rfind(')');
  if (f == std::string::npos || open == std::string::npos || close == std::string::npos || close < open) return false;
  words = up.substr(i, f - i);
  format_text = std::string(t.substr(open, close - open + 1));
  return true;
}

/// The number before `key` in a header line ("... follow on  10 lines" -> 10), or -1.
long long number_before(const std::string& up, const std::string& key) {
  const std::size_t p = up.find(key);
  if (p == std::string::npos) return -1;
  std::size_t e = p;
  while (e > 0 && is_space(up[e - 1])) --e;
  std::size_t b = e;
  while (b > 0 && std::isdigit(static_cast<unsigned char>(up[b - 1]))) --b;
  long long v = -1;
  if (b == e || !parse_integer(std::string_view(up).substr(b, e - b), v)) return -1;
  return v;
}

/// m/s^2 per unit of the data header's "units=" text; 0 when unknown.
double units_scale(std::string u) {
  std::string s;
  for (char c : u) {
    if (!is_space(c)) s.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  }
  auto any = [&](std::initializer_list<const char*> names) {
    for (const char* n : names) {
      if (s == n) return true;
    }
    return false;
  };
  if (any({"cm/sec2", "cm/sec/sec", "cm/s2", "cm/s/s", "cm/s^2", "cm/sec^2", "cm/sec**2", "gal", "gals"})) return 0.01;
  if (any({"m/sec2", "m/sec/sec", "m/s2", "m/s/s", "m/s^2", "m/sec^2"})) return 1.0;
  if (any({"mm/sec2", "mm/sec/sec", "mm/s2", "mm/s/s", "mm/s^2"})) return 0.001;
  if (any({"g"})) return kGravity;
  return 0.0;
}

bool is_text_header_start(std::string_view line) {
  const std::string up = upper(line);
  return up.find("(FORMAT V") != std::string::npos && up.find("TEXT LINES") != std::string::npos;
}

// ---- a channel's text header at lines[li]: its type (V2 corrected acceleration), the event (line 2)
// and the station (line 5). Advances li past it.
void read_cosmos_text_header(const std::string& path, const std::vector<Line>& lines, std::size_t& li, Component& c) {
  const Line& first = lines[li];
  const std::string up1 = upper(first.text);
  if (!is_text_header_start(first.text)) {
    fail(path, first.number,
         "expected a COSMOS text header line ('... (Format v01.20 with 13 text lines) ...'), found " +
             in_quotes(trim(first.text)));
  }
  const std::string kind = std::string(trim(std::string_view(up1).substr(0, std::min<std::size_t>(25, up1.size()))));
  if (kind.find("CORRECTED ACCELERATION") == std::string::npos || kind.find("UNCORRECTED") != std::string::npos) {
    fail(path, first.number,
         "not a COSMOS V2 corrected acceleration record: data type " +
             in_quotes(trim(first.text.substr(0, std::min<std::size_t>(25, first.text.size())))));
  }
  const long long n_text = number_before(up1, "TEXT LINES");
  if (n_text < 1) fail(path, first.number, "bad header: cannot read the number of text lines");
  if (li + static_cast<std::size_t>(n_text) >= lines.size()) {
    fail(path, lines.back().number, "file ends inside the text header (" + std::to_string(n_text) + " lines)");
  }
  c.file = path;
  if (n_text >= 5) c.station = std::string(trim(lines[li + 4].text));
  if (n_text >= 2) c.event = std::string(trim(lines[li + 1].text));
  li += static_cast<std::size_t>(n_text);
}

// ---- the integer ('I') or real ('F') header at lines[li] into `values`; advances li past it and
// returns its first line's number.
std::size_t read_cosmos_numbers(const std::string& path, const std::vector<Line>& lines, std::size_t& li,
                                const char* what, char want_kind, std::vector<double>& values) {
  if (li >= lines.size()) fail(path, lines.back().number, std::string("file ends before the ") + what + " header");
  const Line& h = lines[li];
  long long n = 0;
  std::string words, ftext;
  FortranFormat ff;
  const std::string key = std::string(what) + "-HEADER VALUES FOLLOW";
  if (!split_block_header(h.text, n, words, ftext) || words.find(key) == std::string::npos) {
    fail(path, h.number,
         std::string("expected '<n> ") + what + "-header values follow on <l> lines, Format= (...)', found " +
             in_quotes(trim(h.text)));
  }
  if (!parse_fortran_format(ftext, ff) || (want_kind == 'I') != (ff.kind == 'I')) {
    fail(path, h.number,
         "bad header: format " + in_quotes(ftext) + " is not a Fortran " + (want_kind == 'I' ? "integer" : "real") +
             " format");
  }
  values.clear();
  li = read_fortran_values(lines, li + 1, static_cast<std::size_t>(n), ff, path, values);
  return h.number;
}

// ---- from the numeric headers: dt (real #34, else #62 in ms) and the orientation (integer #54).
void cosmos_dt_and_orientation(const std::string& path, const std::vector<double>& ints, std::size_t int_line,
                               const std::vector<double>& reals, std::size_t real_line, Component& c) {
  if (ints.size() < 54)
    fail(path, int_line,
         "integer header has " + std::to_string(ints.size()) + " values, COSMOS V2 needs at least 54");
  if (reals.size() < 62)
    fail(path, real_line, "real header has " + std::to_string(reals.size()) + " values, COSMOS V2 needs at least 62");
  double dt = reals[33];
  if (dt == kCosmosUndefined) dt = reals[61] == kCosmosUndefined ? kCosmosUndefined : reals[61] / 1000.0;
  if (!(dt > 0.0)) fail(path, real_line, "no sample interval (real header #34 and #62 undefined or not positive)");
  c.dt = dt;
  const long long orient = static_cast<long long>(ints[53]);
  if (orient >= 1 && orient <= 360) {
    c.label = format_azimuth_label(orient == 360 ? 0.0 : static_cast<double>(orient));
  } else if (orient == 400) {
    c.label = "UP";
  } else if (orient == 500) {
    c.label = "DOWN";
  } else {
    fail(path, int_line,
         "integer header #54 (channel orientation) is " + std::to_string(orient) +
             ": expected 1-360 (azimuth), 400 (up) or 500 (down)");
  }
  c.vertical = label_is_vertical(c.label);
}

// ---- "<n> Comment line(s) follow" and the n lines: skipped.
void skip_cosmos_comments(const std::string& path, const std::vector<Line>& lines, std::size_t& li) {
  if (li >= lines.size()) fail(path, lines.back().number, "file ends before the comment lines");
  const Line& h = lines[li];
  const std::string up = upper(h.text);
  const long long n = number_before(up, "COMMENT LINE");
  if (n < 0) fail(path, h.number, "expected '<n> Comment line(s) follow ...', found " + in_quotes(trim(h.text)));
  li += 1 + static_cast<std::size_t>(n);
  if (li > lines.size()) fail(path, lines.back().number, "file ends inside the comment lines");
}

// The acceleration block's values (its header at lines[li]) into c.accel, in m/s^2 by the header's
// "units=", positive up.
void cosmos_acceleration(const std::string& path, const std::vector<Line>& lines, std::size_t li,
                         const std::string& up, const FortranFormat& ff, const std::vector<double>& values,
                         Component& c) {
  const Line& h = lines[li];
  const std::size_t u = up.find("UNITS=");
  if (u == std::string::npos) fail(path, h.number, "data header has no 'units='");
  std::size_t e = u + 6;
  while (e < up.size() && up[e] != '(' && up[e] != ',') ++e;
  const std::string units = std::string(trim(std::string_view(h.text).substr(u + 6, e - u - 6)));
  const double scale = units_scale(units);
  if (scale == 0.0) {
    fail(path, h.number,
         "unknown acceleration units " + in_quotes(units) + " (cm/sec2, cm/s/s, m/sec2, mm/sec2, g)");
  }
  const double sign = label_is_positive_down(c.label) ? -1.0 : 1.0;
  c.accel.reserve(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    // value i sits on data line i / per_line after the data header
    const std::size_t l = std::min(li + 1 + i / std::max<std::size_t>(ff.per_line, 1), lines.size() - 1);
    c.accel.push_back(scaled_or_fail(values[i], scale * sign, path, lines[l].number));
  }
}

// ---- the data blocks up to the next channel's text header: the first acceleration block is kept
// (velocity and displacement are skipped). False: the channel has no acceleration.
bool read_cosmos_data(const std::string& path, const std::vector<Line>& lines, std::size_t& li,
                      std::size_t data_size, Component& c) {
  bool have_accel = false;
  while (li < lines.size()) {
    const Line& h = lines[li];
    if (is_blank(h.text)) {
      ++li;
      continue;
    }
    const std::string up = upper(h.text);
    if (up.find("END-OF-DATA") != std::string::npos) {
      ++li;
      continue;
    }
    if (is_text_header_start(h.text)) break;  // the next channel
    long long npts = 0;
    std::string words, ftext;
    FortranFormat ff;
    if (!split_block_header(h.text, npts, words, ftext) || words.find("PTS") == std::string::npos) {
      fail(path, h.number,
           "expected a data header '<npts> acceleration pts, ..., units=..., Format=(...)', found " +
               in_quotes(trim(h.text)));
    }
    if (!parse_fortran_format(ftext, ff) || ff.kind == 'I') {
      fail(path, h.number, "bad data header: format " + in_quotes(ftext) + " is not a Fortran real format");
    }
    if (npts <= 0) fail(path, h.number, "empty data: " + std::to_string(npts) + " points");
    const bool accel = words.find("ACCEL") != std::string::npos;
    std::vector<double> values;
    values.reserve(std::min<std::size_t>(static_cast<std::size_t>(npts), data_size / 2 + 1));
    const std::size_t next = read_fortran_values(lines, li + 1, static_cast<std::size_t>(npts), ff, path, values);
    if (accel && !have_accel) {
      cosmos_acceleration(path, lines, li, up, ff, values, c);
      have_accel = true;
    }
    li = next;
  }
  return have_accel;
}

}  // namespace

std::vector<Component> read_cosmos(const std::string& path, std::string_view data) {
  const std::vector<Line> lines = split_lines(data);
  std::vector<Component> out;
  std::size_t li = 0;
  while (true) {
    while (li < lines.size() && is_blank(lines[li].text)) ++li;
    if (li >= lines.size()) break;
    Component c;
    read_cosmos_text_header(path, lines, li, c);
    std::vector<double> ints, reals;
    const std::size_t int_line = read_cosmos_numbers(path, lines, li, "INTEGER", 'I', ints);
    const std::size_t real_line = read_cosmos_numbers(path, lines, li, "REAL", 'F', reals);
    cosmos_dt_and_orientation(path, ints, int_line, reals, real_line, c);
    skip_cosmos_comments(path, lines, li);
    if (!read_cosmos_data(path, lines, li, data.size(), c))
      fail(path, lines.back().number, "channel has no acceleration block");
    if (!out.empty() && std::abs(out.front().dt - c.dt) > 1e-9 * out.front().dt) {
      fail(path, real_line,
           "mixed sample rates: channel 1 has dt = " + std::to_string(out.front().dt) + " s, channel " +
               std::to_string(out.size() + 1) + " dt = " + std::to_string(c.dt) + " s (one rate per file)");
    }
    out.push_back(std::move(c));
  }
  if (out.empty()) fail(path, 0, "empty file");
  return out;
}

}  // namespace rocking_monitor::core::record_io
