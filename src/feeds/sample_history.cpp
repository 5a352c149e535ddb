// SampleHistory (see include/rocking_monitor/feeds/sample_history.hpp).
#include "rocking_monitor/feeds/sample_history.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rocking_monitor::feeds {

std::size_t SampleHistory::capacity_for(double length_s, double rate_hz) {
  if (!(length_s > 0.0) || !std::isfinite(length_s))
    throw std::invalid_argument("history length " + std::to_string(length_s) + " s: must be > 0 and finite");
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz))
    throw std::invalid_argument("sample rate " + std::to_string(rate_hz) + " Hz: must be > 0 and finite");
  const double n = std::ceil(length_s * rate_hz) + 1.0;
  if (n > 1e8)
    throw std::invalid_argument("history of " + std::to_string(length_s) + " s at " + std::to_string(rate_hz) +
                                " Hz: more than 1e8 samples");
  return static_cast<std::size_t>(n);
}

SampleHistory::SampleHistory(std::size_t capacity) {
  if (capacity == 0) throw std::invalid_argument("sample history: capacity must be at least 1 sample");
  ring_.resize(capacity);
}

bool SampleHistory::push(std::int64_t stamp_ns, double x, double y, double z) {
  bool restarted = false;
  if (size_ > 0) {
    const std::int64_t newest = at(size_ - 1).stamp_ns;
    if (stamp_ns == newest) {
      ++refused_;
      return false;
    }
    if (stamp_ns < newest) {  // a new time base: what is kept no longer leads up to this sample
      ++restarts_;
      restarted = true;
      discard(newest);
      head_ = 0;
      size_ = 0;
    }
  }
  if (size_ == ring_.size()) {
    discard(at(0).stamp_ns);
    head_ = (head_ + 1) % ring_.size();
    --size_;
    ++overwritten_;
  }
  if (pushed_ == 0 || restarted) first_ns_ = stamp_ns;  // the time base's first sample
  ring_[(head_ + size_) % ring_.size()] = HistorySample{stamp_ns, x, y, z};
  ++size_;
  ++pushed_;
  return true;
}

SampleHistory::Range SampleHistory::since(std::int64_t after_ns, std::vector<HistorySample>& out) const {
  Range r;
  // First kept sample stamped after after_ns (stamps rise: binary search).
  std::size_t lo = 0, hi = size_;
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (at(mid).stamp_ns > after_ns) hi = mid;
    else lo = mid + 1;
  }
  out.resize(size_ - lo);
  for (std::size_t i = lo; i < size_; ++i) out[i - lo] = at(i);
  r.count = out.size();
  // Complete when the ring reaches back to after_ns (its first sample is at or before it: a source
  // started later never had the samples in between) and every sample thrown away since was stamped at
  // or before after_ns.
  r.complete = pushed_ > 0 && first_ns_ <= after_ns && (!discarded_ || lost_newest_ns_ <= after_ns);
  if (size_ > 0) {
    r.oldest_ns = at(0).stamp_ns;
    r.newest_ns = at(size_ - 1).stamp_ns;
  }
  return r;
}

}  // namespace rocking_monitor::feeds
