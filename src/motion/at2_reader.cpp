// PEER NGA AT2 records (units g): the title line in all its header variants, NPTS and DT from line 4,
// the values in free format; DWN verticals are flipped to positive up (see record_reader.cpp).
#include "record_reader_internal.hpp"

#include "rocking_monitor/constants.hpp"

#include <algorithm>
#include <cctype>
#include <string_view>
#include <utility>

namespace rocking_monitor::core::record_io {

namespace {

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

// Four header lines, line 3 saying the values are accelerations in g.
void check_at2_header(const std::string& path, const std::vector<Line>& lines) {
  if (lines.empty()) fail(path, 0, "empty file");
  if (lines.size() < 4) {
    fail(path, lines.size(), "bad header: a PEER AT2 file needs 4 header lines, found " + std::to_string(lines.size()));
  }
  const std::string l3 = upper(lines[2].text);
  if (l3.find("UNITS OF G") == std::string::npos || l3.find("ACCEL") == std::string::npos ||
      l3.find("VELOCITY") != std::string::npos || l3.find("DISPLACEMENT") != std::string::npos) {
    fail(path, 3,
         "bad header: expected 'ACCELERATION ... IN UNITS OF G', found " + in_quotes(trim(lines[2].text)));
  }
}

// line 4's NPTS and DT texts: three "KEY=" variants or "<npts> <dt> NPTS, DT".
void at2_npts_dt_tokens(const std::string& path, std::string_view raw4, std::string_view& npts_tok,
                        std::string_view& dt_tok) {
  const std::string up4 = upper(raw4);
  bool npts_key = false;
  bool dt_key = false;
  const bool has_npts = find_key_value(up4, "NPTS", raw4, npts_tok, npts_key);
  const bool has_dt = find_key_value(up4, "DT", raw4, dt_tok, dt_key);
  if (has_npts || has_dt) {
    if (!has_npts) fail(path, 4, "bad header: missing NPTS in " + in_quotes(trim(raw4)));
    if (!has_dt) fail(path, 4, "bad header: missing DT in " + in_quotes(trim(raw4)));
    return;
  }
  // old NGA header: "5996    0.0050    NPTS, DT"
  std::string compact;
  for (char ch : up4) {
    if (!is_space(ch)) compact.push_back(ch);
  }
  const std::string tail = "NPTS,DT";
  if (compact.size() < tail.size() || compact.compare(compact.size() - tail.size(), tail.size(), tail) != 0) {
    fail(path, 4, "bad header: missing NPTS/DT in " + in_quotes(trim(raw4)));
  }
  const std::vector<std::string_view> toks = ws_tokens(raw4);
  if (toks.size() < 2) fail(path, 4, "bad header: missing NPTS/DT values in " + in_quotes(trim(raw4)));
  npts_tok = toks[0];
  dt_tok = toks[1];
  if (!dt_tok.empty() && dt_tok.back() == ',') dt_tok.remove_suffix(1);
}

// line 4: NPTS and DT, parsed and checked.
void at2_npts_dt(const std::string& path, std::string_view raw4, long long& npts, double& dt) {
  std::string_view npts_tok;
  std::string_view dt_tok;
  at2_npts_dt_tokens(path, raw4, npts_tok, dt_tok);
  if (!parse_integer(npts_tok, npts)) fail(path, 4, "bad header: cannot parse NPTS " + in_quotes(npts_tok));
  // DT may be followed directly by its unit ("DT= .0050SEC")
  std::string_view dt_num = dt_tok;
  {
    const std::string u = upper(dt_num);
    if (u.size() > 3 && u.compare(u.size() - 3, 3, "SEC") == 0) dt_num.remove_suffix(3);
  }
  if (parse_number(dt_num, dt) != NumStatus::Ok) fail(path, 4, "bad header: cannot parse DT " + in_quotes(dt_tok));
  if (npts < 0) fail(path, 4, "bad header: negative NPTS " + std::to_string(npts));
  if (npts == 0) fail(path, 4, "empty data: NPTS = 0");
  if (!(dt > 0.0)) fail(path, 4, "non-positive DT " + in_quotes(dt_tok));
}

}  // namespace

std::vector<Component> read_at2(const std::string& path, std::string_view data) {
  const std::vector<Line> lines = split_lines(data);
  check_at2_header(path, lines);
  long long npts = -1;
  double dt = 0.0;
  at2_npts_dt(path, lines[3].text, npts, dt);

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
      c.accel.push_back(scaled_or_fail(number_or_fail(tok, path, ln.number), scale, path, ln.number));
      any = true;
    });
    if (any) last_data_line = ln.number;
  }
  return npts_checked(std::move(c), want, path, last_data_line);
}

}  // namespace rocking_monitor::core::record_io
