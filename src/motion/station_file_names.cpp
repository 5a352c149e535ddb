// Stations from file names when a directory has no MANIFEST.csv: PEER RSN names, older AT2 names
// (station code + component), K-NET/KiK-net names (<code><time>.NS/.EW/.UD[1|2]), SMC, COSMOS,
// miniSEED and CSV files read for their station; one group per station.
#include "rocking_monitor/motion/station.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>
#include <system_error>
#include <utility>

#include "rocking_monitor/constants.hpp"

#include "station_internal.hpp"

namespace rocking_monitor::core::station_io {

namespace fs = std::filesystem;

namespace {

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

bool is_knet_extension(const std::string& ext) {
  static const char* const names[] = {".ns", ".ew", ".ud", ".ns1", ".ew1", ".ud1", ".ns2", ".ew2", ".ud2"};
  for (const char* n : names) {
    if (ext == n) return true;
  }
  return false;
}

using StationGroups = std::map<std::string, StationInfo>;  // key -> station (sorted by key for a stable order)

// Every regular file below `dir`, sorted.
std::vector<fs::path> files_below(const std::string& dir) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, fs::directory_options::follow_directory_symlink, ec), end; it != end;
       it.increment(ec)) {
    if (ec) break;
    if (it->is_regular_file(ec)) files.push_back(it->path());
  }
  if (ec) fail(dir, 0, "cannot list directory (" + ec.message() + ")");
  std::sort(files.begin(), files.end());
  return files;
}

// An AT2 file: its station and component from the name (RSN, code, component), else a station of
// its own with the header's label.
void add_at2(StationGroups& groups, const std::string& path, const std::string& event, const std::string& stem) {
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
}

// A BBP file: one station, its three components.
void add_bbp(StationGroups& groups, const std::string& path, const std::string& event, const std::string& stem) {
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
}

// K-NET: <code><yymmddhhmm>.NS/.EW/.UD, one component each; KiK-net .NS1.. (borehole) and
// .NS2.. (surface) are two sensors, two stations.
void add_knet(StationGroups& groups, const std::string& path, const std::string& event, const std::string& stem,
              const std::string& ext) {
  const std::vector<Component> comps = read_record(path);
  const char depth = ext.size() == 4 ? ext[3] : '\0';
  std::string name = comps.at(0).station.empty() ? stem : comps.at(0).station;
  if (depth == '1') name += " borehole";
  if (depth == '2') name += " surface";
  StationInfo& st = groups[event + "|knet|" + stem + "|" + std::string(1, depth)];
  st.event = event;
  st.station = name;
  st.source = StationSource::FileNames;
  StationComponent c;
  c.file = path;
  c.label = comps.at(0).label;
  c.vertical = comps.at(0).vertical;
  add_component(st, std::move(c), path);
}

bool is_read_for_station(const std::string& ext) {
  return ext == ".smc" || ext == ".v2" || ext == ".v2c" || ext == ".csv" || ext == ".mseed" || ext == ".miniseed" ||
         ext == ".ms";
}

// SMC names (0111a.smc) do not tell the station, nor do COSMOS or miniSEED names; CSV files
// are one station each: read them (miniSEED: gain and azimuths from CHANNELS.csv beside it).
void add_read_station(StationGroups& groups, const std::string& path, const std::string& event, const std::string& stem,
                      const std::string& ext) {
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
}

}  // namespace

StationListing list_from_file_names(const std::string& dir) {
  StationListing listing;
  listing.records_dir = dir;
  listing.source = StationSource::FileNames;
  StationGroups groups;
  for (const fs::path& p : files_below(dir)) {
    const std::string ext = lower(p.extension().string());
    const std::string path = p.lexically_normal().string();
    fs::path rel = p.lexically_relative(dir).parent_path();
    const std::string event = rel.empty() ? fs::path(dir).filename().string() : rel.string();
    const std::string stem = p.stem().string();
    if (p.filename() == "MANIFEST.csv") {
      listing.ignored_files.push_back(path);  // asked to ignore it (ignore_manifest)
    } else if (p.filename() == "CHANNELS.csv") {
      listing.ignored_files.push_back(path);  // the miniSEED channel table, not a record
    } else if (ext == ".at2") {
      add_at2(groups, path, event, stem);
    } else if (ext == ".bbp") {
      add_bbp(groups, path, event, stem);
    } else if (is_knet_extension(ext)) {
      add_knet(groups, path, event, stem, ext);
    } else if (is_read_for_station(ext)) {
      add_read_station(groups, path, event, stem, ext);
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

}  // namespace rocking_monitor::core::station_io
