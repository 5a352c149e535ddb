#pragma once

// Puts a datagram stream back in order and counts what the network did to it (udp_accel_bridge).
//
// Every sample has a sequence number (binary datagrams carry one; text ones get it from their time,
// time_grid.hpp). The sequencer releases samples strictly in sequence order:
//  * a sample that arrives after a later one but within `window` sequence numbers of the oldest
//    missing one is held and released in its place: counted `reordered`;
//  * when a sample arrives more than `window` ahead of a missing one, the missing one is given up:
//    counted `lost` (the samples after it are released). A lost sample that turns up afterwards is
//    counted `late` instead of lost, and dropped (its place has been published);
//  * the same sequence number twice with the same payload (time and accelerations, bit for bit):
//    `duplicates`, dropped;
//  * the same sequence number with a different payload: `conflicts` (issue 52): the first one is
//    kept (it may already be published), the second dropped; the bridge reports it as an ERROR,
//    since two sources or a broken controller feed one stream. Released samples are compared
//    within the last kResyncSpan sequence numbers, held ones always. A held sample is marked
//    (AccelSample::conflict, counted `conflicts_marked`) and released so marked; one already
//    released cannot be;
//  * a jump of more than kResyncSpan (the controller restarted, or its counter was reset):
//    everything held is released, counted `resyncs`, and the stream continues from there. Unless
//    backward resyncs are off (the bridge with a ~key_file, issue 52): then a sample more than
//    kResyncSpan behind is dropped and counted `stale`, since a captured authenticated datagram
//    replayed later carries a valid tag, and only its old sequence number gives it away. An
//    authenticated sender's counter must therefore never go back (docs/inputs.md).
// A lost sample delays the samples after it by at most `window` samples (or until flush(), which
// the bridge calls when the stream pauses). Nothing is allocated after construction.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rocking_monitor/feeds/udp_datagram.hpp"

namespace rocking_monitor::feeds {

struct SequenceCounts {
  std::uint64_t accepted = 0;    ///< samples given to push()
  std::uint64_t released = 0;    ///< samples released in order
  std::uint64_t lost = 0;        ///< sequence numbers given up (never arrived, or not yet)
  std::uint64_t reordered = 0;   ///< arrived after a later sample, released in order
  std::uint64_t late = 0;        ///< arrived after their place was given up: dropped
  std::uint64_t duplicates = 0;  ///< a sequence number seen twice, same payload: dropped
  std::uint64_t conflicts = 0;   ///< a sequence number seen twice, different payload: first kept
  std::uint64_t conflicts_marked = 0;  ///< of those, found while the first was held: it is marked
  std::uint64_t last_conflict = 0;     ///< the sequence number of the latest conflict
  std::uint64_t resyncs = 0;     ///< jumps of more than kResyncSpan: the stream restarted
  std::uint64_t stale = 0;       ///< more than kResyncSpan behind, backward resyncs off: dropped
};

class SampleSequencer {
 public:
  /// Sequence numbers this far back or ahead are a restart, not a loss.
  static constexpr std::uint64_t kResyncSpan = 4096;

  /// `window`: how many sequence numbers a sample may arrive out of place and still be released
  /// in order (0: no reordering; a sample behind is late).
  /// `resync_backward` false: a sample far behind is `stale` (dropped), not a restart.
  explicit SampleSequencer(std::size_t window, bool resync_backward = true);

  /// Accepts one sample (its `sequence` must be set); the samples it releases are in ready().
  /// ready() is emptied at the start of each push() and flush().
  void push(const AccelSample& sample);
  /// Releases every held sample (the missing ones before them are counted lost).
  void flush();

  const AccelSample* ready() const { return ready_.data(); }
  std::size_t ready_count() const { return ready_count_; }

  const SequenceCounts& counts() const { return counts_; }
  std::size_t held() const { return held_; }
  /// The next sequence number to be released (0 before the first sample).
  std::uint64_t next_sequence() const { return next_; }
  std::size_t window() const { return slots_.size() - 1; }

 private:
  struct Slot {
    bool filled = false;
    AccelSample sample;
  };
  enum class Fate : std::uint8_t { Unknown, Released, Lost };
  struct History {
    std::uint64_t sequence = 0;
    Fate fate = Fate::Unknown;
    AccelSample sample;  // what was released, to tell a duplicate from a conflict
  };

  void release_next();  // releases or gives up next_, then advances
  void remember(std::uint64_t sequence, Fate fate, const AccelSample* sample = nullptr);
  /// Counts a repeat as a duplicate or a conflict; `held`: `first` is not released yet, mark it.
  void count_repeat(AccelSample& first, const AccelSample& again, bool held);

  std::vector<Slot> slots_;       // window + 1, indexed by sequence % size
  std::vector<History> history_;  // kResyncSpan, indexed by sequence % size
  std::vector<AccelSample> ready_;
  std::size_t ready_count_ = 0;
  std::size_t held_ = 0;
  bool resync_backward_ = true;
  bool started_ = false;
  std::uint64_t next_ = 0;
  std::uint64_t max_seen_ = 0;
  SequenceCounts counts_;
};

}  // namespace rocking_monitor::feeds
