#include "rocking_monitor/study/study.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <map>
#include <mutex>
#include <ostream>
#include <set>
#include <sstream>
#include <thread>
#include <tuple>
#include <utility>

#include "rocking_monitor/csv/csv_reader.hpp"
#include "rocking_monitor/csv/csv_writer.hpp"
#include "rocking_monitor/motion/ground_motion_integration.hpp"
#include "rocking_monitor/motion/peak_ground_motion.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "rocking_monitor/motion/response_spectrum.hpp"

namespace rocking_monitor::core::study {
namespace {

namespace fs = std::filesystem;

std::string format_number(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// A CSV file of the study (csv layer); its errors become StudyErrors with the same file:line text.
std::vector<csv::Row> read_csv(const std::string& path) {
  try {
    return csv::read_file(path);
  } catch (const csv::CsvError& e) {
    throw StudyError(e.what());
  }
}

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

// Index of a value in a sorted list of distinct keys (relative tolerance 1e-9).
std::size_t key_index(const std::vector<double>& keys, double v) {
  for (std::size_t i = 0; i < keys.size(); ++i)
    if (std::abs(keys[i] - v) <= 1e-9 * std::max(1.0, std::abs(v))) return i;
  return keys.size();
}

void add_key(std::vector<double>& keys, double v) {
  if (key_index(keys, v) == keys.size()) keys.push_back(v);
}

}  // namespace

// ==================================================================== bodies

std::vector<double> geometric_spacing(double lo, double hi, int n) {
  std::vector<double> v;
  if (n < 1) return v;
  if (n == 1) return {lo};
  v.reserve(static_cast<std::size_t>(n));
  const double ratio = std::log(hi / lo) / (n - 1);
  for (int i = 0; i < n; ++i) v.push_back(i == n - 1 ? hi : lo * std::exp(ratio * i));
  return v;
}

double eccentricity_of(const BodyParameters& body) { return std::min(body.nu1, 1.0 - body.nu1); }

std::vector<StudyBody> grid_bodies(const StudyGrid& g) {
  auto fail = [](const std::string& what) { throw StudyError("invalid body grid: " + what); };
  if (g.heights < 1) fail("heights = " + std::to_string(g.heights) + " (must be >= 1)");
  if (g.widths < 1) fail("widths = " + std::to_string(g.widths) + " (must be >= 1)");
  for (double v : {g.min_height, g.max_height, g.min_width, g.max_width, g.min_width_ratio,
                   g.max_width_ratio})
    if (!(v > 0.0) || !std::isfinite(v)) fail("limits must be finite and > 0");
  if (g.min_height > g.max_height) fail("min_height > max_height");
  if (g.eccentricities.empty()) fail("no eccentricities");
  for (double nu : g.eccentricities)
    if (!(nu > 0.0 && nu < 1.0)) fail("eccentricity " + format_number("%g", nu) + " outside (0, 1)");
  std::vector<StudyBody> bodies;
  const std::vector<double> heights = geometric_spacing(g.min_height, g.max_height, g.heights);
  for (double nu : g.eccentricities) {
    for (double h : heights) {
      const double lo = std::max(g.min_width, g.min_width_ratio * h);
      const double hi = std::min(g.max_width, g.max_width_ratio * h);
      if (lo > hi)
        fail("no width for h = " + format_number("%g", h) + " m: range [" + format_number("%g", lo) +
             ", " + format_number("%g", hi) + "] m is empty");
      for (double b : geometric_spacing(lo, hi, g.widths)) {
        StudyBody sb;
        sb.parameters.width = b;
        sb.parameters.cg_height = h;
        sb.parameters.nu1 = nu;
        // The eccentric body keeps the moment of inertia of its symmetric twin (homogeneous B x 2h).
        sb.parameters.radius_of_gyration = Body::homogeneous_radius_of_gyration(b, h);
        char name[96];
        std::snprintf(name, sizeof name, "h%.3f_B%.4f_nu%.2f", h, b, nu);
        sb.name = name;
        bodies.push_back(std::move(sb));
      }
    }
  }
  return bodies;
}

// ==================================================================== records

StudyRecord make_study_record(const Component& h, const Component* v, std::string event,
                              std::string station, std::string component, std::string file,
                              std::string* notice) {
  if (h.accel.size() < 2) throw StudyError(file + ": fewer than 2 samples");
  if (!(h.dt > 0.0) || !std::isfinite(h.dt)) throw StudyError(file + ": sample interval must be > 0");
  StudyRecord r;
  r.event = std::move(event);
  r.station = std::move(station);
  r.component = std::move(component);
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

// ==================================================================== cases

std::vector<StudyInput> study_inputs(const std::vector<StudyRecord>& records,
                                     const StudyPlanOptions& options) {
  std::vector<StudyInput> inputs;
  for (std::size_t r = 0; r < records.size(); ++r) {
    for (int polarity : {1, -1}) {
      if (polarity < 0 && !options.both_polarities) continue;
      inputs.push_back({r, polarity, false});
      if (options.verticals && records[r].has_vertical()) inputs.push_back({r, polarity, true});
    }
  }
  return inputs;
}

std::size_t study_case_count(std::size_t bodies, const std::vector<StudyRecord>& records,
                             const StudyPlanOptions& plan) {
  return bodies * study_inputs(records, plan).size();
}

CaseRange shard_range(std::size_t total, int k, int n) {
  if (n < 1 || k < 1 || k > n)
    throw StudyError("invalid shard " + std::to_string(k) + "/" + std::to_string(n) +
                     " (need 1 <= k <= n)");
  const auto nn = static_cast<std::size_t>(n);
  const auto kk = static_cast<std::size_t>(k);
  // total * k may overflow only beyond 1e18 cases.
  return {total * (kk - 1) / nn, total * kk / nn};
}

std::pair<int, int> parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  int k = 0, n = 0;
  std::size_t used_k = 0, used_n = 0;
  try {
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    k = std::stoi(text.substr(0, slash), &used_k);
    n = std::stoi(text.substr(slash + 1), &used_n);
  } catch (const std::exception&) {
    throw StudyError("invalid shard '" + text + "' (expected k/n, e.g. 2/8)");
  }
  if (used_k != slash || used_n != text.size() - slash - 1)
    throw StudyError("invalid shard '" + text + "' (expected k/n, e.g. 2/8)");
  shard_range(1, k, n);  // range check
  return {k, n};
}

double pseudo_velocity_at(const std::vector<double>& accel, double dt, double period, double damping) {
  NigamJenningsOscillator osc(period, damping, dt);
  double peak = 0.0;
  for (std::size_t i = 1; i < accel.size(); ++i) {
    osc.step(accel[i - 1], accel[i]);
    peak = std::max(peak, std::abs(osc.displacement()));
  }
  return 2.0 * kPi / period * peak;
}

CaseResult run_case(const Body& body, const StudyRecord& rec, int polarity, bool vertical,
                    const SolverSettings& settings, double psv) {
  CaseResult c;
  c.polarity = polarity;
  c.vertical = vertical && rec.has_vertical();
  c.housner_period = housner_period(body);
  c.housner_psv = std::isnan(psv) ? pseudo_velocity_at(rec.corrected, rec.dt, c.housner_period) : psv;
  c.thresholds = screening_thresholds(body);
  c.prediction = screening_prediction(c.thresholds, rec.pga, rec.pgv, c.housner_psv);

  // Same loop as simulate() (rocking_sim), with the polarity applied to the horizontal only:
  // multiplying by +-1 is exact, so the samples are those of a record written with that sign.
  RockingModel model(body, settings);
  const double s = polarity < 0 ? -1.0 : 1.0;
  const std::vector<double>& ah = rec.horizontal;
  const bool use_v = c.vertical;
  const std::size_t n = ah.size();
  if (n > 0) {
    model.reset(rec.t0, s * ah[0], use_v ? rec.vertical[0] : 0.0);
    for (std::size_t i = 1; i < n; ++i) {
      const StepReport& r = model.step(s * ah[i], use_v ? rec.vertical[i] : 0.0, rec.dt);
      if (r.violation_onsets != 0 && c.violations == 0) c.first_violation_time = model.time();
      c.violations |= r.violation_onsets;
    }
  }
  c.outcome = model.outcome();
  c.final_mode = model.mode();
  if (c.outcome.max_rotation_side != 0)
    c.max_theta = c.outcome.max_rotation_ratio * body.pivot(c.outcome.max_rotation_side).alpha;
  return c;
}

std::vector<CaseResult> run_study(const std::vector<StudyBody>& bodies,
                                  const std::vector<StudyRecord>& records, const StudyOptions& options) {
  if (const std::string e = validate(options.settings); !e.empty()) throw StudyError(e);
  std::vector<Body> rigid;
  rigid.reserve(bodies.size());
  for (const auto& b : bodies) {
    try {
      rigid.emplace_back(b.parameters);
    } catch (const std::exception& e) {
      throw StudyError("body '" + b.name + "': " + e.what());
    }
  }
  const std::vector<StudyInput> inputs = study_inputs(records, options.plan);
  const std::size_t per_body = inputs.size();
  const std::size_t total = bodies.size() * per_body;
  CaseRange range = options.range;
  if (range.end == std::numeric_limits<std::size_t>::max()) range.end = total;
  if (range.begin > range.end || range.end > total)
    throw StudyError("case range [" + std::to_string(range.begin) + ", " + std::to_string(range.end) +
                     ") outside the " + std::to_string(total) + " cases");

  // Work units: (body, record) -> its contiguous inputs [first[r], first[r + 1]).
  // Every record has at least its (polarity +1, vertical off) input, and a record's inputs are
  // contiguous, in record order.
  std::vector<std::size_t> first(records.size() + 1, per_body);
  for (std::size_t i = 0; i < inputs.size(); ++i)
    if (i == 0 || inputs[i].record != inputs[i - 1].record) first[inputs[i].record] = i;
  struct Unit {
    std::size_t body, record, begin, end;  // global case indices
  };
  std::vector<Unit> units;
  if (per_body > 0) {
    for (std::size_t b = range.begin / per_body; b < bodies.size() && b * per_body < range.end; ++b) {
      for (std::size_t r = 0; r < records.size(); ++r) {
        const std::size_t lo = std::max(b * per_body + first[r], range.begin);
        const std::size_t hi = std::min(b * per_body + first[r + 1], range.end);
        if (lo < hi) units.push_back({b, r, lo, hi});
      }
    }
  }

  std::vector<CaseResult> results(range.size());
  std::atomic<std::size_t> next{0}, done{0};
  std::atomic<bool> stop{false};
  std::exception_ptr error;
  std::mutex mutex;
  std::condition_variable finished_cv;
  int running = 0;

  auto worker = [&]() {
    try {
      for (;;) {
        if (stop.load(std::memory_order_relaxed)) break;
        const std::size_t u = next.fetch_add(1);
        if (u >= units.size()) break;
        const Unit& unit = units[u];
        const Body& body = rigid[unit.body];
        const StudyRecord& rec = records[unit.record];
        const double psv = pseudo_velocity_at(rec.corrected, rec.dt, housner_period(body));
        for (std::size_t idx = unit.begin; idx < unit.end; ++idx) {
          const StudyInput& in = inputs[idx - unit.body * per_body];
          CaseResult c = run_case(body, rec, in.polarity, in.vertical, options.settings, psv);
          c.index = idx;
          c.body = unit.body;
          c.record = unit.record;
          results[idx - range.begin] = c;
        }
        done.fetch_add(unit.end - unit.begin);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex);
      if (!error) error = std::current_exception();
      stop = true;
    }
    std::lock_guard<std::mutex> lock(mutex);
    --running;
    finished_cv.notify_all();
  };

  int threads = options.threads > 0 ? options.threads
                                    : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(threads),
                                                   std::max<std::size_t>(1, units.size())));
  std::vector<std::thread> pool;
  running = threads;
  for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
  {
    std::unique_lock<std::mutex> lock(mutex);
    const auto interval = std::chrono::duration<double>(std::max(0.01, options.progress_interval_s));
    while (running > 0) {
      finished_cv.wait_for(lock, interval);
      if (options.progress && running > 0) {
        lock.unlock();
        options.progress(done.load(), range.size());
        lock.lock();
      }
    }
  }
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  if (options.progress) options.progress(done.load(), range.size());
  return results;
}

// ==================================================================== CSV output

const std::vector<std::string>& case_csv_columns() {
  static const std::vector<std::string> columns{
      "case", "body", "body_name", "width_m", "cg_height_m", "nu1", "eccentricity",
      "radius_of_gyration_m", "record", "event", "station", "component", "file", "polarity",
      "vertical", "vertical_component", "overturned", "committed", "beyond_tipping", "final_mode",
      "max_rotation_ratio", "max_theta_rad", "max_rotation_pivot", "impacts", "uplift_time_s",
      "beyond_tipping_time_s", "committed_time_s", "overturn_time_s", "rest_captures",
      "forced_rest_captures", "violations", "first_violation_time_s", "pga_mps2", "pgv_mps", "pga_vertical_mps2",
      "housner_period_s", "housner_psv_mps", "housner_threshold_mps", "ishiyama_v_mps",
      "ishiyama_a_mps2", "ishiyama_equivalent_v_mps", "ishiyama_equivalent_a_mps2",
      "proposed_v_mps", "proposed_a_mps2", "predicts_housner", "predicts_ishiyama",
      "predicts_ishiyama_equivalent", "predicts_proposed", "integrator_steps"};
  return columns;
}

void write_case_csv_header(std::ostream& out) {
  csv::Writer row(out);
  for (const std::string& column : case_csv_columns()) row.text(column);
  row.end_row();
}

namespace {

std::string num(double v) { return std::isnan(v) ? std::string() : format_number("%.9g", v); }

const char* flag(bool on) { return on ? "1" : "0"; }

void header(csv::Writer& row, std::initializer_list<const char*> columns) {
  for (const char* column : columns) row.text(column);
  row.end_row();
}

std::string violation_names(std::uint8_t mask) {
  std::string s;
  for (int c = 0; c < kCriterionCount; ++c) {
    if (mask & (1u << c)) {
      if (!s.empty()) s += '|';
      s += core::to_string(static_cast<Criterion>(c));
    }
  }
  return s;
}

}  // namespace

void write_case_csv_rows(std::ostream& out, const std::vector<CaseResult>& results,
                         const std::vector<StudyBody>& bodies, const std::vector<StudyRecord>& records) {
  csv::Writer row(out);
  for (const CaseResult& c : results) {
    const BodyParameters& b = bodies.at(c.body).parameters;
    const StudyRecord& r = records.at(c.record);
    const RockingOutcome& o = c.outcome;
    const ScreeningThresholds& t = c.thresholds;
    row.value(std::to_string(c.index)).value(std::to_string(c.body)).text(bodies[c.body].name);
    row.value(num(b.width)).value(num(b.cg_height)).value(num(b.nu1)).value(num(eccentricity_of(b)));
    row.value(num(b.radius_of_gyration));
    row.value(std::to_string(c.record)).text(r.event).text(r.station).text(r.component).text(r.file);
    row.value(std::to_string(c.polarity)).value(flag(c.vertical)).text(c.vertical ? r.vertical_component : "");
    row.value(flag(o.overturned)).value(flag(o.committed)).value(flag(o.beyond_tipping));
    row.value(core::to_string(c.final_mode));
    row.value(num(o.max_rotation_ratio)).value(num(c.max_theta)).value(std::to_string(o.max_rotation_side));
    row.value(std::to_string(o.impacts));
    row.value(num(o.uplift_time)).value(num(o.beyond_tipping_time)).value(num(o.committed_time));
    row.value(num(o.overturn_time));
    row.value(std::to_string(o.rest_captures)).value(std::to_string(o.forced_rest_captures));
    row.value(violation_names(c.violations)).value(num(c.first_violation_time));
    row.value(num(r.pga)).value(num(r.pgv)).value(c.vertical ? num(r.pga_vertical) : "");
    row.value(num(c.housner_period)).value(num(c.housner_psv)).value(num(t.housner_pseudo_velocity));
    row.value(num(t.ishiyama.velocity)).value(num(t.ishiyama.acceleration));
    row.value(num(t.ishiyama_equivalent.velocity)).value(num(t.ishiyama_equivalent.acceleration));
    row.value(num(t.proposed.velocity)).value(num(t.proposed.acceleration));
    row.value(flag(c.prediction.housner)).value(flag(c.prediction.ishiyama));
    row.value(flag(c.prediction.ishiyama_equivalent)).value(flag(c.prediction.proposed));
    row.value(std::to_string(o.integrator_steps));
    row.end_row();
  }
}

void write_bodies_csv(std::ostream& out, const std::vector<StudyBody>& bodies) {
  csv::Writer row(out);
  header(row, {"body", "body_name", "width_m", "cg_height_m", "nu1", "eccentricity", "radius_of_gyration_m",
               "alpha1_rad", "alpha2_rad", "p1_radps", "p2_radps", "restitution_to_1", "restitution_to_2",
               "housner_period_s", "housner_threshold_mps", "ishiyama_v_mps", "ishiyama_a_mps2",
               "ishiyama_equivalent_v_mps", "ishiyama_equivalent_a_mps2", "proposed_v_mps", "proposed_a_mps2"});
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body body(bodies[i].parameters);
    const ScreeningThresholds t = screening_thresholds(body);
    const Pivot& p1 = body.pivot(1);
    const Pivot& p2 = body.pivot(-1);
    row.value(std::to_string(i)).text(bodies[i].name);
    row.value(num(body.width())).value(num(body.cg_height())).value(num(body.nu1()));
    row.value(num(eccentricity_of(body.parameters()))).value(num(body.radius_of_gyration()));
    row.value(num(p1.alpha)).value(num(p2.alpha)).value(num(p1.p)).value(num(p2.p));
    row.value(num(p1.restitution)).value(num(p2.restitution));
    row.value(num(housner_period(body))).value(num(t.housner_pseudo_velocity));
    row.value(num(t.ishiyama.velocity)).value(num(t.ishiyama.acceleration));
    row.value(num(t.ishiyama_equivalent.velocity)).value(num(t.ishiyama_equivalent.acceleration));
    row.value(num(t.proposed.velocity)).value(num(t.proposed.acceleration));
    row.end_row();
  }
}

void write_records_csv(std::ostream& out, const std::vector<StudyRecord>& records) {
  csv::Writer row(out);
  header(row, {"record", "event", "station", "component", "file", "vertical_component", "vertical_file", "dt_s",
               "samples", "duration_s", "pga_mps2", "pgv_mps", "pga_vertical_mps2"});
  for (std::size_t i = 0; i < records.size(); ++i) {
    const StudyRecord& r = records[i];
    row.value(std::to_string(i)).text(r.event).text(r.station).text(r.component).text(r.file);
    row.text(r.vertical_component).text(r.vertical_file);
    row.value(num(r.dt)).value(std::to_string(r.horizontal.size()));
    row.value(num(r.dt * static_cast<double>(r.horizontal.size() - 1))).value(num(r.pga)).value(num(r.pgv));
    row.value(r.has_vertical() ? num(r.pga_vertical) : "");
    row.end_row();
  }
}

// ==================================================================== summary

const char* to_string(Screening criterion) {
  switch (criterion) {
    case Screening::Housner: return "housner";
    case Screening::Ishiyama: return "ishiyama";
    case Screening::IshiyamaEquivalent: return "ishiyama_equivalent";
    case Screening::Proposed: return "proposed";
  }
  return "unknown";
}

CaseRow to_case_row(const CaseResult& c, const std::vector<StudyBody>& bodies,
                    const std::vector<StudyRecord>& records) {
  const double pgv = records.at(c.record).pgv;
  CaseRow row;
  row.index = c.index;
  row.body = c.body;
  row.record = c.record;
  const BodyParameters& b = bodies.at(c.body).parameters;
  row.width = b.width;
  row.cg_height = b.cg_height;
  row.nu1 = b.nu1;
  row.pgv = pgv;
  row.polarity = c.polarity;
  row.vertical = c.vertical;
  row.overturned = c.outcome.overturned;
  row.committed = c.outcome.committed;
  row.beyond_tipping = c.outcome.beyond_tipping;
  row.predicted = {c.prediction.housner, c.prediction.ishiyama, c.prediction.ishiyama_equivalent,
                   c.prediction.proposed};
  return row;
}

void Tally::add(const CaseRow& row) {
  ++cases;
  overturned += row.overturned;
  committed += row.committed;
  beyond_tipping += row.beyond_tipping;
  for (int k = 0; k < kScreeningCount; ++k) {
    predicted[k] += row.predicted[k];
    missed[k] += row.overturned && !row.predicted[k];
    false_alarms[k] += !row.overturned && row.predicted[k];
  }
}

int SetSummary::symmetric_index() const {
  for (std::size_t i = 0; i < eccentricities.size(); ++i)
    if (std::abs(eccentricities[i] - 0.5) < 1e-9) return static_cast<int>(i);
  return -1;
}

namespace {

// Ratio of overturn shares (equal to the ratio of counts when both groups have the same cases).
double share_ratio(const Tally& num_t, const Tally& den_t) {
  if (den_t.overturned == 0 || num_t.cases == 0 || den_t.cases == 0) return std::nan("");
  return (static_cast<double>(num_t.overturned) / num_t.cases) /
         (static_cast<double>(den_t.overturned) / den_t.cases);
}

}  // namespace

std::size_t pgv_band(double pgv) {
  const auto& edges = pgv_band_edges();
  return static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), pgv) - edges.begin());
}

double SetSummary::overturn_ratio(std::size_t e, int h) const {
  const int s = symmetric_index();
  if (s < 0 || e >= eccentricities.size()) return std::nan("");
  const auto si = static_cast<std::size_t>(s);
  if (h < 0) return share_ratio(by_eccentricity[e], by_eccentricity[si]);
  const auto hi = static_cast<std::size_t>(h);
  return share_ratio(by_eccentricity_height[e][hi], by_eccentricity_height[si][hi]);
}

double SetSummary::overturn_ratio_pgv(std::size_t e, std::size_t band) const {
  const int s = symmetric_index();
  if (s < 0 || e >= eccentricities.size() || band > pgv_band_edges().size()) return std::nan("");
  return share_ratio(by_eccentricity_pgv[e][band], by_eccentricity_pgv[static_cast<std::size_t>(s)][band]);
}

StudySummary summarize(const std::vector<CaseRow>& rows) {
  StudySummary s;
  std::vector<double> eccs, heights;
  std::set<std::size_t> bodies, records, vertical_records;
  for (const CaseRow& r : rows) {
    add_key(eccs, std::min(r.nu1, 1.0 - r.nu1));
    add_key(heights, r.cg_height);
    bodies.insert(r.body);
    records.insert(r.record);
    if (r.vertical) vertical_records.insert(r.record);
  }
  std::sort(eccs.begin(), eccs.end(), std::greater<double>());
  std::sort(heights.begin(), heights.end());
  s.cases = rows.size();
  s.bodies = bodies.size();
  s.records = records.size();
  s.records_with_vertical = vertical_records.size();

  auto init = [&](SetSummary& set, const char* name) {
    set.name = name;
    set.eccentricities = eccs;
    set.heights = heights;
    set.by_eccentricity.assign(eccs.size(), Tally{});
    set.by_eccentricity_height.assign(eccs.size(), std::vector<Tally>(heights.size()));
    set.by_eccentricity_pgv.assign(eccs.size(), std::vector<Tally>(pgv_band_edges().size() + 1));
  };
  init(s.horizontal, "horizontal_only");
  init(s.subset_without_vertical, "vertical_subset_without_vertical");
  init(s.with_vertical, "vertical_subset_with_vertical");
  auto add = [](SetSummary& set, std::size_t e, std::size_t h, const CaseRow& r) {
    set.all.add(r);
    set.by_eccentricity[e].add(r);
    set.by_eccentricity_height[e][h].add(r);
    set.by_eccentricity_pgv[e][pgv_band(r.pgv)].add(r);
  };

  VerticalEffect& ve = s.vertical_effect;
  ve.eccentricities = eccs;
  for (auto* v : {&ve.pairs, &ve.overturned_without, &ve.overturned_with, &ve.only_with, &ve.only_without})
    v->assign(eccs.size(), 0);
  // (body, record, polarity) -> overturned without (bit 0/1 set) and with (bit 2/3 set) the vertical.
  std::map<std::tuple<std::size_t, std::size_t, int>, int> pairs;

  for (const CaseRow& r : rows) {
    const std::size_t e = key_index(eccs, std::min(r.nu1, 1.0 - r.nu1));
    const std::size_t h = key_index(heights, r.cg_height);
    const bool in_subset = vertical_records.count(r.record) > 0;
    if (r.vertical) {
      add(s.with_vertical, e, h, r);
    } else {
      add(s.horizontal, e, h, r);
      if (in_subset) add(s.subset_without_vertical, e, h, r);
    }
    if (in_subset) {
      int& bits = pairs[{r.body, r.record, r.polarity}];
      bits |= (r.vertical ? 4 : 1) << (r.overturned ? 1 : 0);
      bits |= static_cast<int>(e) << 8;
    }
  }
  for (const auto& [key, bits] : pairs) {
    const bool have_off = bits & 3, have_on = bits & 12;
    if (!have_off || !have_on) continue;
    const std::size_t e = static_cast<std::size_t>(bits >> 8);
    const bool off = bits & 2, on = bits & 8;
    ++ve.pairs[e];
    ve.overturned_without[e] += off;
    ve.overturned_with[e] += on;
    ve.only_with[e] += on && !off;
    ve.only_without[e] += off && !on;
  }
  return s;
}

std::string format_summary(const StudySummary& s) {
  std::ostringstream o;
  char buf[512];
  auto pct = [](long a, long b) { return b ? 100.0 * a / b : 0.0; };
  o << "rocking_study: " << s.cases << " cases, " << s.bodies << " bodies x " << s.records
    << " horizontal record components (" << s.records_with_vertical
    << " with the station's vertical), both polarities\n";
  const SetSummary& h = s.horizontal;
  const int sym = h.symmetric_index();
  if (sym >= 0) {
    const Tally& t = h.by_eccentricity[static_cast<std::size_t>(sym)];
    std::snprintf(buf, sizeof buf,
                  "\nSymmetric bodies (nu = 0.5), horizontal only: Ishiyama's criterion satisfied in "
                  "%.2f %% of %ld cases (paper: 99.4 %%); %ld overturns it did not predict.\n",
                  t.consistent_percent(Screening::Ishiyama), t.cases,
                  t.missed[static_cast<int>(Screening::Ishiyama)]);
    o << buf;
  }
  for (const SetSummary* set : {&s.horizontal, &s.subset_without_vertical, &s.with_vertical}) {
    if (set->all.cases == 0) continue;
    o << "\n[" << set->name << "] overturns and screening criteria by eccentricity "
      << "(missed = overturned where the criterion predicts safety; false = predicted, stayed)\n";
    std::snprintf(buf, sizeof buf, "  %-5s %8s %8s %7s %8s | %-17s | %-17s | %-17s | %-17s\n", "nu",
                  "cases", "overturn", "%", "x sym", "Housner miss/false", "Ishiyama miss/fals",
                  "B'=2nuB miss/fals", "0.2 rule miss/fal");
    o << buf;
    for (std::size_t e = 0; e < set->eccentricities.size(); ++e) {
      const Tally& t = set->by_eccentricity[e];
      if (t.cases == 0) continue;
      std::snprintf(buf, sizeof buf, "  %-5.2f %8ld %8ld %6.2f%% %8.2f |", set->eccentricities[e],
                    t.cases, t.overturned, t.overturned_percent(), set->overturn_ratio(e));
      o << buf;
      for (int k = 0; k < kScreeningCount; ++k) {
        std::snprintf(buf, sizeof buf, " %7ld / %-7ld |", t.missed[k], t.false_alarms[k]);
        o << buf;
      }
      o << '\n';
    }
    o << "  overturned % by height (rows) and eccentricity (columns) [Figure 7]; "
      << "ratio to nu = 0.5 in brackets [Figure 8]\n";
    o << "  h [m]       ";
    for (double e : set->eccentricities) {
      std::snprintf(buf, sizeof buf, " %17s", ("nu=" + format_number("%.2f", e)).c_str());
      o << buf;
    }
    o << '\n';
    for (std::size_t hi = 0; hi < set->heights.size(); ++hi) {
      std::snprintf(buf, sizeof buf, "  %-12.3f", set->heights[hi]);
      o << buf;
      for (std::size_t e = 0; e < set->eccentricities.size(); ++e) {
        const Tally& t = set->by_eccentricity_height[e][hi];
        if (t.cases == 0) {
          std::snprintf(buf, sizeof buf, " %17s", "-");
        } else {
          std::snprintf(buf, sizeof buf, " %6.2f%% [%6.2f]", t.overturned_percent(),
                        set->overturn_ratio(e, static_cast<int>(hi)));
        }
        o << buf;
      }
      o << '\n';
    }
    o << "  overturned % by PGV band (rows) and eccentricity; ratio to nu = 0.5 in brackets\n";
    const auto& edges = pgv_band_edges();
    for (std::size_t b = 0; b <= edges.size(); ++b) {
      const std::string band = b == 0 ? "< " + format_number("%g", edges[0])
                                      : b == edges.size() ? ">= " + format_number("%g", edges.back())
                                                          : format_number("%g", edges[b - 1]) + "-" +
                                                                format_number("%g", edges[b]);
      std::snprintf(buf, sizeof buf, "  %-12s", (band + " m/s").c_str());
      o << buf;
      for (std::size_t e = 0; e < set->eccentricities.size(); ++e) {
        const Tally& t = set->by_eccentricity_pgv[e][b];
        if (t.cases == 0) {
          std::snprintf(buf, sizeof buf, " %17s", "-");
        } else {
          std::snprintf(buf, sizeof buf, " %6.2f%% [%6.2f]", t.overturned_percent(), set->overturn_ratio_pgv(e, b));
        }
        o << buf;
      }
      o << '\n';
    }
  }
  const VerticalEffect& v = s.vertical_effect;
  long total_pairs = 0;
  for (long p : v.pairs) total_pairs += p;
  if (total_pairs > 0) {
    o << "\nVertical component (same body, record and polarity, without vs with the vertical)\n";
    std::snprintf(buf, sizeof buf, "  %-5s %8s %12s %12s %10s %12s\n", "nu", "pairs", "overturned",
                  "with vert.", "only with", "only without");
    o << buf;
    for (std::size_t e = 0; e < v.eccentricities.size(); ++e) {
      if (v.pairs[e] == 0) continue;
      std::snprintf(buf, sizeof buf, "  %-5.2f %8ld %12ld %12ld %10ld %12ld   (%.2f %% -> %.2f %%)\n",
                    v.eccentricities[e], v.pairs[e], v.overturned_without[e], v.overturned_with[e],
                    v.only_with[e], v.only_without[e], pct(v.overturned_without[e], v.pairs[e]),
                    pct(v.overturned_with[e], v.pairs[e]));
      o << buf;
    }
  }
  return o.str();
}

// ==================================================================== reading cases.csv

CaseFile read_case_csv(const std::string& path) {
  const std::vector<csv::Row> rows = read_csv(path);
  if (rows.empty()) throw StudyError(path + ": empty (no header)");
  CaseFile file;
  file.header = rows[0].text;
  const std::map<std::string, std::size_t> col = csv::column_index(rows[0]);
  const char* needed[] = {"case", "body", "record", "width_m", "cg_height_m", "nu1", "pgv_mps", "polarity",
                          "vertical", "overturned", "committed", "beyond_tipping", "predicts_housner",
                          "predicts_ishiyama", "predicts_ishiyama_equivalent", "predicts_proposed"};
  for (const char* n : needed)
    if (!col.count(n))
      throw StudyError(path + ":" + std::to_string(rows[0].line) + ": no column '" + n +
                       "' (not a rocking_study cases.csv)");
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const std::vector<std::string>& f = rows[i].fields;
    const std::string where = path + ":" + std::to_string(rows[i].line) + ": ";
    if (f.size() != col.size())
      throw StudyError(where + std::to_string(f.size()) + " fields, header has " + std::to_string(col.size()));
    auto get = [&](const char* name) -> const std::string& { return f[col.at(name)]; };
    auto to_size = [&](const char* name) {
      try {
        std::size_t used = 0;
        const unsigned long long v = std::stoull(get(name), &used);
        if (used != get(name).size()) throw std::invalid_argument(name);
        return static_cast<std::size_t>(v);
      } catch (const std::exception&) {
        throw StudyError(where + name + ": not a non-negative integer: '" + get(name) + "'");
      }
    };
    auto to_double = [&](const char* name) {
      try {
        std::size_t used = 0;
        const double v = std::stod(get(name), &used);
        if (used != get(name).size()) throw std::invalid_argument(name);
        return v;
      } catch (const std::exception&) {
        throw StudyError(where + name + ": not a number: '" + get(name) + "'");
      }
    };
    auto to_bool = [&](const char* name) {
      const std::string& v = get(name);
      if (v == "1") return true;
      if (v == "0") return false;
      throw StudyError(where + name + ": expected 0 or 1, got '" + v + "'");
    };
    CaseRow r;
    r.index = to_size("case");
    r.body = to_size("body");
    r.record = to_size("record");
    r.width = to_double("width_m");
    r.cg_height = to_double("cg_height_m");
    r.nu1 = to_double("nu1");
    r.pgv = to_double("pgv_mps");
    const std::string& pol = get("polarity");
    if (pol != "1" && pol != "-1") throw StudyError(where + "polarity: expected 1 or -1, got '" + pol + "'");
    r.polarity = pol == "1" ? 1 : -1;
    r.vertical = to_bool("vertical");
    r.overturned = to_bool("overturned");
    r.committed = to_bool("committed");
    r.beyond_tipping = to_bool("beyond_tipping");
    r.predicted = {to_bool("predicts_housner"), to_bool("predicts_ishiyama"),
                   to_bool("predicts_ishiyama_equivalent"), to_bool("predicts_proposed")};
    file.rows.push_back(r);
    file.lines.push_back(rows[i].text);
  }
  return file;
}

}  // namespace rocking_monitor::core::study
