#include "rocking_monitor/notify/notify_config.hpp"

#include <fnmatch.h>
#include <netdb.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "rocking_monitor/notify/notify_alarm.hpp"
#include "rocking_monitor/notify/redact.hpp"
#include "rocking_monitor/private_files.hpp"

namespace rocking_monitor::notify {

const char* to_string(ChannelType type) {
  switch (type) {
    case ChannelType::Smtp: return "smtp";
    case ChannelType::Webhook: return "webhook";
    case ChannelType::Mqtt: return "mqtt";
  }
  return "?";
}

bool RecipientConfig::wants(const std::string& item, int level, bool probability_alarm) const {
  if (probability_alarm && !probability) return false;
  if (!levels.empty() && std::find(levels.begin(), levels.end(), level) == levels.end()) return false;
  if (items.empty()) return true;
  for (const auto& pattern : items)
    if (fnmatch(pattern.c_str(), item.c_str(), 0) == 0) return true;
  return false;
}

namespace {

// Every error names the file, the line of the node and the field's path.
struct Ctx {
  const std::string& file;
  [[noreturn]] void fail(const YAML::Node& node, const std::string& field, const std::string& what) const {
    std::string where = file;
    if (node.IsDefined() && node.Mark().line >= 0) where += ":" + std::to_string(node.Mark().line + 1);
    throw NotifyConfigError(where + ": " + field + ": " + what);
  }
  void known_keys(const YAML::Node& map, const std::string& field, const std::set<std::string>& known) const {
    if (!map.IsMap()) fail(map, field, "must be a mapping (key: value)");
    for (const auto& kv : map) {
      const auto key = kv.first.as<std::string>();
      if (known.count(key)) continue;
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      fail(kv.first, field.empty() ? key : field + "." + key, "unknown key (known: " + list + ")");
    }
  }
  template <class T>
  T get(const YAML::Node& map, const std::string& key, const std::string& field, T fallback) const {
    const YAML::Node n = map[key];
    if (!n.IsDefined() || n.IsNull()) return fallback;
    try {
      if (!n.IsScalar()) throw YAML::Exception(n.Mark(), "not a scalar");
      return n.as<T>();
    } catch (const YAML::Exception&) {
      fail(n, field, std::string("not a ") + kind<T>() + ": '" + (n.IsScalar() ? n.Scalar() : "(not a scalar)") + "'");
    }
  }
  double positive(const YAML::Node& map, const std::string& key, const std::string& field, double fallback) const {
    const double v = get<double>(map, key, field, fallback);
    if (!(v > 0.0) || !std::isfinite(v)) fail(map[key], field, "must be a positive number of seconds, got " + std::to_string(v));
    return v;
  }
  template <class T>
  static const char* kind() {
    if constexpr (std::is_same_v<T, bool>) return "boolean (true/false)";
    else if constexpr (std::is_same_v<T, int>) return "whole number";
    else if constexpr (std::is_same_v<T, double>) return "number";
    else return "string";
  }
};

bool valid_address(const std::string& a) {
  static const std::regex re(R"(^[^@\s<>,;"]+@[A-Za-z0-9]([A-Za-z0-9.-]*[A-Za-z0-9])?$)");
  return std::regex_match(a, re);
}

// A relative path in the configuration is relative to the configuration file's folder.
std::string beside(const std::string& config_file, const std::string& path) {
  if (path.empty() || path[0] == '/') return path;
  const auto slash = config_file.rfind('/');
  return slash == std::string::npos ? path : config_file.substr(0, slash + 1) + path;
}

// The channel's password (issue 52 item 5): from `password_file` (mode 0600 or stricter, one line),
// `password_env` (an environment variable's value) or, said at every start, `password` inline;
// at most one of them.
void parse_password(const Ctx& c, const YAML::Node& n, const std::string& f, ChannelConfig& ch,
                    std::vector<std::string>& warnings) {
  const char* keys[] = {"password", "password_file", "password_env"};
  std::string given;
  for (const char* k : keys)
    if (n[k].IsDefined()) {
      if (!given.empty()) c.fail(n[k], f + "." + k, std::string("give one of password, password_file, password_env, not ") + given + " too");
      given = k;
    }
  if (given == "password") {
    ch.password = c.get<std::string>(n, "password", f + ".password", "");
    warnings.push_back(c.file + ": " + f + ".password: inline in the configuration: prefer password_file (mode 0600) or password_env");
  } else if (given == "password_file") {
    const std::string path = beside(c.file, c.get<std::string>(n, "password_file", f + ".password_file", ""));
    std::string text, error;
    if (!read_private_file(path, "password file", 4096, text, error)) c.fail(n["password_file"], f + ".password_file", error);
    if (!text.empty() && text.back() == '\n') text.pop_back();  // the one line's end, as an editor writes it
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.empty()) c.fail(n["password_file"], f + ".password_file", "password file '" + path + "' is empty");
    if (text.find_first_of("\r\n") != std::string::npos)
      c.fail(n["password_file"], f + ".password_file", "password file '" + path + "' has more than one line");
    ch.password = text;
  } else if (given == "password_env") {
    const std::string var = c.get<std::string>(n, "password_env", f + ".password_env", "");
    const char* value = var.empty() ? nullptr : std::getenv(var.c_str());
    if (value == nullptr || *value == '\0')
      c.fail(n["password_env"], f + ".password_env", "environment variable '" + var + "' is not set or empty");
    ch.password = value;
  }
}

// TLS settings of an smtp or webhook channel, or an mqtt one with tls: true: ca_file must be readable now (not at the first alarm);
// verify_tls false is said at every start.
void parse_tls(const Ctx& c, const YAML::Node& n, const std::string& f, ChannelConfig& ch,
               std::vector<std::string>& warnings) {
  ch.verify_tls = c.get<bool>(n, "verify_tls", f + ".verify_tls", true);
  ch.ca_file = beside(c.file, c.get<std::string>(n, "ca_file", f + ".ca_file", ""));
  if (!ch.ca_file.empty() && !std::ifstream(ch.ca_file))
    c.fail(n["ca_file"], f + ".ca_file", "cannot read '" + ch.ca_file + "'");
  if (!ch.verify_tls)
    warnings.push_back(c.file + ": " + f + ".verify_tls: false: the server's certificate is not checked, so anyone "
                       "between here and the server can read and change the alarms");
}

std::string url_scheme(const std::string& url) {
  const auto pos = url.find("://");
  return pos == std::string::npos ? std::string() : url.substr(0, pos);
}

ChannelConfig parse_channel(const Ctx& c, const std::string& name, const YAML::Node& n, std::vector<std::string>& warnings) {
  const std::string f = "channels." + name;
  ChannelConfig ch;
  ch.name = name;
  if (!n.IsMap()) c.fail(n, f, "must be a mapping with a type (smtp, webhook or mqtt)");
  const std::string type = c.get<std::string>(n, "type", f + ".type", "");
  if (type == "smtp") {
    ch.type = ChannelType::Smtp;
    c.known_keys(n, f, {"type", "url", "from", "starttls", "username", "password", "password_file", "password_env",
                        "verify_tls", "ca_file", "timeout"});
  } else if (type == "webhook") {
    ch.type = ChannelType::Webhook;
    c.known_keys(n, f, {"type", "url", "verify_tls", "ca_file", "timeout"});
  } else if (type == "mqtt") {
    ch.type = ChannelType::Mqtt;
    c.known_keys(n, f, {"type", "host", "port", "topic_prefix", "client_id", "qos", "retain", "username", "password",
                        "password_file", "password_env", "timeout", "tls", "verify_tls", "ca_file"});
  } else {
    c.fail(n["type"].IsDefined() ? n["type"] : n, f + ".type",
           type.empty() ? "missing (smtp, webhook or mqtt)" : "unknown channel type '" + type + "' (smtp, webhook or mqtt)");
  }
  ch.timeout = c.positive(n, "timeout", f + ".timeout", ch.timeout);
  ch.username = c.get<std::string>(n, "username", f + ".username", "");
  parse_password(c, n, f, ch, warnings);
  if (ch.type == ChannelType::Mqtt) {
    // MQTT is plain unless tls: true; a CA or verify_tls without it would look checked and not be.
    ch.tls = c.get<bool>(n, "tls", f + ".tls", false);
    for (const char* k : {"verify_tls", "ca_file"})
      if (!ch.tls && n[k].IsDefined()) c.fail(n[k], f + "." + k, "only with tls: true (this channel is plain MQTT)");
  }
  if (ch.type != ChannelType::Mqtt || ch.tls) parse_tls(c, n, f, ch, warnings);
  if (ch.type == ChannelType::Smtp || ch.type == ChannelType::Webhook) {
    ch.url = c.get<std::string>(n, "url", f + ".url", "");
    const std::string scheme = url_scheme(ch.url);
    const bool ok = ch.type == ChannelType::Smtp ? (scheme == "smtp" || scheme == "smtps")
                                                 : (scheme == "http" || scheme == "https");
    if (!ok || channel_host(ch).empty())
      c.fail(n["url"], f + ".url",
             (ch.url.empty() ? std::string("missing") : "bad URL '" + redact_url(ch.url) + "'") +
                 (ch.type == ChannelType::Smtp ? " (smtp://host:port or smtps://host:port)" : " (http://host:port/path or https://...)"));
  }
  if (ch.type == ChannelType::Smtp) {
    ch.from = c.get<std::string>(n, "from", f + ".from", "");
    if (!valid_address(ch.from))
      c.fail(n["from"], f + ".from", ch.from.empty() ? "missing (the sender's e-mail address)" : "bad e-mail address '" + ch.from + "'");
    ch.starttls = c.get<bool>(n, "starttls", f + ".starttls", false);
  }
  if (ch.type == ChannelType::Mqtt) {
    ch.host = c.get<std::string>(n, "host", f + ".host", "");
    if (ch.host.empty() || ch.host.find_first_of(" /:") != std::string::npos)
      c.fail(n["host"], f + ".host", ch.host.empty() ? "missing (the broker's host name or address)" : "bad host '" + ch.host + "'");
    ch.port = c.get<int>(n, "port", f + ".port", ch.tls ? 8883 : 1883);
    if (ch.port < 1 || ch.port > 65535) c.fail(n["port"], f + ".port", "must be 1..65535, got " + std::to_string(ch.port));
    ch.topic_prefix = c.get<std::string>(n, "topic_prefix", f + ".topic_prefix", ch.topic_prefix);
    if (ch.topic_prefix.empty() || ch.topic_prefix.find_first_of("+#") != std::string::npos || ch.topic_prefix.back() == '/')
      c.fail(n["topic_prefix"], f + ".topic_prefix", "must be a topic without + # or a trailing /, got '" + ch.topic_prefix + "'");
    ch.client_id = c.get<std::string>(n, "client_id", f + ".client_id", ch.client_id);
    ch.qos = c.get<int>(n, "qos", f + ".qos", 1);
    if (ch.qos != 1 && ch.qos != 2)
      c.fail(n["qos"], f + ".qos", "must be 1 or 2 (QoS 0 is never acknowledged, so never known delivered), got " + std::to_string(ch.qos));
    ch.retain = c.get<bool>(n, "retain", f + ".retain", true);
  }
  return ch;
}

RecipientConfig parse_recipient(const Ctx& c, const NotifyConfig& cfg, std::size_t i, const YAML::Node& n) {
  const std::string f = "recipients[" + std::to_string(i) + "]";
  c.known_keys(n, f, {"name", "channel", "to", "items", "levels", "probability", "digest", "digest_window"});
  RecipientConfig r;
  r.name = c.get<std::string>(n, "name", f + ".name", "");
  if (r.name.empty() || r.name.find_first_of(" \t\n\"") != std::string::npos)
    c.fail(n["name"].IsDefined() ? n["name"] : n, f + ".name", r.name.empty() ? "missing" : "must have no spaces or quotes: '" + r.name + "'");
  r.channel = c.get<std::string>(n, "channel", f + ".channel", "");
  auto ch = cfg.channels.find(r.channel);
  if (ch == cfg.channels.end()) {
    std::string defined;
    for (const auto& [name, unused] : cfg.channels) defined += (defined.empty() ? "" : ", ") + name;
    c.fail(n["channel"].IsDefined() ? n["channel"] : n, f + ".channel",
           (r.channel.empty() ? std::string("missing") : "unknown channel '" + r.channel + "'") + " (defined: " +
               (defined.empty() ? "none" : defined) + ")");
  }
  r.to = c.get<std::string>(n, "to", f + ".to", "");
  if (ch->second.type == ChannelType::Smtp && !valid_address(r.to))
    c.fail(n["to"].IsDefined() ? n["to"] : n, f + ".to", r.to.empty() ? "missing (an e-mail address)" : "bad e-mail address '" + r.to + "'");
  if (ch->second.type != ChannelType::Smtp && !r.to.empty())
    c.fail(n["to"], f + ".to", "only for an smtp channel ('" + r.channel + "' is " + to_string(ch->second.type) + ")");
  if (const YAML::Node items = n["items"]; items.IsDefined() && !items.IsNull()) {
    if (!items.IsSequence()) c.fail(items, f + ".items", "must be a list of item ids or patterns, e.g. [ming_vase, 'amphora_*']");
    for (std::size_t k = 0; k < items.size(); ++k) {
      if (!items[k].IsScalar() || items[k].Scalar().empty()) c.fail(items[k], f + ".items[" + std::to_string(k) + "]", "must be an item id or pattern");
      r.items.push_back(items[k].Scalar());
    }
  }
  if (const YAML::Node levels = n["levels"]; levels.IsDefined() && !levels.IsNull()) {
    if (!levels.IsSequence()) c.fail(levels, f + ".levels", "must be a list, e.g. [COMMITTED, OVERTURNED]");
    for (std::size_t k = 0; k < levels.size(); ++k) {
      const int code = levels[k].IsScalar() ? level_code(levels[k].Scalar()) : 0;
      if (code == 0)
        c.fail(levels[k], f + ".levels[" + std::to_string(k) + "]",
               "unknown level '" + (levels[k].IsScalar() ? levels[k].Scalar() : std::string("?")) + "' (BEYOND_TIPPING, COMMITTED, OVERTURNED)");
      r.levels.push_back(code);
    }
  }
  r.probability = c.get<bool>(n, "probability", f + ".probability", true);
  r.digest = c.get<bool>(n, "digest", f + ".digest", false);
  r.digest_window = c.positive(n, "digest_window", f + ".digest_window", r.digest_window);
  if (ch->second.type == ChannelType::Mqtt && r.digest)
    c.fail(n["digest"], f + ".digest", "an mqtt recipient gets each item's state, not digests");
  return r;
}

}  // namespace

NotifyConfig parse_notify_config(const std::string& yaml, const std::string& file) {
  Ctx c{file};
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw NotifyConfigError(file + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
  // The notifier's own section may stand alone or under `notify:` (one file with other parameters).
  if (root.IsMap() && root["notify"].IsDefined()) root = root["notify"];
  if (!root.IsMap()) throw NotifyConfigError(file + ": must be a mapping with channels: and recipients:");
  c.known_keys(root, "", {"site", "dashboard_url", "report_url", "window", "retry", "remember", "max_items_listed", "channels", "recipients"});
  NotifyConfig cfg;
  cfg.file = file;
  cfg.site = c.get<std::string>(root, "site", "site", cfg.site);
  cfg.dashboard_url = c.get<std::string>(root, "dashboard_url", "dashboard_url", "");
  cfg.report_url = c.get<std::string>(root, "report_url", "report_url", "");
  cfg.window = c.positive(root, "window", "window", cfg.window);
  cfg.remember = c.positive(root, "remember", "remember", cfg.remember);
  const int listed = c.get<int>(root, "max_items_listed", "max_items_listed", 50);
  if (listed < 1) c.fail(root["max_items_listed"], "max_items_listed", "must be at least 1");
  cfg.max_items_listed = static_cast<std::size_t>(listed);
  if (const YAML::Node retry = root["retry"]; retry.IsDefined()) {
    c.known_keys(retry, "retry", {"initial", "factor", "max"});
    cfg.retry_initial = c.positive(retry, "initial", "retry.initial", cfg.retry_initial);
    cfg.retry_factor = c.get<double>(retry, "factor", "retry.factor", cfg.retry_factor);
    if (!(cfg.retry_factor >= 1.0)) c.fail(retry["factor"], "retry.factor", "must be >= 1");
    cfg.retry_max = c.positive(retry, "max", "retry.max", cfg.retry_max);
    if (cfg.retry_max < cfg.retry_initial) c.fail(retry["max"], "retry.max", "must be >= retry.initial");
  }
  const YAML::Node channels = root["channels"];
  if (!channels.IsDefined() || !channels.IsMap() || channels.size() == 0)
    c.fail(channels.IsDefined() ? channels : root, "channels", "missing or empty: name at least one channel (type smtp, webhook or mqtt)");
  for (const auto& kv : channels) {
    const auto name = kv.first.as<std::string>();
    cfg.channels.emplace(name, parse_channel(c, name, kv.second, cfg.warnings));
  }
  const YAML::Node recipients = root["recipients"];
  if (!recipients.IsDefined() || !recipients.IsSequence() || recipients.size() == 0)
    c.fail(recipients.IsDefined() ? recipients : root, "recipients", "missing or empty: a list of recipients (name, channel, ...)");
  std::set<std::string> names;
  for (std::size_t i = 0; i < recipients.size(); ++i) {
    cfg.recipients.push_back(parse_recipient(c, cfg, i, recipients[i]));
    if (!names.insert(cfg.recipients.back().name).second)
      c.fail(recipients[i]["name"], "recipients[" + std::to_string(i) + "].name", "'" + cfg.recipients.back().name + "' is used twice");
  }
  return cfg;
}

NotifyConfig load_notify_config(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw NotifyConfigError(path + ": cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  return parse_notify_config(text.str(), path);
}

std::string channel_host(const ChannelConfig& c) {
  if (c.type == ChannelType::Mqtt) return c.host;
  const auto start = c.url.find("://");
  if (start == std::string::npos) return "";
  std::string rest = c.url.substr(start + 3);
  rest = rest.substr(0, rest.find('/'));
  if (const auto at = rest.rfind('@'); at != std::string::npos) rest = rest.substr(at + 1);
  if (!rest.empty() && rest[0] == '[') return rest.substr(1, rest.find(']') - 1);
  return rest.substr(0, rest.find(':'));
}

void check_hosts(const NotifyConfig& config) {
  for (const auto& [name, ch] : config.channels) {
    const std::string host = channel_host(ch);
    addrinfo* found = nullptr;
    const int rc = getaddrinfo(host.c_str(), nullptr, nullptr, &found);
    if (found) freeaddrinfo(found);
    if (rc != 0)
      throw NotifyConfigError(config.file + ": channels." + name + (ch.type == ChannelType::Mqtt ? ".host" : ".url") +
                              ": host '" + host + "' not found: " + gai_strerror(rc));
  }
}

}  // namespace rocking_monitor::notify
