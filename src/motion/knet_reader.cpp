// K-NET / KiK-net ASCII records (NIED, "About K-NET ASCII format"): 17 header lines, a name in
// columns 1-18 and its value from column 19, then integer counts, 8 per line. One component per
// file (.NS .EW .UD; KiK-net .NS1 .EW1 .UD1 borehole, .NS2 .EW2 .UD2 surface).
//  * acceleration (gal) = counts x Scale Factor "<a>(gal)/<b>" = counts x a / b, in m/s^2 / 100;
//  * the mean of the whole record is subtracted: the counts carry the logger's offset (thousands of
//    counts in NIED's example), and NIED's "Max. Acc. (gal)" is defined on the record with its
//    whole-record average removed. That peak is checked against the data (a truncated file or a
//    wrong scale factor shows there);
//  * Dir.: N-S, E-W, U-D (K-NET) or the KiK-net channel number 1-6 (1/4 N-S, 2/5 E-W, 3/6 U-D).
#include <cmath>

#include "record_reader_internal.hpp"

namespace rocking_monitor::core::record_io {

namespace {

struct HeaderKey {
  const char* names[2];  // accepted spellings (NIED wrote "Long." and "Max. Acc." in older files)
};

const HeaderKey kHeader[17] = {
    {{"Origin Time", nullptr}},
    {{"Lat.", nullptr}},
    {{"Lon.", "Long."}},
    {{"Depth. (km)", nullptr}},
    {{"Mag.", nullptr}},
    {{"Station Code", nullptr}},
    {{"Station Lat.", nullptr}},
    {{"Station Lon.", "Station Long."}},
    {{"Station Height(m)", nullptr}},
    {{"Record Time", nullptr}},
    {{"Sampling Freq(Hz)", nullptr}},
    {{"Duration Time(s)", nullptr}},
    {{"Dir.", nullptr}},
    {{"Scale Factor", nullptr}},
    {{"Max. Acc. (gal)", "Max Acc. (gal)"}},
    {{"Last Correction", nullptr}},
    {{"Memo.", nullptr}},
};

/// The value after the header name, or fails naming the line and the name expected.
std::string_view header_value(const Line& ln, const HeaderKey& key, const std::string& path) {
  for (const char* name : key.names) {
    if (name == nullptr) continue;
    const std::string_view n(name);
    if (ln.text.substr(0, n.size()) == n) return trim(ln.text.substr(n.size()));
  }
  fail(path, ln.number,
       std::string("bad K-NET header: expected '") + key.names[0] + "', found " + in_quotes(trim(ln.text)));
}

// Sampling Freq(Hz): "100Hz".
double knet_rate(const std::string& path, const Line& line, std::string_view value) {
  std::string_view f = value;
  if (f.size() > 2 && upper(f.substr(f.size() - 2)) == "HZ") f.remove_suffix(2);
  double rate = 0.0;
  if (parse_number(trim(f), rate) != NumStatus::Ok || !(rate > 0.0)) {
    fail(path, line.number, "bad sampling frequency " + in_quotes(value));
  }
  return rate;
}

// Dir.: K-NET's N-S, E-W, U-D or a KiK-net channel 1-6 (4-6 at the surface).
std::string knet_direction(const std::string& path, const Line& line, std::string_view value) {
  const std::string dir = upper(value);
  if (dir == "N-S" || dir == "1" || dir == "4") return "N";
  if (dir == "E-W" || dir == "2" || dir == "5") return "E";
  if (dir == "U-D" || dir == "3" || dir == "6") return "UP";
  fail(path, line.number, "unknown direction " + in_quotes(value) + " (N-S, E-W, U-D or a KiK-net channel 1-6)");
}

// Scale Factor: "<a>(gal)/<b>" -> a / b gal per count.
double knet_gal_per_count(const std::string& path, const Line& line, std::string_view sf) {
  const std::size_t open = sf.find('(');
  const std::size_t close = sf.find(')');
  const std::size_t slash = sf.find('/', close == std::string_view::npos ? 0 : close);
  double num = 0.0, den = 0.0;
  if (open == std::string_view::npos || close == std::string_view::npos || slash == std::string_view::npos ||
      close < open || upper(sf.substr(open, close - open + 1)) != "(GAL)" ||
      parse_number(trim(sf.substr(0, open)), num) != NumStatus::Ok ||
      parse_number(trim(sf.substr(slash + 1)), den) != NumStatus::Ok || !(num > 0.0) || !(den > 0.0)) {
    fail(path, line.number, "bad scale factor " + in_quotes(sf) + " (expected '<a>(gal)/<b>' with a, b > 0)");
  }
  return num / den;
}

// Counts: integers, 8 per line (the last line may hold fewer). `last_line`: the last data line's number.
std::vector<long long> knet_counts(const std::string& path, const std::vector<Line>& lines, std::size_t data_size,
                                   std::size_t& last_line) {
  std::vector<long long> counts;
  counts.reserve(data_size / 9 + 1);
  last_line = 17;
  std::size_t short_line = 0;  // a line with fewer than 8 values: only the last may have it
  for (std::size_t li = 17; li < lines.size(); ++li) {
    const Line& ln = lines[li];
    if (is_blank(ln.text)) continue;
    if (short_line != 0) fail(path, short_line, "only the last data line may hold fewer than 8 values");
    std::size_t n = 0;
    for_each_ws_token(ln.text, [&](std::string_view tok) {
      long long x = 0;
      if (!parse_integer(tok, x)) fail(path, ln.number, "not an integer count: " + in_quotes(tok));
      counts.push_back(x);
      ++n;
    });
    if (n > 8) fail(path, ln.number, "more than 8 values on a line (" + std::to_string(n) + ")");
    if (n < 8) short_line = ln.number;
    last_line = ln.number;
  }
  if (counts.empty()) fail(path, lines[16].number, "no data after the header");
  return counts;
}

// The counts, mean removed, in m/s^2 into c.accel. Returns their peak, gal.
double knet_accelerations(const std::string& path, const std::vector<long long>& counts, double gal_per_count,
                          const Line& scale_line, Component& c) {
  long double sum = 0.0L;
  for (long long x : counts) sum += static_cast<long double>(x);
  const double mean = static_cast<double>(sum / static_cast<long double>(counts.size()));
  c.accel.reserve(counts.size());
  double peak_gal = 0.0;
  for (long long x : counts) {
    const double gal = (static_cast<double>(x) - mean) * gal_per_count;
    peak_gal = std::max(peak_gal, std::abs(gal));
    c.accel.push_back(scaled_or_fail(gal, 0.01, path, scale_line.number));  // the Scale Factor line
  }
  return peak_gal;
}

}  // namespace

std::vector<Component> read_knet(const std::string& path, std::string_view data) {
  const std::vector<Line> lines = split_lines(data);
  if (lines.size() < 17) {
    fail(path, lines.empty() ? 0 : lines.back().number,
         "file ends inside the K-NET header (17 lines needed, " + std::to_string(lines.size()) + " found)");
  }
  std::string_view v[17];
  for (std::size_t i = 0; i < 17; ++i) v[i] = header_value(lines[i], kHeader[i], path);

  Component c;
  c.file = path;
  c.station = std::string(v[5]);
  c.event = std::string(v[0]);
  c.dt = 1.0 / knet_rate(path, lines[10], v[10]);
  c.label = knet_direction(path, lines[12], v[12]);
  c.vertical = c.label == "UP";
  const double gal_per_count = knet_gal_per_count(path, lines[13], v[13]);
  double max_acc = 0.0;
  if (parse_number(v[14], max_acc) != NumStatus::Ok || max_acc < 0.0) {
    fail(path, lines[14].number, "bad maximum acceleration " + in_quotes(v[14]));
  }
  std::size_t last_line = 17;
  const std::vector<long long> counts = knet_counts(path, lines, data.size(), last_line);
  const double peak_gal = knet_accelerations(path, counts, gal_per_count, lines[13], c);
  // NIED prints the peak rounded; allow that and half a count.
  const double allowance = printed_resolution(v[14]) + 0.5 * gal_per_count + 1e-9 * max_acc;
  if (std::abs(peak_gal - max_acc) > allowance) {
    fail(path, last_line,
         "the data's peak (" + std::to_string(peak_gal) + " gal, mean removed) differs from Max. Acc. " +
             std::to_string(max_acc) + " gal (line " + std::to_string(lines[14].number) +
             "): truncated file or wrong scale factor");
  }
  std::vector<Component> out;
  out.push_back(std::move(c));
  return out;
}

}  // namespace rocking_monitor::core::record_io
