#pragma once

// The alarm notifier's core (issue 44; the ROS node src/ros/alarm_notifier.cpp is a shim around it).
//   accept(): an alarm from a monitor. Repeats (a monitor re-sending its journal, the other monitor of a
//             pair) are dropped by monitoring/AlarmDedup, counted; a new one is routed to the recipients
//             that want it and appended to the outbox.
//   tick():   fsyncs the outbox, forms the messages that are due (grouping below), appends them, fsyncs,
//             and only then hands them to the channels' sender threads.
// Grouping: at most one message per recipient per `window`. A COMMITTED or OVERTURNED alarm goes at
// once when the recipient had no message in the last window (lead time matters); everything else waits
// for the window (from the first alarm waiting, or from the last message) and goes in one message.
// A digest recipient gets one message per digest_window. An mqtt recipient gets each alarm at once, as
// retained per-item state (compose_mqtt).
// Each channel has one sender thread: each recipient's messages go in order; a failed delivery is
// retried after a backoff (retry_initial * retry_factor^(n-1), at most retry_max) of that recipient,
// while the other recipients' messages go on; a message is acknowledged in the outbox
// (fsync'd) when the server accepted it, and never sent again. Killed before the ack is on disk, the
// message is sent again after the restart (at least once); its id (Message-ID, Idempotency-Key) is the
// same, so the receiver can tell.

#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "rocking_monitor/monitoring/alarm_dedup.hpp"
#include "rocking_monitor/notify/notify_alarm.hpp"
#include "rocking_monitor/notify/notify_config.hpp"
#include "rocking_monitor/notify/outbox.hpp"

namespace rocking_monitor::notify {

/// Delivers messages to one server. Implementations: channels.hpp (libcurl SMTP and HTTP, libmosquitto).
class Channel {
 public:
  virtual ~Channel() = default;
  /// Delivers `batch` in order; returns how many of its first messages the server acknowledged. Fewer
  /// than all: *error says why, with the server's own reply where there is one.
  virtual std::size_t deliver(const std::vector<OutMessage>& batch, std::string* error) = 0;
  /// Messages per deliver() call (an MQTT broker acknowledges many in flight).
  virtual std::size_t batch_size() const { return 1; }
  /// After a deliver() that stopped short: whether the server refused the first undelivered message
  /// for good (SMTP 5xx, HTTP 4xx other than 408 and 429), so that retrying cannot help (issue 54).
  virtual bool refusal_is_permanent() const { return false; }
};
using ChannelFactory = std::function<std::unique_ptr<Channel>(const ChannelConfig&)>;

/// The wait before retry `attempt` (1, 2, ...), s.
double backoff_delay(const NotifyConfig& config, unsigned attempt);

class Notifier {
 public:
  enum class Accepted { Routed, Unrouted, Repeat, Merged };

  /// Opens and replays the outbox (throws std::runtime_error naming it when it cannot be opened or is
  /// corrupt), makes each channel with `factory` and starts its sender with the unacknowledged messages.
  Notifier(NotifyConfig config, const std::string& outbox_path, const ChannelFactory& factory, double now);
  ~Notifier();
  Notifier(const Notifier&) = delete;
  Notifier& operator=(const Notifier&) = delete;

  Accepted accept(const NotifyAlarm& alarm, double now);
  /// Empty string, or the outbox's write error (nothing is sent that is not on disk).
  std::string tick(double now);
  /// The earliest time a waiting group is due (infinity: none): the node's timer can sleep until then.
  double next_due() const;

  struct ChannelStatus {
    std::string name;
    ChannelType type = ChannelType::Smtp;
    std::size_t queued = 0;          ///< messages not yet acknowledged
    std::uint64_t delivered = 0;     ///< acknowledged since start
    std::uint64_t failures = 0;      ///< failed attempts since start
    std::uint64_t refused = 0;       ///< messages refused for good (marked failed in the outbox, not retried)
    unsigned failing_attempts = 0;   ///< consecutive failed attempts of the recipient failing longest (0: none failing)
    std::string last_error;          ///< the last failure's reason (the server's reply)
  };
  std::vector<ChannelStatus> status() const;
  struct Counts {
    std::uint64_t accepted = 0, unrouted = 0, repeats = 0, merged = 0, messages = 0;
  };
  Counts counts() const;
  /// Start warnings: the outbox's (a cut last line), messages of a channel no longer configured.
  std::vector<std::string> warnings() const {
    auto all = outbox_.warnings();
    all.insert(all.end(), warnings_.begin(), warnings_.end());
    return all;
  }
  /// Waits until every channel's queue is empty (for tests and a clean shutdown); false at timeout.
  bool wait_idle(double timeout_s) const;

 private:
  struct Waiting {
    std::vector<std::uint64_t> alarms;
    double first = std::numeric_limits<double>::quiet_NaN();
    double last_sent = -std::numeric_limits<double>::infinity();
    bool urgent = false;
  };
  struct Sender;
  void route(const OutboxAlarm& a, double now);
  double due_at(const RecipientConfig& r, const Waiting& w) const;
  void sender_loop(Sender& s);
  void acknowledge(Sender& s, const std::vector<std::string>& ids);
  void give_up(Sender& s, const OutMessage& m, const std::string& reason);

  NotifyConfig config_;
  mutable std::mutex outbox_mutex_;   // outbox_, counts_
  Outbox outbox_;
  core::AlarmDedup dedup_;
  std::map<std::uint64_t, std::pair<OutboxAlarm, int>> alarms_;  // waiting for a group: the alarm, in how many
  std::map<std::string, Waiting> waiting_;              // by recipient
  std::map<std::string, int> item_state_;               // mqtt: highest level per item (and channel)
  std::vector<OutboxAlarm> to_route_;                   // accepted since the last tick
  Counts counts_;
  std::vector<std::string> warnings_;
  std::map<std::string, std::unique_ptr<Sender>> senders_;  // by channel
};

}  // namespace rocking_monitor::notify
