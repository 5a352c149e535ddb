// rocking_study's flags: one table in --help's order (the order --help prints them in, which a test
// compares byte for byte), and the comma lists some of them take.
#include "study_options.hpp"

#include <exception>
#include <sstream>

namespace rocking_monitor::tools::study {

void add_options(CLI::App& app, Options& o) {
  app.add_option("--records", o.records_dir,
                 "Records directory (MANIFEST.csv if present, else every AT2/BBP/SMC/CSV file below it)")
      ->default_val(o.records_dir);
  app.add_option("--bodies", o.bodies_file,
                 "YAML file of bodies or a monitor catalogue (items:); replaces the paper's grid. Bodies "
                 "with a depth are two-plane items, run on station pairs (see docs/study.md)");
  app.add_option("--azimuth", o.azimuth_texts,
                 "Two-plane items: azimuths of the item's x axis, degrees clockwise from north (repeatable "
                 "or a comma list; y is 90 deg counter-clockwise of x)")
      ->default_val("0,90");
  app.add_option("--solid-model", o.solid_model,
                 "Two-plane items: auto (default: items with a base_polygon also run the 3-D model, "
                 "columns solid_* of item_cases.csv) | 3d (every item, boxes as B x D) | planar (the planes only)")
      ->check(CLI::IsMember({"auto", "3d", "planar"}))->default_val(o.solid_model);
  app.add_option("--heights", o.grid.heights, "Grid: number of centre-of-mass heights, log-spaced 0.25-4 m")
      ->default_val(o.grid.heights)->check(CLI::Range(1, 1000));
  app.add_option("--widths", o.grid.widths, "Grid: base widths per height, geometric in [max(0.08,0.16h), min(3.5,1.2h)]")
      ->default_val(o.grid.widths)->check(CLI::Range(1, 1000));
  app.add_option("--eccentricities", o.eccentricities_text, "Grid: comma-separated nu values (0.5 = symmetric)")
      ->default_val(o.eccentricities_text);
  app.add_option("--only", o.only, "Keep components whose file path, event or station contains this (repeatable)");
  app.add_option("--exclude", o.exclude, "Drop files whose path contains this (repeatable)");
  app.add_flag("--no-vertical", o.no_vertical, "Do not run the cases with the vertical component");
  app.add_flag("--one-polarity", o.one_polarity, "Only the records as recorded (no reversed polarity)");
  app.add_option("--method", o.method_text, "dopri5 | rk4 | analytic (analytic needs --model linearized)")
      ->check(CLI::IsMember({"dopri5", "rk4", "analytic"}))->default_val(o.method_text);
  app.add_option("--model", o.model_text, "nonlinear | linearized")
      ->check(CLI::IsMember({"nonlinear", "linearized"}))->default_val(o.model_text);
  app.add_option("--tol", o.settings.tol, "dopri5 relative tolerance")->default_val(o.settings.tol);
  app.add_option("--substeps", o.settings.substeps, "rk4 sub-steps per input sample")->default_val(o.settings.substeps);
  app.add_option("--threads", o.threads, "Worker threads (0 = all cores)")->default_val(0)->check(CLI::Range(0, 4096));
  app.add_option("--shard", o.shard_text, "Run only shard k of n (contiguous case range), e.g. 3/8")
      ->default_val(o.shard_text);
  app.add_option("--out", o.out_dir, "Output directory")->default_val(o.out_dir);
  app.add_option("--merge", o.merge_files,
                 "Merge the cases.csv files of shards into --out (checks every case is there once) and "
                 "summarize; nothing is simulated");
  app.add_flag("--fragility", o.fragility,
               "Fragility curves instead of the study: every body (and each plane of a two-plane item) under "
               "every record component scaled to --levels PGVs over --pgv-range; writes fragility_runs.csv and "
               "fragility.json (lognormal fit, bootstrap band); plot with scripts/plot_fragility.py");
  app.add_option("--im", o.im_text, "--fragility: intensity measure of the fit: pgv | pga | psv (at the body's Housner period)")
      ->check(CLI::IsMember({"pgv", "pga", "psv"}))->default_val(o.im_text);
  app.add_option("--levels", o.levels, "--fragility: intensity levels per record")->default_val(o.levels)->check(CLI::Range(2, 1000));
  app.add_option("--pgv-range", o.pgv_range_text, "--fragility: PGV range the records are scaled over, m/s (lo,hi)")
      ->default_val(o.pgv_range_text);
  app.add_option("--bootstrap", o.bootstrap, "--fragility: bootstrap resamples of each fit")->default_val(o.bootstrap)
      ->check(CLI::Range(10, 100000));
  app.add_option("--members", o.members,
                 "--fragility: members per catalogue item given with distributions (its own ensemble_size wins); "
                 "the fit pools every member's runs")
      ->default_val(o.members)->check(CLI::Range(1, 100000));
  app.add_option("--member-seed", o.member_seed, "--fragility: seed of the members' Latin hypercube (the node's ~ensemble_seed)")
      ->default_val(o.member_seed);
  app.add_flag("--fast-trig", o.fast_trig,
               "Batch engine with Highway's vector sin/cos (a few ulp; the default: it meets the accuracy policy, "
               "docs/performance.md); kept for old command lines");
  app.add_flag("--exact-trig", o.exact_trig,
               "Batch engine with libm's sin/cos per lane: bit-identical to --scalar (for cross-checks)")
      ->excludes("--fast-trig");
  app.add_flag("--scalar", o.scalar,
               "One RockingModel per case instead of the batch engine (bodies of a record input stepped together, "
               "SIMD across bodies): for timing and cross-checks");
  app.add_flag("--quiet", o.quiet, "No progress bar");
  app.add_flag("--dry-run", o.dry_run, "Load bodies and records, print the plan and exit");
}

std::vector<double> parse_number_list(const std::string& text, const char* what) {
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

}  // namespace rocking_monitor::tools::study
