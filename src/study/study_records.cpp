#include "rocking_monitor/study/study_records.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "rocking_monitor/csv/csv_reader.hpp"
#include "rocking_monitor/motion/ground_motion_integration.hpp"
#include "rocking_monitor/motion/peak_ground_motion.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "study_internal.hpp"

namespace rocking_monitor::core::study {

using detail::format_number;
using detail::read_csv;

StudyRecord make_study_record(const Component& h, const Component* v, std::string event,
                              std::string station, std::string component, std::string file,
                              std::string* notice) {
  if (h.accel.size() < 2) throw StudyError(file + ": fewer than 2 samples");
  if (!(h.dt > 0.0) || !std::isfinite(h.dt)) throw StudyError(file + ": sample interval must be > 0");
  StudyRecord r;
  r.event = std::move(event);
  r.station = std::move(station);
  r.component = std::move(component);
  r.header_label = h.label;
  r.file = std::move(file);
  r.dt = h.dt;
  r.t0 = h.t0;
  r.horizontal = h.accel;
  const PeakGroundMotion peaks = peak_ground_motion(h);
  r.pga = peaks.pga.value;
  r.pgv = peaks.pgv.value;
  r.corrected = integrate_ground_motion(h).accel;
  if (v != nullptr) {
    if (std::abs(v->dt - h.dt) > 1e-6 * h.dt) {
      if (notice)
        *notice = v->file + ": vertical dt " + format_number("%g", v->dt) + " s differs from " +
                  r.file + " (" + format_number("%g", h.dt) + " s): not paired";
    } else {
      r.vertical.assign(h.accel.size(), 0.0);
      const std::size_t n = std::min(v->accel.size(), h.accel.size());
      for (std::size_t i = 0; i < n; ++i) {
        r.vertical[i] = v->accel[i];
        r.pga_vertical = std::max(r.pga_vertical, std::abs(v->accel[i]));
      }
      if (notice && v->accel.size() != h.accel.size())
        *notice = v->file + " (vertical, " + std::to_string(v->accel.size()) + " samples) with " +
                  r.file + " (" + std::to_string(h.accel.size()) + " samples): " +
                  (v->accel.size() < h.accel.size() ? "zero-padded" : "cut at the horizontal's end");
    }
  }
  return r;
}

namespace {

namespace fs = std::filesystem;

std::string strip_label(const std::string& s) {
  std::string t;
  for (char c : s) {
    if (c == '-' && t.empty()) continue;
    t += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  }
  while (!t.empty() && t.back() == ' ') t.pop_back();
  return t;
}

bool contains_any(const std::string& s, const std::vector<std::string>& needles) {
  for (const auto& n : needles)
    if (!n.empty() && s.find(n) != std::string::npos) return true;
  return false;
}

bool selected(const RecordSelection& sel, const std::string& file, const std::string& event,
              const std::string& station) {
  if (!sel.only.empty() && !contains_any(file, sel.only) && !contains_any(event, sel.only) &&
      !contains_any(station, sel.only))
    return false;
  return !contains_any(file, sel.exclude);
}

using ComponentCache = std::map<std::string, std::vector<Component>>;

const std::vector<Component>& cached_read(ComponentCache& cache, const fs::path& root,
                                          const std::string& rel) {
  auto it = cache.find(rel);
  if (it != cache.end()) return it->second;
  const std::string path = (root / rel).string();
  if (!fs::exists(path)) throw StudyError(path + ": listed in MANIFEST.csv but not found");
  return cache.emplace(rel, read_record(path)).first->second;
}

// The component of a (possibly multi-component) file that a manifest label names.
const Component& pick_component(const std::vector<Component>& comps, const std::string& label,
                                bool vertical, const std::string& path) {
  const Component* only = nullptr;
  int count = 0;
  for (const auto& c : comps) {
    if (c.vertical != vertical) continue;
    ++count;
    only = &c;
    if (strip_label(c.label) == strip_label(label)) return c;
  }
  if (count == 1) return *only;
  if (comps.size() == 1) return comps.front();  // e.g. a label the reader classifies differently
  throw StudyError(path + ": no " + std::string(vertical ? "vertical" : "horizontal") +
                   " component labelled '" + label + "' in this file");
}

StudyRecords load_from_manifest(const fs::path& root, const RecordSelection& sel) {
  const std::string manifest = (root / "MANIFEST.csv").string();
  const std::vector<csv::Row> rows = read_csv(manifest);
  if (rows.empty()) throw StudyError(manifest + ": empty");
  const std::map<std::string, std::size_t> col = csv::column_index(rows[0]);
  const std::string header_at = manifest + ":" + std::to_string(rows[0].line) + ": ";
  for (const char* need : {"event", "station", "component", "file"})
    if (!col.count(need)) throw StudyError(header_at + "no column '" + need + "'");
  struct Row {
    std::string event, station, label, file;
    bool vertical;
    std::size_t line;
  };
  std::vector<Row> horizontals;
  std::map<std::pair<std::string, std::string>, Row> verticals;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const std::vector<std::string>& f = rows[i].fields;
    if (f.size() < col.size())
      throw StudyError(manifest + ":" + std::to_string(rows[i].line) + ": " + std::to_string(f.size()) +
                       " fields, header has " + std::to_string(col.size()));
    Row r{f[col.at("event")], f[col.at("station")], f[col.at("component")], f[col.at("file")], false,
          rows[i].line};
    if (r.label.size() >= 2 && (r.label[0] == 'V' || r.label[0] == 'H') && r.label[1] == ':') {
      r.vertical = r.label[0] == 'V';
      r.label = r.label.substr(2);
    } else {
      r.vertical = label_is_vertical(r.label);
    }
    if (r.vertical)
      verticals.emplace(std::make_pair(r.event, r.station), r);  // the first listed vertical
    else
      horizontals.push_back(r);
  }
  StudyRecords out;
  out.root = root.string();
  out.from_manifest = true;
  ComponentCache cache;
  for (const Row& r : horizontals) {
    if (!selected(sel, r.file, r.event, r.station)) continue;
    const Component& h = pick_component(cached_read(cache, root, r.file), r.label, false,
                                        (root / r.file).string());
    const Component* v = nullptr;
    std::string vlabel, vfile, vrel;
    if (auto it = verticals.find({r.event, r.station}); it != verticals.end()) {
      if (contains_any(it->second.file, sel.exclude)) {
        out.notes.push_back(it->second.file + ": vertical excluded by --exclude");
      } else {
        v = &pick_component(cached_read(cache, root, it->second.file), it->second.label, true,
                            (root / it->second.file).string());
        vrel = it->second.file;
        vlabel = it->second.label;
        vfile = it->second.file;
      }
    }
    std::string notice;
    Component vcopy;
    if (v != nullptr) {  // notices name the file as the manifest does
      vcopy = *v;
      vcopy.file = vrel;
      v = &vcopy;
    }
    out.records.push_back(make_study_record(h, v, r.event, r.station, r.label, r.file, &notice));
    if (!notice.empty()) out.notes.push_back(notice);
    if (out.records.back().has_vertical()) {
      out.records.back().vertical_component = vlabel;
      out.records.back().vertical_file = vfile;
    }
  }
  return out;
}

StudyRecords load_from_scan(const fs::path& root, const RecordSelection& sel) {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (e.is_regular_file()) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  StudyRecords out;
  out.root = root.string();
  struct Item {
    std::string rel, event, station;
    Component comp;
  };
  std::vector<Item> horizontals;
  std::map<std::pair<std::string, std::string>, Item> verticals;
  for (const fs::path& p : files) {
    const std::string rel = fs::relative(p, root).generic_string();
    const std::string ext = p.extension().string();
    if (ext == ".md" || ext == ".json" || ext == ".yaml" || ext == ".yml" || ext == ".py") continue;
    if (p.filename() == "CHANNELS.csv") continue;  // the miniSEED channel table, not a record
    if (contains_any(rel, sel.exclude)) continue;
    if (detect_format(p.string()) == RecordFormat::Auto) {
      out.notes.push_back(rel + ": not a recognised record format, skipped");
      continue;
    }
    std::vector<Component> comps = read_record(p.string());
    const std::string event = fs::path(rel).parent_path().generic_string();
    for (auto& c : comps) {
      c.file = rel;
      const std::string station = c.station.empty() ? p.stem().string() : c.station;
      if (c.vertical) {
        if (!verticals.count({event, station}))
          verticals.emplace(std::make_pair(event, station), Item{rel, event, station, c});
        else
          out.notes.push_back(rel + ": second vertical for station '" + station + "', not used");
      } else {
        horizontals.push_back(Item{rel, event, station, std::move(c)});
      }
    }
  }
  for (const Item& h : horizontals) {
    if (!selected(sel, h.rel, h.event, h.station)) continue;
    const Item* v = nullptr;
    if (auto it = verticals.find({h.event, h.station}); it != verticals.end()) v = &it->second;
    std::string notice;
    out.records.push_back(make_study_record(h.comp, v ? &v->comp : nullptr, h.event, h.station,
                                            h.comp.label, h.rel, &notice));
    if (!notice.empty()) out.notes.push_back(notice);
    if (out.records.back().has_vertical()) {
      out.records.back().vertical_component = v->comp.label;
      out.records.back().vertical_file = v->rel;
    }
  }
  return out;
}

}  // namespace

StudyRecords load_study_records(const std::string& dir, const RecordSelection& selection) {
  const fs::path root(dir);
  std::error_code ec;
  if (!fs::is_directory(root, ec)) throw StudyError(dir + ": not a directory");
  StudyRecords r = fs::exists(root / "MANIFEST.csv") ? load_from_manifest(root, selection)
                                                    : load_from_scan(root, selection);
  if (r.records.empty())
    throw StudyError(dir + ": no horizontal record component" +
                     std::string(selection.only.empty() && selection.exclude.empty()
                                     ? ""
                                     : " matches the selection"));
  return r;
}

}  // namespace rocking_monitor::core::study
