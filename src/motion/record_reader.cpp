// Strong-motion record readers (PEER AT2, SCEC BBP, USGS SMC V2, plain CSV/whitespace).
//
// Design notes
//  * The whole file is read into memory and split into lines (LF, CRLF or lone CR); numbers are
//    parsed with a strict grammar check followed by std::from_chars (locale independent, fast).
//    A token must be consumed completely: "1.2.3", "0x10", "1e" or "12abc" are rejected.
//    FORTRAN "D" exponents (1.0D-03) are accepted; NaN/inf/overflow are rejected as non-finite.
//  * Every problem throws RecordError("<file>:<line>: <problem>") (line omitted when not tied to a
//    line). Nothing is truncated silently; the only data deliberately ignored is what follows the
//    NPTS values of an AT2/SMC file (documented quirk: RSN960_NORTHR_LOS270.AT2 has a ".0" pad).
//  * Output is SI (m/s^2); vertical components are positive up.
//
// Sign convention for vertical components labelled "DWN" (PEER) / "down" (SMC):
//   PEER NGA names each component by the direction in which its acceleration is positive: the
//   horizontals carry the azimuth of their positive axis ("180", "W": the Chi-Chi files whose name
//   says -E but header says W are positive west), and the verticals are labelled either "UP" or
//   "DWN". Neither the AT2 header nor the README says that PEER re-oriented the DWN channels, and
//   the label is kept "as recorded" like the azimuths, so DWN is read as "positive downward".
//   These components are therefore multiplied by -1 on reading, so that every stored vertical is
//   positive up; Component::label keeps "DWN" as written. (PGA, i.e. max |a|, is unaffected.)
//   BBP U-D columns are "+ is upward" (header) and SMC "up" is positive up: not flipped.

#include "rocking_monitor/motion/record_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>
#include <system_error>
#include <utility>

#include "rocking_monitor/constants.hpp"

namespace rocking_monitor::core {

namespace {

// ------------------------------------------------------------------ errors

/// Makes arbitrary file text safe for a one-line message: control/non-ASCII bytes are escaped,
/// long text is shortened.
std::string printable(std::string_view s, std::size_t max_len = 60) {
  std::string out;
  const std::size_t n = std::min(s.size(), max_len);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7f) {
      out.push_back(static_cast<char>(c));
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out.push_back(hex[c >> 4]);
      out.push_back(hex[c & 0xf]);
    }
  }
  if (s.size() > max_len) out += "...";
  return out;
}

std::string quoted(std::string_view s) { return "'" + printable(s) + "'"; }

/// Throws RecordError "<path>:<line>: <problem>" (line == 0: "<path>: <problem>").
[[noreturn]] void fail(const std::string& path, std::size_t line, const std::string& problem) {
  std::string msg = path;
  if (line > 0) msg += ":" + std::to_string(line);
  msg += ": " + problem;
  throw RecordError(msg);
}

// ------------------------------------------------------------------ files and lines

std::string read_whole_file(const std::string& path) {
  errno = 0;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    const int err = errno;
    fail(path, 0, std::string("cannot open file (") + (err != 0 ? std::strerror(err) : "unknown error") + ")");
  }
  std::string data;
  char buf[1 << 16];
  for (;;) {
    const std::size_t got = std::fread(buf, 1, sizeof buf, f);
    data.append(buf, got);
    if (got < sizeof buf) break;
  }
  const bool error = std::ferror(f) != 0;
  const int err = errno;
  std::fclose(f);
  if (error) {
    fail(path, 0, std::string("cannot read file (") + (err != 0 ? std::strerror(err) : "read error") + ")");
  }
  return data;
}

/// Reads at most max_bytes from the start of a file (for format detection).
std::string read_file_head(const std::string& path, std::size_t max_bytes, bool* whole) {
  errno = 0;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    const int err = errno;
    fail(path, 0, std::string("cannot open file (") + (err != 0 ? std::strerror(err) : "unknown error") + ")");
  }
  std::string data(max_bytes, '\0');
  const std::size_t got = std::fread(data.data(), 1, max_bytes, f);
  const bool error = std::ferror(f) != 0;
  const int err = errno;
  std::fclose(f);
  if (error) {
    fail(path, 0, std::string("cannot read file (") + (err != 0 ? std::strerror(err) : "read error") + ")");
  }
  data.resize(got);
  *whole = got < max_bytes;
  return data;
}

struct Line {
  std::string_view text;  ///< without the line terminator
  std::size_t number;     ///< 1-based
};

/// Splits on LF, CRLF or a lone CR. A leading UTF-8 BOM is skipped.
std::vector<Line> split_lines(std::string_view data) {
  std::vector<Line> lines;
  lines.reserve(data.size() / 64 + 16);
  std::size_t pos = 0;
  if (data.size() >= 3 && data.substr(0, 3) == "\xEF\xBB\xBF") pos = 3;
  std::size_t number = 1;
  const std::size_t n = data.size();
  while (pos < n) {
    std::size_t end = pos;
    while (end < n && data[end] != '\n' && data[end] != '\r') ++end;
    lines.push_back({data.substr(pos, end - pos), number++});
    if (end < n && data[end] == '\r' && end + 1 < n && data[end + 1] == '\n') {
      pos = end + 2;
    } else {
      pos = end + 1;
    }
  }
  return lines;
}

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

std::string_view trim(std::string_view s) {
  std::size_t b = 0;
  std::size_t e = s.size();
  while (b < e && is_space(s[b])) ++b;
  while (e > b && is_space(s[e - 1])) --e;
  return s.substr(b, e - b);
}

bool is_blank(std::string_view s) { return trim(s).empty(); }

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

/// Calls f(token) for every whitespace-separated token of a line.
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

std::vector<std::string_view> ws_tokens(std::string_view line) {
  std::vector<std::string_view> out;
  for_each_ws_token(line, [&](std::string_view t) { out.push_back(t); });
  return out;
}

/// Splits a CSV/whitespace line: fields are separated by a comma (with optional blanks around it)
/// or by blanks. Returns false (and sets *bad_column, 1-based) when a field is empty ("1,,2",
/// "1,2,", ",1").
bool csv_tokens(std::string_view line, std::vector<std::string_view>& out, std::size_t* bad_column) {
  out.clear();
  std::size_t i = 0;
  const std::size_t n = line.size();
  bool need_field = false;  // a comma was just consumed
  while (true) {
    while (i < n && is_space(line[i])) ++i;
    if (i >= n) {
      if (need_field) {
        *bad_column = out.size() + 1;
        return false;
      }
      return true;
    }
    if (line[i] == ',') {
      // a comma with no field before it (",1" or "1,,2")
      if (need_field || out.empty()) {
        *bad_column = out.size() + 1;
        return false;
      }
      need_field = true;
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < n && !is_space(line[j]) && line[j] != ',') ++j;
    out.push_back(line.substr(i, j - i));
    need_field = false;
    i = j;
    // after a field: blanks, then optionally one comma
    while (i < n && is_space(line[i])) ++i;
    if (i < n && line[i] == ',') {
      need_field = true;
      ++i;
    }
  }
}

std::string file_extension_lower(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  return lower(std::string_view(path).substr(dot + 1));
}

std::string file_stem(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const std::size_t dot = name.find_last_of('.');
  if (dot != std::string::npos && dot > 0) name.resize(dot);
  return name;
}

// ------------------------------------------------------------------ numbers

enum class NumStatus { Ok, NonNumeric, NonFinite };

bool is_nonfinite_word(std::string_view t) {
  if (!t.empty() && (t[0] == '+' || t[0] == '-')) t.remove_prefix(1);
  const std::string l = lower(t);
  return l == "nan" || l == "inf" || l == "infinity" || l == "-nan" || (l.size() > 4 && l.compare(0, 4, "nan(") == 0);
}

/// Strict decimal number: [+-] (digits [. digits] | . digits) [(E|e|D|d) [+-] digits], nothing else.
NumStatus parse_number(std::string_view tok, double& out) {
  const std::size_t n = tok.size();
  std::size_t i = 0;
  if (i < n && (tok[i] == '+' || tok[i] == '-')) ++i;
  std::size_t digits = 0;
  while (i < n && tok[i] >= '0' && tok[i] <= '9') ++i, ++digits;
  bool has_d_exponent = false;
  if (i < n && tok[i] == '.') {
    ++i;
    while (i < n && tok[i] >= '0' && tok[i] <= '9') ++i, ++digits;
  }
  if (digits == 0) return is_nonfinite_word(tok) ? NumStatus::NonFinite : NumStatus::NonNumeric;
  if (i < n && (tok[i] == 'e' || tok[i] == 'E' || tok[i] == 'd' || tok[i] == 'D')) {
    has_d_exponent = tok[i] == 'd' || tok[i] == 'D';
    ++i;
    if (i < n && (tok[i] == '+' || tok[i] == '-')) ++i;
    std::size_t exp_digits = 0;
    while (i < n && tok[i] >= '0' && tok[i] <= '9') ++i, ++exp_digits;
    if (exp_digits == 0) return NumStatus::NonNumeric;
  }
  if (i != n) return NumStatus::NonNumeric;

  // from_chars does not take a leading '+' nor a 'D' exponent: normalise into a buffer.
  char small[128];
  std::string big;
  char* buf = small;
  if (n + 1 > sizeof small) {
    big.resize(n + 1);
    buf = big.data();
  }
  std::size_t m = 0;
  for (std::size_t k = 0; k < n; ++k) {
    char c = tok[k];
    if (k == 0 && c == '+') continue;
    if (has_d_exponent && (c == 'd' || c == 'D')) c = 'e';
    buf[m++] = c;
  }
  buf[m] = '\0';
  double value = 0.0;
  const auto res = std::from_chars(buf, buf + m, value, std::chars_format::general);
  if (res.ec == std::errc::result_out_of_range) {
    // Overflow (1e999) or underflow (1e-999): strtod tells which (the grammar is already checked).
    value = std::strtod(buf, nullptr);
    if (!std::isfinite(value)) return NumStatus::NonFinite;
  } else if (res.ec != std::errc() || res.ptr != buf + m) {
    return NumStatus::NonNumeric;
  }
  if (!std::isfinite(value)) return NumStatus::NonFinite;
  out = value;
  return NumStatus::Ok;
}

/// Parses a token or throws the standard "non-numeric value '...'" / "non-finite value '...'".
double number_or_fail(std::string_view tok, const std::string& path, std::size_t line) {
  double v = 0.0;
  switch (parse_number(tok, v)) {
    case NumStatus::Ok:
      return v;
    case NumStatus::NonFinite:
      fail(path, line, "non-finite value " + quoted(tok));
    case NumStatus::NonNumeric:
      break;
  }
  fail(path, line, "non-numeric value " + quoted(tok));
}

bool is_number(std::string_view tok) {
  double v = 0.0;
  return parse_number(tok, v) == NumStatus::Ok;
}

/// Strict non-negative/negative integer (digits only, optional sign).
bool parse_integer(std::string_view tok, long long& out) {
  if (tok.empty()) return false;
  const char* b = tok.data();
  const char* e = tok.data() + tok.size();
  if (*b == '+') {
    ++b;
    if (b == e || *b == '-') return false;
  }
  const auto res = std::from_chars(b, e, out, 10);
  return res.ec == std::errc() && res.ptr == e;
}

/// One unit in the last printed digit of a (validated) number token, e.g.
/// "5.000000e-03" -> 1e-9, "79.980000" -> 1e-6, "12" -> 1. Used as the rounding allowance of
/// printed time stamps.
double printed_resolution(std::string_view tok) {
  int frac_digits = 0;
  long exponent = 0;
  std::size_t i = 0;
  const std::size_t n = tok.size();
  while (i < n && tok[i] != '.' && tok[i] != 'e' && tok[i] != 'E' && tok[i] != 'd' && tok[i] != 'D') ++i;
  if (i < n && tok[i] == '.') {
    ++i;
    while (i < n && tok[i] >= '0' && tok[i] <= '9') ++i, ++frac_digits;
  }
  if (i < n && (tok[i] == 'e' || tok[i] == 'E' || tok[i] == 'd' || tok[i] == 'D')) {
    exponent = std::strtol(std::string(tok.substr(i + 1)).c_str(), nullptr, 10);
  }
  return std::pow(10.0, static_cast<double>(exponent - frac_digits));
}

// ------------------------------------------------------------------ time columns

struct TimeSample {
  double t;
  double res;  // rounding allowance of the printed value
  std::size_t line;
};

/// Checks that the time column is uniform and returns dt.
///
/// The README defines dt = t[1] - t[0]. Every step must equal it, and every time stamp must lie on
/// the grid t0 + i*dt (dt refined from the end points, the more accurate estimate; this catches
/// slow drifts that no single step reveals), within
///     1e-6*dt + the rounding of the printed digits involved (one unit in the last printed digit
///     of each time stamp, which also covers printers that truncate),
/// but the rounding part never exceeds 1 % of dt: when the time stamps are printed so coarsely
/// that their rounding is comparable to dt (e.g. dt = 0.01 s printed with 2 decimals), a missing
/// row would otherwise pass as rounding. Every step must also be positive.
double check_uniform_time(const std::string& path, const std::vector<TimeSample>& ts) {
  const std::size_t n = ts.size();
  if (n < 2) fail(path, ts.empty() ? 0 : ts[0].line, "need at least 2 samples to determine the time step");
  auto describe = [](const char* what, double t, double t_prev, double step, double expected) {
    char buf[240];
    std::snprintf(buf, sizeof buf, "%s: t=%.9g after t=%.9g (step %.9g, expected %.9g)", what, t, t_prev, step,
                  expected);
    return std::string(buf);
  };
  const double dt1 = ts[1].t - ts[0].t;
  if (!(dt1 > 0.0)) {
    fail(path, ts[1].line, describe("non-positive time step", ts[1].t, ts[0].t, dt1, dt1));
  }
  const double cap = 0.01 * dt1;
  const double base = ts[0].res + ts[1].res;
  for (std::size_t i = 1; i < n; ++i) {
    const double step = ts[i].t - ts[i - 1].t;
    const double tol = 1e-6 * dt1 + std::min(cap, base + ts[i].res + ts[i - 1].res);
    if (!(step > 0.0) || !(std::fabs(step - dt1) <= tol)) {
      fail(path, ts[i].line,
           describe(step > 0.0 ? "non-uniform time step" : "non-uniform time step (not increasing)", ts[i].t,
                    ts[i - 1].t, step, dt1));
    }
  }
  const double dt = (ts[n - 1].t - ts[0].t) / static_cast<double>(n - 1);
  // A drift is reported where it is largest (where the time stamps depart most from the grid
  // through the end points), which is near where it starts rather than where it first shows.
  const double ends = ts[0].res + ts[n - 1].res;
  std::size_t worst = n;
  double worst_excess = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double expected = ts[0].t + static_cast<double>(i) * dt;
    const double tol = 1e-6 * dt + std::min(0.01 * dt, ends + ts[i].res);
    const double excess = std::fabs(ts[i].t - expected) - tol;
    if (excess > worst_excess) {
      worst_excess = excess;
      worst = i;
    }
  }
  if (worst < n) {
    char buf[240];
    std::snprintf(buf, sizeof buf,
                  "non-uniform time step: t=%.9g is off the uniform grid t0 + i*dt (expected %.9g, dt %.9g)",
                  ts[worst].t, ts[0].t + static_cast<double>(worst) * dt, dt);
    fail(path, ts[worst].line, buf);
  }
  return dt;
}

// ------------------------------------------------------------------ labels

std::string normalised_label(const std::string& label) {
  std::string l = upper(trim(label));
  while (!l.empty() && (l[0] == '-' || l[0] == '_')) l.erase(0, 1);
  return l;
}

// ------------------------------------------------------------------ PEER AT2

/// Line 2 of an AT2 file -> event, station, component.
///  NGA-West2: "<Event>, <M/D/YYYY>, <Station (may contain commas)>, <Component>"
///  older:     "<EVENT> <MM/DD/YY> <HH:MM>, <STATION>, <COMP> (<AGENCY> STATION <n>)", with variants
///             "NORTHRIDGE EQ 1/17/94, 12:31, ..." and "NORTHRIDGE, 1/17/94 12:31, ...".
void parse_at2_title(std::string_view line, Component& c) {
  line = trim(line);
  std::vector<std::pair<std::size_t, std::size_t>> fields;  // [begin, end) in line
  std::size_t b = 0;
  for (std::size_t i = 0; i <= line.size(); ++i) {
    if (i == line.size() || line[i] == ',') {
      fields.emplace_back(b, i);
      b = i + 1;
    }
  }
  if (fields.size() < 2) return;
  auto field = [&](std::size_t k) { return trim(line.substr(fields[k].first, fields[k].second - fields[k].first)); };

  // component: last field, without a trailing "(...)" note
  std::string_view comp = field(fields.size() - 1);
  const std::size_t paren = comp.find('(');
  if (paren != std::string_view::npos) comp = trim(comp.substr(0, paren));
  c.label = std::string(comp);

  // date: first field holding d/d/dd
  auto find_date = [](std::string_view s) -> std::size_t {
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (!std::isdigit(static_cast<unsigned char>(s[i]))) continue;
      std::size_t j = i;
      int groups = 0;
      while (true) {
        std::size_t k = j;
        while (k < s.size() && std::isdigit(static_cast<unsigned char>(s[k]))) ++k;
        if (k == j) break;
        ++groups;
        j = k;
        if (groups == 3 || j >= s.size() || s[j] != '/') break;
        ++j;
      }
      if (groups == 3 && (i == 0 || !std::isdigit(static_cast<unsigned char>(s[i - 1])))) return i;
    }
    return std::string_view::npos;
  };
  std::size_t date_field = fields.size();
  std::size_t date_pos = 0;
  for (std::size_t k = 0; k + 1 < fields.size(); ++k) {
    const std::string_view s = line.substr(fields[k].first, fields[k].second - fields[k].first);
    const std::size_t p = find_date(s);
    if (p != std::string_view::npos) {
      date_field = k;
      date_pos = fields[k].first + p;
      break;
    }
  }
  auto is_time_only = [](std::string_view s) {
    s = trim(s);
    if (s.empty()) return false;
    for (char ch : s) {
      if (!std::isdigit(static_cast<unsigned char>(ch)) && ch != ':') return false;
    }
    return true;
  };
  std::size_t station_first = 1;
  if (date_field < fields.size()) {
    c.event = std::string(trim(line.substr(0, date_pos)));
    while (!c.event.empty() && c.event.back() == ',') c.event.pop_back();
    c.event = std::string(trim(c.event));
    station_first = date_field + 1;
    while (station_first + 1 < fields.size() && is_time_only(field(station_first))) ++station_first;
  } else {
    c.event = std::string(field(0));
  }
  if (station_first + 1 <= fields.size() - 1) {
    const std::size_t sb = fields[station_first].first;
    const std::size_t se = fields[fields.size() - 2].second;
    c.station = std::string(trim(line.substr(sb, se - sb)));
  }
}

/// Finds "<key> = <token>" (case-insensitive key) in an upper-cased line; returns the token.
bool find_key_value(const std::string& up, const std::string& key, std::string_view raw, std::string_view& value,
                    bool& key_seen) {
  std::size_t from = 0;
  while (true) {
    const std::size_t p = up.find(key, from);
    if (p == std::string::npos) return false;
    from = p + key.size();
    // key must not be the tail of a longer word (e.g. "NPTS" inside "XNPTS")
    if (p > 0 && std::isalpha(static_cast<unsigned char>(up[p - 1]))) continue;
    std::size_t i = p + key.size();
    while (i < up.size() && is_space(up[i])) ++i;
    if (i >= up.size() || up[i] != '=') continue;
    key_seen = true;
    ++i;
    while (i < up.size() && is_space(up[i])) ++i;
    std::size_t j = i;
    while (j < up.size() && !is_space(up[j]) && up[j] != ',' && up[j] != ';') ++j;
    value = raw.substr(i, j - i);
    return true;
  }
}

std::vector<Component> read_at2(const std::string& path, std::string_view data) {
  const std::vector<Line> lines = split_lines(data);
  if (lines.empty()) fail(path, 0, "empty file");
  if (lines.size() < 4) {
    fail(path, lines.size(), "bad header: a PEER AT2 file needs 4 header lines, found " + std::to_string(lines.size()));
  }

  // line 3: acceleration in g
  const std::string l3 = upper(lines[2].text);
  if (l3.find("UNITS OF G") == std::string::npos || l3.find("ACCEL") == std::string::npos ||
      l3.find("VELOCITY") != std::string::npos || l3.find("DISPLACEMENT") != std::string::npos) {
    fail(path, 3,
         "bad header: expected 'ACCELERATION ... IN UNITS OF G', found " + quoted(trim(lines[2].text)));
  }

  // line 4: NPTS and DT (three "KEY=" variants or "<npts> <dt> NPTS, DT")
  const std::string_view raw4 = lines[3].text;
  const std::string up4 = upper(raw4);
  long long npts = -1;
  double dt = 0.0;
  std::string_view npts_tok;
  std::string_view dt_tok;
  bool npts_key = false;
  bool dt_key = false;
  const bool has_npts = find_key_value(up4, "NPTS", raw4, npts_tok, npts_key);
  const bool has_dt = find_key_value(up4, "DT", raw4, dt_tok, dt_key);
  if (has_npts || has_dt) {
    if (!has_npts) fail(path, 4, "bad header: missing NPTS in " + quoted(trim(raw4)));
    if (!has_dt) fail(path, 4, "bad header: missing DT in " + quoted(trim(raw4)));
  } else {
    // old NGA header: "5996    0.0050    NPTS, DT"
    std::string compact;
    for (char ch : up4) {
      if (!is_space(ch)) compact.push_back(ch);
    }
    const std::string tail = "NPTS,DT";
    if (compact.size() < tail.size() || compact.compare(compact.size() - tail.size(), tail.size(), tail) != 0) {
      fail(path, 4, "bad header: missing NPTS/DT in " + quoted(trim(raw4)));
    }
    const std::vector<std::string_view> toks = ws_tokens(raw4);
    if (toks.size() < 2) fail(path, 4, "bad header: missing NPTS/DT values in " + quoted(trim(raw4)));
    npts_tok = toks[0];
    dt_tok = toks[1];
    if (!dt_tok.empty() && dt_tok.back() == ',') dt_tok.remove_suffix(1);
  }
  if (!parse_integer(npts_tok, npts)) fail(path, 4, "bad header: cannot parse NPTS " + quoted(npts_tok));
  // DT may be followed directly by its unit ("DT= .0050SEC")
  std::string_view dt_num = dt_tok;
  {
    const std::string u = upper(dt_num);
    if (u.size() > 3 && u.compare(u.size() - 3, 3, "SEC") == 0) dt_num.remove_suffix(3);
  }
  if (parse_number(dt_num, dt) != NumStatus::Ok) fail(path, 4, "bad header: cannot parse DT " + quoted(dt_tok));
  if (npts < 0) fail(path, 4, "bad header: negative NPTS " + std::to_string(npts));
  if (npts == 0) fail(path, 4, "empty data: NPTS = 0");
  if (!(dt > 0.0)) fail(path, 4, "non-positive DT " + quoted(dt_tok));

  Component c;
  c.file = path;
  c.dt = dt;
  c.t0 = 0.0;
  parse_at2_title(lines[1].text, c);
  c.vertical = label_is_vertical(c.label);
  const double scale = label_is_positive_down(c.label) ? -kGravity : kGravity;  // see the note at the top

  const auto want = static_cast<std::size_t>(npts);
  // Never trust NPTS for the allocation size: a corrupt header must not cause bad_alloc.
  c.accel.reserve(std::min<std::size_t>(want, data.size() / 2 + 1));
  std::size_t last_data_line = 4;
  for (std::size_t li = 4; li < lines.size() && c.accel.size() < want; ++li) {
    const Line& ln = lines[li];
    bool any = false;
    for_each_ws_token(ln.text, [&](std::string_view tok) {
      if (c.accel.size() >= want) return;  // values after NPTS are ignored
      c.accel.push_back(number_or_fail(tok, path, ln.number) * scale);
      any = true;
    });
    if (any) last_data_line = ln.number;
  }
  if (c.accel.size() < want) {
    fail(path, last_data_line,
         "expected " + std::to_string(want) + " values (NPTS), found " + std::to_string(c.accel.size()));
  }
  std::vector<Component> out;
  out.push_back(std::move(c));
  return out;
}

// ------------------------------------------------------------------ SCEC BBP

std::vector<Component> read_bbp(const std::string& path, std::string_view data) {
  const std::vector<Line> lines = split_lines(data);
  if (lines.empty()) fail(path, 0, "empty file");

  std::string station;
  std::string event;
  std::vector<TimeSample> ts;
  std::vector<double> col[3];
  const std::size_t guess = data.size() / 40 + 1;
  ts.reserve(guess);
  for (auto& v : col) v.reserve(guess);

  std::vector<std::string_view> toks;
  toks.reserve(8);
  for (const Line& ln : lines) {
    const std::string_view t = trim(ln.text);
    if (t.empty()) continue;
    if (t[0] == '#') {
      const std::string_view body = trim(t.substr(1));
      const std::string lb = lower(body);
      if (lb.compare(0, 8, "station:") == 0) station = std::string(trim(body.substr(8)));
      const std::string prefix = "strong motion recording for ";
      if (lb.compare(0, prefix.size(), prefix) == 0) event = std::string(trim(body.substr(prefix.size())));
      if (lb.find("velocity") != std::string::npos || lb.find("displacement") != std::string::npos ||
          lb.find("(cm/s)") != std::string::npos || lb.find("(cm)") != std::string::npos) {
        fail(path, ln.number, "not an acceleration file (header says " + quoted(body) + ")");
      }
      continue;
    }
    toks.clear();
    for_each_ws_token(t, [&](std::string_view tok) { toks.push_back(tok); });
    if (toks.size() != 4) {
      fail(path, ln.number,
           "expected 4 columns (time N-S E-W U-D), found " + std::to_string(toks.size()) + " in " + quoted(t));
    }
    const double time = number_or_fail(toks[0], path, ln.number);
    ts.push_back({time, printed_resolution(toks[0]), ln.number});
    for (int k = 0; k < 3; ++k) col[k].push_back(number_or_fail(toks[static_cast<std::size_t>(k) + 1], path, ln.number) * 0.01);
  }
  if (ts.empty()) fail(path, 0, "empty data: no data rows");
  const double dt = check_uniform_time(path, ts);

  if (station.empty()) station = file_stem(path);  // gmsvtoolkit files: the file name is the BBP id
  static const char* labels[3] = {"N-S", "E-W", "U-D"};
  std::vector<Component> out(3);
  for (int k = 0; k < 3; ++k) {
    Component& c = out[static_cast<std::size_t>(k)];
    c.file = path;
    c.event = event;
    c.station = station;
    c.label = labels[k];
    c.vertical = k == 2;  // "+ is upward": stored as is
    c.dt = dt;
    c.t0 = ts.front().t;
    c.accel = std::move(col[k]);
  }
  return out;
}

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

std::vector<Component> read_smc(const std::string& path, std::string_view data) {
  const std::vector<Line> lines = split_lines(data);
  if (lines.empty()) fail(path, 0, "empty file");
  const std::string l1 = upper(trim(lines[0].text));
  if (l1.empty() || l1[0] != '2' || l1.find("CORRECTED ACCELEROGRAM") == std::string::npos ||
      l1.find("UNCORRECTED") != std::string::npos) {
    fail(path, 1,
         "unsupported SMC file type " + quoted(trim(lines[0].text)) + " (only '2 CORRECTED ACCELEROGRAM' is supported)");
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
      fail(path, ln.number, "bad header: expected 8 integers in 10-character fields, found " + quoted(trim(ln.text)));
    }
    for (std::size_t j = 0; j < 8; ++j) {
      long long v = 0;
      if (!parse_integer(f[j], v)) {
        fail(path, ln.number, "bad header: integer field " + std::to_string(k * 8 + j + 1) + " is " + quoted(f[j]));
      }
      ints.push_back(v);
    }
  }
  std::vector<double> reals;
  for (std::size_t k = 0; k < kRealLines; ++k) {
    const Line& ln = lines[kText + kIntLines + k];
    if (!fixed_fields(ln.text, 15, 5, f) || f.size() != 5) {
      fail(path, ln.number, "bad header: expected 5 reals in 15-character fields, found " + quoted(trim(ln.text)));
    }
    for (std::size_t j = 0; j < 5; ++j) {
      double v = 0.0;
      if (parse_number(f[j], v) != NumStatus::Ok) {
        fail(path, ln.number, "bad header: real field " + std::to_string(k * 5 + j + 1) + " is " + quoted(f[j]));
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
               " starting with '|', found " + quoted(trim(t)));
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
      fail(path, ln.number, "data line longer than 8 fields of 10 characters: " + quoted(trim(ln.text)));
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
      c.accel.push_back(number_or_fail(f[j], path, ln.number) * scale);
    }
    last_data_line = ln.number;
    if (f.size() < 8 && c.accel.size() < want) {
      short_line = ln.number;
      short_problem = "short data line (" + std::to_string(f.size()) + " of 8 values) before the end of the data";
    }
  }
  if (c.accel.size() < want) {
    fail(path, last_data_line,
         "expected " + std::to_string(want) + " values (NPTS), found " + std::to_string(c.accel.size()));
  }
  std::vector<Component> out;
  out.push_back(std::move(c));
  return out;
}

// ------------------------------------------------------------------ CSV / whitespace

std::vector<Component> read_csv(const std::string& path, std::string_view data, AccelUnits units) {
  const std::vector<Line> lines = split_lines(data);
  if (lines.empty()) fail(path, 0, "empty file");
  double scale = 1.0;
  switch (units) {
    case AccelUnits::MetersPerSecond2:
      scale = 1.0;
      break;
    case AccelUnits::G:
      scale = kGravity;
      break;
    case AccelUnits::CentimetersPerSecond2:
      scale = 0.01;
      break;
  }

  std::vector<TimeSample> ts;
  std::vector<double> h;
  std::vector<double> v;
  const std::size_t guess = data.size() / 20 + 1;
  ts.reserve(guess);
  h.reserve(guess);
  std::size_t ncols = 0;
  bool seen_first = false;
  std::vector<std::string_view> toks;
  for (const Line& ln : lines) {
    if (is_blank(ln.text)) continue;
    // '#' lines are comments (provenance notes), anywhere in the file.
    if (const auto first = ln.text.find_first_not_of(" \t"); ln.text[first] == '#') continue;
    std::size_t bad_col = 0;
    const bool ok = csv_tokens(ln.text, toks, &bad_col);
    if (!seen_first) {
      seen_first = true;
      // one header line is allowed: a line in which no field is a number
      bool any_number = false;
      for (std::string_view t : toks) {
        double x = 0.0;
        if (parse_number(t, x) != NumStatus::NonNumeric) any_number = true;
      }
      if (!any_number) continue;
    }
    if (!ok) fail(path, ln.number, "empty field in column " + std::to_string(bad_col));
    if (ncols == 0) {
      if (toks.size() != 2 && toks.size() != 3) {
        fail(path, ln.number,
             "expected 2 or 3 columns (time_s accel [accel_v]), found " + std::to_string(toks.size()));
      }
      ncols = toks.size();
      if (ncols == 3) v.reserve(guess);
    } else if (toks.size() != ncols) {
      fail(path, ln.number,
           "expected " + std::to_string(ncols) + " columns like the first data row, found " + std::to_string(toks.size()));
    }
    const double t = number_or_fail(toks[0], path, ln.number);
    ts.push_back({t, printed_resolution(toks[0]), ln.number});
    h.push_back(number_or_fail(toks[1], path, ln.number) * scale);
    if (ncols == 3) v.push_back(number_or_fail(toks[2], path, ln.number) * scale);
  }
  if (ts.empty()) fail(path, 0, "empty data: no data rows");
  const double dt = check_uniform_time(path, ts);

  std::vector<Component> out;
  Component c;
  c.file = path;
  c.label = "H";
  c.vertical = false;
  c.dt = dt;
  c.t0 = ts.front().t;
  c.accel = std::move(h);
  out.push_back(c);
  if (ncols == 3) {
    c.label = "V";
    c.vertical = true;
    c.accel = std::move(v);
    out.push_back(std::move(c));
  }
  return out;
}

// ------------------------------------------------------------------ detection

RecordFormat detect_from_content(std::string_view head, bool whole_file, const std::string& path) {
  std::vector<Line> lines = split_lines(head);
  if (!whole_file && !lines.empty()) lines.pop_back();  // possibly cut in the middle
  if (lines.size() > 40) lines.resize(40);

  std::size_t first = 0;
  while (first < lines.size() && is_blank(lines[first].text)) ++first;
  if (first < lines.size()) {
    const std::string l1 = upper(lines[first].text);
    if (l1.find("PEER") != std::string::npos &&
        (l1.find("STRONG MOTION") != std::string::npos || l1.find("DATABASE") != std::string::npos)) {
      return RecordFormat::PeerAt2;
    }
    const std::string_view t1 = trim(lines[first].text);
    if (l1.find("ACCELEROGRAM") != std::string::npos && !t1.empty() &&
        std::isdigit(static_cast<unsigned char>(t1[0]))) {
      return RecordFormat::UsgsSmc;
    }
  }
  // AT2-like without the PEER title: line 3 "... UNITS OF G", line 4 "NPTS=" or "... NPTS, DT"
  if (lines.size() >= 4) {
    const std::string l3 = upper(lines[2].text);
    const std::string l4 = upper(lines[3].text);
    if (l3.find("UNITS OF G") != std::string::npos && l4.find("NPTS") != std::string::npos) {
      return RecordFormat::PeerAt2;
    }
  }
  // Tabular: '#' header lines then 4 numeric columns -> BBP; 2 or 3 -> CSV.
  bool header_used = false;
  std::vector<std::string_view> toks;
  for (std::size_t i = first; i < lines.size(); ++i) {
    const std::string_view t = trim(lines[i].text);
    if (t.empty()) continue;
    if (t[0] == '#') continue;
    std::size_t bad = 0;
    const bool ok = csv_tokens(t, toks, &bad);
    bool all_numeric = ok && !toks.empty();
    for (std::string_view tok : toks) all_numeric = all_numeric && is_number(tok);
    if (all_numeric) {
      if (toks.size() == 4 && t.find(',') == std::string_view::npos) return RecordFormat::Bbp;
      if (toks.size() == 2 || toks.size() == 3) return RecordFormat::Csv;
      break;
    }
    if (header_used) break;
    header_used = true;  // one non-numeric header line allowed
  }

  const std::string ext = file_extension_lower(path);
  if (ext == "at2") return RecordFormat::PeerAt2;
  if (ext == "bbp") return RecordFormat::Bbp;
  if (ext == "smc" || ext == "v2") return RecordFormat::UsgsSmc;
  if (ext == "csv" || ext == "txt" || ext == "dat" || ext == "tsv") return RecordFormat::Csv;
  return RecordFormat::Auto;
}

}  // namespace

// ------------------------------------------------------------------ public API

bool label_is_vertical(const std::string& label) {
  const std::string l = normalised_label(label);
  return l == "UP" || l == "DWN" || l == "DOWN" || l == "DN" || l == "U-D" || l == "UD" || l == "D-U" ||
         l == "V" || l == "VER" || l == "VERT" || l == "VRT" || l == "VERTICAL" || l == "Z" || l == "UP-DOWN";
}

bool label_is_positive_down(const std::string& label) {
  const std::string l = normalised_label(label);
  return l == "DWN" || l == "DOWN" || l == "DN";
}

RecordFormat detect_format(const std::string& path) {
  bool whole = false;
  const std::string head = read_file_head(path, 16384, &whole);
  return detect_from_content(head, whole, path);
}

std::vector<Component> read_record(const std::string& path, const ReadOptions& options) {
  const std::string data = read_whole_file(path);
  if (trim(data).empty()) fail(path, 0, data.empty() ? "empty file" : "empty file (only blanks)");
  RecordFormat format = options.format;
  if (format == RecordFormat::Auto) {
    const std::size_t head_len = std::min<std::size_t>(data.size(), 16384);
    format = detect_from_content(std::string_view(data).substr(0, head_len), head_len == data.size(), path);
  }
  switch (format) {
    case RecordFormat::PeerAt2:
      return read_at2(path, data);
    case RecordFormat::Bbp:
      return read_bbp(path, data);
    case RecordFormat::UsgsSmc:
      return read_smc(path, data);
    case RecordFormat::Csv:
      return read_csv(path, data, options.csv_units);
    case RecordFormat::Auto:
      break;
  }
  const std::string ext = file_extension_lower(path);
  fail(path, 0,
       "unknown record format (not PEER AT2, SCEC BBP, USGS SMC V2 or CSV by content, and extension " +
           (ext.empty() ? std::string("none") : quoted(ext)) + " does not tell)");
}

const char* to_string(RecordFormat format) {
  switch (format) {
    case RecordFormat::Auto:
      return "auto";
    case RecordFormat::PeerAt2:
      return "peer_at2";
    case RecordFormat::Bbp:
      return "bbp";
    case RecordFormat::UsgsSmc:
      return "usgs_smc";
    case RecordFormat::Csv:
      return "csv";
  }
  return "unknown";
}

}  // namespace rocking_monitor::core
