// The reorder window and the loss accounting of a datagram stream (sample_sequencer.hpp).
#include "rocking_monitor/feeds/sample_sequencer.hpp"

#include <cstring>

namespace rocking_monitor::feeds {

SampleSequencer::SampleSequencer(std::size_t window, bool resync_backward)
    : slots_(window + 1), history_(kResyncSpan), ready_(window + 2), resync_backward_(resync_backward) {}

void SampleSequencer::remember(std::uint64_t sequence, Fate fate, const AccelSample* sample) {
  History& h = history_[sequence % history_.size()];
  h.sequence = sequence;
  h.fate = fate;
  if (sample) h.sample = *sample;
}

// Bit for bit: a resent datagram is the same bytes; any difference means another source.
void SampleSequencer::count_repeat(AccelSample& first, const AccelSample& again, bool held) {
  const bool same = std::memcmp(&first.time_s, &again.time_s, sizeof first.time_s) == 0 &&
                    std::memcmp(first.accel, again.accel, sizeof first.accel) == 0;
  if (same) {
    ++counts_.duplicates;
    return;
  }
  ++counts_.conflicts;
  counts_.last_conflict = first.sequence;
  if (held) {
    ++counts_.conflicts_marked;
    first.conflict = true;
  }
}

void SampleSequencer::release_next() {
  Slot& slot = slots_[next_ % slots_.size()];
  if (slot.filled) {
    ready_[ready_count_++] = slot.sample;
    slot.filled = false;
    --held_;
    ++counts_.released;
    remember(next_, Fate::Released, &slot.sample);
  } else {
    ++counts_.lost;
    remember(next_, Fate::Lost);
  }
  ++next_;
}

void SampleSequencer::flush() {
  ready_count_ = 0;
  if (!started_) return;
  // Release up to the newest held sample; the holes before it are lost.
  while (held_ > 0) {
    if (ready_count_ == ready_.size()) break;  // cannot happen: held_ <= window + 1
    release_next();
  }
}

void SampleSequencer::push(const AccelSample& sample) {
  ready_count_ = 0;
  ++counts_.accepted;
  const std::uint64_t s = sample.sequence;
  if (!started_) {
    started_ = true;
    next_ = s;
    max_seen_ = s;
  }
  const std::size_t cap = slots_.size();
  // A restart of the controller's counter (far back or far ahead): release what is held, go on from s.
  const bool far_back = s < next_ && next_ - s > kResyncSpan;
  const bool far_ahead = s > next_ && s - next_ > kResyncSpan;
  if (far_back && !resync_backward_) {
    ++counts_.stale;
    return;
  }
  if (far_back || far_ahead) {
    while (held_ > 0) release_next();
    ++counts_.resyncs;
    next_ = s;
    max_seen_ = s;
  }
  if (s < next_) {
    History& h = history_[s % history_.size()];
    if (h.sequence == s && h.fate == Fate::Lost) {
      // it did come, but after its place was given up
      ++counts_.late;
      --counts_.lost;
      h.fate = Fate::Unknown;
    } else if (h.sequence == s && h.fate == Fate::Released) {
      count_repeat(h.sample, sample, false);
    } else {
      ++counts_.late;
    }
    return;
  }
  // Make room: give up (or release) the oldest until s fits in the window.
  while (s >= next_ + cap) release_next();
  Slot& slot = slots_[s % cap];
  if (slot.filled) {
    count_repeat(slot.sample, sample, true);
  } else {
    if (s < max_seen_) ++counts_.reordered;
    slot.filled = true;
    slot.sample = sample;
    ++held_;
  }
  if (s > max_seen_) max_seen_ = s;
  // Release the run that is complete.
  while (slots_[next_ % cap].filled) release_next();
}

}  // namespace rocking_monitor::feeds
