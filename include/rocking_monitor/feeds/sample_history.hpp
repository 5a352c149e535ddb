#pragma once

// The last minutes of a bridge's samples, kept so that a restarted monitor can fetch what it missed
// (issue 29 part 2: catch up instead of freezing). A ring of fixed capacity, allocated once: push()
// never allocates, so it can sit in a bridge's per-sample path. Stamps must rise: a repeated stamp is
// refused (counted), an earlier one means the source restarted its time base, so the ring starts
// afresh (counted) rather than serve a history that goes back in time.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rocking_monitor::feeds {

struct HistorySample {
  std::int64_t stamp_ns = 0;  ///< the stamp the sample was published with, ns since 1970
  double x = 0.0, y = 0.0, z = 0.0;  ///< as published, m/s^2
};

class SampleHistory {
 public:
  /// Samples needed to keep `length_s` s at `rate_hz` (rounded up, plus one). Throws
  /// std::invalid_argument naming the bad value (length <= 0 or not finite, rate <= 0, > 1e8 samples).
  static std::size_t capacity_for(double length_s, double rate_hz);

  /// Allocates the ring. Throws std::invalid_argument when capacity is 0.
  explicit SampleHistory(std::size_t capacity);

  /// Appends a sample, overwriting the oldest when full. False (counted in refused()) when the stamp
  /// equals the newest's; a stamp before the newest empties the ring first (counted in restarts()).
  bool push(std::int64_t stamp_ns, double x, double y, double z);

  struct Range {
    std::size_t count = 0;      ///< samples copied
    bool complete = false;      ///< the ring reaches back to `after_ns` (its first sample is at or before it) and
                                ///< no sample stamped after `after_ns` was overwritten or thrown away
    std::int64_t oldest_ns = 0; ///< stamp of the oldest sample kept (0: none kept)
    std::int64_t newest_ns = 0; ///< stamp of the newest sample kept (0: none kept)
  };
  /// The samples stamped strictly after `after_ns`, oldest first, into `out` (resized to them).
  Range since(std::int64_t after_ns, std::vector<HistorySample>& out) const;

  std::size_t size() const { return size_; }
  std::size_t capacity() const { return ring_.size(); }
  std::uint64_t pushed() const { return pushed_; }        ///< samples accepted
  std::uint64_t overwritten() const { return overwritten_; }  ///< oldest samples pushed out by newer ones
  std::uint64_t refused() const { return refused_; }      ///< repeated stamps
  std::uint64_t restarts() const { return restarts_; }    ///< earlier stamps: the ring emptied

 private:
  const HistorySample& at(std::size_t i) const { return ring_[(head_ + i) % ring_.size()]; }  ///< i-th oldest

  std::vector<HistorySample> ring_;
  std::size_t head_ = 0;  ///< index of the oldest sample
  std::size_t size_ = 0;
  void discard(std::int64_t stamp_ns) {
    lost_newest_ns_ = discarded_ ? std::max(lost_newest_ns_, stamp_ns) : stamp_ns;
    discarded_ = true;
  }
  bool discarded_ = false;         ///< some sample was overwritten or thrown away (the ring no longer holds all)
  std::int64_t lost_newest_ns_ = 0;  ///< the newest stamp thrown away: requests after it are complete
  std::int64_t first_ns_ = 0;      ///< the first stamp of the current time base: requests before it are not complete
  std::uint64_t pushed_ = 0, overwritten_ = 0, refused_ = 0, restarts_ = 0;
};

}  // namespace rocking_monitor::feeds
