// Loading a station: reading its component files, checking them against the listing (dt, npts,
// labels), and ordering the horizontals right-handed with their azimuths.
#include "rocking_monitor/motion/station.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <utility>

#include "rocking_monitor/constants.hpp"

#include "station_internal.hpp"

namespace rocking_monitor::core {

namespace fs = std::filesystem;
using namespace station_io;

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

}  // namespace rocking_monitor::core
