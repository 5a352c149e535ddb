// Listing stations: from MANIFEST.csv when there is one, else from file names; a station from
// explicit files; finding one station by id, name, file name or a unique part of it.
#include "rocking_monitor/motion/station.hpp"

#include <filesystem>
#include <system_error>
#include <utility>

#include "rocking_monitor/constants.hpp"

#include "station_internal.hpp"

namespace rocking_monitor::core {

namespace fs = std::filesystem;
using namespace station_io;

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

}  // namespace rocking_monitor::core
