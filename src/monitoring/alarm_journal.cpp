#include "rocking_monitor/monitoring/alarm_journal.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "rocking_monitor/json_text.hpp"
#include "rocking_monitor/monitoring/event_clock.hpp"
#include "rocking_monitor/private_files.hpp"

namespace rocking_monitor::core {
namespace {

using nlohmann::json;

const char* level_name(int level) {
  switch (level) {
    case 2: return "BEYOND_TIPPING";
    case 3: return "COMMITTED";
    case 4: return "OVERTURNED";
    default: return nullptr;
  }
}

int level_code(const std::string& name) {
  for (int l = 2; l <= 4; ++l)
    if (name == level_name(l)) return l;
  return 0;
}

bool parse_kind(const std::string& s, JournalKind& k) {
  for (JournalKind c :
       {JournalKind::Alarm, JournalKind::ProbabilityAlarm, JournalKind::Reset, JournalKind::Stale, JournalKind::End})
    if (s == to_string(c)) { k = c; return true; }
  return false;
}

// JSON has no NaN: an unknown number is left out of the line.
void put(json& j, const char* key, double v) {
  if (std::isfinite(v)) j[key] = v;
}

double number(const json& j, const char* key, bool required) {
  const auto it = j.find(key);
  if (it == j.end()) {
    if (required) throw std::runtime_error(std::string("field '") + key + "' missing");
    return JournalRecord::kNaN;
  }
  if (!it->is_number()) throw std::runtime_error(std::string("field '") + key + "' is not a number");
  return it->get<double>();
}

std::string text(const json& j, const char* key, bool required) {
  const auto it = j.find(key);
  if (it == j.end()) {
    if (required) throw std::runtime_error(std::string("field '") + key + "' missing");
    return {};
  }
  if (!it->is_string()) throw std::runtime_error(std::string("field '") + key + "' is not a string");
  return it->get<std::string>();
}

JournalRecord from_json_line(const std::string& line) {
  const json j = json::parse(line);  // throws json::parse_error with the column
  if (!j.is_object()) throw std::runtime_error("not a JSON object");
  JournalRecord r;
  const std::string kind = text(j, "kind", true);
  if (!parse_kind(kind, r.kind)) throw std::runtime_error("unknown kind '" + kind + "'");
  r.written = number(j, "written", true);
  r.time = number(j, "time", true);
  if (r.kind == JournalKind::Reset) {
    r.reason = text(j, "reason", false);
    return r;
  }
  r.event = text(j, "event", true);
  if (r.event.empty()) throw std::runtime_error("field 'event' is empty");
  const double seq = number(j, "sequence", true);
  if (!(seq >= 1.0) || seq != std::floor(seq)) throw std::runtime_error("field 'sequence' must be an integer >= 1");
  r.sequence = static_cast<std::uint64_t>(seq);
  r.event_start = number(j, "event_start", true);
  r.since_event_start = number(j, "since_event_start", true);
  r.sensor = text(j, "sensor", r.kind == JournalKind::Stale);
  if (const auto it = j.find("stamp_ns"); it != j.end()) {
    if (!it->is_number_integer()) throw std::runtime_error("field 'stamp_ns' is not an integer");
    r.stamp_ns = it->get<std::int64_t>();
  }
  if (r.kind == JournalKind::Stale) {
    r.end_time = number(j, "end_time", false);
    return r;
  }
  if (r.kind == JournalKind::End) {
    r.reason = text(j, "reason", false);
    return r;
  }
  r.item = text(j, "item", true);
  const std::string level = text(j, "level", true);
  r.level = level_code(level);
  if (r.level == 0) throw std::runtime_error("unknown level '" + level + "'");
  if (r.kind == JournalKind::Alarm) {
    r.plane = text(j, "plane", true);
    if (r.plane != "x" && r.plane != "y" && r.plane != "3d")
      throw std::runtime_error("field 'plane' must be \"x\", \"y\" or \"3d\"");
    r.rotation_ratio = number(j, "rotation_ratio", false);
    const std::string cause = text(j, "cause", false);
    if (!cause.empty() && !parse_alarm_cause(cause.c_str(), r.cause))
      throw std::runtime_error("unknown cause '" + cause + "'");
  } else {
    r.probability = number(j, "probability", true);
    r.lower = number(j, "lower", false);
    r.upper = number(j, "upper", false);
    r.threshold = number(j, "threshold", false);
    r.ensemble_size = static_cast<int>(number(j, "ensemble_size", false) >= 0 ? number(j, "ensemble_size", false) : 0);
  }
  return r;
}

// Within the window either way: a clock that jumped back by more than the window (sim time replaying
// an old record after a live event) is another event too.
bool within(double now, double written, double window) { return std::abs(now - written) <= window; }

std::string errno_text(const std::string& what, const std::string& path) {
  return what + " " + path + ": " + std::strerror(errno);
}

}  // namespace

const char* to_string(JournalKind kind) {
  switch (kind) {
    case JournalKind::Alarm: return "alarm";
    case JournalKind::ProbabilityAlarm: return "probability_alarm";
    case JournalKind::Reset: return "reset";
    case JournalKind::Stale: return "stale";
    case JournalKind::End: return "end";
  }
  return "?";
}

std::string to_json_line(const JournalRecord& r) {
  json j;
  j["kind"] = to_string(r.kind);
  if (r.kind != JournalKind::Reset) {
    j["event"] = r.event;
    j["sequence"] = r.sequence;
  }
  if (!r.item.empty()) j["item"] = r.item;
  if (r.level != 0 && level_name(r.level) != nullptr) j["level"] = level_name(r.level);
  if (!r.plane.empty()) j["plane"] = r.plane;
  if (r.kind == JournalKind::Alarm && r.cause != AlarmCause::Rocking) j["cause"] = to_string(r.cause);
  if (!r.sensor.empty()) j["sensor"] = r.sensor;
  put(j, "time", r.time);
  j["time_utc"] = iso8601_utc(r.time);  // for a person reading the file; not read back
  if (r.stamp_ns != 0) j["stamp_ns"] = r.stamp_ns;
  put(j, "end_time", r.end_time);
  put(j, "event_start", r.event_start);
  put(j, "since_event_start", r.since_event_start);
  put(j, "rotation_ratio", r.rotation_ratio);
  put(j, "probability", r.probability);
  put(j, "lower", r.lower);
  put(j, "upper", r.upper);
  put(j, "threshold", r.threshold);
  if (r.kind == JournalKind::ProbabilityAlarm) j["ensemble_size"] = r.ensemble_size;
  if (r.kind == JournalKind::Reset || r.kind == JournalKind::End) j["reason"] = r.reason;
  put(j, "written", r.written);
  return json_text(j);
}

namespace {

/// The event id and kind of a journal line read without parsing it, for the lines before the last
/// event: to_json_line writes `"event":"<id>"` (ids hold no quote) and `"kind":"<kind>"`. A quote
/// inside a string value is escaped (\"), so the patterns cannot match inside one. False: the line
/// does not look like a record; it is then parsed in full.
bool peek_record(const std::string& line, std::string_view& event, bool& reset) {
  if (line.size() < 2 || line.front() != '{' || line.back() != '}') return false;
  constexpr std::string_view kKind = "\"kind\":\"";
  const std::size_t k = line.find(kKind);
  if (k == std::string::npos) return false;
  const std::size_t ke = line.find('"', k + kKind.size());
  if (ke == std::string::npos) return false;
  JournalKind kind;
  if (!parse_kind(line.substr(k + kKind.size(), ke - k - kKind.size()), kind)) return false;
  reset = kind == JournalKind::Reset;
  event = {};
  constexpr std::string_view kEvent = "\"event\":\"";
  const std::size_t e = line.find(kEvent);
  if (e == std::string::npos) return reset;  // only a reset has no event
  const std::size_t ee = line.find('"', e + kEvent.size());
  if (ee == std::string::npos) return false;
  event = std::string_view(line).substr(e + kEvent.size(), ee - e - kEvent.size());
  return !event.empty();
}

}  // namespace

// Streams the file twice with a line buffer, never whole: a journal grows by every event's alarms
// (10,000 items on Kobe Takatori: ~10 MB) and is read at every start. The first pass finds where the
// last event begins and counts the events from each line's event field; the second parses the lines
// from there. Earlier lines are parsed only when they do not look like records (corrupt: reported).
// Reading everything into records took 8.7 s and 1.4 GB for 430 MB of journal.
JournalReading read_journal(const std::string& path) {
  JournalReading out;
  std::ifstream in(path, std::ios::binary);
  if (!in) return out;
  out.exists = true;
  std::set<std::string, std::less<>> ids;
  std::vector<std::pair<std::size_t, std::string>> errors;  // line, what is wrong
  std::string line, last_id;
  std::uint64_t pos = 0, tail_pos = 0;
  std::size_t line_no = 0, tail_line = 0;
  bool tail_found = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (in.eof()) {  // no newline after it
      out.warnings.push_back(path + ":" + std::to_string(line_no) + ": last line cut in the middle (" +
                             std::to_string(line.size()) +
                             " bytes without a newline: power cut while writing?); read up to line " +
                             std::to_string(line_no - 1));
      break;
    }
    const std::uint64_t line_pos = pos;
    pos += line.size() + 1;
    out.whole_bytes = pos;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    std::string_view event;
    bool reset = false;
    std::string parsed_event;
    if (!peek_record(line, event, reset)) {
      try {
        const JournalRecord r = from_json_line(line);
        parsed_event = r.event;
        event = parsed_event;
        reset = r.kind == JournalKind::Reset;
      } catch (const std::exception& e) {
        errors.emplace_back(line_no, e.what());
        continue;
      }
    }
    if (!event.empty() && ids.find(event) == ids.end()) ids.emplace(event);
    // The last event: that of the last record that is not a reset; its lines from its first one on.
    if (!reset && !event.empty() && (!tail_found || event != last_id)) {
      last_id.assign(event);
      tail_pos = line_pos;
      tail_line = line_no - 1;
      tail_found = true;
    }
  }
  out.events = ids.size();
  auto report = [&] {
    std::sort(errors.begin(), errors.end());
    for (const auto& [n, what] : errors)
      out.errors.push_back(path + ":" + std::to_string(n) + ": not a journal record (skipped): " + what);
  };
  if (!tail_found) {
    report();
    return out;
  }
  // Second pass: the last event's lines (and the resets among and after them) parsed in full.
  in.clear();
  in.seekg(static_cast<std::streamoff>(tail_pos));
  pos = tail_pos;
  line_no = tail_line;
  while (pos < out.whole_bytes && std::getline(in, line)) {
    ++line_no;
    pos += line.size() + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    try {
      out.records.push_back(from_json_line(line));
    } catch (const std::exception& e) {
      std::string_view event;
      bool reset = false;
      if (peek_record(line, event, reset)) errors.emplace_back(line_no, e.what());  // else the first pass has it
    }
  }
  report();
  return out;
}

OpenEvent last_event(const JournalReading& reading, bool* closed) {
  OpenEvent ev;
  if (closed) *closed = false;
  // The last event is the one of the last non-reset record; a later reset, or its own end, closes it.
  std::size_t last = reading.records.size();
  for (std::size_t i = reading.records.size(); i-- > 0;) {
    if (reading.records[i].kind != JournalKind::Reset) { last = i; break; }
    if (closed) *closed = true;
  }
  if (last == reading.records.size()) return ev;
  if (closed && reading.records[last].kind == JournalKind::End) *closed = true;
  ev.id = reading.records[last].event;
  for (const JournalRecord& r : reading.records) {
    if (r.event != ev.id) continue;
    if (ev.records.empty()) ev.start = r.event_start;
    ev.records.push_back(r);
    ev.last_sequence = std::max(ev.last_sequence, r.sequence);
    ev.last_written = r.written;
  }
  return ev;
}

OpenEvent open_event(const JournalReading& reading, double now, double window) {
  bool reset = false;
  OpenEvent ev = last_event(reading, &reset);
  if (reset || !ev.open() || !within(now, ev.last_written, window)) return OpenEvent{};
  return ev;
}

OpenEvent shown_event(const JournalReading& reading, double now, double window) {
  bool closed = false;
  OpenEvent ev = last_event(reading, &closed);
  const bool ended = ev.open() && ev.records.back().kind == JournalKind::End;
  if (!ev.open() || (closed && !ended) || !within(now, ev.last_written, window)) return OpenEvent{};
  return ev;
}

AlarmJournal::~AlarmJournal() {
  if (writer_.joinable()) {  // a job in flight is finished first: the loop stops only without one
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    cv_.notify_all();
    writer_.join();
  }
  if (fd_ >= 0) {
    sync();  // lines appended without sync: on disk before the file is closed
    ::close(fd_);
  }
}

std::string AlarmJournal::open(const std::string& path, double window, double now) {
  if (fd_ >= 0) {
    sync();
    ::close(fd_);
  }
  fd_ = -1;
  pending_.clear();
  path_ = path;
  window_ = window;
  memory_ = path.empty();
  reading_ = JournalReading{};
  event_ = OpenEvent{};
  held_.clear();
  events_ = 0;
  if (memory_) return {};
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  if (ec) return "cannot create the directory " + dir.string() + ": " + ec.message();
  reading_ = read_journal(path);
  const int fd = ::open(path.c_str(), kPrivateAppendFlags, kPrivateFileMode);
  if (fd < 0) return errno_text("cannot open", path);
  // A line cut by a power cut is dropped, so that the next record starts on a line of its own.
  struct stat st {};
  if (::fstat(fd, &st) == 0 && static_cast<std::uint64_t>(st.st_size) > reading_.whole_bytes) {
    if (::ftruncate(fd, static_cast<off_t>(reading_.whole_bytes)) != 0 || ::fsync(fd) != 0) {
      const std::string e = errno_text("cannot cut the last line of", path);
      ::close(fd);
      return e;
    }
  }
  fd_ = fd;
  // sync_async()'s thread, started here on the caller's thread (not later, where drain() may run on
  // another thread and read writer_).
  if (!writer_.joinable()) writer_ = std::thread([this] { writer_loop(); });
  events_ = reading_.events;
  event_ = open_event(reading_, now, window_);
  index_event();
  return {};
}

std::string AlarmJournal::key(JournalKind kind, const std::string& item, int level) {
  return std::to_string(static_cast<int>(kind)) + "/" + std::to_string(level) + "/" + item;
}

void AlarmJournal::index_event() {
  held_.clear();
  for (const JournalRecord& r : event_.records) held_.insert(key(r.kind, r.item, r.level));
}

bool AlarmJournal::holds(JournalKind kind, const std::string& item, int level) const {
  return held_.count(key(kind, item, level)) > 0;
}

std::string AlarmJournal::write_lines(std::string& lines) {
  if (lines.empty()) return {};
  std::size_t done = 0;
  std::string e;
  while (done < lines.size()) {
    const ssize_t n = ::write(fd_, lines.data() + done, lines.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      e = errno_text("cannot write", path_);  // not retried: the next line must not follow half a line
      break;
    }
    done += static_cast<std::size_t>(n);
  }
  lines.clear();  // keeps its capacity
  if (e.empty() && ::fsync(fd_) != 0) e = errno_text("cannot fsync", path_);
  return e;
}

std::string AlarmJournal::sync() {
  drain();
  if (fd_ < 0) {
    pending_.clear();
    return {};
  }
  return write_lines(pending_);
}

void AlarmJournal::sync_async(std::function<void(const std::string& error)> after) {
  if (fd_ < 0) {  // no file: nothing to wait for
    pending_.clear();
    after(std::string());
    return;
  }
  drain();
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    job_lines_.swap(pending_);  // pending_ takes the job's empty buffer (and its capacity)
    job_after_ = std::move(after);
    job_ = true;
  }
  cv_.notify_all();
}

void AlarmJournal::drain() {
  if (!writer_.joinable()) return;
  std::unique_lock<std::mutex> lock(mutex_);
  cv_.wait(lock, [this] { return !job_; });
}

// The only place besides the caller's thread that touches fd_: while a job runs, the caller waits in
// drain() before any other write.
void AlarmJournal::writer_loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    cv_.wait(lock, [this] { return job_ || stop_; });
    if (!job_) return;
    lock.unlock();
    const std::string e = write_lines(job_lines_);
    job_after_(e);
    job_after_ = nullptr;
    lock.lock();
    job_ = false;
    cv_.notify_all();
  }
}

// Lines appended with sync = false wait in pending_ and go to the file with sync(), in one write():
// in the strongest shaking ~90 alarms a sample were ~90 write() calls on the sample path.
std::string AlarmJournal::write_line(const JournalRecord& r, bool sync) {
  if (memory_) return {};
  if (fd_ < 0) return "journal not open";
  pending_ += to_json_line(r);
  pending_ += '\n';
  return sync ? this->sync() : std::string();
}

std::string AlarmJournal::append(JournalRecord& r, double run_start, double now, bool sync) {
  // The open event is changed only once the line is written (no copy of its records: thousands of
  // items may alarm in one event).
  const bool fresh = !event_.open() || !within(now, event_.last_written, window_);
  r.event = fresh ? iso8601_utc(run_start) + "/" + std::to_string(events_ + 1) : event_.id;
  r.sequence = fresh ? 1 : event_.last_sequence + 1;
  r.event_start = fresh ? run_start : event_.start;
  r.since_event_start = r.time - r.event_start;
  r.written = now;
  if (std::string e = write_line(r, sync); !e.empty()) return e;
  if (fresh) {
    ++events_;
    event_ = OpenEvent{};
    event_.id = r.event;
    event_.start = r.event_start;
    held_.clear();
  }
  event_.last_sequence = r.sequence;
  event_.last_written = now;
  event_.records.push_back(r);
  held_.insert(key(r.kind, r.item, r.level));
  return {};
}

std::string AlarmJournal::append_stale(const std::string& sensor, double from, double to, double run_start,
                                       double now, JournalRecord* written) {
  JournalRecord r;
  r.kind = JournalKind::Stale;
  r.sensor = sensor;
  r.time = from;
  r.end_time = to;
  std::string e = append(r, run_start, now);
  if (written != nullptr && e.empty()) *written = r;
  return e;
}

std::string AlarmJournal::append_end(const std::string& reason, double time, double now) {
  if (!event_.open() || !within(now, event_.last_written, window_)) return {};  // none open: nothing to end
  JournalRecord r;
  r.kind = JournalKind::End;
  r.time = time;
  r.reason = reason;
  if (std::string e = append(r, event_.start, now); !e.empty()) return e;
  event_ = OpenEvent{};
  held_.clear();
  return {};
}

std::string AlarmJournal::append_reset(const std::string& reason, double now) {
  JournalRecord r;
  r.kind = JournalKind::Reset;
  r.time = now;
  r.written = now;
  r.reason = reason;
  if (std::string e = write_line(r); !e.empty()) return e;
  event_ = OpenEvent{};
  held_.clear();
  return {};
}

}  // namespace rocking_monitor::core
