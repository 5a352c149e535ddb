// Plain tables: rows "time accel [accel_v]" separated by commas or white space, one header line and
// '#' comments allowed, units from the caller (g, m/s^2, cm/s^2).
#include "record_reader_internal.hpp"

#include "rocking_monitor/constants.hpp"

#include <string_view>
#include <utility>

namespace rocking_monitor::core::record_io {

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
    h.push_back(scaled_or_fail(number_or_fail(toks[1], path, ln.number), scale, path, ln.number));
    if (ncols == 3) v.push_back(scaled_or_fail(number_or_fail(toks[2], path, ln.number), scale, path, ln.number));
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

}  // namespace rocking_monitor::core::record_io
