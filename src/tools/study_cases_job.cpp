// rocking_study's main job: every body under every record component (the grid's or a body file's
// bodies), and the two-plane items on station pairs; cases.csv, bodies.csv, records.csv,
// item_cases.csv (with --bodies), summary.json and the printed summary.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#include "progress_meter.hpp"
#include "study_jobs.hpp"
#include "study_output_files.hpp"

namespace fs = std::filesystem;

namespace rocking_monitor::tools::study {

namespace {

/// What the job runs: the body cases of this shard and the item cases.
struct Plan {
  st::StudyOptions options;
  std::size_t total = 0;  ///< body cases over all shards
  st::StationPairs pairs;
  st::ItemStudyOptions item_options;
};

/// What the job ran.
struct Results {
  std::vector<st::CaseResult> cases;
  std::vector<st::ItemCaseResult> items;
  double wall_s = 0.0;
};

/// The body cases: the engine, the shard's range, and their count on stderr.
void plan_body_cases(const Options& o, const Inputs& in, Plan& plan) {
  st::StudyOptions& options = plan.options;
  options.settings = in.settings;
  options.plan.both_polarities = !o.one_polarity;
  options.plan.verticals = !o.no_vertical;
  options.threads = o.threads;
  options.batch = !o.scalar;
  options.trig = o.exact_trig ? rm::BatchTrig::Exact : rm::BatchTrig::Fast;
  plan.total = st::study_case_count(in.bodies.size(), in.records.records, options.plan);
  options.range = st::shard_range(plan.total, in.shard_k, in.shard_n);
  std::size_t with_v = 0, samples = 0;
  std::map<std::string, int> events;
  for (const auto& r : in.records.records) {
    with_v += r.has_vertical();
    samples += r.horizontal.size();
    ++events[r.event];
  }
  std::fprintf(stderr,
               "rocking_study: %zu bodies x %zu record components (%zu with a vertical, %zu events, "
               "%zu samples, loaded in %.1f s from %s%s) = %zu cases; shard %d/%d runs [%zu, %zu)\n",
               in.bodies.size(), in.records.records.size(), with_v, events.size(), samples, in.load_s,
               o.records_dir.c_str(), in.records.from_manifest ? "/MANIFEST.csv" : "", plan.total, in.shard_k,
               in.shard_n, options.range.begin, options.range.end);
}

/// The two-plane items: the station pairs they run on, and their count on stderr.
void plan_item_cases(const Options& o, const Inputs& in, Plan& plan) {
  if (in.items.empty()) return;
  plan.pairs = st::pair_stations(in.records.records);
  st::ItemStudyOptions& item_options = plan.item_options;
  item_options.settings = in.settings;
  item_options.azimuths = in.azimuths;
  item_options.both_polarities = !o.one_polarity;
  item_options.verticals = !o.no_vertical;
  item_options.threads = o.threads;
  const st::StationPairs& pairs = plan.pairs;
  for (const auto& n : pairs.notes) std::cerr << "rocking_study: note: " << n << "\n";
  std::fprintf(stderr,
               "rocking_study: %zu two-plane items x %zu station pairs x %zu azimuths x %d polarities = %zu "
               "item cases (stations not run: %ld with one horizontal, %ld different dt, %ld without "
               "direction, %ld not resolvable; %ld pairs zero-padded)\n",
               in.items.size(), pairs.pairs.size(), in.azimuths.size(), o.one_polarity ? 1 : 2,
               st::item_case_count(in.items.size(), pairs.pairs.size(), item_options), pairs.single_horizontal,
               pairs.different_dt, pairs.no_azimuth, pairs.not_resolvable, pairs.zero_padded);
}

Results run_cases(const Options& o, const Inputs& in, Plan& plan) {
  Results r;
  ProgressMeter bar("cases", o.quiet);
  plan.options.progress = [&bar](std::size_t done, std::size_t n) { bar(done, n); };
  const auto t0 = std::chrono::steady_clock::now();
  r.cases = st::run_study(in.bodies, in.records.records, plan.options);
  if (!in.items.empty()) {
    ProgressMeter item_bar("item cases", o.quiet);
    plan.item_options.progress = [&item_bar](std::size_t done, std::size_t n) { item_bar(done, n); };
    r.items = st::run_item_study(in.items, in.records.records, plan.pairs, plan.item_options);
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

/// cases.csv, bodies.csv and records.csv.
void write_case_files(const fs::path& out, const Inputs& in, const Results& r) {
  {
    std::ofstream f(out / "cases.csv", std::ios::binary);
    if (!f) throw st::StudyError((out / "cases.csv").string() + ": cannot open for writing");
    st::write_case_csv_header(f);
    st::write_case_csv_rows(f, r.cases, in.bodies, in.records.records);
    if (!f) throw st::StudyError((out / "cases.csv").string() + ": write failed");
  }
  std::ostringstream b, rec;
  st::write_bodies_csv(b, in.bodies);
  st::write_records_csv(rec, in.records.records);
  write_file(out / "bodies.csv", b.str());
  write_file(out / "records.csv", rec.str());
}

/// summary.json's "run" block: where the cases came from and how they were run.
st::StudyRunInfo run_info(const Options& o, const Inputs& in, const Plan& plan, double wall_s) {
  st::StudyRunInfo run;
  run.records_dir = o.records_dir;
  run.from_manifest = in.records.from_manifest;
  run.bodies_source = o.bodies_file.empty() ? "paper grid" : o.bodies_file;
  run.method = rm::to_string(in.settings.method);
  run.model = rm::to_string(in.settings.model);
  run.tol = in.settings.tol;
  run.substeps = in.settings.substeps;
  run.threads = o.threads > 0 ? o.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  run.shard = o.shard_text;
  run.case_begin = plan.options.range.begin;
  run.case_end = plan.options.range.end;
  run.total_cases = plan.total;
  run.wall_time_s = wall_s;
  run.notes = in.records.notes;
  return run;
}

/// item_cases.csv (with --bodies) and summary.json; returns the body cases' summary.
st::StudySummary write_summaries(const Options& o, const fs::path& out, const Inputs& in, const Plan& plan,
                                 const Results& r) {
  std::vector<st::CaseRow> rows;
  rows.reserve(r.cases.size());
  for (const auto& c : r.cases) rows.push_back(st::to_case_row(c, in.bodies, in.records.records));
  const st::StudySummary summary = st::summarize(rows);
  const st::StudyRunInfo run = run_info(o, in, plan, r.wall_s);
  if (!o.bodies_file.empty()) {
    // Written for every body file (header only without two-plane items), so that a script over a
    // catalogue always finds it; the grid runs keep their files.
    std::ostringstream ic;
    st::write_item_cases_csv(ic, r.items, in.items, in.records.records, plan.pairs);
    write_file(out / "item_cases.csv", ic.str());
  }
  if (in.items.empty()) {
    write_file(out / "summary.json", st::summary_json(summary, run));
  } else {
    const st::ItemSummary item_summary = st::summarize_items(r.items, in.items, plan.pairs, in.azimuths);
    write_file(out / "summary.json", st::summary_json(summary, run, &item_summary));
  }
  return summary;
}

/// The summary on stdout: the body cases' tables, the two-plane items' lines.
void print_summary(const Inputs& in, const Plan& plan, const Results& r, const st::StudySummary& summary) {
  if (!in.bodies.empty()) std::cout << st::format_summary(summary);
  if (in.items.empty()) return;
  const st::ItemTally t = st::summarize_items(r.items, in.items, plan.pairs, in.azimuths).all;
  std::printf("Two-plane items (pure rocking, planes uncoupled): %ld item cases, %ld overturned "
              "(%ld decided by the y plane; x only %ld, y only %ld, both %ld)\n",
              t.cases, t.overturned, t.overturned_decided_by_y, t.overturned_x_only, t.overturned_y_only,
              t.overturned_both);
  if (t.solid_cases > 0)
    std::printf("The 3-D model on both horizontals at once (items with a base polygon): %ld of %ld item cases "
                "overturned; its overturn decision differs from the planar pair's in %ld\n",
                t.solid_overturned, t.solid_cases, t.solid_differs);
}

}  // namespace

int run_cases_job(const Options& o, const Inputs& in) {
  Plan plan;
  plan_body_cases(o, in, plan);
  plan_item_cases(o, in, plan);
  if (o.dry_run) return 0;
  const Results r = run_cases(o, in, plan);
  const fs::path out(o.out_dir);
  fs::create_directories(out);
  write_case_files(out, in, r);
  const st::StudySummary summary = write_summaries(o, out, in, plan, r);
  print_summary(in, plan, r, summary);
  std::fprintf(stderr, "rocking_study: %zu cases%s in %.1f s (%.0f cases/s); wrote %s/{cases.csv,bodies.csv,"
               "records.csv,summary.json%s}\n",
               r.cases.size(), in.items.empty() ? "" : (" + " + std::to_string(r.items.size()) + " item cases").c_str(),
               r.wall_s, r.wall_s > 0 ? (r.cases.size() + r.items.size()) / r.wall_s : 0.0, o.out_dir.c_str(),
               o.bodies_file.empty() ? "" : ",item_cases.csv");
  return 0;
}

}  // namespace rocking_monitor::tools::study
