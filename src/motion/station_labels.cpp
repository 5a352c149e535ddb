// Component labels: the azimuth a label names ("N", "090", "W", "UP" has none), its canonical text,
// and the slugs that make station ids.
#include "rocking_monitor/motion/station.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "rocking_monitor/constants.hpp"

#include "station_internal.hpp"

namespace rocking_monitor::core {

namespace fs = std::filesystem;
using namespace station_io;

// ------------------------------------------------------------------ labels

std::optional<double> label_azimuth_deg(const std::string& label) {
  const std::string l = normalised_label(label);
  if (l.empty() || label_is_vertical(label)) return std::nullopt;
  if (l == "N" || l == "NORTH" || l == "N-S" || l == "NS") return 0.0;
  if (l == "E" || l == "EAST" || l == "E-W" || l == "EW") return 90.0;
  if (l == "S" || l == "SOUTH" || l == "S-N" || l == "SN") return 180.0;
  if (l == "W" || l == "WEST" || l == "W-E" || l == "WE") return 270.0;
  // a plain non-negative number: digits with an optional fraction
  bool digits = false;
  bool dot = false;
  for (char c : l) {
    if (c >= '0' && c <= '9') {
      digits = true;
    } else if (c == '.' && !dot) {
      dot = true;
    } else {
      return std::nullopt;
    }
  }
  if (!digits) return std::nullopt;
  double v = 0.0;
  if (!parse_double(l, v)) return std::nullopt;
  return normalise_azimuth(v);
}

std::string format_azimuth_label(double azimuth_deg) {
  const double a = normalise_azimuth(azimuth_deg);
  char buf[64];
  if (a == std::floor(a)) {
    std::snprintf(buf, sizeof buf, "%03d", static_cast<int>(a));
  } else {
    std::snprintf(buf, sizeof buf, "%.10g", a);
  }
  return buf;
}

std::string slugify(const std::string& text) {
  std::string out;
  bool pending = false;
  for (char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (std::isalnum(c) && c < 0x80) {
      if (pending && !out.empty()) out.push_back('_');
      pending = false;
      out.push_back(static_cast<char>(std::tolower(c)));
    } else {
      pending = true;
    }
  }
  return out.empty() ? "station" : out;
}

}  // namespace rocking_monitor::core
