#pragma once

// The words of the notifier's messages (issue 44 "readable in a burst"): one e-mail or webhook body for
// a group of alarms of one recipient (which items, which levels, the event, what to do, links), and an
// MQTT recipient's per-item publications.

#include <string>
#include <vector>

#include "rocking_monitor/notify/notify_config.hpp"
#include "rocking_monitor/notify/outbox.hpp"

namespace rocking_monitor::notify {

/// What the operator should do, in plain words, for an item at `level`.
std::string instructions(int level);
/// What the level means for `count` items, in plain words ("has fallen", "have fallen").
std::string meaning(int level, std::size_t count = 1);
/// ISO 8601 UTC with milliseconds, e.g. 1994-01-17T12:30:55.250Z.
std::string iso_utc(double seconds_since_1970);

/// An e-mail (smtp) or a JSON document (webhook) for `alarms` (at least one), routed to `recipient`.
/// Sets subject, body, to, channel, recipient, alarms; not id or created.
OutMessage compose_group(const NotifyConfig& config, const RecipientConfig& recipient,
                         const std::vector<const OutboxAlarm*>& alarms);

/// One MQTT topic level from outside text (an item id): valid UTF-8 (U+FFFD for bad bytes), and '/', '+',
/// '#' and control characters (NUL included) as '_'; empty as "_". Cannot name another topic or be refused.
std::string mqtt_topic_level(const std::string& text);

/// An mqtt recipient's publications for one alarm: <prefix>/<item>/<level> (the alarm as JSON) and
/// <prefix>/<item>/state (the highest level reached, `state_level`), both retained when the channel says so.
/// A probability alarm: <prefix>/<item>/probability/<level> only.
std::vector<OutMessage> compose_mqtt(const ChannelConfig& channel, const RecipientConfig& recipient,
                                     const OutboxAlarm& alarm, int state_level);

}  // namespace rocking_monitor::notify
