#pragma once
// One progress display for the long command-line tools (issue 53): rocking_study, rocking_experiments
// and rocking_accuracy say how far they are (done / total, rate, time left) so that a user can tell a
// slow run from a hung one. Only on a terminal: a log, a pipe, ctest or a batch job gets nothing, so
// what they record does not change; --quiet turns it off on a terminal too. stderr only: stdout and
// the written files are the same with or without it.

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <mutex>
#include <string>

namespace rocking_monitor::tools {

/// "7s", "2m05s", "1h02m"; "--" when unknown (not finite or negative).
std::string duration_text(double seconds);

/// The drawn line (without the leading carriage return): a 30-column bar, the percentage, done/total
/// units, the rate and the time left, e.g. "[===============>              ]  50.0%  5/10 tests  2.5 tests/s  left 2s".
std::string progress_line(std::size_t done, std::size_t total, double elapsed_s, const std::string& unit);

/// Redraws progress_line on one line of a stream. Thread-safe: workers of a pool may each report.
class ProgressMeter {
 public:
  /// Shown when stderr is a terminal and not quiet (the tools' --quiet).
  ProgressMeter(std::string unit, bool quiet);
  /// Drawn on `out` when `shown` (the tests' way in: any stream, terminal or not).
  ProgressMeter(std::string unit, std::FILE* out, bool shown);

  /// done of total: redrawn (at most every 0.1 s, so a fast loop does not flood the terminal; the
  /// last one, done == total, always and ended with a newline).
  void update(std::size_t done, std::size_t total);
  void operator()(std::size_t done, std::size_t total) { update(done, total); }
  bool shown() const { return shown_; }

 private:
  std::string unit_;
  std::FILE* out_;
  bool shown_;
  bool finished_ = false;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  bool drawn_ = false;
};

}  // namespace rocking_monitor::tools
