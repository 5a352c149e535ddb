#pragma once

// Sequence numbers for samples that carry none (the text datagrams "time,ax,ay,az"): the controller
// samples at a nominal rate, so a sample's place is round((t - t_first) * rate). A time more than a
// quarter of a sample off that grid is not a sample of this stream (counted, dropped by the bridge).

#include <cstdint>
#include <optional>

namespace rocking_monitor::feeds {

class TimeGrid {
 public:
  /// rate_hz > 0 (throws std::invalid_argument otherwise).
  explicit TimeGrid(double rate_hz);

  /// The sequence number of a sample at `time_s`, or nullopt when it is off the grid (more than a
  /// quarter sample) or before the grid's origin by more than the origin's own offset (sequence
  /// numbers start at kOrigin, so samples up to kOrigin places before the first one still count).
  /// The first call sets the origin.
  std::optional<std::uint64_t> sequence(double time_s);
  /// Forget the origin (the next sample starts a new grid), e.g. after the controller restarted.
  void reset() { started_ = false; }

  static constexpr std::uint64_t kOrigin = 1u << 20;

 private:
  double rate_;
  bool started_ = false;
  double t_first_ = 0.0;
};

}  // namespace rocking_monitor::feeds
