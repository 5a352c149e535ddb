// rocking_experiments' setup shared by its jobs, and running one member through one test.
#include "experiment_run.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "rocking_monitor/monitoring/catalogue_file.hpp"

namespace fs = std::filesystem;

namespace rocking_monitor::tools::experiments {

namespace {

std::vector<std::string> test_files(const Options& o) {
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(fs::path(o.dir) / "tests")) {
    const std::string name = e.path().filename().string();
    if (name.rfind("Test", 0) == 0 && (name.size() > 4 && (name.find(".csv") != std::string::npos)))
      files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  if (o.max_tests > 0 && static_cast<int>(files.size()) > o.max_tests) files.resize(o.max_tests);
  if (files.empty()) throw std::runtime_error(o.dir + "/tests: no TestNNN.csv(.gz) files");
  return files;
}

}  // namespace

Run prepare_run(const Options& o) {
  Run run;
  run.options = o;
  run.outcomes = rm::read_outcomes((fs::path(o.dir) / "outcomes.csv").string());
  const auto items = rm::load_catalogue_items_file(o.catalogue);
  run.solid = uses_solid_model(o, items);
  run.search = o.search;
  run.search.lo = o.margin_range[0];
  run.search.hi = o.margin_range[1];
  if (!o.margins.empty()) rm::validate(run.search);
  run.specimens = load_specimens(o, run.outcomes, items, run.solid);
  run.files = test_files(o);
  run.history = parse_history_choice(o);
  run.settings.direction = o.direction;
  run.settings.tail_s = o.tail_s;
  if (!run.solid && o.azimuth_deg != 0.0)
    throw std::runtime_error("--table-azimuth needs the 3-D model (--model 3d): a planar plane has one axis");
  return run;
}

rm::TestPrediction predict(const Run& run, const Member& m, const std::string& id, const rm::TableTest& test,
                           std::vector<rm::TableHistorySample>* history) {
  if (!run.solid) return rm::predict_table_test(m.planar, id, test, run.settings, history);
  rm::ExperimentSettings member_settings = run.settings;
  member_settings.table_azimuth = m.azimuth;
  member_settings.input_gain = m.gain;
  return rm::predict_table_test_3d(m.solid, id, test, member_settings, history);
}

}  // namespace rocking_monitor::tools::experiments
