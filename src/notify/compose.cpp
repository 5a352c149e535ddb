#include "rocking_monitor/notify/compose.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "rocking_monitor/json_text.hpp"
#include "rocking_monitor/safe_text.hpp"

namespace rocking_monitor::notify {

using nlohmann::json;

std::string meaning(int level, std::size_t count) {
  const bool one = count == 1;
  switch (level) {
    case kBeyondTipping:
      return one ? "rocked past its tipping angle; it may still settle back"
                 : "rocked past their tipping angles; they may still settle back";
    case kCommitted: return "will fall even if the shaking stopped now";
    case kOverturned: return one ? "has fallen" : "have fallen";
  }
  return "reached level " + std::to_string(level);
}

std::string instructions(int level) {
  switch (level) {
    case kBeyondTipping:
      return "Keep people away from its shelf until the shaking stops, then check that it stands firm.";
    case kCommitted:
      return "Do not try to catch it. Keep everyone clear of it and of what it can fall onto; "
             "check it only after the shaking has stopped.";
    case kOverturned:
      return "Keep the area closed until the shaking has stopped and the building is declared safe. "
             "Photograph the item where it lies before anything is moved, then call the curator or conservator.";
  }
  return "Check the dashboard.";
}

std::string iso_utc(double t) {
  if (!std::isfinite(t)) return "unknown time";
  const double whole = std::floor(t);
  const std::time_t s = static_cast<std::time_t>(whole);
  int ms = static_cast<int>(std::lround((t - whole) * 1000.0));
  std::time_t secs = s;
  if (ms >= 1000) { ms -= 1000; ++secs; }
  std::tm tm{};
  gmtime_r(&secs, &tm);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday,
                tm.tm_hour, tm.tm_min, tm.tm_sec, ms);
  return buf;
}

namespace {

const char* const kFellOffText =
    "fell off its support (slid or tipped over the edge of its plinth, shelf or pedestal: look for it on the floor beside "
    "the support)";

double when(const NotifyAlarm& a) {
  return std::isfinite(a.event_time) ? a.event_time : static_cast<double>(a.stamp_ns) * 1e-9;
}

bool notify_fell_off(const NotifyAlarm& a) { return !a.probability && a.cause == core::AlarmCause::FellOffSupport; }

std::string line_of(const NotifyAlarm& a) {
  std::ostringstream s;
  s << "  - " << a.item;
  if (!a.description.empty()) s << " (" << a.description << ")";
  s << " at " << iso_utc(when(a));
  // Overturned either way; falling off a plinth or shelf is a fall from a height, often further away.
  if (notify_fell_off(a)) s << ": " << kFellOffText;
  if (a.probability) {
    char buf[96];
    std::snprintf(buf, sizeof buf, ": probability %.2f >= %.2f over its uncertain parameters", a.probability_value,
                  a.threshold);
    s << buf;
  }
  return s.str();
}

json alarm_doc(const OutboxAlarm& o) {
  const NotifyAlarm& a = o.alarm;
  json j{{"item", a.item}, {"description", a.description}, {"level", level_name(a.level)}, {"time", iso_utc(when(a))},
         {"event_id", a.event_id}, {"sequence", a.sequence}, {"monitor", a.source},
         {"kind", a.probability ? "probability" : "alarm"}};
  if (!a.probability) j["cause"] = core::to_string(a.cause);  // "rocking" or "fell_off_support"
  if (a.probability) {
    j["probability"] = std::isfinite(a.probability_value) ? json(a.probability_value) : json(nullptr);
    j["threshold"] = std::isfinite(a.threshold) ? json(a.threshold) : json(nullptr);
  }
  return j;
}

}  // namespace

OutMessage compose_group(const NotifyConfig& config, const RecipientConfig& recipient,
                         const std::vector<const OutboxAlarm*>& alarms) {
  const ChannelConfig& channel = config.channel_of(recipient);
  // Highest level first: what needs doing most comes first in a long message.
  std::map<int, std::vector<const OutboxAlarm*>, std::greater<int>> by_level;
  std::set<std::string> events;
  double first = INFINITY;
  for (const auto* a : alarms) {
    by_level[a->alarm.level].push_back(a);
    if (!a->alarm.event_id.empty()) events.insert(a->alarm.event_id);
    first = std::min(first, when(a->alarm));
  }
  for (auto& [level, list] : by_level)
    std::stable_sort(list.begin(), list.end(), [](auto* x, auto* y) { return when(x->alarm) < when(y->alarm); });

  std::ostringstream subject;
  subject << "[" << config.site << "] ";
  bool comma = false;
  for (const auto& [level, list] : by_level) {
    subject << (comma ? ", " : "") << list.size() << (list.size() == 1 ? " item " : " items ") << level_name(level);
    comma = true;
  }
  if (alarms.size() == 1)
    subject << ": " << alarms.front()->alarm.item << (notify_fell_off(alarms.front()->alarm) ? " (fell off its support)" : "");

  std::string events_text;
  for (const auto& e : events) events_text += (events_text.empty() ? "" : ", ") + e;
  std::ostringstream body;
  body << "Rocking monitor alarm for " << recipient.name << " at " << config.site << ".\n"
       << "Event " << (events_text.empty() ? "(no journal id)" : events_text) << ", first alarm of this message at "
       << iso_utc(first) << " (sensor time).\n";
  for (const auto& [level, list] : by_level) {
    body << "\n" << level_name(level) << ": " << list.size() << (list.size() == 1 ? " item " : " items ") << meaning(level, list.size())
         << ".\nWhat to do: " << instructions(level) << "\n";
    const std::size_t shown = std::min(list.size(), config.max_items_listed);
    for (std::size_t i = 0; i < shown; ++i) body << line_of(list[i]->alarm) << "\n";
    if (list.size() > shown) body << "  ... and " << list.size() - shown << " more (every item is on the dashboard)\n";
  }
  if (!config.dashboard_url.empty()) body << "\nDashboard: " << config.dashboard_url << "\n";
  if (!config.report_url.empty()) body << "Post-event report (written when the shaking has stopped): " << config.report_url << "\n";
  body << "\n-- \nSent by the rocking_monitor alarm notifier. Each alarm is in one message only; a message "
          "received twice has the same Message-ID.\n";

  OutMessage m;
  m.recipient = recipient.name;
  m.channel = channel.name;
  m.to = recipient.to;
  m.subject = subject.str();
  if (channel.type == ChannelType::Webhook) {
    json doc{{"site", config.site}, {"recipient", recipient.name}, {"subject", m.subject}, {"text", body.str()},
             {"events", std::vector<std::string>(events.begin(), events.end())}, {"dashboard_url", config.dashboard_url},
             {"report_url", config.report_url}};
    json counts = json::object(), what = json::object(), list = json::array();
    for (const auto& [level, l] : by_level) {
      counts[level_name(level)] = l.size();
      what[level_name(level)] = instructions(level);
      for (const auto* a : l) list.push_back(alarm_doc(*a));
    }
    doc["counts"] = counts;
    doc["instructions"] = what;
    doc["alarms"] = list;
    m.body = json_text(doc);
  } else {
    m.body = body.str();
  }
  for (const auto* a : alarms) m.alarms.push_back(a->number);
  return m;
}

std::string mqtt_topic_level(const std::string& text) {
  // An alarm from a topic may carry any bytes (a catalogue's ids are names, issue 54). A topic
  // separator or wildcard would name other topics, NUL and invalid UTF-8 make the broker refuse the
  // publication (MQTT 3.1.1 section 4.7.3: every retry refused too), other control characters
  // garble a subscriber's display: each becomes '_'. Invalid UTF-8 first becomes U+FFFD.
  std::string level = valid_utf8(text);
  std::replace_if(level.begin(), level.end(), [](char ch) {
    const auto c = static_cast<unsigned char>(ch);
    return ch == '/' || ch == '+' || ch == '#' || c < 0x20 || c == 0x7F;
  }, '_');
  return level.empty() ? "_" : level;  // "prefix//COMMITTED" would be a level nobody subscribes to by name
}

std::vector<OutMessage> compose_mqtt(const ChannelConfig& channel, const RecipientConfig& recipient,
                                     const OutboxAlarm& alarm, int state_level) {
  const std::string base = channel.topic_prefix + "/" + mqtt_topic_level(alarm.alarm.item) + "/";
  OutMessage level;
  level.recipient = recipient.name;
  level.channel = channel.name;
  level.retain = channel.retain;
  level.alarms = {alarm.number};
  json doc = alarm_doc(alarm);
  doc["what_to_do"] = instructions(alarm.alarm.level);
  level.topic = base + (alarm.alarm.probability ? "probability/" : "") + level_name(alarm.alarm.level);
  level.body = json_text(doc);
  if (alarm.alarm.probability) return {level};  // a share of an ensemble is not the item's state
  OutMessage state = level;
  state.topic = base + "state";
  state.body = level_name(state_level);
  return {level, state};
}

}  // namespace rocking_monitor::notify
