#pragma once
// rocking_experiments --histories: which tests get a rotation history, and writing one.

#include <set>
#include <string>
#include <vector>

#include "experiments_options.hpp"
#include "rocking_monitor/study/shaking_table_experiments.hpp"

namespace rocking_monitor::tools::experiments {

/// --history-tests: 'misses', 'all' or test numbers.
struct HistoryChoice {
  std::set<int> numbers;  ///< each must be among the tests run (checked after the run)
  bool misses = false, all = false;
  /// Whether a test (predicted wrongly or not) gets a history.
  bool wants(int test, bool wrong) const { return all || (misses && wrong) || numbers.count(test) > 0; }
};

/// Parses --history-tests and creates --histories' directory (nothing without --histories). Throws
/// naming a cell that is not a test number.
HistoryChoice parse_history_choice(const Options& o);

/// Writes --histories/TestNNN_<specimen>.csv, every --history-every'th sample and the last. Throws
/// naming the file when it cannot be written.
void write_history(const Options& o, int test, const std::string& specimen,
                   const std::vector<core::TableHistorySample>& history);

}  // namespace rocking_monitor::tools::experiments
