#pragma once

// The alarm journal (issue 19, part 2): every alarm, probability alarm, reset and stale period of the
// live monitor as one JSON line in a file, written with write(2) and fsync'd before the node publishes,
// so that a node killed and restarted (or a late dashboard or report) finds the alarms of the event
// still open. docs/journal.md has the format and the rules; this is the ROS-free core of it.
//
// Event: the alarms of one shaking. An event opens with the first record written when none is open
// (first record of the file, after a reset, or when the node's clock is more than ~journal_window from
// when the open event's last record was written); a reset closes it. Its id is the ISO 8601 UTC time of the first
// sample of the sensor run in which it opened, then '/' and its ordinal in the file:
// "1994-01-17T12:30:55.000Z/3". Every record of an event carries a sequence number (1, 2, ... over all
// the event's records: alarms, probability alarms and stale periods share it).

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <limits>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_set>
#include <vector>

#include "rocking_monitor/monitoring/item_modes.hpp"

namespace rocking_monitor::core {

/// End (issue 29): the shaking stopped (every sensor quiet, every item at rest or overturned, for the
/// node's ~event_quiet_time of input); the event's last record: it closes the event as a reset does.
enum class JournalKind { Alarm, ProbabilityAlarm, Reset, Stale, End };
const char* to_string(JournalKind kind);

/// One line of the journal. Times in s since 1970 (the clock of the input stamps) unless said.
struct JournalRecord {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  JournalKind kind = JournalKind::Alarm;
  std::string event;            ///< event id (empty for a reset)
  std::uint64_t sequence = 0;   ///< 1, 2, ... within the event (0 for a reset)
  std::string item;             ///< catalogue item id (alarms)
  int level = 0;                ///< 2 BEYOND_TIPPING, 3 COMMITTED, 4 OVERTURNED (codes of OverturnAlarm.msg)
  std::string plane;            ///< "x" or "y" (alarm)
  /// alarm: how the item reached the level; "cause" in the line only when not Rocking (older lines: Rocking)
  AlarmCause cause = AlarmCause::Rocking;
  std::string sensor;           ///< sensor name (stale period; alarms: the item's sensor)
  double time = kNaN;           ///< alarm: when the level was reached; stale: start of the period; reset: node clock
  std::int64_t stamp_ns = 0;    ///< alarms: header stamp of the input sample, ns since 1970 (0: unknown)
  double end_time = kNaN;       ///< stale: the sample that ended the period (NaN while it lasts)
  double event_start = kNaN;    ///< the event's first sample
  double since_event_start = kNaN;  ///< time - event_start, s
  double written = kNaN;        ///< node clock (wall or /clock) when written: the window is measured on it
  double rotation_ratio = kNaN; ///< alarm: |theta| / alpha, dimensionless
  double probability = kNaN, lower = kNaN, upper = kNaN;  ///< probability alarm: share and 95 % Wilson interval
  double threshold = kNaN;      ///< probability alarm: ~alarm_probability
  int ensemble_size = 0;        ///< probability alarm: members
  std::string reason;           ///< reset, end: why
};

/// The JSON line of a record (no newline). Allocates: only when a record is written.
std::string to_json_line(const JournalRecord& r);

/// What a journal file holds. Never throws for bad content: each problem is a "file:line: ..." text.
struct JournalReading {
  /// The valid records of the file's last event (that of its last record other than a reset), from
  /// its first line on, resets among them included, in file order. Earlier events are counted in
  /// `events`, not kept: a journal holds every event since it was created, and only the last can be open.
  std::vector<JournalRecord> records;
  std::vector<std::string> warnings;   ///< a last line cut in the middle (power cut while writing)
  std::vector<std::string> errors;     ///< corrupt lines (skipped), file:line and what is wrong
  std::uint64_t whole_bytes = 0;       ///< length of the file up to its last whole line
  std::uint64_t events = 0;            ///< distinct event ids in the file
  bool exists = false;
};
JournalReading read_journal(const std::string& path);

/// The event still open at `now` (node clock, s since 1970): the last event of the reading, unless it
/// ended (its last record an end), a reset followed it or `now` is more than `window` s from when its
/// last record was written (either
/// way: a clock far behind, as sim time replaying an old record, is another event too). Empty id: none.
struct OpenEvent {
  std::string id;
  double start = JournalRecord::kNaN;       ///< its first sample, s since 1970
  std::uint64_t last_sequence = 0;
  double last_written = JournalRecord::kNaN;
  std::vector<JournalRecord> records;       ///< its records, in order
  bool open() const { return !id.empty(); }
};
OpenEvent open_event(const JournalReading& reading, double now, double window);
/// What a late subscriber or dashboard is shown at `now`: the last event while `now` is within `window`
/// of its last record, open or ended by its shaking stopping (not after a reset). Empty id: none.
OpenEvent shown_event(const JournalReading& reading, double now, double window);
/// The last event of the reading whatever its age (the report reads a journal after the fact), and
/// whether it is closed (by a reset after it, or by its own end record).
OpenEvent last_event(const JournalReading& reading, bool* closed = nullptr);

/// The node's writer. open() reads the file, cuts a last line left in the middle back to the last
/// whole line (the warning says so), and keeps the file open for appending. Appending allocates and
/// blocks on fsync: it runs only when something is journaled (alarms are rare), never per sample.
class AlarmJournal {
 public:
  AlarmJournal() = default;
  ~AlarmJournal();
  AlarmJournal(const AlarmJournal&) = delete;
  AlarmJournal& operator=(const AlarmJournal&) = delete;

  /// Creates missing directories and the file. `now`: node clock, s since 1970. Empty string on
  /// success, else what failed (path and errno text). The reading is kept (warnings, errors).
  /// An empty path: no file (~journal off); events and sequence numbers are still kept, in memory.
  std::string open(const std::string& path, double window, double now);
  bool is_open() const { return fd_ >= 0 || memory_; }
  bool in_memory() const { return memory_; }
  const std::string& path() const { return path_; }
  const JournalReading& reading() const { return reading_; }
  /// The event open at the last open() or append.
  const OpenEvent& event() const { return event_; }
  /// Whether the open event already holds an alarm (kind Alarm or ProbabilityAlarm) of item at level.
  bool holds(JournalKind kind, const std::string& item, int level) const;

  /// Appends r: sets r.event, r.sequence, r.event_start, r.since_event_start and r.written (opening
  /// a new event with first sample `run_start` if none is open at `now`), writes the line and
  /// fsyncs (sync = false: the line waits in memory and the caller calls sync() before it publishes:
  /// one write and one fsync for all the alarms of a sample, which matters when thousands of items
  /// alarm at once). Empty string on success, else the error (the record is then not in the file).
  std::string append(JournalRecord& r, double run_start, double now, bool sync = true);
  /// Writes the lines appended with sync = false (one write()), then fsync (none: nothing to do). Empty
  /// string on success. A write error loses the lines not written (the error says so).
  std::string sync();
  /// sync() on the journal's own thread, so that the caller does not wait for the disk: the lines
  /// appended since go to the file, then `after(error)` runs on that thread (empty error: they are on
  /// disk). The next sync_async(), sync(), append() with sync, append_*(), open() or the destructor
  /// first waits for it. Without a file (journal off or not open) `after` runs here, at once.
  void sync_async(std::function<void(const std::string& error)> after);
  /// Waits until the sync_async() in flight, if any, has run its `after`.
  void drain();
  /// A stale period of a sensor (its items frozen): from `from` to `to` (s since 1970; NaN `to`: still
  /// stale), in the sensor run that started at `run_start`; `now` is the node clock.
  std::string append_stale(const std::string& sensor, double from, double to, double run_start, double now,
                           JournalRecord* written = nullptr);
  /// A reset (the ~reset service): closes the open event; the next record opens a new one.
  std::string append_reset(const std::string& reason, double now);
  /// The end of the open event's shaking (`time`: the input stamp that completed the quiet time, s since
  /// 1970): its last record, numbered on; the next record opens a new event. Nothing open: nothing done.
  std::string append_end(const std::string& reason, double time, double now);

 private:
  std::string write_line(const JournalRecord& r, bool sync = true);
  static std::string key(JournalKind kind, const std::string& item, int level);
  void index_event();  // held_ from event_.records
  int fd_ = -1;
  bool memory_ = false;
  std::string path_;
  double window_ = 3600.0;
  JournalReading reading_;
  OpenEvent event_;
  std::unordered_set<std::string> held_;  // key() of the open event's alarms: holds() in O(1)
  std::string pending_;                   // lines appended with sync = false, written by sync()
  // sync_async()'s thread (started by open() with a file) and its one job: the lines and what follows.
  std::string write_lines(std::string& lines);  // write + fsync on fd_ (lines cleared); the error or ""
  void writer_loop();
  std::thread writer_;
  std::mutex mutex_;
  std::condition_variable cv_;
  bool job_ = false, stop_ = false;
  std::string job_lines_;
  std::function<void(const std::string&)> job_after_;
  std::uint64_t events_ = 0;  // events in the file, to number the next one
};

}  // namespace rocking_monitor::core
