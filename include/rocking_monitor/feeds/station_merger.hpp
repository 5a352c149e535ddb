#pragma once

// Merges the three channels of one station, which arrive in separate records and out of step, into
// samples (t, east, north, up) on their common sample times. A sample goes out only when all three
// channels have it; times one channel skipped (a gap) are dropped for all and counted. Samples a
// channel sends twice (an overlap) are counted and dropped; sent again with another value they are a
// conflict (issue 52 item 3): the first value kept, counted, and a sample not yet emitted goes out
// marked (MergedSample::conflict). Channels and their order are fixed by
// the first records: the first location + band/instrument code seen for each slot (N/1, E/2, Z).
//
// Times are kept as integer sample indices on the station's sampling grid (the first record's
// time modulo the sample period, microseconds), so no rounding drifts over days of data. Memory is
// fixed at construction: a ring of `capacity` samples per channel; nothing is allocated per sample.

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "rocking_monitor/feeds/mseed_record.hpp"
#include "rocking_monitor/feeds/seed_channels.hpp"

namespace rocking_monitor::feeds {

struct MergedSample {
  std::int64_t time_ns = 0;  ///< data time, ns since the epoch (UTC)
  std::array<double, 3> enu{};  ///< ground acceleration east, north, up, m/s^2 (station frame)
  bool conflict = false;  ///< a channel sent this time again with another value before it went out (first kept)
};

struct MergerCounters {
  std::uint64_t samples_out = 0;     ///< merged samples emitted
  std::uint64_t gaps = 0;            ///< times a channel's next record started later than expected
  std::uint64_t gap_samples = 0;     ///< samples missing in those gaps (per channel, summed)
  std::uint64_t overlaps = 0;        ///< times a channel's record started before its last sample's end
  std::uint64_t overlap_samples = 0; ///< samples received twice (dropped)
  std::uint64_t overlap_conflicts = 0;  ///< of those, with another value than the first (issue 52; first kept)
  std::uint64_t conflicts_marked = 0;   ///< sample times with a conflict found before they went out: emitted marked
  std::uint64_t incomplete = 0;      ///< sample times dropped because a channel never had them
  std::uint64_t output_gaps = 0;     ///< breaks in the emitted times (a sample time skipped)
  std::uint64_t foreign_records = 0; ///< records of other channels (orientation, band or location)
  std::uint64_t rate_mismatches = 0; ///< records at another rate than the station's (dropped)
  std::uint64_t late_samples = 0;    ///< samples for times already emitted or given up (dropped)
};

class StationMerger {
 public:
  /// `azimuth_deg`: that of channel 1 when the station has 1/2 channels (ignored for N/E).
  /// `numbered_azimuth_given` false: 1/2 records are refused (counted in foreign_records) because
  /// their directions are unknown. capacity: ring size, samples per channel (a power of two).
  StationMerger(double gain_counts_per_mps2, double azimuth_deg, bool numbered_azimuth_given,
                std::size_t capacity = 1u << 15);

  using Emit = std::function<void(const MergedSample&)>;
  /// Adds one record of this station; calls `emit` for every sample completed by it, in time order.
  void add(const DecodedRecord& record, const Emit& emit);

  const MergerCounters& counters() const { return counters_; }
  /// The channel codes in use per slot (H1, H2, Z), e.g. "HN1", empty before its first record.
  const std::array<std::string, 3>& channels() const { return channels_; }
  double sample_rate() const { return rate_; }
  /// Data time of the last sample emitted, ns (0 before the first).
  std::int64_t last_time_ns() const { return last_emitted_ns_; }

 private:
  std::size_t ring(std::int64_t index) const { return static_cast<std::size_t>(index) & (capacity_ - 1); }
  std::int64_t time_us(std::int64_t index) const { return phase_us_ + index * period_us_; }
  /// Emits or drops the sample at out_; false when it must wait for more records.
  bool settle(bool force, const Emit& emit);
  /// Channel c sent sample `index` again (an overlap) with `value`: a conflict when the ring still
  /// holds the first and the two differ.
  void note_overlap(int c, std::int64_t index, double value);

  StationFrame frame_;
  bool azimuth_given_;
  std::size_t capacity_;
  std::array<std::vector<double>, 3> values_;
  std::array<std::vector<std::uint8_t>, 3> present_;
  // The sample index whose value each slot holds (kNone: none): an overlap is compared only with its
  // own first value, never with an older time's that the slot held before. 8 B per slot and channel.
  std::array<std::vector<std::int64_t>, 3> stored_;
  std::vector<std::uint8_t> conflict_;  ///< per slot: a conflict was found for this time before it went out
  std::array<std::string, 3> channels_;
  std::array<std::string, 3> locations_;
  std::array<bool, 3> started_{};
  std::array<std::int64_t, 3> head_{};  ///< per channel: one past its last sample index
  bool numbered_ = false;
  bool grid_ = false;  ///< sampling grid known (first record seen)
  double rate_ = 0.0;
  std::int64_t period_us_ = 0;
  std::int64_t phase_us_ = 0;
  std::int64_t out_ = 0;  ///< index of the next sample to emit
  std::int64_t last_emitted_ = 0;
  bool emitted_any_ = false;
  std::int64_t last_emitted_ns_ = 0;
  MergerCounters counters_;
};

}  // namespace rocking_monitor::feeds
