// What the station files share: text helpers and errors naming file and line, azimuth arithmetic,
// number fields, station ids, and the rule that adds a component to a station (duplicates,
// too many components and mismatched labels are errors).
#include "rocking_monitor/motion/station.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <system_error>
#include <utility>

#include "rocking_monitor/constants.hpp"

#include "station_internal.hpp"

namespace rocking_monitor::core::station_io {

namespace fs = std::filesystem;

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  std::size_t b = 0;
  std::size_t e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

/// Upper case, trimmed, without a leading '-' / '_' (PEER file names write "-N", "-UP").
std::string normalised_label(const std::string& label) {
  std::string l = upper(trim(label));
  while (!l.empty() && (l[0] == '-' || l[0] == '_')) l.erase(0, 1);
  return l;
}

std::string base_name(const std::string& path) { return fs::path(path).filename().string(); }

std::string squote(const std::string& s) { return "'" + s + "'"; }

[[noreturn]] void fail(const std::string& where, std::size_t line, const std::string& problem) {
  std::string msg = where;
  if (line > 0) msg += ":" + std::to_string(line);
  msg += ": " + problem;
  throw StationError(msg);
}

/// cos of an angle in degrees; exact (0, +-1) at whole multiples of 90 deg so that rotations by
/// 0/90/180/270 deg copy or negate samples without rounding.
double cos_deg(double deg) {
  double r = std::fmod(deg, 360.0);
  if (r < 0.0) r += 360.0;
  if (r == 0.0) return 1.0;
  if (r == 90.0 || r == 270.0) return 0.0;
  if (r == 180.0) return -1.0;
  return std::cos(r * kPi / 180.0);
}

std::string deg_text(double deg) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", deg);
  return buf;
}

/// Two horizontals closer than this (or to anti-parallel) cannot resolve the horizontal motion.

double normalise_azimuth(double deg) {
  double r = std::fmod(deg, 360.0);
  if (r < 0.0) r += 360.0;
  if (r >= 360.0) r -= 360.0;  // fmod of a tiny negative value + 360 can round to 360
  return r;
}

/// Smallest angle between two azimuths, degrees in [0, 180].
double azimuth_difference(double a, double b) {
  const double d = normalise_azimuth(a - b);
  return d > 180.0 ? 360.0 - d : d;
}

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, 0, "cannot open file");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) fail(path, 0, "cannot read file");
  return ss.str();
}

bool parse_double(const std::string& s, double& out) {
  const std::string t = trim(s);
  if (t.empty()) return false;
  const char* b = t.data();
  const char* e = t.data() + t.size();
  if (*b == '+') ++b;
  const auto res = std::from_chars(b, e, out);
  return res.ec == std::errc() && res.ptr == e && std::isfinite(out);
}

bool parse_size(const std::string& s, std::size_t& out) {
  const std::string t = trim(s);
  if (t.empty()) return false;
  unsigned long long v = 0;
  const auto res = std::from_chars(t.data(), t.data() + t.size(), v);
  if (res.ec != std::errc() || res.ptr != t.data() + t.size()) return false;
  out = static_cast<std::size_t>(v);
  return true;
}

/// Assigns unique ids "<event>/<slug>" (a suffix _2, _3, ... on collisions, in listing order).
void assign_ids(std::vector<StationInfo>& stations) {
  std::set<std::string> used;
  for (StationInfo& s : stations) {
    const std::string base = slugify(s.event) + "/" + slugify(s.station);
    s.id = base;
    for (int k = 2; used.count(s.id) > 0; ++k) s.id = base + "_" + std::to_string(k);
    used.insert(s.id);
  }
}

void add_component(StationInfo& st, StationComponent c, const std::string& where) {
  auto& list = c.vertical ? st.verticals : st.horizontals;
  for (const StationComponent& other : list) {
    if (other.file == c.file && normalised_label(other.label) == normalised_label(c.label)) {
      fail(where, c.manifest_line, "component " + squote(c.label) + " of " + base_name(c.file) + " is listed twice for station " + squote(st.station));
    }
  }
  const std::size_t limit = c.vertical ? 1 : 2;
  if (list.size() >= limit) {
    std::string names;
    for (const StationComponent& other : list) names += base_name(other.file) + " [" + other.label + "], ";
    names += base_name(c.file) + " [" + c.label + "]";
    fail(where, c.manifest_line,
         "station " + squote(st.station) + " has more than " + std::to_string(limit) + (c.vertical ? " vertical" : " horizontal") +
             " component" + (limit > 1 ? "s" : "") + ": " + names);
  }
  list.push_back(std::move(c));
}

bool same_label(const std::string& a, const std::string& b) {
  const std::optional<double> aa = label_azimuth_deg(a);
  const std::optional<double> ab = label_azimuth_deg(b);
  if (aa && ab) return azimuth_difference(*aa, *ab) < 1e-9;
  return normalised_label(a) == normalised_label(b);
}

}  // namespace rocking_monitor::core::station_io
