// SCEC Broadband Platform records (.bbp): time plus N-S, E-W, U-D columns in cm/s^2, '#' headers
// with the station; the first horizontal is N-S.
#include "record_reader_internal.hpp"

#include <string_view>
#include <utility>

namespace rocking_monitor::core::record_io {

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
        fail(path, ln.number, "not an acceleration file (header says " + in_quotes(body) + ")");
      }
      continue;
    }
    toks.clear();
    for_each_ws_token(t, [&](std::string_view tok) { toks.push_back(tok); });
    if (toks.size() != 4) {
      fail(path, ln.number,
           "expected 4 columns (time N-S E-W U-D), found " + std::to_string(toks.size()) + " in " + in_quotes(t));
    }
    const double time = number_or_fail(toks[0], path, ln.number);
    ts.push_back({time, printed_resolution(toks[0]), ln.number});
    for (int k = 0; k < 3; ++k) col[k].push_back(scaled_or_fail(number_or_fail(toks[static_cast<std::size_t>(k) + 1], path, ln.number), 0.01, path, ln.number));
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

}  // namespace rocking_monitor::core::record_io
