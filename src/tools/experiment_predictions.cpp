// rocking_experiments' main job: every test x specimen predicted (P(overturn) over the specimen's
// members), scored against the measured outcome, with the per-test table (--out) and the chosen
// rotation histories (--histories).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>

#include "experiment_run.hpp"
#include "experiment_scores.hpp"
#include "progress_meter.hpp"

namespace rocking_monitor::tools::experiments {

namespace {

/// What the loop over the tests gathers besides the scores.
struct PredictionLog {
  Scores scores;
  std::set<int> history_done;
  long histories_written = 0;
  std::vector<rm::TableHistorySample> history;
};

std::ofstream open_table(const std::string& out) {
  std::ofstream table;
  if (out.empty()) return table;
  table.open(out);
  if (!table) throw std::runtime_error(out + ": cannot open for writing");
  table << "test,specimen,peak_table_accel_mps2,offset_mps2,exceeds_static_uplift,uplift,"
           "max_rotation_ratio,impacts,overturn_time_s,predicted_overturned,measured_overturned,"
           "members,p_overturn,final_face,rests_off_base\n";
  return table;
}

std::string table_row(const rm::TestPrediction& p, const Specimen& s, const rm::TableTest& test, bool predicted,
                      double prob) {
  char line[512];
  std::snprintf(line, sizeof line, "%d,%s,%.6g,%.6g,%d,%d,%.6g,%ld,%.4f,%d,%s,%zu,%.4f,%d,%ld\n", p.test,
                s.id.c_str(), test.peak_mps2, test.offset_mps2, p.exceeds_static_uplift, p.uplift,
                p.max_rotation_ratio, p.impacts, p.overturn_time, predicted,
                p.measured < 0 ? "" : std::to_string(p.measured).c_str(), s.members.size(), prob, p.final_face,
                p.rests_off_base);
  return line;
}

/// One specimen on one test: the first member (the nominal geometry) gives the row's details, the
/// members P(overturn); measured: the test's row in outcomes.csv has one. Scored, its history written when chosen, its table row written.
void predict_specimen(const Run& run, const rm::TableTest& test, std::optional<int> measured, const Specimen& s,
                      std::ofstream& table, PredictionLog& log) {
  auto p = predict(run, s.members.front(), s.id, test, nullptr);
  long over = p.predicted;
  for (std::size_t k = 1; k < s.members.size(); ++k) over += predict(run, s.members[k], s.id, test, nullptr).predicted;
  const double prob = static_cast<double>(over) / static_cast<double>(s.members.size());
  const bool predicted = prob >= 0.5;
  if (measured) p.measured = *measured;  // the outcomes' cell (-1: none); no row: as predicted
  log.scores.add(s.id, prob, predicted, p.measured);
  const bool wrong = p.measured >= 0 && predicted != (p.measured == 1);
  if (!run.options.histories.empty() && run.history.wants(test.number, wrong)) {
    predict(run, s.members.front(), s.id, test, &log.history);
    write_history(run.options, test.number, s.id, log.history);
    ++log.histories_written;
    log.history_done.insert(test.number);
  }
  // an unopened table (no --out) takes the rows into a failed stream: nothing is written
  if (table) table << table_row(p, s, test, predicted, prob);
}

std::string restitution_text(const Run& run) {
  const Options& o = run.options;
  if (run.solid)
    return std::isnan(o.restitution_factor) ? "3-D law x the catalogue's factor"
                                            : "3-D law x " + std::to_string(o.restitution_factor);
  return std::isnan(o.restitution) ? "eq. 34" : std::to_string(o.restitution);
}

/// The closing lines, and the checks that can only be made after the run.
void report(const Run& run, const PredictionLog& log) {
  const Options& o = run.options;
  std::printf("rocking_experiments: %zu tests x %zu specimens, direction %+d, model %s, restitution %s\n",
              run.files.size(), run.specimens.size(), o.direction, run.solid ? "3d" : "planar",
              restitution_text(run).c_str());
  const bool ensembles = std::any_of(run.specimens.begin(), run.specimens.end(),
                                     [](const Specimen& sp) { return sp.members.size() > 1; });
  print_scores(log.scores, ensembles);
  for (int n : run.history.numbers)
    if (!log.history_done.count(n))
      throw std::runtime_error("--history-tests: test " + std::to_string(n) + " is not among the tests run");
  if (!o.histories.empty())
    std::printf("rocking_experiments: %ld histories written to %s (%s)\n", log.histories_written,
                o.histories.c_str(), o.history_tests.c_str());
  if (log.scores.without_outcome)
    std::printf("rocking_experiments: %ld predictions without a measured outcome (not scored)\n",
                log.scores.without_outcome);
}

}  // namespace

int run_predictions(const Run& run) {
  std::ofstream table = open_table(run.options.out);
  PredictionLog log;
  ProgressMeter progress("tests", run.options.quiet);
  progress.update(0, run.files.size());
  for (std::size_t i = 0; i < run.files.size(); ++i) {
    const auto test = rm::read_table_test(run.files[i]);
    const auto row = run.outcomes.by_test.find(test.number);
    for (const auto& s : run.specimens)
      predict_specimen(run, test, row != run.outcomes.by_test.end() ? std::optional<int>(row->second[s.column])
                                                                     : std::nullopt, s, table, log);
    progress.update(i + 1, run.files.size());
  }
  report(run, log);
  if (table && !table.flush()) throw std::runtime_error(run.options.out + ": write failed");
  return 0;
}

}  // namespace rocking_monitor::tools::experiments
