// rocking_study --fragility: every body (each plane of a two-plane item its own planar body) under
// every record component scaled over --pgv-range; fragility_runs.csv, fragility.json and the table.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "rocking_monitor/study/fragility_io.hpp"
#include "rocking_monitor/study/fragility_study.hpp"
#include "study_jobs.hpp"
#include "study_output_files.hpp"

namespace fs = std::filesystem;

namespace rocking_monitor::tools::study {

namespace {

st::FragilityOptions fragility_options(const Options& o, const Inputs& in) {
  st::FragilityOptions fo;
  fo.settings = in.settings;
  fo.im = st::parse_intensity_measure(o.im_text);
  fo.levels = o.levels;
  const std::vector<double> range = parse_number_list(o.pgv_range_text, "--pgv-range");
  if (range.size() != 2) throw st::StudyError("--pgv-range '" + o.pgv_range_text + "': expected lo,hi in m/s");
  fo.pgv_min = range[0];
  fo.pgv_max = range[1];
  fo.both_polarities = !o.one_polarity;
  fo.vertical = !o.no_vertical;
  fo.bootstrap = o.bootstrap;
  fo.threads = o.threads;
  fo.members = o.members;
  fo.member_seed = o.member_seed;
  return fo;
}

void print_plan(const Options& o, const Inputs& in) {
  std::size_t runs_per_component = 0;
  for (const st::StudyBody& b : in.bodies)
    runs_per_component += b.uncertain ? static_cast<std::size_t>(b.ensemble_size > 0 ? b.ensemble_size : o.members) : 1;
  std::fprintf(stderr,
               "rocking_study: fragility of %zu bodies (%zu models with the members of uncertain items) x %zu "
               "record components x %d levels x %d polarities\n",
               in.bodies.size(), runs_per_component, in.records.records.size(), o.levels, o.one_polarity ? 1 : 2);
}

}  // namespace

int run_fragility_job(const Options& o, Inputs in) {
  // Each plane of a two-plane item is its own planar body here (planar decomposition).
  for (const st::StudyItem& it : in.items) {
    in.bodies.push_back({it.name + " (x)", it.x, it.uncertain, rm::Plane::X, it.ensemble_size});
    in.bodies.push_back({it.name + " (y)", it.y, it.uncertain, rm::Plane::Y, it.ensemble_size});
  }
  const st::FragilityOptions fo = fragility_options(o, in);
  print_plan(o, in);
  if (o.dry_run) return 0;
  const st::FragilityResult fr = st::run_fragility(in.bodies, in.records.records, fo);
  const fs::path out(o.out_dir);
  fs::create_directories(out);
  std::ostringstream runs_csv, json;
  st::write_fragility_runs_csv(runs_csv, fr, in.bodies, in.records.records, fo);
  st::write_fragility_json(json, fr, in.bodies, fo);
  write_file(out / "fragility_runs.csv", runs_csv.str());
  write_file(out / "fragility.json", json.str());
  std::cout << st::format_fragility(fr, in.bodies, fo);
  std::cerr << "rocking_study: wrote " << out.string() << "/{fragility_runs.csv,fragility.json}\n";
  return 0;
}

}  // namespace rocking_monitor::tools::study
