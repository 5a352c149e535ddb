#pragma once

// The notifier's durable outbox (issue 44 "never lost, never repeated"): one JSON line per record in a
// file, written with write(2) and fsync'd before anything is sent, as the alarm journal is.
//   alarm: an alarm accepted (not a repeat): its identity (for deduplication after a restart), its
//          fields and the recipients it was routed to
//   msg:   a message formed for one recipient (its text, the alarms it covers); sent until acknowledged
//   ack:   the server acknowledged a message: it is never sent again
//   failed: the server refused a message for good (SMTP 5xx, HTTP 4xx but 408/429): never sent again,
//          its reason kept; like an ack, it lets the outbox compact
// On open the file is replayed: alarms routed to a recipient but in no message go back to the grouper,
// messages without an ack are sent again. Compaction (when everything is acknowledged) rewrites the file
// with the alarms younger than `remember` only (rename over the old file, then fsync of the folder).

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "rocking_monitor/notify/notify_alarm.hpp"

namespace rocking_monitor::notify {

/// One delivery to one recipient: an e-mail, a webhook POST or an MQTT publication.
struct OutMessage {
  std::string id;          ///< unique and stable (outbox ordinal and recipient): Message-ID, Idempotency-Key
  std::string recipient;   ///< RecipientConfig::name
  std::string channel;     ///< ChannelConfig::name
  std::string to;          ///< smtp: the address
  std::string subject;     ///< smtp: Subject
  std::string body;        ///< smtp: plain text; webhook: JSON; mqtt: the payload
  std::string topic;       ///< mqtt: the topic
  bool retain = false;     ///< mqtt
  std::vector<std::uint64_t> alarms;  ///< the outbox numbers of the alarms it covers
  double created = 0.0;    ///< notifier clock, s since 1970, when it was formed
};

/// An accepted alarm in the outbox.
struct OutboxAlarm {
  std::uint64_t number = 0;          ///< 1, 2, ... in the outbox
  NotifyAlarm alarm;
  std::vector<std::string> recipients;  ///< routed to
  double accepted = 0.0;             ///< notifier clock, s since 1970
};

class Outbox {
 public:
  Outbox() = default;
  ~Outbox();
  Outbox(const Outbox&) = delete;
  Outbox& operator=(const Outbox&) = delete;

  /// Opens (creating folders and file) and replays `path`. Empty string on success, else what failed.
  /// A last line cut in the middle (killed while writing) is cut off and counted in warnings().
  std::string open(const std::string& path);
  const std::vector<std::string>& warnings() const { return warnings_; }

  /// A new message id: "<outbox token>.<n>.<recipient>", unique across outboxes (the token is random,
  /// written in the file's first line) and stable across restarts (it is stored with the message).
  std::string new_message_id(const std::string& recipient);
  /// Appends (in memory until sync()). add_alarm numbers the alarm; add_message sets nothing.
  std::uint64_t add_alarm(OutboxAlarm& a);
  void add_message(const OutMessage& m);
  void add_ack(const std::string& message_id);
  /// The message was refused for good: closed as an ack is, with the server's reason on record.
  void add_failed(const std::string& message_id, const std::string& reason);
  /// Messages closed as failed in the file (replayed) and since.
  std::uint64_t failed() const { return failed_; }
  /// Writes what was appended and fsyncs. Empty string on success, else the error.
  std::string sync();

  /// After open(): every alarm in the file (oldest first), the messages not yet acknowledged (in
  /// order), and for each alarm the recipients that already have a message covering it.
  const std::vector<OutboxAlarm>& alarms() const { return alarms_; }
  std::vector<OutMessage> unacknowledged() const;
  bool covered(std::uint64_t alarm, const std::string& recipient) const;
  std::size_t pending() const { return unacked_.size(); }
  std::uint64_t messages_formed() const { return next_message_; }
  /// When the last message to `recipient` was formed (notifier clock; -infinity: never, or before a compaction).
  double last_message(const std::string& recipient) const;

  /// Rewrites the file when nothing is pending and it holds more than `min_alarms` alarm records:
  /// keeps alarms accepted after `now - remember` (so that a monitor re-sending its journal is still
  /// recognised). Empty string on success or when there was nothing to do.
  std::string compact(double now, double remember, std::size_t min_alarms = 1000);

 private:
  std::string replay();
  int fd_ = -1;
  std::string path_;
  std::string pending_;
  std::vector<std::string> warnings_;
  std::vector<OutboxAlarm> alarms_;
  std::map<std::string, OutMessage> unacked_;       // by id
  std::vector<std::string> unacked_order_;          // ids, formation order (acked ones removed lazily)
  std::set<std::pair<std::uint64_t, std::string>> covered_;
  std::uint64_t next_alarm_ = 1;
  std::uint64_t next_message_ = 0;
  std::uint64_t failed_ = 0;
  std::string token_;
  std::map<std::string, double> last_message_;
};

std::string to_json(const NotifyAlarm& a);
}  // namespace rocking_monitor::notify
