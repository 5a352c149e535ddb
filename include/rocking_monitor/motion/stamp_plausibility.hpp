#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace rocking_monitor::core {

/// Decides whether a sample's stamp can be trusted before SampleTiming turns it into a step (issue 19).
/// One bad stamp (a clock glitch in one packet) must not be bridged nor restart the items: a stamp
/// too far ahead of the node's clock, or too far from the last accepted stamp, is held as a candidate
/// for a new time base. The new base is adopted only after `rebase_samples` consistent candidates in a
/// row; a run broken earlier (a plausible stamp comes back, or the candidates disagree) is dropped and
/// counted as rejected. Time as double seconds (stamps and the node's clock in the same base).
class StampPlausibility {
 public:
  struct Config {
    double max_future = 1.0;     ///< s, a stamp further ahead of the node's clock is never used
    double max_bridge = 1.0;     ///< s, a forward jump longer than this is never bridged
    double backward_jump = 1.0;  ///< s, a stamp this much older than the last is not out-of-order but a new base
    double max_step = 0.1;       ///< s, candidates closer than this to each other (and later) are consistent
    int rebase_samples = 20;     ///< consistent candidates that confirm a new time base
  };
  enum class Verdict : std::uint8_t {
    Plausible,       ///< hand the stamp to SampleTiming (any held run was dropped and counted)
    Rejected,        ///< ahead of the node's clock by more than max_future: dropped and counted
    Held,            ///< candidate for a new time base: keep the sample until confirmed or dropped
    RebaseForward,   ///< this candidate confirms a later base: continue the items, offset absorbed
    RebaseBackward,  ///< this candidate confirms an earlier base: restart the items (bag loop, sim restart)
  };
  struct Counters {
    std::uint64_t rejected = 0;         ///< samples with an implausible stamp dropped (future + broken runs)
    std::uint64_t rejected_future = 0;  ///< of which ahead of the node's clock
    std::uint64_t rebased_forward = 0, rebased_backward = 0;
    double last_rejected_jump = 0.0;    ///< s, stamp - last accepted of the latest dropped sample
    std::uint64_t restamped = 0;        ///< of the rejected, re-stamped from their sequence and stepped
  };

  StampPlausibility() = default;
  explicit StampPlausibility(const Config& config) : config_(config) {}

  /// t: the sample's stamp; now: the node's clock (0: not running yet, e.g. sim time before the first
  /// /clock, and then not checked); started/last: whether a stamp was accepted before and which.
  Verdict check(double t, double now, bool started, double last) {
    if (now > 0.0 && t > now + config_.max_future) {
      drop_run();
      ++counters_.rejected;
      ++counters_.rejected_future;
      counters_.last_rejected_jump = started ? t - last : 0.0;
      return Verdict::Rejected;
    }
    const double d = t - last;
    if (!started || (d <= config_.max_bridge && d > -config_.backward_jump)) {
      drop_run();
      return Verdict::Plausible;
    }
    const double step = t - run_last_;
    if (run_ > 0 && step > 0.0 && step <= config_.max_step) {
      ++run_;
    } else {
      drop_run();
      run_ = 1;
      run_first_ = t;
      run_jump_ = d;
    }
    run_last_ = t;
    if (run_ < config_.rebase_samples) return Verdict::Held;
    run_ = 0;
    if (run_first_ > last) {
      ++counters_.rebased_forward;
      return Verdict::RebaseForward;
    }
    ++counters_.rebased_backward;
    return Verdict::RebaseBackward;
  }

  /// The k samples rejected since the last accepted stamp `last` (their stamps were implausible, their
  /// readings passed every check) are re-stamped from their sequence when the next plausible stamp t
  /// lies k + 1 nominal periods after `last` (within a quarter period) and nothing else arrived in
  /// between: then they sat in order in the stream and only their stamps were wrong (a clock glitch in
  /// the packets), so their data is stepped at the stamps it must have had instead of being lost.
  /// Returns whether they fit; if so they are counted as restamped (they stay counted as rejected).
  bool restamp(double last, double t, std::size_t k, double period) {
    if (k == 0 || !(period > 0.0)) return false;
    const double expected = last + static_cast<double>(k + 1) * period;
    if (std::abs(t - expected) > 0.25 * period) return false;
    counters_.restamped += k;
    return true;
  }

  /// Forgets a held run without counting it (~reset: the caller drops what it held).
  void clear() { run_ = 0; }
  /// Candidates held now (1 right after a new run started).
  int held() const { return run_; }
  /// First stamp of the run that confirmed (or is building) a new base, s.
  double run_first() const { return run_first_; }
  const Counters& counters() const { return counters_; }
  const Config& config() const { return config_; }

 private:
  void drop_run() {
    if (run_ == 0) return;
    counters_.rejected += static_cast<std::uint64_t>(run_);
    counters_.last_rejected_jump = run_jump_;
    run_ = 0;
  }

  Config config_;
  Counters counters_;
  int run_ = 0;
  double run_first_ = 0.0, run_last_ = 0.0, run_jump_ = 0.0;
};

}  // namespace rocking_monitor::core
