// rocking_experiments --margins (issue 41): each test's margin per specimen member, the table
// motion scaled until the model overturns. A run that overturns stops there, so most of the cost is
// in the scales that stand.
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "experiment_run.hpp"
#include "progress_meter.hpp"

namespace rocking_monitor::tools::experiments {

namespace {

/// How the margins came out over all tests, for the closing line.
struct MarginTally {
  long chaotic = 0, below = 0, above = 0, count = 0;
};

/// One member's margin on one test, as its CSV line.
std::string margin_line(const Run& run, const rm::TableTest& test, const Specimen& sp, std::size_t k,
                        int measured, MarginTally& tally) {
  Member m = sp.members[k];
  const double gain = m.gain;
  const auto margin = rm::table_test_margin([&](double scale) {
    m.gain = gain * scale;
    return predict(run, m, sp.id, test, nullptr).predicted;
  }, run.search);
  tally.chaotic += margin.chaotic;
  tally.below += margin.censored < 0;
  tally.above += margin.censored > 0;
  ++tally.count;
  char line[512];
  std::snprintf(line, sizeof line, "%d,%s,%zu,%s,%.6g,%.6g,%d,%d,%s,%.6g,%.6g,%d\n", test.number, sp.id.c_str(), k,
                measured < 0 ? "" : std::to_string(measured).c_str(), test.peak_mps2, margin.scale,
                margin.censored, margin.chaotic, margin.pattern.c_str(), margin.bracket_lo, margin.bracket_hi,
                margin.runs);
  return line;
}

}  // namespace

int run_margins(const Run& run) {
  const std::string& path = run.options.margins;
  std::ofstream mf(path);
  if (!mf) throw std::runtime_error(path + ": cannot open for writing");
  mf << "test,specimen,member,measured_overturned,peak_table_accel_mps2,margin_scale,censored,chaotic,"
        "grid_outcomes,bracket_lo,bracket_hi,runs\n";
  MarginTally tally;
  ProgressMeter progress("tests", run.options.quiet);
  progress.update(0, run.files.size());
  for (std::size_t i = 0; i < run.files.size(); ++i) {
    const auto test = rm::read_table_test(run.files[i]);
    const auto row = run.outcomes.by_test.find(test.number);
    for (const auto& sp : run.specimens) {
      const int measured = row == run.outcomes.by_test.end() ? -1 : row->second[sp.column];
      for (std::size_t k = 0; k < sp.members.size(); ++k) mf << margin_line(run, test, sp, k, measured, tally);
    }
    progress.update(i + 1, run.files.size());
  }
  if (!mf.flush()) throw std::runtime_error(path + ": write failed");
  std::printf("rocking_experiments: %ld margins (%zu tests) written to %s: %ld chaotic (not monotone on the "
              "grid), %ld overturn at %g already, %ld stand at %g\n", tally.count, run.files.size(), path.c_str(),
              tally.chaotic, tally.below, run.search.lo, tally.above, run.search.hi);
  return 0;
}

}  // namespace rocking_monitor::tools::experiments
