#include "rocking_monitor/study/study_items.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <map>
#include <mutex>
#include <optional>
#include <ostream>
#include <sstream>
#include <thread>
#include <utility>

#include "rocking_monitor/csv/csv_writer.hpp"
#include "rocking_monitor/motion/station.hpp"
#include "study_internal.hpp"

namespace rocking_monitor::core::study {

using detail::format_number;

namespace {

std::string num(double v) { return std::isnan(v) ? std::string() : format_number("%.9g", v); }
const char* flag(bool on) { return on ? "1" : "0"; }

// Direction of a record component: its header's label when that carries one, else its listing's.
std::optional<double> record_azimuth(const StudyRecord& r) {
  if (auto az = label_azimuth_deg(r.header_label)) return az;
  return label_azimuth_deg(r.component);
}

std::string station_name(const StudyRecord& r) { return r.event + "/" + r.station; }

}  // namespace

StationPairs pair_stations(const std::vector<StudyRecord>& records) {
  StationPairs out;
  // (event, station) -> record indices, in first-appearance order.
  std::map<std::pair<std::string, std::string>, std::size_t> slot;
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const auto key = std::make_pair(records[i].event, records[i].station);
    auto it = slot.find(key);
    if (it == slot.end()) {
      slot.emplace(key, groups.size());
      groups.push_back({i});
    } else {
      groups[it->second].push_back(i);
    }
  }
  for (const auto& g : groups) {
    const StudyRecord& a = records[g.front()];
    const std::string who = station_name(a);
    if (g.size() == 1) {
      ++out.single_horizontal;
      out.notes.push_back(who + ": one horizontal (" + a.file + "): two-plane items not run here");
      continue;
    }
    if (g.size() > 2) {
      ++out.not_resolvable;
      out.notes.push_back(who + ": " + std::to_string(g.size()) +
                          " horizontals, which two to rotate is ambiguous: two-plane items not run here");
      continue;
    }
    const StudyRecord& b = records[g[1]];
    const std::string both = a.file + " and " + b.file;
    if (std::abs(a.dt - b.dt) > 1e-6 * a.dt) {
      ++out.different_dt;
      out.notes.push_back(who + ": " + both + " have different sample intervals (" + format_number("%g", a.dt) +
                          " s and " + format_number("%g", b.dt) + " s): two-plane items not run here");
      continue;
    }
    if (std::abs(a.t0 - b.t0) > 1e-9 * std::max(1.0, std::abs(a.t0))) {
      ++out.not_resolvable;
      out.notes.push_back(who + ": " + both + " start at different times: two-plane items not run here");
      continue;
    }
    const auto az_a = record_azimuth(a), az_b = record_azimuth(b);
    if (!az_a || !az_b) {
      ++out.no_azimuth;
      const StudyRecord& r = !az_a ? a : b;
      out.notes.push_back(who + ": the label '" + r.component + "' of " + r.file +
                          " carries no direction: two-plane items not run here");
      continue;
    }
    // rotate() refuses nearly parallel sensors; find out now rather than in a worker.
    double sep = std::fmod(std::abs(*az_a - *az_b), 360.0);
    if (sep > 180.0) sep = 360.0 - sep;
    if (sep < 10.0 || sep > 170.0) {
      ++out.not_resolvable;
      out.notes.push_back(who + ": " + both + " are nearly parallel (" + format_number("%g", sep) +
                          " deg apart): two-plane items not run here");
      continue;
    }
    StationPair p;
    p.event = a.event;
    p.station = a.station;
    p.first = g[0];
    p.second = g[1];
    p.azimuth_first = *az_a;
    p.azimuth_second = *az_b;
    p.samples = std::max(a.horizontal.size(), b.horizontal.size());
    if (a.horizontal.size() != b.horizontal.size()) {
      // As the study pairs a short vertical: pad with zeros (no ground acceleration after the end).
      ++out.zero_padded;
      const StudyRecord& s = a.horizontal.size() < b.horizontal.size() ? a : b;
      out.notes.push_back(who + ": " + both + " have " + std::to_string(a.horizontal.size()) + " and " +
                          std::to_string(b.horizontal.size()) + " samples: " + s.file +
                          " zero-padded for the two-plane items");
    }
    out.pairs.push_back(std::move(p));
  }
  return out;
}

PlaneInputs plane_inputs(const StationPair& pair, const std::vector<StudyRecord>& records, double azimuth_deg) {
  const StudyRecord& ra = records.at(pair.first);
  const StudyRecord& rb = records.at(pair.second);
  auto component = [&](const StudyRecord& r, double azimuth) {
    Component c;
    c.file = r.file;
    c.label = format_azimuth_label(azimuth);  // the direction pair_stations() settled on
    c.dt = ra.dt;                             // equal within 1e-6 (checked); one grid for both
    c.t0 = ra.t0;
    c.accel = r.horizontal;
    c.accel.resize(pair.samples, 0.0);
    return c;
  };
  RotatedPair rotated;
  try {
    rotated = rotate(component(ra, pair.azimuth_first), component(rb, pair.azimuth_second), azimuth_deg);
  } catch (const std::exception& e) {
    throw StudyError(pair.event + "/" + pair.station + ": " + e.what());
  }
  PlaneInputs in;
  in.dt = ra.dt;
  in.t0 = ra.t0;
  in.x = std::move(rotated.along.accel);
  in.y = std::move(rotated.left.accel);  // 90 deg counter-clockwise of x: REP 103's y
  // Both records carry the station's vertical on their own grid (padded / cut to their length);
  // the longer one's covers the pair.
  const StudyRecord& longer = ra.horizontal.size() >= rb.horizontal.size() ? ra : rb;
  if (longer.has_vertical()) {
    in.vertical = longer.vertical;
    in.vertical.resize(pair.samples, 0.0);
  }
  return in;
}

LevelTimes level_times(const RockingOutcome& o) {
  LevelTimes t;
  if (o.beyond_tipping) t.time[static_cast<int>(Level::BeyondTipping)] = o.beyond_tipping_time;
  if (o.committed) t.time[static_cast<int>(Level::Committed)] = o.committed_time;
  if (o.overturned) t.time[static_cast<int>(Level::Overturned)] = o.overturn_time;
  return t;
}

namespace {

// The 3-D model on the same inputs as the planes: both horizontals (flipped together by the
// polarity) and the vertical, run_case()'s samples from the same start at rest.
void run_solid_case(const BaseBodyParameters& params, const PlaneInputs& in, int polarity, ItemCaseResult& c,
                    const SolverSettings& settings) {
  SolverSettings s = settings;
  s.method = Method::Dopri5;  // the 3-D model's only integrator
  s.model = ModelKind::Nonlinear;
  Rocking3DModel model(BaseBody(params), s);
  const double sign = polarity < 0 ? -1.0 : 1.0;
  auto a = [&](std::size_t i) {
    return Eigen::Vector3d(sign * in.x[i], sign * in.y[i], c.vertical ? in.vertical[i] : 0.0);
  };
  if (in.x.empty()) return;
  model.reset(in.t0, a(0));
  for (std::size_t i = 1; i < in.x.size() && !model.outcome().overturned; ++i) model.step(a(i), in.dt);
  c.solid_run = true;
  c.solid = model.outcome();
  c.solid_3d = model.outcome_3d();
}

}  // namespace

ItemCaseResult run_item_case(const StudyItem& item, const PlaneInputs& in, int polarity, bool vertical,
                             const SolverSettings& settings) {
  ItemCaseResult c;
  c.polarity = polarity;
  c.vertical = vertical && !in.vertical.empty();
  const BodyParameters* bodies[kPlaneCount] = {&item.x, &item.y};
  const std::vector<double>* series[kPlaneCount] = {&in.x, &in.y};
  for (int p = 0; p < kPlaneCount; ++p) {
    // The single-plane runner, on a record holding this plane's input: same model, same loop,
    // polarity applied by it (both planes flipped together, the vertical never).
    StudyRecord rec;
    rec.dt = in.dt;
    rec.t0 = in.t0;
    rec.horizontal = *series[p];
    if (c.vertical) rec.vertical = in.vertical;
    for (double a : rec.horizontal) c.pga[p] = std::max(c.pga[p], std::abs(a));
    const Body body(*bodies[p]);
    c.planes[p] = run_case(body, rec, polarity, c.vertical, settings, 0.0);
  }
  const LevelTimes x = level_times(c.planes[0].outcome), y = level_times(c.planes[1].outcome);
  c.verdict = combine(x, &y);
  if (item.solid) run_solid_case(*item.solid, in, polarity, c, settings);
  return c;
}

std::size_t item_case_count(std::size_t items, std::size_t pairs, const ItemStudyOptions& options) {
  return items * pairs * options.azimuths.size() * (options.both_polarities ? 2u : 1u);
}

std::vector<ItemCaseResult> run_item_study(const std::vector<StudyItem>& items,
                                           const std::vector<StudyRecord>& records, const StationPairs& pairs,
                                           const ItemStudyOptions& options) {
  if (const std::string e = validate(options.settings); !e.empty()) throw StudyError(e);
  for (const auto& item : items) {
    for (const BodyParameters* b : {&item.x, &item.y})
      if (const std::string e = validate(*b); !e.empty()) throw StudyError("item '" + item.name + "': " + e);
  }
  const std::size_t polarities = options.both_polarities ? 2 : 1;
  const std::size_t per_pair = options.azimuths.size() * polarities;
  const std::size_t per_item = pairs.pairs.size() * per_pair;
  const std::size_t total = items.size() * per_item;
  std::vector<ItemCaseResult> results(total);
  const std::size_t units = items.size() * pairs.pairs.size();
  std::atomic<std::size_t> next{0}, done{0};
  std::atomic<bool> stop{false};
  std::exception_ptr error;
  std::mutex mutex;

  auto worker = [&]() {
    try {
      for (;;) {
        if (stop.load(std::memory_order_relaxed)) break;
        const std::size_t u = next.fetch_add(1);
        if (u >= units) break;
        const std::size_t item = u / pairs.pairs.size(), pair = u % pairs.pairs.size();
        std::size_t idx = item * per_item + pair * per_pair;
        for (double azimuth : options.azimuths) {
          // Rotation is exact arithmetic on the samples, the same for any thread.
          const PlaneInputs in = plane_inputs(pairs.pairs[pair], records, azimuth);
          for (int polarity : {1, -1}) {
            if (polarity < 0 && !options.both_polarities) continue;
            ItemCaseResult c = run_item_case(items[item], in, polarity, options.verticals, options.settings);
            c.index = idx;
            c.item = item;
            c.pair = pair;
            c.azimuth_deg = azimuth;
            results[idx++] = std::move(c);
          }
        }
        done.fetch_add(per_pair);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex);
      if (!error) error = std::current_exception();
      stop = true;
    }
  };
  int threads = options.threads > 0 ? options.threads
                                    : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(threads), std::max<std::size_t>(1, units)));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
  if (options.progress) {
    // Report from the calling thread about every 0.5 s until the workers are through the units
    // (polled often, so that a short run does not wait for the next report).
    auto last = std::chrono::steady_clock::now();
    while (done.load() < total && !stop.load()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      if (std::chrono::steady_clock::now() - last >= std::chrono::milliseconds(500)) {
        options.progress(done.load(), total);
        last = std::chrono::steady_clock::now();
      }
    }
  }
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  if (options.progress) options.progress(done.load(), total);
  return results;
}

const std::vector<std::string>& item_case_csv_columns() {
  static const std::vector<std::string> columns{
      "case", "item", "item_name", "width_m", "depth_m", "cg_height_m", "eccentricity", "eccentricity_y",
      "radius_of_gyration_m", "radius_of_gyration_y_m", "pair", "event", "station", "file_1", "file_2",
      "azimuth_deg", "polarity", "vertical", "pga_x_mps2", "pga_y_mps2",
      "x_overturned", "x_committed", "x_beyond_tipping", "x_max_rotation_ratio", "x_uplift_time_s",
      "x_overturn_time_s", "x_impacts",
      "y_overturned", "y_committed", "y_beyond_tipping", "y_max_rotation_ratio", "y_uplift_time_s",
      "y_overturn_time_s", "y_impacts",
      "item_level", "item_overturned", "item_overturn_time_s", "deciding_plane",
      "solid_overturned", "solid_committed", "solid_beyond_tipping", "solid_max_rotation_ratio",
      "solid_max_tilt_rad", "solid_uplift_time_s", "solid_overturn_time_s", "solid_impacts",
      "solid_edge_to_vertex"};
  return columns;
}

void write_item_cases_csv(std::ostream& out, const std::vector<ItemCaseResult>& results,
                          const std::vector<StudyItem>& items, const std::vector<StudyRecord>& records,
                          const StationPairs& pairs) {
  csv::Writer row(out);
  for (const std::string& column : item_case_csv_columns()) row.text(column);
  row.end_row();
  for (const ItemCaseResult& c : results) {
    const StudyItem& it = items.at(c.item);
    const StationPair& p = pairs.pairs.at(c.pair);
    row.value(std::to_string(c.index)).value(std::to_string(c.item)).text(it.name);
    row.value(num(it.x.width)).value(num(it.y.width)).value(num(it.x.cg_height));
    row.value(num(it.x.nu1)).value(num(it.y.nu1));
    row.value(num(it.x.radius_of_gyration)).value(num(it.y.radius_of_gyration));
    row.value(std::to_string(c.pair)).text(p.event).text(p.station);
    row.text(records.at(p.first).file).text(records.at(p.second).file);
    row.value(num(c.azimuth_deg)).value(std::to_string(c.polarity)).value(flag(c.vertical));
    row.value(num(c.pga[0])).value(num(c.pga[1]));
    for (const CaseResult& pl : c.planes) {
      const RockingOutcome& o = pl.outcome;
      row.value(flag(o.overturned)).value(flag(o.committed)).value(flag(o.beyond_tipping));
      row.value(num(o.max_rotation_ratio)).value(num(o.uplift_time)).value(num(o.overturn_time));
      row.value(std::to_string(o.impacts));
    }
    // The item's most severe level and the plane that reached it first (combine(): tie -> x).
    const char* level = "none";
    const char* plane = "";
    const char* names[kLevelCount] = {"beyond_tipping", "committed", "overturned"};
    for (int l = kLevelCount - 1; l >= 0; --l) {
      if (c.verdict.levels.reached(static_cast<Level>(l))) {
        level = names[l];
        plane = core::to_string(c.verdict.plane[l]);
        break;
      }
    }
    row.value(level).value(flag(c.verdict.overturned())).value(num(c.verdict.levels.at(Level::Overturned)));
    row.value(plane);
    if (c.solid_run) {  // empty fields: the item has no 3-D description
      const RockingOutcome& o = c.solid;
      row.value(flag(o.overturned)).value(flag(o.committed)).value(flag(o.beyond_tipping));
      row.value(num(o.max_rotation_ratio)).value(num(c.solid_3d.max_tilt)).value(num(o.uplift_time));
      row.value(num(o.overturn_time)).value(std::to_string(o.impacts)).value(std::to_string(c.solid_3d.edge_to_vertex));
    } else {
      for (int k = 0; k < 9; ++k) row.value("");
    }
    row.end_row();
  }
}

void ItemTally::add(const ItemCaseResult& c) {
  ++cases;
  const bool x = c.planes[0].outcome.overturned, y = c.planes[1].outcome.overturned;
  overturned += c.verdict.overturned();
  committed += c.verdict.levels.reached(Level::Committed);
  beyond_tipping += c.verdict.levels.reached(Level::BeyondTipping);
  if (c.verdict.overturned() && c.verdict.plane[static_cast<int>(Level::Overturned)] == Plane::Y)
    ++overturned_decided_by_y;
  overturned_x_only += x && !y;
  overturned_y_only += y && !x;
  overturned_both += x && y;
  if (c.solid_run) {
    ++solid_cases;
    solid_overturned += c.solid.overturned;
    solid_differs += c.solid.overturned != c.verdict.overturned();
  }
}

ItemSummary summarize_items(const std::vector<ItemCaseResult>& results, const std::vector<StudyItem>& items,
                            const StationPairs& pairs, const std::vector<double>& azimuths) {
  ItemSummary s;
  s.items = items.size();
  s.pairs = pairs.pairs.size();
  s.azimuths = azimuths;
  s.by_azimuth.resize(azimuths.size());
  s.by_item.resize(items.size());
  for (const auto& it : items) s.item_names.push_back(it.name);
  s.skipped = pairs;
  s.skipped.pairs.clear();
  for (const ItemCaseResult& c : results) {
    s.all.add(c);
    s.by_item.at(c.item).add(c);
    for (std::size_t a = 0; a < azimuths.size(); ++a)
      if (azimuths[a] == c.azimuth_deg) {
        s.by_azimuth[a].add(c);
        break;
      }
  }
  return s;
}

std::vector<double> parse_azimuths(const std::vector<std::string>& texts) {
  std::vector<double> out;
  for (const std::string& text : texts) {
    std::stringstream ss(text);
    std::string item;
    bool any = false;
    while (std::getline(ss, item, ',')) {
      any = true;
      std::size_t used = 0;
      double v = 0.0;
      try {
        v = std::stod(item, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != item.size() || !std::isfinite(v))
        throw StudyError("--azimuth: bad azimuth '" + item + "' (degrees clockwise from north, e.g. 0,45,90)");
      if (std::find(out.begin(), out.end(), v) != out.end())
        throw StudyError("--azimuth: " + item + " given twice");
      out.push_back(v);
    }
    if (!any) throw StudyError("--azimuth: empty");
  }
  return out;
}

}  // namespace rocking_monitor::core::study
