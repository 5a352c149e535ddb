// rocking_study: the paper's study (Boroschek & Romo) over every record of a directory.
// Thin command-line layer over rocking_monitor/study/study.hpp (grid, records, cases, summary) and
// study_io.hpp (YAML bodies, JSON summary). See docs/study.md.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "rocking_monitor/motion/record_reader.hpp"
#include "rocking_monitor/study/fragility_io.hpp"
#include "rocking_monitor/study/fragility_study.hpp"
#include "rocking_monitor/study/study.hpp"
#include "rocking_monitor/study/study_io.hpp"
#include "command_line.hpp"

#ifndef ROCKING_RECORDS_DIR
#define ROCKING_RECORDS_DIR "../shared/records"
#endif

namespace rm = rocking_monitor::core;
namespace st = rocking_monitor::core::study;
namespace fs = std::filesystem;

namespace {

std::string duration_text(double s) {
  if (!std::isfinite(s) || s < 0) return "--";
  char buf[32];
  const long t = std::lround(s);
  if (t >= 3600)
    std::snprintf(buf, sizeof buf, "%ldh%02ldm", t / 3600, (t / 60) % 60);
  else if (t >= 60)
    std::snprintf(buf, sizeof buf, "%ldm%02lds", t / 60, t % 60);
  else
    std::snprintf(buf, sizeof buf, "%lds", t);
  return buf;
}

// Progress on stderr: a redrawn bar on a terminal, a line every ~10 % or 30 s otherwise.
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled), tty_(::isatty(2) != 0) {
    start_ = last_line_ = std::chrono::steady_clock::now();
  }
  void operator()(std::size_t done, std::size_t total) {
    if (!enabled_ || total == 0) return;
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double rate = elapsed > 0 ? done / elapsed : 0.0;
    const double left = rate > 0 ? (total - done) / rate : NAN;
    const double frac = static_cast<double>(done) / total;
    char line[200];
    if (tty_) {
      const int width = 30, fill = static_cast<int>(frac * width);
      std::string bar(static_cast<std::size_t>(fill), '=');
      if (fill < width) bar += '>' + std::string(static_cast<std::size_t>(width - fill - 1), ' ');
      std::snprintf(line, sizeof line, "\r[%s] %5.1f%%  %zu/%zu cases  %.0f cases/s  left %s   ",
                    bar.c_str(), 100 * frac, done, total, rate, duration_text(left).c_str());
      std::cerr << line << (done == total ? "\n" : "") << std::flush;
    } else {
      const double since = std::chrono::duration<double>(now - last_line_).count();
      const int decile = static_cast<int>(frac * 10);
      if (done == total || decile > last_decile_ || since > 30) {
        std::snprintf(line, sizeof line, "rocking_study: %5.1f%%  %zu/%zu cases  %.0f cases/s  left %s\n",
                      100 * frac, done, total, rate, duration_text(left).c_str());
        std::cerr << line << std::flush;
        last_decile_ = decile;
        last_line_ = now;
      }
    }
  }

 private:
  bool enabled_, tty_;
  int last_decile_ = 0;
  std::chrono::steady_clock::time_point start_, last_line_;
};

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw st::StudyError(path.string() + ": cannot open for writing");
  out << text;
  if (!out) throw st::StudyError(path.string() + ": write failed");
}

std::vector<double> parse_list(const std::string& text, const char* what) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    std::size_t used = 0;
    double x = 0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size()) throw st::StudyError(std::string(what) + ": bad number '" + item + "'");
    v.push_back(x);
  }
  return v;
}

// --merge: concatenate shard case files in case order, check they cover 0..N-1 once, summarize.
int merge(const std::vector<std::string>& files, const fs::path& out_dir) {
  std::vector<std::pair<std::size_t, std::pair<std::size_t, std::size_t>>> order;  // case, (file, row)
  std::vector<st::CaseFile> parts;
  for (const auto& f : files) {
    parts.push_back(st::read_case_csv(f));
    if (parts.back().header != parts.front().header)
      throw st::StudyError(f + ": header differs from " + files.front());
    for (std::size_t i = 0; i < parts.back().rows.size(); ++i)
      order.push_back({parts.back().rows[i].index, {parts.size() - 1, i}});
  }
  std::sort(order.begin(), order.end());
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (order[i].first != i) {
      const std::string what = order[i].first < i ? "appears twice" : "is missing";
      throw st::StudyError("case " + std::to_string(order[i].first < i ? order[i].first : i) + " " + what +
                           " in the merged files (each case must be in exactly one shard)");
    }
  }
  fs::create_directories(out_dir);
  std::ofstream out(out_dir / "cases.csv", std::ios::binary);
  out << parts.front().header << '\n';
  std::vector<st::CaseRow> rows;
  rows.reserve(order.size());
  for (const auto& o : order) {
    out << parts[o.second.first].lines[o.second.second] << '\n';
    rows.push_back(parts[o.second.first].rows[o.second.second]);
  }
  if (!out) throw st::StudyError((out_dir / "cases.csv").string() + ": write failed");
  for (const char* side : {"bodies.csv", "records.csv"}) {
    const fs::path src = fs::path(files.front()).parent_path() / side;
    if (fs::exists(src) && fs::absolute(src) != fs::absolute(out_dir / side))
      fs::copy_file(src, out_dir / side, fs::copy_options::overwrite_existing);
  }
  const st::StudySummary summary = st::summarize(rows);
  st::StudyRunInfo run;
  run.shard = "merged from " + std::to_string(files.size()) + " files";
  run.case_end = run.total_cases = rows.size();
  run.wall_time_s = -1;
  write_file(out_dir / "summary.json", st::summary_json(summary, run));
  std::cout << st::format_summary(summary);
  std::cerr << "rocking_study: merged " << rows.size() << " cases into " << out_dir.string() << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "rocking_study: the overturning study of Boroschek & Romo over every horizontal record component "
      "of a directory (both polarities, with and without the station's vertical), for the paper's "
      "body grid or your own bodies; bodies with a depth (two-plane items) run on both horizontals of each "
      "station rotated to --azimuth. Writes cases.csv, bodies.csv, records.csv, summary.json (and with "
      "--bodies item_cases.csv) to "
      "--out and prints the summary. See docs/study.md."};
  std::string records_dir = ROCKING_RECORDS_DIR, bodies_file, out_dir = "study_out", shard_text = "1/1";
  std::string method_text = "dopri5", model_text = "nonlinear", eccentricities_text = "0.5,0.4,0.3,0.2";
  std::vector<std::string> only, exclude, merge_files, azimuth_texts{"0,90"};
  st::StudyGrid grid;
  rm::SolverSettings settings;
  int threads = 0;
  bool no_vertical = false, one_polarity = false, quiet = false, dry_run = false;

  app.add_option("--records", records_dir,
                 "Records directory (MANIFEST.csv if present, else every AT2/BBP/SMC/CSV file below it)")
      ->default_val(records_dir);
  app.add_option("--bodies", bodies_file,
                 "YAML file of bodies or a monitor catalogue (items:); replaces the paper's grid. Bodies "
                 "with a depth are two-plane items, run on station pairs (see docs/study.md)");
  app.add_option("--azimuth", azimuth_texts,
                 "Two-plane items: azimuths of the item's x axis, degrees clockwise from north (repeatable "
                 "or a comma list; y is 90 deg counter-clockwise of x)")
      ->default_val("0,90");
  std::string solid_model = "auto";
  app.add_option("--solid-model", solid_model,
                 "Two-plane items: auto (default: items with a base_polygon also run the 3-D model, "
                 "columns solid_* of item_cases.csv) | 3d (every item, boxes as B x D) | planar (the planes only)")
      ->check(CLI::IsMember({"auto", "3d", "planar"}))->default_val(solid_model);
  app.add_option("--heights", grid.heights, "Grid: number of centre-of-mass heights, log-spaced 0.25-4 m")
      ->default_val(grid.heights)->check(CLI::Range(1, 1000));
  app.add_option("--widths", grid.widths, "Grid: base widths per height, geometric in [max(0.08,0.16h), min(3.5,1.2h)]")
      ->default_val(grid.widths)->check(CLI::Range(1, 1000));
  app.add_option("--eccentricities", eccentricities_text, "Grid: comma-separated nu values (0.5 = symmetric)")
      ->default_val(eccentricities_text);
  app.add_option("--only", only, "Keep components whose file path, event or station contains this (repeatable)");
  app.add_option("--exclude", exclude, "Drop files whose path contains this (repeatable)");
  app.add_flag("--no-vertical", no_vertical, "Do not run the cases with the vertical component");
  app.add_flag("--one-polarity", one_polarity, "Only the records as recorded (no reversed polarity)");
  app.add_option("--method", method_text, "dopri5 | rk4 | analytic (analytic needs --model linearized)")
      ->check(CLI::IsMember({"dopri5", "rk4", "analytic"}))->default_val(method_text);
  app.add_option("--model", model_text, "nonlinear | linearized")
      ->check(CLI::IsMember({"nonlinear", "linearized"}))->default_val(model_text);
  app.add_option("--tol", settings.tol, "dopri5 relative tolerance")->default_val(settings.tol);
  app.add_option("--substeps", settings.substeps, "rk4 sub-steps per input sample")->default_val(settings.substeps);
  app.add_option("--threads", threads, "Worker threads (0 = all cores)")->default_val(0)->check(CLI::Range(0, 4096));
  app.add_option("--shard", shard_text, "Run only shard k of n (contiguous case range), e.g. 3/8")
      ->default_val(shard_text);
  app.add_option("--out", out_dir, "Output directory")->default_val(out_dir);
  app.add_option("--merge", merge_files,
                 "Merge the cases.csv files of shards into --out (checks every case is there once) and "
                 "summarize; nothing is simulated");
  bool fragility = false;
  std::string im_text = "pgv", pgv_range_text = "0.02,2";
  int levels = 12, bootstrap = 200, members = 32;
  std::uint64_t member_seed = 1;
  app.add_flag("--fragility", fragility,
               "Fragility curves instead of the study: every body (and each plane of a two-plane item) under "
               "every record component scaled to --levels PGVs over --pgv-range; writes fragility_runs.csv and "
               "fragility.json (lognormal fit, bootstrap band); plot with scripts/plot_fragility.py");
  app.add_option("--im", im_text, "--fragility: intensity measure of the fit: pgv | pga | psv (at the body's Housner period)")
      ->check(CLI::IsMember({"pgv", "pga", "psv"}))->default_val(im_text);
  app.add_option("--levels", levels, "--fragility: intensity levels per record")->default_val(levels)->check(CLI::Range(2, 1000));
  app.add_option("--pgv-range", pgv_range_text, "--fragility: PGV range the records are scaled over, m/s (lo,hi)")
      ->default_val(pgv_range_text);
  app.add_option("--bootstrap", bootstrap, "--fragility: bootstrap resamples of each fit")->default_val(bootstrap)
      ->check(CLI::Range(10, 100000));
  app.add_option("--members", members,
                 "--fragility: members per catalogue item given with distributions (its own ensemble_size wins); "
                 "the fit pools every member's runs")
      ->default_val(members)->check(CLI::Range(1, 100000));
  app.add_option("--member-seed", member_seed, "--fragility: seed of the members' Latin hypercube (the node's ~ensemble_seed)")
      ->default_val(member_seed);
  bool scalar = false, fast_trig = false, exact_trig = false;
  app.add_flag("--fast-trig", fast_trig,
               "Batch engine with Highway's vector sin/cos (a few ulp; the default: it meets the accuracy policy, "
               "docs/performance.md); kept for old command lines");
  app.add_flag("--exact-trig", exact_trig,
               "Batch engine with libm's sin/cos per lane: bit-identical to --scalar (for cross-checks)")
      ->excludes("--fast-trig");
  app.add_flag("--scalar", scalar,
               "One RockingModel per case instead of the batch engine (bodies of a record input stepped together, "
               "SIMD across bodies): for timing and cross-checks");
  app.add_flag("--quiet", quiet, "No progress bar");
  app.add_flag("--dry-run", dry_run, "Load bodies and records, print the plan and exit");
  if (const auto status = rocking_monitor::tools::parse_command_line(app, argc, argv, "rocking_study")) return *status;

  try {
    if (!merge_files.empty()) return merge(merge_files, out_dir);

    rm::parse_method(method_text, settings.method);
    rm::parse_model(model_text, settings.model);
    if (const std::string e = rm::validate(settings); !e.empty()) throw st::StudyError(e);
    const auto [shard_k, shard_n] = st::parse_shard(shard_text);

    std::vector<st::StudyBody> bodies;
    std::vector<st::StudyItem> items;
    const std::vector<double> azimuths = st::parse_azimuths(azimuth_texts);
    if (!bodies_file.empty()) {
      st::BodyFile file = st::load_body_file(bodies_file);
      bodies = std::move(file.bodies);
      items = std::move(file.items);
      for (const std::string& n : file.notes) std::cerr << "rocking_study: note: " << n << "\n";
      for (st::StudyItem& it : items) {
        if (solid_model == "planar") it.solid.reset();
        // a box: its planes' bodies exactly (the y plane's own radius of gyration)
        else if (solid_model == "3d" && !it.solid)
          it.solid = rocking_monitor::core::box_base_body(it.x, it.depth.depth, it.depth.eccentricity_y, it.y.radius_of_gyration);
      }
      // Item cases are numbered apart from the body cases and have no merge step yet.
      if (!items.empty() && shard_n != 1)
        throw st::StudyError(bodies_file + ": two-plane items (bodies with a depth) cannot be run with --shard yet");
    } else {
      grid.eccentricities = parse_list(eccentricities_text, "--eccentricities");
      bodies = st::grid_bodies(grid);
    }
    const auto t_load = std::chrono::steady_clock::now();
    st::RecordSelection selection{only, exclude};
    const st::StudyRecords records = st::load_study_records(records_dir, selection);
    const double load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_load).count();
    for (const auto& n : records.notes) std::cerr << "rocking_study: note: " << n << "\n";
    if (fragility) {
      // Each plane of a two-plane item is its own planar body here (planar decomposition).
      for (const st::StudyItem& it : items) {
        bodies.push_back({it.name + " (x)", it.x, it.uncertain, rocking_monitor::core::Plane::X, it.ensemble_size});
        bodies.push_back({it.name + " (y)", it.y, it.uncertain, rocking_monitor::core::Plane::Y, it.ensemble_size});
      }
      st::FragilityOptions fo;
      fo.settings = settings;
      fo.im = st::parse_intensity_measure(im_text);
      fo.levels = levels;
      const std::vector<double> range = parse_list(pgv_range_text, "--pgv-range");
      if (range.size() != 2) throw st::StudyError("--pgv-range '" + pgv_range_text + "': expected lo,hi in m/s");
      fo.pgv_min = range[0];
      fo.pgv_max = range[1];
      fo.both_polarities = !one_polarity;
      fo.vertical = !no_vertical;
      fo.bootstrap = bootstrap;
      fo.threads = threads;
      fo.members = members;
      fo.member_seed = member_seed;
      std::size_t runs_per_component = 0;
      for (const st::StudyBody& b : bodies)
        runs_per_component += b.uncertain ? static_cast<std::size_t>(b.ensemble_size > 0 ? b.ensemble_size : members) : 1;
      std::fprintf(stderr,
                   "rocking_study: fragility of %zu bodies (%zu models with the members of uncertain items) x %zu "
                   "record components x %d levels x %d polarities\n",
                   bodies.size(), runs_per_component, records.records.size(), levels, one_polarity ? 1 : 2);
      if (dry_run) return 0;
      const st::FragilityResult fr = st::run_fragility(bodies, records.records, fo);
      const fs::path out(out_dir);
      fs::create_directories(out);
      std::ostringstream runs_csv, json;
      st::write_fragility_runs_csv(runs_csv, fr, bodies, records.records, fo);
      st::write_fragility_json(json, fr, bodies, fo);
      write_file(out / "fragility_runs.csv", runs_csv.str());
      write_file(out / "fragility.json", json.str());
      std::cout << st::format_fragility(fr, bodies, fo);
      std::cerr << "rocking_study: wrote " << out.string() << "/{fragility_runs.csv,fragility.json}\n";
      return 0;
    }

    st::StudyOptions options;
    options.settings = settings;
    options.plan.both_polarities = !one_polarity;
    options.plan.verticals = !no_vertical;
    options.threads = threads;
    options.batch = !scalar;
    options.trig = exact_trig ? rocking_monitor::core::BatchTrig::Exact : rocking_monitor::core::BatchTrig::Fast;
    const std::size_t total = st::study_case_count(bodies.size(), records.records, options.plan);
    options.range = st::shard_range(total, shard_k, shard_n);
    std::size_t with_v = 0, samples = 0;
    std::map<std::string, int> events;
    for (const auto& r : records.records) {
      with_v += r.has_vertical();
      samples += r.horizontal.size();
      ++events[r.event];
    }
    std::fprintf(stderr,
                 "rocking_study: %zu bodies x %zu record components (%zu with a vertical, %zu events, "
                 "%zu samples, loaded in %.1f s from %s%s) = %zu cases; shard %d/%d runs [%zu, %zu)\n",
                 bodies.size(), records.records.size(), with_v, events.size(), samples, load_s,
                 records_dir.c_str(), records.from_manifest ? "/MANIFEST.csv" : "", total, shard_k, shard_n,
                 options.range.begin, options.range.end);
    st::StationPairs pairs;
    st::ItemStudyOptions item_options;
    if (!items.empty()) {
      pairs = st::pair_stations(records.records);
      item_options.settings = settings;
      item_options.azimuths = azimuths;
      item_options.both_polarities = !one_polarity;
      item_options.verticals = !no_vertical;
      item_options.threads = threads;
      for (const auto& n : pairs.notes) std::cerr << "rocking_study: note: " << n << "\n";
      std::fprintf(stderr,
                   "rocking_study: %zu two-plane items x %zu station pairs x %zu azimuths x %d polarities = %zu "
                   "item cases (stations not run: %ld with one horizontal, %ld different dt, %ld without "
                   "direction, %ld not resolvable; %ld pairs zero-padded)\n",
                   items.size(), pairs.pairs.size(), azimuths.size(), one_polarity ? 1 : 2,
                   st::item_case_count(items.size(), pairs.pairs.size(), item_options), pairs.single_horizontal,
                   pairs.different_dt, pairs.no_azimuth, pairs.not_resolvable, pairs.zero_padded);
    }
    if (dry_run) return 0;

    ProgressBar bar(!quiet);
    options.progress = [&bar](std::size_t done, std::size_t n) { bar(done, n); };
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<st::CaseResult> results = st::run_study(bodies, records.records, options);
    std::vector<st::ItemCaseResult> item_results;
    if (!items.empty()) {
      ProgressBar item_bar(!quiet);
      item_options.progress = [&item_bar](std::size_t done, std::size_t n) { item_bar(done, n); };
      item_results = st::run_item_study(items, records.records, pairs, item_options);
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    const fs::path out(out_dir);
    fs::create_directories(out);
    {
      std::ofstream f(out / "cases.csv", std::ios::binary);
      if (!f) throw st::StudyError((out / "cases.csv").string() + ": cannot open for writing");
      st::write_case_csv_header(f);
      st::write_case_csv_rows(f, results, bodies, records.records);
      if (!f) throw st::StudyError((out / "cases.csv").string() + ": write failed");
    }
    {
      std::ostringstream b, r;
      st::write_bodies_csv(b, bodies);
      st::write_records_csv(r, records.records);
      write_file(out / "bodies.csv", b.str());
      write_file(out / "records.csv", r.str());
    }
    std::vector<st::CaseRow> rows;
    rows.reserve(results.size());
    for (const auto& c : results) rows.push_back(st::to_case_row(c, bodies, records.records));
    const st::StudySummary summary = st::summarize(rows);
    st::StudyRunInfo run;
    run.records_dir = records_dir;
    run.from_manifest = records.from_manifest;
    run.bodies_source = bodies_file.empty() ? "paper grid" : bodies_file;
    run.method = rm::to_string(settings.method);
    run.model = rm::to_string(settings.model);
    run.tol = settings.tol;
    run.substeps = settings.substeps;
    run.threads = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    run.shard = shard_text;
    run.case_begin = options.range.begin;
    run.case_end = options.range.end;
    run.total_cases = total;
    run.wall_time_s = wall;
    run.notes = records.notes;
    if (!bodies_file.empty()) {
      // Written for every body file (header only without two-plane items), so that a script over a
      // catalogue always finds it; the grid runs keep their files.
      std::ostringstream ic;
      st::write_item_cases_csv(ic, item_results, items, records.records, pairs);
      write_file(out / "item_cases.csv", ic.str());
    }
    if (items.empty()) {
      write_file(out / "summary.json", st::summary_json(summary, run));
    } else {
      const st::ItemSummary item_summary = st::summarize_items(item_results, items, pairs, azimuths);
      write_file(out / "summary.json", st::summary_json(summary, run, &item_summary));
    }
    if (!bodies.empty()) std::cout << st::format_summary(summary);
    if (!items.empty()) {
      const st::ItemTally t = st::summarize_items(item_results, items, pairs, azimuths).all;
      std::printf("Two-plane items (pure rocking, planes uncoupled): %ld item cases, %ld overturned "
                  "(%ld decided by the y plane; x only %ld, y only %ld, both %ld)\n",
                  t.cases, t.overturned, t.overturned_decided_by_y, t.overturned_x_only, t.overturned_y_only,
                  t.overturned_both);
      if (t.solid_cases > 0)
        std::printf("The 3-D model on both horizontals at once (items with a base polygon): %ld of %ld item cases "
                    "overturned; its overturn decision differs from the planar pair's in %ld\n",
                    t.solid_overturned, t.solid_cases, t.solid_differs);
    }
    std::fprintf(stderr, "rocking_study: %zu cases%s in %.1f s (%.0f cases/s); wrote %s/{cases.csv,bodies.csv,"
                 "records.csv,summary.json%s}\n",
                 results.size(), items.empty() ? "" : (" + " + std::to_string(item_results.size()) + " item cases").c_str(),
                 wall, wall > 0 ? (results.size() + item_results.size()) / wall : 0.0, out_dir.c_str(),
                 bodies_file.empty() ? "" : ",item_cases.csv");
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "rocking_study: error: " << e.what() << "\n";
    return 2;
  }
}
