#pragma once

// The notifier's routing configuration (issue 44, config/notify.yaml, docs/notify.md): which channels
// (SMTP e-mail, HTTP webhook, MQTT) exist and which recipients get which items and levels through them.
// Parsed from YAML (yaml-cpp); a bad value throws NotifyConfigError naming the file, line and field,
// e.g. "notify.yaml:14: recipients[1].channel: unknown channel 'mial' (defined: mail, chat)".

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace rocking_monitor::notify {

struct NotifyConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

enum class ChannelType { Smtp, Webhook, Mqtt };
const char* to_string(ChannelType type);

struct ChannelConfig {
  std::string name;             ///< its key under `channels:`
  ChannelType type = ChannelType::Smtp;
  // smtp and webhook
  std::string url;              ///< smtp://host:port, smtps://host:port; http(s)://host:port/path
  double timeout = 10.0;        ///< s for one delivery attempt (connect + transfer)
  // smtp
  std::string from;             ///< envelope and From: address
  bool starttls = false;        ///< require STARTTLS (smtp://); smtps:// is TLS from the start
  std::string username, password;  ///< SMTP AUTH LOGIN/PLAIN (empty: none); MQTT username/password
                                   ///< (from `password`, `password_file` or `password_env`)
  bool verify_tls = true;       ///< check the server's certificate
  std::string ca_file;          ///< PEM certificates to check the server's against (empty: the system's)
  // mqtt
  std::string host;
  int port = 1883;              ///< 8883 with tls (MQTT's TLS port)
  bool tls = false;             ///< MQTT over TLS (verify_tls and ca_file as for smtp and webhook)
  std::string topic_prefix = "rocking_monitor";
  std::string client_id = "rocking_monitor_notifier";
  int qos = 1;                  ///< 1 or 2 (0 would not be acknowledged, so never known delivered)
  bool retain = true;           ///< per-item topics are retained state
};

struct RecipientConfig {
  std::string name;                 ///< unique; names the recipient in the outbox and in diagnostics
  std::string channel;              ///< a key of `channels:`
  std::string to;                   ///< smtp: the e-mail address (required); others: unused
  std::vector<std::string> items;   ///< item id patterns (fnmatch: vase_*, *); empty: every item
  std::vector<int> levels;          ///< level codes; empty: every level
  bool probability = true;          ///< also the monitor's probability alarms
  bool digest = false;              ///< no message at once: one message per digest window
  double digest_window = 60.0;      ///< s, with digest: true
  bool wants(const std::string& item, int level, bool probability_alarm) const;
};

struct NotifyConfig {
  std::string file;                 ///< where it was read from (for messages)
  std::string site = "rocking monitor";  ///< names the installation in subjects ("[Museum store] ...")
  std::string dashboard_url;        ///< linked from every message (empty: none)
  std::string report_url;           ///< the post-event report (empty: none)
  double window = 10.0;             ///< s: at most one message per recipient per window
  double retry_initial = 0.5;       ///< s: first retry after a failed delivery
  double retry_factor = 2.0;        ///< each further retry waits this much longer ...
  double retry_max = 30.0;          ///< ... up to this, s
  double remember = 86400.0;        ///< s: alarms kept in the outbox for deduplication (> the monitor's journal_window)
  std::size_t max_items_listed = 50;  ///< per level in one message; the rest are counted ("and 120 more")
  std::map<std::string, ChannelConfig> channels;
  std::vector<RecipientConfig> recipients;
  /// Said at every start, not refused (issue 52 item 5): verify_tls false, a password inline.
  std::vector<std::string> warnings;
  const ChannelConfig& channel_of(const RecipientConfig& r) const { return channels.at(r.channel); }
};

/// Parses YAML text; `file` names it in errors. Throws NotifyConfigError.
NotifyConfig parse_notify_config(const std::string& yaml, const std::string& file = "<notify config>");
/// Reads and parses a file. Throws NotifyConfigError (also when it cannot be read).
NotifyConfig load_notify_config(const std::string& path);
/// Resolves every channel's host name (getaddrinfo). Throws NotifyConfigError naming the field
/// (channels.mail.url: host 'x' not found: ...). A host that resolves but refuses connections is a
/// server that is down, not a configuration error: its messages wait in the outbox.
void check_hosts(const NotifyConfig& config);
/// The host of a channel (from url or host).
std::string channel_host(const ChannelConfig& c);

}  // namespace rocking_monitor::notify
