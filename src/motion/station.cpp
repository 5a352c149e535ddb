// Stations: grouping of components (MANIFEST.csv or file names), loading, rotation.
// See include/rocking_monitor/motion/station.hpp for the conventions.

#include "rocking_monitor/motion/station.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <system_error>
#include <utility>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/csv/csv_reader.hpp"

namespace rocking_monitor::core {

namespace fs = std::filesystem;

namespace {

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
constexpr double kMinSeparationDeg = 10.0;

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

// ------------------------------------------------------------------ MANIFEST.csv

/// The manifest's rows (csv layer); its errors become StationErrors with the same file:line text.
std::vector<csv::Row> parse_manifest(const std::string& data, const std::string& path) {
  try {
    return csv::parse(data, path);
  } catch (const csv::CsvError& e) {
    throw StationError(e.what());
  }
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

StationListing list_from_manifest(const std::string& dir, const std::string& manifest) {
  const std::vector<csv::Row> rows = parse_manifest(read_text_file(manifest), manifest);
  if (rows.empty()) fail(manifest, 0, "empty manifest (no header line)");
  const std::vector<std::string>& header = rows[0].fields;
  const std::map<std::string, std::size_t> col = csv::column_index(rows[0], true);
  for (const char* required : {"event", "station", "component", "file"}) {
    if (col.count(required) == 0) fail(manifest, rows[0].line, std::string("missing column '") + required + "' in the header");
  }
  StationListing listing;
  listing.records_dir = dir;
  listing.source = StationSource::Manifest;
  std::map<std::pair<std::string, std::string>, std::size_t> index;  // (event, station) -> position
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const csv::Row& row = rows[r];
    if (row.fields.size() != header.size()) {
      fail(manifest, row.line,
           "expected " + std::to_string(header.size()) + " fields like the header, found " + std::to_string(row.fields.size()) +
               " (quote fields that contain commas)");
    }
    auto field = [&](const char* name) { return trim(row.fields[col.at(name)]); };
    const std::string event = field("event");
    const std::string station = field("station");
    const std::string component = field("component");
    const std::string file = field("file");
    if (event.empty()) fail(manifest, row.line, "empty 'event'");
    if (station.empty()) fail(manifest, row.line, "empty 'station'");
    if (file.empty()) fail(manifest, row.line, "empty 'file'");
    StationComponent c;
    c.manifest_line = row.line;
    const std::string up = upper(component);
    if (up.size() > 2 && (up.compare(0, 2, "H:") == 0 || up.compare(0, 2, "V:") == 0)) {
      c.vertical = up[0] == 'V';
      c.label = trim(component.substr(2));
    } else {
      fail(manifest, row.line, "component " + squote(component) + " must start with 'H:' (horizontal) or 'V:' (vertical)");
    }
    if (c.vertical != label_is_vertical(c.label)) {
      fail(manifest, row.line, "component " + squote(component) + ": the label says " +
                                   (label_is_vertical(c.label) ? "vertical" : "horizontal") + " but the prefix does not");
    }
    c.file = (fs::path(dir) / file).lexically_normal().string();
    if (col.count("dt_s") != 0 && !field("dt_s").empty() && !parse_double(field("dt_s"), c.manifest_dt)) {
      fail(manifest, row.line, "non-numeric dt_s " + squote(field("dt_s")));
    }
    if (col.count("npts") != 0 && !field("npts").empty() && !parse_size(field("npts"), c.manifest_npts)) {
      fail(manifest, row.line, "non-integer npts " + squote(field("npts")));
    }
    const auto key = std::make_pair(event, station);
    auto it = index.find(key);
    if (it == index.end()) {
      StationInfo st;
      st.event = event;
      st.station = station;
      st.source = StationSource::Manifest;
      listing.stations.push_back(std::move(st));
      it = index.emplace(key, listing.stations.size() - 1).first;
    }
    add_component(listing.stations[it->second], std::move(c), manifest);
  }
  assign_ids(listing.stations);
  return listing;
}

// ------------------------------------------------------------------ grouping by file name

struct NameParts {
  std::string code;   ///< station code ("CHY002", "H-BRA", "Rinaldi")
  std::string label;  ///< component label ("N", "090", "UP")
  std::string rsn;    ///< "1180" for RSN files, else empty
};

/// Splits an AT2 file stem into station code and component; false when the name has no component.
bool split_at2_name(const std::string& stem, NameParts& out) {
  static const std::regex rsn_re("^RSN([0-9]+)_(.+)_([^_]+)$", std::regex::icase);
  static const std::regex vert_re("^(.*[^-])-?(UP|DWN|DOWN)$", std::regex::icase);
  static const std::regex compass_re("^(.+)-([NESW])$", std::regex::icase);
  static const std::regex digits_re("^(.+?)-?([0-9]{3})$", std::regex::icase);
  std::string tail = stem;
  std::smatch m;
  out = NameParts{};
  if (std::regex_match(stem, m, rsn_re)) {
    out.rsn = m[1].str();
    tail = m[3].str();
  }
  if (std::regex_match(tail, m, vert_re) || std::regex_match(tail, m, compass_re) || std::regex_match(tail, m, digits_re)) {
    out.code = m[1].str();
    out.label = upper(m[2].str());
    return !out.code.empty();
  }
  return false;
}

StationListing list_from_file_names(const std::string& dir) {
  StationListing listing;
  listing.records_dir = dir;
  listing.source = StationSource::FileNames;
  std::map<std::string, StationInfo> groups;  // key -> station (sorted by key for a stable order)
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, fs::directory_options::follow_directory_symlink, ec), end; it != end;
       it.increment(ec)) {
    if (ec) break;
    if (it->is_regular_file(ec)) files.push_back(it->path());
  }
  if (ec) fail(dir, 0, "cannot list directory (" + ec.message() + ")");
  std::sort(files.begin(), files.end());
  for (const fs::path& p : files) {
    const std::string ext = lower(p.extension().string());
    const std::string path = p.lexically_normal().string();
    fs::path rel = p.lexically_relative(dir).parent_path();
    const std::string event = rel.empty() ? fs::path(dir).filename().string() : rel.string();
    const std::string stem = p.stem().string();
    if (p.filename() == "MANIFEST.csv") {
      listing.ignored_files.push_back(path);  // asked to ignore it (ignore_manifest)
    } else if (ext == ".at2") {
      NameParts parts;
      StationComponent c;
      c.file = path;
      std::string key;
      std::string name;
      if (split_at2_name(stem, parts)) {
        c.label = parts.label;
        name = parts.code;
        key = event + "|" + (parts.rsn.empty() ? "" : "RSN" + parts.rsn + "|") + upper(parts.code);
      } else {
        // no component in the name: a station of its own, label from the header
        const std::vector<Component> comps = read_record(path);
        c.label = comps.at(0).label;
        name = stem;
        key = event + "|file|" + stem;
      }
      c.vertical = label_is_vertical(c.label);
      StationInfo& st = groups[key];
      if (st.station.empty()) {
        st.event = event;
        st.station = name;
        st.source = StationSource::FileNames;
      }
      add_component(st, std::move(c), path);
    } else if (ext == ".bbp") {
      StationInfo& st = groups[event + "|bbp|" + stem];
      st.event = event;
      st.station = stem;
      st.source = StationSource::FileNames;
      for (const char* label : {"N-S", "E-W", "U-D"}) {
        StationComponent c;
        c.file = path;
        c.label = label;
        c.vertical = label_is_vertical(label);
        add_component(st, std::move(c), path);
      }
    } else if (ext == ".smc" || ext == ".v2" || ext == ".csv") {
      // SMC names (0111a.smc) do not tell the station; CSV files are one station each: read them.
      const std::vector<Component> comps = read_record(path);
      const bool smc = ext != ".csv";
      const std::string name = smc && !comps.at(0).station.empty() ? comps.at(0).station : stem;
      StationInfo& st = groups[event + (smc ? "|smc|" : "|csv|") + (smc ? name : stem)];
      st.event = event;
      st.station = name;
      st.source = StationSource::FileNames;
      for (const Component& comp : comps) {
        StationComponent c;
        c.file = path;
        c.label = comp.label;
        c.vertical = comp.vertical;
        add_component(st, std::move(c), path);
      }
    } else {
      listing.ignored_files.push_back(path);
    }
  }
  for (auto& kv : groups) listing.stations.push_back(std::move(kv.second));
  assign_ids(listing.stations);
  std::sort(listing.stations.begin(), listing.stations.end(),
            [](const StationInfo& a, const StationInfo& b) { return a.id < b.id; });
  return listing;
}

bool same_label(const std::string& a, const std::string& b) {
  const std::optional<double> aa = label_azimuth_deg(a);
  const std::optional<double> ab = label_azimuth_deg(b);
  if (aa && ab) return azimuth_difference(*aa, *ab) < 1e-9;
  return normalised_label(a) == normalised_label(b);
}

}  // namespace

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

// ------------------------------------------------------------------ listing

StationListing list_stations(const std::string& records_dir, const StationListOptions& options) {
  std::error_code ec;
  if (!fs::is_directory(records_dir, ec)) fail(records_dir, 0, "not a directory (records directory)");
  const fs::path manifest = fs::path(records_dir) / "MANIFEST.csv";
  if (!options.ignore_manifest && fs::exists(manifest, ec)) return list_from_manifest(records_dir, manifest.string());
  return list_from_file_names(records_dir);
}

StationInfo station_from_files(const std::vector<std::string>& files, const ReadOptions& options) {
  if (files.empty()) throw StationError("station_from_files: no file given");
  StationInfo st;
  st.source = StationSource::Files;
  for (const std::string& f : files) {
    const std::vector<Component> comps = read_record(f, options);
    for (const Component& comp : comps) {
      if (st.station.empty()) st.station = comp.station;
      if (st.event.empty()) st.event = comp.event;
      StationComponent c;
      c.file = f;
      c.label = comp.label;
      c.vertical = comp.vertical;
      add_component(st, std::move(c), f);
    }
  }
  if (st.station.empty()) st.station = fs::path(files.front()).stem().string();
  st.id = slugify(st.event.empty() ? std::string("files") : st.event) + "/" + slugify(st.station);
  return st;
}

const StationInfo& find_station(const StationListing& listing, const std::string& query) {
  const std::string q = lower(trim(query));
  if (q.empty()) throw StationError("station name is empty");
  std::vector<const StationInfo*> hits;
  auto collect = [&](auto&& pred) {
    hits.clear();
    for (const StationInfo& s : listing.stations) {
      if (pred(s)) hits.push_back(&s);
    }
    return hits.size();
  };
  auto full = [](const StationInfo& s) { return lower(s.event + "/" + s.station); };
  if (collect([&](const StationInfo& s) { return lower(s.id) == q; }) == 1) return *hits[0];
  if (collect([&](const StationInfo& s) { return lower(s.station) == q || full(s) == q; }) == 1) return *hits[0];
  if (hits.empty()) {
    auto has_file = [&](const StationInfo& s) {
      for (const auto* list : {&s.horizontals, &s.verticals}) {
        for (const StationComponent& c : *list) {
          if (lower(base_name(c.file)) == q || lower(c.file) == q) return true;
        }
      }
      return false;
    };
    if (collect(has_file) == 1) return *hits[0];
  }
  if (hits.empty()) {
    collect([&](const StationInfo& s) { return full(s).find(q) != std::string::npos || lower(s.id).find(q) != std::string::npos; });
    if (hits.size() == 1) return *hits[0];
  }
  if (hits.empty()) {
    throw StationError(listing.records_dir + ": no station matches " + squote(query) + " (" +
                       std::to_string(listing.stations.size()) + " stations; list them with --list)");
  }
  std::string names;
  for (std::size_t k = 0; k < hits.size() && k < 8; ++k) names += (k ? ", " : "") + hits[k]->id;
  if (hits.size() > 8) names += ", ...";
  throw StationError(listing.records_dir + ": " + std::to_string(hits.size()) + " stations match " + squote(query) +
                     ", give one of: " + names);
}

// ------------------------------------------------------------------ loading

StationRecord load_station(const StationInfo& info, const ReadOptions& options) {
  StationRecord rec;
  rec.info = info;
  std::map<std::string, std::vector<Component>> cache;
  auto where = [&](const StationComponent& c) {
    return c.manifest_line > 0 ? "MANIFEST.csv:" + std::to_string(c.manifest_line) + ": " : std::string();
  };
  auto take = [&](const StationComponent& ref) -> Component {
    auto it = cache.find(ref.file);
    if (it == cache.end()) it = cache.emplace(ref.file, read_record(ref.file, options)).first;
    const std::vector<Component>& comps = it->second;
    const Component* found = nullptr;
    if (comps.size() == 1) {
      found = &comps[0];
    } else {
      for (const Component& c : comps) {
        if (c.vertical == ref.vertical && same_label(c.label, ref.label)) found = &c;
      }
    }
    if (found == nullptr) {
      std::string have;
      for (const Component& c : comps) have += (have.empty() ? "" : ", ") + c.label;
      throw StationError(where(ref) + ref.file + ": no component labelled " + squote(ref.label) + " (the file has " + have + ")");
    }
    if (found->vertical != ref.vertical) {
      throw StationError(where(ref) + ref.file + ": listed as " + (ref.vertical ? "vertical" : "horizontal") +
                         " but the header label " + squote(found->label) + " says otherwise");
    }
    if (!same_label(found->label, ref.label)) {
      rec.notes.push_back(base_name(ref.file) + ": " + (ref.manifest_line > 0 ? "manifest" : "file name") + " says " +
                          squote(ref.label) + ", header says " + squote(found->label) + "; the header is used");
    }
    if (ref.manifest_npts > 0 && ref.manifest_npts != found->accel.size()) {
      rec.notes.push_back(base_name(ref.file) + " [" + found->label + "]: manifest npts " + std::to_string(ref.manifest_npts) +
                          ", file holds " + std::to_string(found->accel.size()) + " samples (all used)");
    }
    if (ref.manifest_dt > 0.0 && std::fabs(ref.manifest_dt - found->dt) > 1e-6 * found->dt) {
      char buf[160];
      std::snprintf(buf, sizeof buf, ": manifest dt %.9g s, file %.9g s (file used)", ref.manifest_dt, found->dt);
      rec.notes.push_back(base_name(ref.file) + " [" + found->label + "]" + buf);
    }
    return *found;
  };
  for (const StationComponent& h : info.horizontals) rec.horizontals.push_back(take(h));
  if (!info.verticals.empty()) rec.vertical = take(info.verticals.front());

  // Files put together by hand (--file a --file b) may come from different stations: say so.
  std::vector<const Component*> all;
  for (const Component& c : rec.horizontals) all.push_back(&c);
  if (rec.vertical) all.push_back(&*rec.vertical);
  for (const Component* c : all) {
    if (!c->station.empty() && !all.front()->station.empty() && lower(trim(c->station)) != lower(trim(all.front()->station))) {
      rec.notes.push_back("the headers name different stations: " + squote(all.front()->station) + " (" + base_name(all.front()->file) +
                          ") and " + squote(c->station) + " (" + base_name(c->file) + ")");
      break;
    }
  }

  if (rec.horizontals.size() == 2) {
    const auto a0 = label_azimuth_deg(rec.horizontals[0].label);
    const auto a1 = label_azimuth_deg(rec.horizontals[1].label);
    if (a0 && a1) {
      // want h1 counter-clockwise of h0 (h1 = h0 - 90 deg when orthogonal): (h0, h1, up) right-handed
      const double d = normalise_azimuth(*a1 - *a0);
      if (d > 0.0 && d < 180.0) std::swap(rec.horizontals[0], rec.horizontals[1]);
      const double sep = azimuth_difference(*a0, *a1);
      if (std::fabs(sep - 90.0) > 1e-6) {
        rec.notes.push_back("horizontals " + base_name(rec.horizontals[0].file) + " [" + rec.horizontals[0].label + "] and " +
                            base_name(rec.horizontals[1].file) + " [" + rec.horizontals[1].label + "] are " +
                            deg_text(sep) + " deg apart, not orthogonal");
      }
    } else {
      rec.notes.push_back("the horizontal labels " + squote(rec.horizontals[0].label) + " and " + squote(rec.horizontals[1].label) +
                          " carry no azimuth: orientation unknown, listing order kept");
    }
  }
  return rec;
}

// ------------------------------------------------------------------ rotation

RotatedPair rotate(const Component& a, const Component& b, double azimuth_deg) {
  auto name = [](const Component& c) { return base_name(c.file) + " [" + c.label + "]"; };
  const std::string both = name(a) + " and " + name(b);
  if (!std::isfinite(azimuth_deg)) throw StationError("rotate " + both + ": azimuth is not finite");
  if (a.vertical || b.vertical) throw StationError("rotate " + both + ": only horizontal components can be rotated");
  if (a.dt != b.dt) {
    char buf[128];
    std::snprintf(buf, sizeof buf, ": different sample intervals (%.9g s and %.9g s)", a.dt, b.dt);
    throw StationError("rotate " + both + buf);
  }
  if (a.accel.size() != b.accel.size()) {
    throw StationError("rotate " + both + ": different lengths (" + std::to_string(a.accel.size()) + " and " +
                       std::to_string(b.accel.size()) + " samples)");
  }
  if (std::fabs(a.t0 - b.t0) > 1e-9 * std::max(1.0, std::fabs(a.t0))) {
    throw StationError("rotate " + both + ": different start times");
  }
  const auto az_a = label_azimuth_deg(a.label);
  const auto az_b = label_azimuth_deg(b.label);
  if (!az_a || !az_b) {
    throw StationError("rotate " + both + ": the label " + squote(!az_a ? a.label : b.label) + " carries no azimuth");
  }
  const double separation = azimuth_difference(*az_a, *az_b);
  if (separation < kMinSeparationDeg || separation > 180.0 - kMinSeparationDeg) {
    throw StationError("rotate " + both + ": components are nearly parallel (" + deg_text(separation) +
                       " deg apart), the horizontal motion cannot be resolved");
  }
  // Weights of a and b in the ground acceleration along an azimuth `t` (degrees).
  double ca = 0.0, cb = 0.0, la = 0.0, lb = 0.0;
  if (std::fabs(separation - 90.0) <= 1e-6) {
    // Orthogonal: along(t) = a cos(t - az_a) + b cos(t - az_b), exact at multiples of 90 deg.
    ca = cos_deg(azimuth_deg - *az_a);
    cb = cos_deg(azimuth_deg - *az_b);
    la = cos_deg(azimuth_deg - 90.0 - *az_a);
    lb = cos_deg(azimuth_deg - 90.0 - *az_b);
  } else {
    // Not orthogonal (e.g. Lucerne 260/345, 85 deg apart): a = g.u_a, b = g.u_b with u(az) =
    // (sin az, cos az) in (east, north); solve for g, then project: along(t) = g.u(t), i.e.
    // along(t) = [a sin(az_b - t) - b sin(az_a - t)] / sin(az_b - az_a).
    const double det = std::sin((*az_b - *az_a) * kPi / 180.0);
    auto sin_deg = [](double d) { return std::sin(d * kPi / 180.0); };
    ca = sin_deg(*az_b - azimuth_deg) / det;
    cb = -sin_deg(*az_a - azimuth_deg) / det;
    la = sin_deg(*az_b - (azimuth_deg - 90.0)) / det;
    lb = -sin_deg(*az_a - (azimuth_deg - 90.0)) / det;
  }
  RotatedPair out;
  out.along = a;
  out.left = a;
  out.along.label = format_azimuth_label(azimuth_deg);
  out.left.label = format_azimuth_label(azimuth_deg - 90.0);
  const std::size_t n = a.accel.size();
  for (std::size_t i = 0; i < n; ++i) {
    out.along.accel[i] = a.accel[i] * ca + b.accel[i] * cb;
    out.left.accel[i] = a.accel[i] * la + b.accel[i] * lb;
  }
  return out;
}

}  // namespace rocking_monitor::core
