#include "rocking_monitor/notify/notifier.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <stdexcept>

#include "rocking_monitor/notify/compose.hpp"

namespace rocking_monitor::notify {

double backoff_delay(const NotifyConfig& c, unsigned attempt) {
  if (attempt == 0) return 0.0;
  return std::min(c.retry_max, c.retry_initial * std::pow(c.retry_factor, static_cast<double>(attempt - 1)));
}

struct Notifier::Sender {
  ChannelConfig config;
  std::unique_ptr<Channel> channel;
  std::deque<OutMessage> queue;      // formed, on disk, not yet acknowledged; front goes first
  mutable std::mutex mutex;
  mutable std::condition_variable cv;
  bool stop = false;
  ChannelStatus status;
  std::thread thread;
};

namespace {

core::AlarmIdentity identity(const NotifyAlarm& a) {
  core::AlarmIdentity id;
  id.source = a.source;
  id.item = a.item;
  // A probability alarm and an alarm of the same item and level are two alarms.
  id.level = a.level + (a.probability ? 100 : 0);
  id.stamp_ns = a.stamp_ns;
  id.event_id = a.event_id;
  id.sequence = a.sequence;
  id.whole = a.whole;
  return id;
}

}  // namespace

Notifier::Notifier(NotifyConfig config, const std::string& outbox_path, const ChannelFactory& factory, double now)
    // The pair's copies: the dedup's own window on input stamps (10 s, as the dashboard's), not the
    // grouping window, which is about people.
    : config_(std::move(config)), dedup_(core::AlarmDedup::kDefaultWindow) {
  if (std::string e = outbox_.open(outbox_path); !e.empty()) throw std::runtime_error("notify outbox: " + e);
  for (const auto& [name, ch] : config_.channels) {
    auto s = std::make_unique<Sender>();
    s->config = ch;
    s->channel = factory(ch);
    s->status.name = name;
    s->status.type = ch.type;
    senders_.emplace(name, std::move(s));
  }
  // Replay: the alarms seen (deduplication), the per-item state, the alarms still waiting for a group.
  for (const auto& r : config_.recipients) waiting_[r.name].last_sent = outbox_.last_message(r.name);
  for (const auto& a : outbox_.alarms()) {
    dedup_.add(identity(a.alarm));
    ++counts_.accepted;
    OutboxAlarm left = a;
    left.recipients.clear();
    for (const auto& r : a.recipients) {
      if (outbox_.covered(a.number, r)) {
        const auto rc = std::find_if(config_.recipients.begin(), config_.recipients.end(), [&](auto& x) { return x.name == r; });
        if (rc != config_.recipients.end() && !a.alarm.probability) {
          int& state = item_state_[rc->channel + "\n" + a.alarm.item];
          state = std::max(state, a.alarm.level);
        }
      } else {
        left.recipients.push_back(r);
      }
    }
    if (!left.recipients.empty()) to_route_.push_back(std::move(left));
  }
  for (auto& m : outbox_.unacknowledged()) {
    auto it = senders_.find(m.channel);
    if (it != senders_.end()) {
      it->second->queue.push_back(std::move(m));
      continue;
    }
    // Its channel was removed from the configuration since: it cannot be sent. Said, and closed.
    warnings_.push_back("outbox message " + m.id + " for channel '" + m.channel +
                        "', no longer configured, dropped: " + m.subject);
    outbox_.add_ack(m.id);
  }
  if (std::string e = outbox_.sync(); !e.empty()) throw std::runtime_error("notify outbox: " + e);
  for (auto& [name, s] : senders_) {
    Sender* sp = s.get();
    sp->status.queued = sp->queue.size();
    sp->thread = std::thread([this, sp] { sender_loop(*sp); });
  }
  (void)now;
}

Notifier::~Notifier() {
  for (auto& [name, s] : senders_) {
    std::lock_guard<std::mutex> l(s->mutex);
    s->stop = true;
    s->cv.notify_all();
  }
  for (auto& [name, s] : senders_)
    if (s->thread.joinable()) s->thread.join();
}

Notifier::Accepted Notifier::accept(const NotifyAlarm& alarm, double now) {
  std::lock_guard<std::mutex> l(outbox_mutex_);
  const auto result = dedup_.add(identity(alarm));
  if (result.outcome == core::AlarmDedup::Outcome::Repeat) {
    ++counts_.repeats;
    return Accepted::Repeat;
  }
  if (result.outcome == core::AlarmDedup::Outcome::Merged) {
    ++counts_.merged;
    return Accepted::Merged;
  }
  OutboxAlarm a;
  a.alarm = alarm;
  a.accepted = now;
  for (const auto& r : config_.recipients)
    if (r.wants(alarm.item, alarm.level, alarm.probability)) a.recipients.push_back(r.name);
  if (a.recipients.empty()) {
    ++counts_.unrouted;
    return Accepted::Unrouted;
  }
  outbox_.add_alarm(a);
  ++counts_.accepted;
  to_route_.push_back(std::move(a));
  return Accepted::Routed;
}

double Notifier::due_at(const RecipientConfig& r, const Waiting& w) const {
  if (w.alarms.empty()) return INFINITY;
  if (r.digest) return std::max(w.first + r.digest_window, w.last_sent + config_.window);
  return w.urgent ? std::max(w.last_sent + config_.window, w.first)
                  : std::max(w.last_sent + config_.window, w.first + config_.window);
}

double Notifier::next_due() const {
  std::lock_guard<std::mutex> l(outbox_mutex_);
  double due = to_route_.empty() ? INFINITY : 0.0;
  for (const auto& r : config_.recipients) due = std::min(due, due_at(r, waiting_.at(r.name)));
  return due;
}

std::string Notifier::tick(double now) {
  std::vector<OutMessage> formed;
  {
    std::lock_guard<std::mutex> l(outbox_mutex_);
    if (std::string e = outbox_.sync(); !e.empty()) return e;  // nothing goes out that is not on disk
    for (const auto& a : to_route_) {
      int refs = 0;
      for (const auto& name : a.recipients) {
        const auto r = std::find_if(config_.recipients.begin(), config_.recipients.end(), [&](auto& x) { return x.name == name; });
        if (r == config_.recipients.end()) continue;  // a recipient removed from the configuration since
        const ChannelConfig& ch = config_.channel_of(*r);
        if (ch.type == ChannelType::Mqtt) {
          int& state = item_state_[ch.name + "\n" + a.alarm.item];
          if (!a.alarm.probability) state = std::max(state, a.alarm.level);
          for (auto& m : compose_mqtt(ch, *r, a, std::max(state, static_cast<int>(kBeyondTipping)))) {
            m.id = outbox_.new_message_id(r->name);
            m.created = now;
            outbox_.add_message(m);
            formed.push_back(std::move(m));
          }
          continue;
        }
        Waiting& w = waiting_[r->name];
        if (w.alarms.empty()) w.first = now;
        w.alarms.push_back(a.number);
        w.urgent = w.urgent || (!r->digest && a.alarm.level >= kCommitted);
        ++refs;
      }
      if (refs > 0) alarms_.emplace(a.number, std::make_pair(a, refs));
    }
    to_route_.clear();
    for (const auto& r : config_.recipients) {
      Waiting& w = waiting_[r.name];
      if (now < due_at(r, w)) continue;
      std::vector<const OutboxAlarm*> group;
      for (auto n : w.alarms) group.push_back(&alarms_.at(n).first);
      OutMessage m = compose_group(config_, r, group);
      m.id = outbox_.new_message_id(r.name);
      m.created = now;
      outbox_.add_message(m);
      formed.push_back(std::move(m));
      for (auto n : w.alarms)
        if (--alarms_.at(n).second == 0) alarms_.erase(n);
      w = Waiting{{}, NAN, now, false};
    }
    counts_.messages += formed.size();
    if (std::string e = outbox_.sync(); !e.empty()) return e;
    bool idle = formed.empty() && alarms_.empty() && outbox_.pending() == 0;
    if (idle) {
      if (std::string e = outbox_.compact(now, config_.remember); !e.empty()) return e;
    }
  }
  for (auto& m : formed) {
    Sender& s = *senders_.at(m.channel);
    std::lock_guard<std::mutex> l(s.mutex);
    s.queue.push_back(std::move(m));
    s.status.queued = s.queue.size();
    s.cv.notify_all();
  }
  return "";
}

void Notifier::acknowledge(Sender& s, const std::vector<std::string>& ids) {
  std::string error;
  {
    std::lock_guard<std::mutex> l(outbox_mutex_);
    for (const auto& id : ids) outbox_.add_ack(id);
    error = outbox_.sync();
  }
  std::lock_guard<std::mutex> l(s.mutex);
  const std::set<std::string> done(ids.begin(), ids.end());
  s.queue.erase(std::remove_if(s.queue.begin(), s.queue.end(), [&](const OutMessage& m) { return done.count(m.id) > 0; }),
                s.queue.end());
  s.status.delivered += ids.size();
  s.status.queued = s.queue.size();
  // Delivered, but the ack did not reach the disk: sent again after a restart. Said, not hidden.
  if (!error.empty()) s.status.last_error = "outbox: " + error;
  s.cv.notify_all();
}

// A message the server refused for good (550 user unknown, HTTP 404): retrying cannot help and would
// hold up the recipient's later messages for ever. Closed as failed in the outbox, said, not retried.
void Notifier::give_up(Sender& s, const OutMessage& m, const std::string& reason) {
  std::string error;
  {
    std::lock_guard<std::mutex> l(outbox_mutex_);
    outbox_.add_failed(m.id, reason);
    error = outbox_.sync();
  }
  std::lock_guard<std::mutex> l(s.mutex);
  s.queue.erase(std::remove_if(s.queue.begin(), s.queue.end(), [&](const OutMessage& q) { return q.id == m.id; }),
                s.queue.end());
  ++s.status.failures;
  ++s.status.refused;
  s.status.queued = s.queue.size();
  s.status.last_error = "refused for good, not retried: message " + m.id + " to " + m.recipient + ": " + reason;
  if (!error.empty()) s.status.last_error += "; outbox: " + error;
  s.cv.notify_all();
}

// Backoff is per recipient: a recipient the server refuses for now (451, HTTP 503) waits and is
// retried, without holding up the others' messages; each recipient's messages stay in order.
void Notifier::sender_loop(Sender& s) {
  using Clock = std::chrono::steady_clock;
  struct Backoff {
    unsigned attempt = 0;
    Clock::time_point next{};
  };
  std::map<std::string, Backoff> backoff;  // recipients in backoff
  auto failing = [&] {
    unsigned most = 0;
    for (const auto& [r, b] : backoff) most = std::max(most, b.attempt);
    return most;
  };
  for (;;) {
    std::vector<OutMessage> batch;
    {
      std::unique_lock<std::mutex> l(s.mutex);
      for (;;) {
        if (s.stop) return;
        const auto now = Clock::now();
        auto earliest = Clock::time_point::max();
        const std::size_t most = std::max<std::size_t>(1, s.channel->batch_size());
        std::set<std::string> waiting;  // recipients skipped: none of their later messages may overtake
        for (const auto& m : s.queue) {
          if (batch.size() >= most) break;
          auto b = backoff.find(m.recipient);
          if (waiting.count(m.recipient) || (b != backoff.end() && b->second.next > now)) {
            if (b != backoff.end()) earliest = std::min(earliest, b->second.next);
            waiting.insert(m.recipient);
            continue;
          }
          batch.push_back(m);
        }
        if (!batch.empty()) break;
        if (earliest == Clock::time_point::max()) s.cv.wait(l);
        else s.cv.wait_until(l, earliest);
      }
    }
    std::string error;
    const std::size_t done = std::min(batch.size(), s.channel->deliver(batch, &error));
    if (done > 0) {
      std::vector<std::string> ids;
      for (std::size_t i = 0; i < done; ++i) {
        ids.push_back(batch[i].id);
        backoff.erase(batch[i].recipient);
      }
      acknowledge(s, ids);
    }
    if (done < batch.size() && s.channel->refusal_is_permanent()) {
      backoff.erase(batch[done].recipient);
      give_up(s, batch[done], error.empty() ? "refused (no reason given)" : error);
      std::lock_guard<std::mutex> l(s.mutex);
      s.status.failing_attempts = failing();
      continue;
    }
    std::lock_guard<std::mutex> l(s.mutex);
    if (done < batch.size()) {
      Backoff& b = backoff[batch[done].recipient];
      ++b.attempt;
      b.next = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                  std::chrono::duration<double>(backoff_delay(config_, b.attempt)));
      ++s.status.failures;
      s.status.last_error = error.empty() ? "delivery failed (no reason given)" : error;
    }
    s.status.failing_attempts = failing();
  }
}

std::vector<Notifier::ChannelStatus> Notifier::status() const {
  std::vector<ChannelStatus> out;
  for (const auto& [name, s] : senders_) {
    std::lock_guard<std::mutex> l(s->mutex);
    out.push_back(s->status);
  }
  return out;
}

Notifier::Counts Notifier::counts() const {
  std::lock_guard<std::mutex> l(outbox_mutex_);
  return counts_;
}

bool Notifier::wait_idle(double timeout_s) const {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                             std::chrono::duration<double>(timeout_s));
  for (const auto& [name, s] : senders_) {
    std::unique_lock<std::mutex> l(s->mutex);
    if (!s->cv.wait_until(l, deadline, [&] { return s->queue.empty(); })) return false;
  }
  return true;
}

}  // namespace rocking_monitor::notify
