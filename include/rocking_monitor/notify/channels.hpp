#pragma once

// The notifier's channels over well-kept libraries (issue 44): e-mail over SMTP and webhooks over HTTP
// with libcurl, MQTT with libmosquitto. Each keeps its connection between messages and reports a failure
// with the server's own reply (e.g. "smtp://mail:25: 550 5.1.1 <x@y>: Recipient address rejected").

#include <memory>

#include "rocking_monitor/notify/notifier.hpp"

namespace rocking_monitor::notify {

/// SMTP (smtp:// with optional STARTTLS, smtps://, optional login): one e-mail per message, its
/// Message-ID the message id.
std::unique_ptr<Channel> make_smtp_channel(const ChannelConfig& config);
/// HTTP POST of the message's JSON body; 2xx is an acknowledgement. Idempotency-Key: the message id.
std::unique_ptr<Channel> make_webhook_channel(const ChannelConfig& config);
/// MQTT publications at QoS 1 or 2 (acknowledged by PUBACK / PUBCOMP), retained as configured.
std::unique_ptr<Channel> make_mqtt_channel(const ChannelConfig& config);
/// The factory the node uses: the channel of the config's type.
std::unique_ptr<Channel> make_channel(const ChannelConfig& config);

}  // namespace rocking_monitor::notify
