// rocking_experiments --histories: the test choice and one history's CSV.
#include "experiment_histories.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace rocking_monitor::tools::experiments {

HistoryChoice parse_history_choice(const Options& o) {
  HistoryChoice choice;
  choice.misses = o.history_tests == "misses";
  choice.all = o.history_tests == "all";
  if (o.histories.empty()) return choice;
  if (!choice.misses && !choice.all) {
    std::stringstream list(o.history_tests);
    std::string cell;
    while (std::getline(list, cell, ',')) {
      char* end = nullptr;
      const long n = std::strtol(cell.c_str(), &end, 10);
      if (cell.empty() || *end != '\0' || n <= 0)
        throw std::runtime_error("--history-tests: '" + cell + "' is not a test number (or use misses, all)");
      choice.numbers.insert(static_cast<int>(n));
    }
  }
  fs::create_directories(o.histories);
  return choice;
}

void write_history(const Options& o, int test, const std::string& specimen,
                   const std::vector<core::TableHistorySample>& history) {
  char name[64];
  std::snprintf(name, sizeof name, "Test%03d_%s.csv", test, specimen.c_str());
  const std::string path = (fs::path(o.histories) / name).string();
  std::ofstream h(path);
  if (!h) throw std::runtime_error(path + ": cannot open for writing");
  h << "t_s,table_accel_mps2,theta_rad,omega_radps,rotation_ratio,max_rotation_ratio,mode\n";
  char line[256];
  for (std::size_t k = 0; k < history.size(); ++k) {
    if (k % static_cast<std::size_t>(o.history_every) != 0 && k + 1 != history.size()) continue;
    const auto& r = history[k];
    std::snprintf(line, sizeof line, "%.6f,%.6g,%.8g,%.8g,%.8g,%.8g,%s\n", r.t, r.table_accel_mps2, r.theta,
                  r.omega, r.rotation_ratio, r.max_rotation_ratio, r.mode);
    h << line;
  }
  if (!h.flush()) throw std::runtime_error(path + ": write failed");
}

}  // namespace rocking_monitor::tools::experiments
