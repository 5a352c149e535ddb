// The three channels of a station -> merged samples on common times (see the header).
#include "rocking_monitor/feeds/station_merger.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace rocking_monitor::feeds {
namespace {

// Floor division for indices on either side of the grid's origin.
std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  std::int64_t q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return q;
}

constexpr std::int64_t kNone = std::numeric_limits<std::int64_t>::min();

// The same sample value, bit for bit: a repeat (NaN equals NaN here, -0 is not 0: the records' own bytes).
bool same_value(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

StationMerger::StationMerger(double gain, double azimuth_deg, bool numbered_azimuth_given, std::size_t capacity)
    : frame_(gain, numbered_azimuth_given ? azimuth_deg : 0.0), azimuth_given_(numbered_azimuth_given), capacity_(capacity) {
  if (capacity_ < 2 || (capacity_ & (capacity_ - 1)) != 0)
    throw std::invalid_argument("merger capacity must be a power of two >= 2");
  for (int c = 0; c < 3; ++c) {
    values_[c].assign(capacity_, 0.0);
    present_[c].assign(capacity_, 0);
    stored_[c].assign(capacity_, kNone);
  }
  conflict_.assign(capacity_, 0);
}

void StationMerger::note_overlap(int c, std::int64_t index, double value) {
  const std::size_t k = ring(index);
  if (stored_[c][k] != index || same_value(values_[c][k], value)) return;  // a repeat, or the first is gone
  ++counters_.overlap_conflicts;
  if (index >= out_ && conflict_[k] == 0) {  // not out yet: it goes out marked
    conflict_[k] = 1;
    ++counters_.conflicts_marked;
  }
}

bool StationMerger::settle(bool force, const Emit& emit) {
  bool all = true, dead = false;
  for (int c = 0; c < 3; ++c) {
    const bool here = started_[c] && present_[c][ring(out_)] != 0;
    all = all && here;
    if (!here && started_[c] && head_[c] > out_) dead = true;  // channel c went past out_ without it
  }
  if (all) {
    MergedSample s;
    s.time_ns = time_us(out_) * 1000;
    const std::size_t k = ring(out_);
    s.enu = frame_.to_enu(values_[0][k], values_[1][k], values_[2][k]);
    s.conflict = conflict_[k] != 0;
    conflict_[k] = 0;
    if (emitted_any_ && out_ != last_emitted_ + 1) ++counters_.output_gaps;
    emitted_any_ = true;
    last_emitted_ = out_;
    last_emitted_ns_ = s.time_ns;
    ++counters_.samples_out;
    for (int c = 0; c < 3; ++c) present_[c][k] = 0;
    ++out_;
    emit(s);
    return true;
  }
  if (dead || force) {
    for (int c = 0; c < 3; ++c) present_[c][ring(out_)] = 0;
    conflict_[ring(out_)] = 0;
    ++counters_.incomplete;
    ++out_;
    return true;
  }
  return false;
}

void StationMerger::add(const DecodedRecord& r, const Emit& emit) {
  const std::optional<ChannelRole> role = channel_role(r.channel);
  const bool mixed = role && (started_[0] || started_[1]) && role->slot != Slot::Z && role->numbered != numbered_;
  if (!role || (role->numbered && !azimuth_given_) || mixed) {
    ++counters_.foreign_records;
    return;
  }
  const int c = static_cast<int>(role->slot);
  if (started_[c] && (r.channel != channels_[c] || r.location != locations_[c])) {
    ++counters_.foreign_records;  // another instrument or location of the same station
    return;
  }
  if (!grid_) {
    rate_ = r.sample_rate;
    period_us_ = std::llround(1e6 / rate_);
    if (period_us_ <= 0 || std::fabs(static_cast<double>(period_us_) * rate_ - 1e6) > 1e-3) {
      ++counters_.rate_mismatches;  // a period that is not a whole number of microseconds
      return;
    }
    phase_us_ = ((r.start_us % period_us_) + period_us_) % period_us_;
    out_ = floor_div(r.start_us - phase_us_ + period_us_ / 2, period_us_);
    grid_ = true;
  } else if (std::fabs(r.sample_rate - rate_) > 1e-9 * rate_) {
    ++counters_.rate_mismatches;
    return;
  }
  const std::int64_t first = floor_div(r.start_us - phase_us_ + period_us_ / 2, period_us_);
  if (!started_[c]) {
    started_[c] = true;
    channels_[c] = r.channel;
    locations_[c] = r.location;
    if (role->slot != Slot::Z) numbered_ = role->numbered;
    head_[c] = first;
  } else if (first > head_[c]) {
    ++counters_.gaps;
    counters_.gap_samples += static_cast<std::uint64_t>(first - head_[c]);
  } else if (first < head_[c]) {
    ++counters_.overlaps;
  }
  for (std::size_t i = 0; i < r.samples.size(); ++i) {
    const std::int64_t index = first + static_cast<std::int64_t>(i);
    if (index < head_[c]) {
      ++counters_.overlap_samples;
      note_overlap(c, index, r.samples[i]);
      continue;
    }
    head_[c] = index + 1;
    if (index < out_) {
      ++counters_.late_samples;
      continue;
    }
    // No room: the oldest time waits for a channel that is too far behind; give it up.
    while (index - out_ >= static_cast<std::int64_t>(capacity_)) settle(true, emit);
    values_[c][ring(index)] = r.samples[i];
    present_[c][ring(index)] = 1;
    stored_[c][ring(index)] = index;
  }
  while (out_ < std::max({head_[0], head_[1], head_[2]}) && settle(false, emit)) {
  }
}

}  // namespace rocking_monitor::feeds
