#pragma once

#include <cstdint>

namespace rocking_monitor::core {

/// Classifies the time stamps of one sensor's samples (robot_localization-style guards):
/// the model advances with dt from the stamps, never from arrival times.
class SampleTiming {
 public:
  enum class Verdict : std::uint8_t {
    First,         ///< first sample (or first after a reset): starts the models, no step
    Accept,        ///< step by dt
    AcceptGap,     ///< dt > max_gap: a data gap (reported); the caller does not bridge it (issue 19)
    Duplicate,     ///< same stamp as the previous sample (within 1 us): dropped and counted
    OutOfOrder,    ///< older than the previous sample by less than the jump threshold: dropped
    BackwardJump,  ///< older by more than the threshold (bag loop, sim time restart): reset
  };
  struct Config {
    double max_gap = 0.1;          ///< s, longer intervals are data gaps, reported
    double backward_jump = 1.0;    ///< s, a stamp this much older than the last resets the models
    double duplicate_window = 1e-6;  ///< s
  };
  struct Counters {
    std::uint64_t accepted = 0, gaps = 0, duplicates = 0, out_of_order = 0, backward_jumps = 0;
    double longest_gap = 0.0;  ///< s
  };

  SampleTiming() = default;
  explicit SampleTiming(const Config& config) : config_(config) {}

  /// Classifies stamp t (s); for Accept/AcceptGap, dt is set to t - last. Only First, Accept and
  /// AcceptGap (and BackwardJump, which restarts) move the last stamp.
  Verdict classify(double t, double& dt) {
    dt = 0.0;
    if (!started_) {
      started_ = true;
      last_ = t;
      return Verdict::First;
    }
    const double d = t - last_;
    if ((d < 0.0 ? -d : d) <= config_.duplicate_window) {
      ++counters_.duplicates;
      return Verdict::Duplicate;
    }
    if (d < 0.0) {
      if (-d >= config_.backward_jump) {
        ++counters_.backward_jumps;
        last_ = t;
        return Verdict::BackwardJump;
      }
      ++counters_.out_of_order;
      return Verdict::OutOfOrder;
    }
    dt = d;
    last_ = t;
    ++counters_.accepted;
    if (d > config_.max_gap) {
      ++counters_.gaps;
      if (d > counters_.longest_gap) counters_.longest_gap = d;
      return Verdict::AcceptGap;
    }
    return Verdict::Accept;
  }

  void restart() { started_ = false; }
  /// Moves the last stamp into a new time base (offset s): the next stamp of that base steps by its
  /// difference from the last one as if the base had never changed (StampPlausibility::RebaseForward).
  void shift(double offset) { last_ += offset; }
  bool started() const { return started_; }
  double last_stamp() const { return last_; }
  const Counters& counters() const { return counters_; }
  const Config& config() const { return config_; }

 private:
  Config config_;
  Counters counters_;
  bool started_ = false;
  double last_ = 0.0;
};

}  // namespace rocking_monitor::core
