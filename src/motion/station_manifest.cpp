// Stations from a records directory's MANIFEST.csv (read through the csv layer): one row per
// component file, its event, station, component label and optional dt/npts checks.
#include "rocking_monitor/motion/station.hpp"

#include <filesystem>
#include <map>
#include <utility>

#include "rocking_monitor/constants.hpp"

#include "rocking_monitor/csv/csv_reader.hpp"

#include "station_internal.hpp"

namespace rocking_monitor::core::station_io {

namespace fs = std::filesystem;

namespace {

/// The manifest's rows (csv layer); its errors become StationErrors with the same file:line text.
std::vector<csv::Row> parse_manifest(const std::string& data, const std::string& path) {
  try {
    return csv::parse(data, path);
  } catch (const csv::CsvError& e) {
    throw StationError(e.what());
  }
}

}  // namespace

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

}  // namespace rocking_monitor::core::station_io
