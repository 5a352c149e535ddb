#include "rocking_monitor/notify/outbox.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "rocking_monitor/json_text.hpp"
#include "rocking_monitor/private_files.hpp"

namespace rocking_monitor::notify {

using nlohmann::json;

namespace {

std::string errno_text(const std::string& what, const std::string& path) {
  return what + " " + path + ": " + std::strerror(errno);
}

// NaN is no JSON number: null.
json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
double num(const json& j) { return j.is_number() ? j.get<double>() : NotifyAlarm::kNaN; }

json alarm_json(const NotifyAlarm& a) {
  return json{{"probability", a.probability}, {"source", a.source}, {"item", a.item}, {"description", a.description},
              {"level", a.level}, {"cause", core::to_string(a.cause)}, {"stamp_ns", a.stamp_ns}, {"event_time", num(a.event_time)},
              {"event_id", a.event_id}, {"sequence", a.sequence}, {"whole", a.whole},
              {"value", num(a.probability_value)}, {"threshold", num(a.threshold)}};
}

NotifyAlarm alarm_from(const json& j) {
  NotifyAlarm a;
  a.probability = j.at("probability").get<bool>();
  a.source = j.at("source").get<std::string>();
  a.item = j.at("item").get<std::string>();
  a.description = j.at("description").get<std::string>();
  a.level = j.at("level").get<int>();
  // an outbox written before issue 51 has no cause: those alarms rocked
  if (!core::parse_alarm_cause(j.value("cause", "rocking").c_str(), a.cause))
    throw std::runtime_error("unknown cause '" + j.at("cause").get<std::string>() + "'");
  a.stamp_ns = j.at("stamp_ns").get<std::int64_t>();
  a.event_time = num(j.at("event_time"));
  a.event_id = j.at("event_id").get<std::string>();
  a.sequence = j.at("sequence").get<std::uint64_t>();
  a.whole = j.at("whole").get<bool>();
  a.probability_value = num(j.at("value"));
  a.threshold = num(j.at("threshold"));
  return a;
}

json message_json(const OutMessage& m) {
  return json{{"t", "msg"}, {"id", m.id}, {"recipient", m.recipient}, {"channel", m.channel}, {"to", m.to},
              {"subject", m.subject}, {"body", m.body}, {"topic", m.topic}, {"retain", m.retain},
              {"alarms", m.alarms}, {"created", m.created}};
}

std::string line_of(const json& j) { return json_text(j) + "\n"; }

std::string write_all(int fd, const std::string& text, const std::string& path) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno_text("cannot write", path);
    }
    done += static_cast<std::size_t>(n);
  }
  return "";
}

std::string fsync_folder(const std::string& path) {
  const auto dir = std::filesystem::path(path).parent_path();
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return errno_text("cannot open folder of", path);
  const int rc = ::fsync(fd);
  ::close(fd);
  return rc == 0 ? "" : errno_text("cannot fsync folder of", path);
}

}  // namespace

std::string to_json(const NotifyAlarm& a) { return json_text(alarm_json(a)); }

Outbox::~Outbox() {
  if (fd_ >= 0) {
    sync();
    ::close(fd_);
  }
}

std::string Outbox::open(const std::string& path) {
  path_ = path;
  std::error_code ec;
  const auto dir = std::filesystem::path(path).parent_path();
  if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  if (ec) return "cannot create folder " + dir.string() + ": " + ec.message();
  if (std::string e = replay(); !e.empty()) return e;
  fd_ = ::open(path.c_str(), kPrivateAppendFlags, kPrivateFileMode);
  if (fd_ < 0) return errno_text("cannot open", path);
  if (token_.empty()) {
    std::random_device rd;
    std::ostringstream t;
    t << std::hex << rd() << rd();
    token_ = t.str();
    pending_ += line_of(json{{"t", "outbox"}, {"token", token_}});
    return sync();
  }
  return "";
}

std::string Outbox::replay() {
  std::ifstream in(path_, std::ios::binary);
  if (!in) return "";  // a new outbox
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::size_t start = 0, line_no = 0, whole = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    ++line_no;
    if (end == std::string::npos) {  // killed while writing: the cut line was never acted on
      warnings_.push_back(path_ + ":" + std::to_string(line_no) + ": last line cut in the middle (" +
                          std::to_string(text.size() - start) + " bytes), dropped");
      break;
    }
    const std::string line = text.substr(start, end - start);
    start = end + 1;
    whole = start;
    try {
      const json j = json::parse(line);
      const std::string t = j.at("t").get<std::string>();
      if (t == "outbox") {
        token_ = j.at("token").get<std::string>();
        next_message_ = j.value("messages", std::uint64_t{0});
      } else if (t == "alarm") {
        OutboxAlarm a;
        a.number = j.at("n").get<std::uint64_t>();
        a.alarm = alarm_from(j.at("alarm"));
        a.recipients = j.at("recipients").get<std::vector<std::string>>();
        a.accepted = j.at("accepted").get<double>();
        next_alarm_ = std::max(next_alarm_, a.number + 1);
        alarms_.push_back(std::move(a));
      } else if (t == "msg") {
        OutMessage m;
        m.id = j.at("id").get<std::string>();
        m.recipient = j.at("recipient").get<std::string>();
        m.channel = j.at("channel").get<std::string>();
        m.to = j.at("to").get<std::string>();
        m.subject = j.at("subject").get<std::string>();
        m.body = j.at("body").get<std::string>();
        m.topic = j.at("topic").get<std::string>();
        m.retain = j.at("retain").get<bool>();
        m.alarms = j.at("alarms").get<std::vector<std::uint64_t>>();
        m.created = j.at("created").get<double>();
        for (auto n : m.alarms) covered_.insert({n, m.recipient});
        last_message_[m.recipient] = std::max(last_message(m.recipient), m.created);
        ++next_message_;
        unacked_order_.push_back(m.id);
        unacked_[m.id] = std::move(m);
      } else if (t == "ack") {
        unacked_.erase(j.at("id").get<std::string>());
      } else if (t == "failed") {
        unacked_.erase(j.at("id").get<std::string>());
        ++failed_;
      } else {
        throw std::runtime_error("unknown record type '" + t + "'");
      }
    } catch (const std::exception& e) {
      return path_ + ":" + std::to_string(line_no) + ": corrupt outbox line (" + e.what() +
             "); move the file aside to start a new outbox";
    }
  }
  in.close();
  if (whole < text.size() && ::truncate(path_.c_str(), static_cast<off_t>(whole)) != 0)
    return errno_text("cannot cut the last line of", path_);
  return "";
}

std::string Outbox::new_message_id(const std::string& recipient) {
  return token_ + "." + std::to_string(++next_message_) + "." + recipient;
}

std::uint64_t Outbox::add_alarm(OutboxAlarm& a) {
  a.number = next_alarm_++;
  pending_ += line_of(json{{"t", "alarm"}, {"n", a.number}, {"alarm", alarm_json(a.alarm)}, {"recipients", a.recipients},
                           {"accepted", a.accepted}});
  alarms_.push_back(a);
  return a.number;
}

double Outbox::last_message(const std::string& recipient) const {
  auto it = last_message_.find(recipient);
  return it == last_message_.end() ? -INFINITY : it->second;
}

void Outbox::add_message(const OutMessage& m) {
  pending_ += line_of(message_json(m));
  last_message_[m.recipient] = std::max(last_message(m.recipient), m.created);
  for (auto n : m.alarms) covered_.insert({n, m.recipient});
  unacked_order_.push_back(m.id);
  unacked_[m.id] = m;
}

void Outbox::add_ack(const std::string& id) {
  pending_ += line_of(json{{"t", "ack"}, {"id", id}});
  unacked_.erase(id);
}

void Outbox::add_failed(const std::string& id, const std::string& reason) {
  pending_ += line_of(json{{"t", "failed"}, {"id", id}, {"reason", reason}});
  unacked_.erase(id);
  ++failed_;
}

std::string Outbox::sync() {
  if (pending_.empty() || fd_ < 0) return "";
  std::string e = write_all(fd_, pending_, path_);
  pending_.clear();
  if (e.empty() && ::fsync(fd_) != 0) e = errno_text("cannot fsync", path_);
  return e;
}

std::vector<OutMessage> Outbox::unacknowledged() const {
  std::vector<OutMessage> out;
  for (const auto& id : unacked_order_)
    if (auto it = unacked_.find(id); it != unacked_.end()) out.push_back(it->second);
  return out;
}

bool Outbox::covered(std::uint64_t alarm, const std::string& recipient) const {
  return covered_.count({alarm, recipient}) > 0;
}

std::string Outbox::compact(double now, double remember, std::size_t min_alarms) {
  if (!unacked_.empty() || alarms_.size() <= min_alarms || fd_ < 0) return "";
  if (std::string e = sync(); !e.empty()) return e;
  std::vector<OutboxAlarm> kept;
  // Message numbers go on from where they were (the header keeps the count): ids stay unique.
  std::string text = line_of(json{{"t", "outbox"}, {"token", token_}, {"messages", next_message_}});
  for (const auto& a : alarms_) {
    if (a.accepted < now - remember) continue;
    // Kept for deduplication only: every recipient has had it (nothing is pending), so a message-less
    // replay must not route it again: recorded with no recipients.
    OutboxAlarm k = a;
    k.recipients.clear();
    text += line_of(json{{"t", "alarm"}, {"n", k.number}, {"alarm", alarm_json(k.alarm)}, {"recipients", k.recipients},
                         {"accepted", k.accepted}});
    kept.push_back(std::move(k));
  }
  std::string tmp;
  const int fd = create_temp_beside(path_, tmp);  // 0600, a fresh name: never an existing file or link
  if (fd < 0) return errno_text("cannot create a temporary file beside", path_);
  std::string e = write_all(fd, text, tmp);
  if (e.empty() && ::fsync(fd) != 0) e = errno_text("cannot fsync", tmp);
  ::close(fd);
  if (e.empty() && ::rename(tmp.c_str(), path_.c_str()) != 0) e = errno_text("cannot rename over", path_);
  if (!e.empty()) {
    ::unlink(tmp.c_str());
    return e;
  }
  if (e = fsync_folder(path_); !e.empty()) return e;
  ::close(fd_);
  fd_ = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) return errno_text("cannot reopen", path_);
  alarms_ = std::move(kept);
  covered_.clear();
  unacked_order_.clear();
  return "";
}

}  // namespace rocking_monitor::notify
