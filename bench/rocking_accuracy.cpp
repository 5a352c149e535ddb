// Accuracy against cost, overturn-decision agreement and stability maps of the rocking
// integrators (issue 6). Writes CSV files that scripts/plot_performance.py turns into the charts
// of docs/performance/ (run everything with `bash scripts/make_performance_charts.sh`).
//
//   rocking_accuracy [--out DIR] [--records DIR] [--jobs N] [--quick] [--quiet] [--batch-lanes N]
//                    [work-precision] [overturn] [stability]     (default: all three)
//                    [policy]    the accuracy policy of fast paths (issue 28): prints its table,
//                                writes accuracy_policy.csv, exit status 1 when a fast path fails it
//
// Reference: dopri5 at tol = 1e-12 on the same piecewise-linear input re-sampled 8x finer (the
// identical signal, with 8x shorter forced steps); the CVODE tests (reference_tests) show that
// dopri5 at 1e-10 agrees with an independent integrator to 1e-8 s on impact times.
//
// work_precision.csv   one row per (model, input, case, method setting): cost (ns per simulated
//                      second, ns per item-step) and errors (max |theta|/alpha, first-10 impact
//                      times, overturn time) against the reference; the nonlinear dopri5
//                      settings also through the batch engine (BatchRocking, --batch-lanes
//                      identical lanes, exact and fast trig: cost per lane-step; the exact-trig
//                      batch must reproduce the scalar run bit for bit, else exit status 1)
// overturn_agreement.csv  every .AT2 record x 4 bodies x every method: overturned or not, against
//                      the reference (dopri5 1e-12 on the record's own samples)
// stability_map.csv    per (method setting, p, alpha): free-rocking impacts, impact-time error,
//                      energy gain between successive peaks, rest time, wrong decisions over a
//                      set of pulses near the overturning boundary, events and steps per sample
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "accuracy/accuracy_parts.hpp"
#include "bench_common.hpp"
#include "command_line.hpp"

namespace rb = rocking_monitor::bench;
using namespace rocking_monitor::bench::accuracy;  // NOLINT(google-build-using-namespace): the parts

int main(int argc, char** argv) {
  std::string out = "docs/performance";
  std::string records = rb::records_dir();
  int jobs = 2;
  std::size_t batch_lanes = 128;
  bool quick = false, quiet = false;
  std::vector<std::string> parts;
  CLI::App app{"rocking_accuracy: work-precision, overturn-agreement and stability-map tables (docs/performance)",
                "rocking_accuracy"};
  app.add_option("--out", out, "Output directory")->default_val(out);
  app.add_option("--records", records, "Strong-motion records directory")->default_val(records);
  app.add_option("--jobs", jobs, "Worker threads")->default_val(jobs)->check(CLI::PositiveNumber);
  app.add_flag("--quick", quick, "Fewer cases (a smoke run)");
  app.add_flag("--quiet", quiet, "No progress bar (there is one only when stderr is a terminal)");
  app.add_option("--batch-lanes", batch_lanes,
                 "Identical lanes of the batch engine in work-precision (cost per lane-step)")
      ->default_val(batch_lanes)
      ->check(CLI::PositiveNumber);
  app.add_option("parts", parts, "work-precision | overturn | stability | planar-vs-3d | policy (default: the "
                 "first three)")
      ->check(CLI::IsMember({"work-precision", "overturn", "stability", "planar-vs-3d", "policy"}));
  if (const auto status = rocking_monitor::tools::parse_command_line(app, argc, argv, "rocking_accuracy")) return *status;
  if (parts.empty()) parts = {"work-precision", "overturn", "stability"};
  std::filesystem::create_directories(out);
  int status = 0;
  for (const std::string& p : parts) {
    const auto t0 = std::chrono::steady_clock::now();
    if (p == "work-precision") {
      if (work_precision(out, records, quick, batch_lanes) != 0) status = 1;
    } else if (p == "planar-vs-3d") {
      planar_vs_3d(out, records, quick);
    } else if (p == "overturn") {
      overturn_agreement(out, records, jobs, quick, quiet);
    } else if (p == "policy") {
      if (accuracy_policy(out, records, jobs, quick, quiet) != 0) {
        status = 1;
        std::fprintf(stderr, "rocking_accuracy: error: a fast path fails the accuracy policy (FAIL lines above)\n");
      }
    } else {
      stability_maps(out, jobs, quick, quiet);
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "rocking_accuracy: %s written to %s in %.0f s\n", p.c_str(), out.c_str(), s);
  }
  if (status != 0)
    std::fprintf(stderr, "rocking_accuracy: error: the exact-trig batch engine differs from the "
                         "scalar model (see the lines above)\n");
  return status;
}
