// SMTP and HTTP webhook channels over libcurl (channels.hpp).
#include <curl/curl.h>

#include <algorithm>
#include <cstring>
#include <ctime>
#include <mutex>

#include "rocking_monitor/notify/channels.hpp"
#include "rocking_monitor/notify/mail_text.hpp"
#include "rocking_monitor/notify/redact.hpp"
#include "rocking_monitor/safe_text.hpp"

namespace rocking_monitor::notify {
namespace {

void global_init() {
  static std::once_flag once;
  std::call_once(once, [] { curl_global_init(CURL_GLOBAL_DEFAULT); });
}

// The server's first refusal (an SMTP or HTTP reply line starting 4xx or 5xx: "550 5.1.1 <x>: Recipient
// address rejected"), from libcurl's debug stream; what follows it (QUIT's "221 Bye") says nothing.
int on_debug(CURL*, curl_infotype type, char* data, size_t size, void* user) {
  auto* reply = static_cast<std::string*>(user);
  if (type != CURLINFO_HEADER_IN || !reply->empty()) return 0;
  std::string line(data, size);
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
  if (line.rfind("HTTP/", 0) == 0 && line.size() > 9) line = line.substr(line.find(' ') + 1);
  if (!line.empty() && (line[0] == '4' || line[0] == '5')) *reply = line;
  return 0;
}

// Permanent refusals (issue 54): retrying cannot deliver the message. Refused logins (SMTP 530, 534,
// 535, 538; HTTP 401, 403, 407) are the channel's credentials, not the message: they stay temporary,
// so that fixing the configuration delivers every message that waited.
bool smtp_refusal_permanent(const std::string& reply) {
  if (reply.size() < 3 || reply[0] != '5') return false;  // 5xx: permanent negative (RFC 5321 4.2.1)
  const std::string code = reply.substr(0, 3);
  return code != "530" && code != "534" && code != "535" && code != "538";
}
bool http_refusal_permanent(long status) {  // 4xx: the request itself is refused; 408, 429: come back later
  return status >= 400 && status < 500 && status != 408 && status != 429 && status != 401 && status != 403 && status != 407;
}

size_t on_body(char* data, size_t size, size_t n, void* user) {
  auto* body = static_cast<std::string*>(user);
  if (body->size() < 400) body->append(data, std::min<size_t>(size * n, 400 - body->size()));
  return size * n;
}

struct Upload {
  std::string text;
  size_t at = 0;
};
size_t on_read(char* buffer, size_t size, size_t n, void* user) {
  auto* u = static_cast<Upload*>(user);
  const size_t k = std::min(size * n, u->text.size() - u->at);
  std::memcpy(buffer, u->text.data() + u->at, k);
  u->at += k;
  return k;
}

class CurlChannel : public Channel {
 public:
  explicit CurlChannel(const ChannelConfig& c) : config_(c) {
    global_init();
    curl_ = curl_easy_init();
  }
  ~CurlChannel() override { curl_easy_cleanup(curl_); }

 protected:
  // Common settings, reset before each message (the connection itself is kept by the handle).
  void prepare(std::string* reply) {
    permanent_ = false;
    curl_easy_reset(curl_);
    errbuf_[0] = '\0';
    reply->clear();
    curl_easy_setopt(curl_, CURLOPT_URL, config_.url.c_str());
    curl_easy_setopt(curl_, CURLOPT_NOSIGNAL, 1L);
    curl_easy_setopt(curl_, CURLOPT_ERRORBUFFER, errbuf_);
    curl_easy_setopt(curl_, CURLOPT_TIMEOUT_MS, static_cast<long>(config_.timeout * 1000));
    curl_easy_setopt(curl_, CURLOPT_CONNECTTIMEOUT_MS, static_cast<long>(config_.timeout * 1000));
    curl_easy_setopt(curl_, CURLOPT_SSL_VERIFYPEER, config_.verify_tls ? 1L : 0L);
    curl_easy_setopt(curl_, CURLOPT_SSL_VERIFYHOST, config_.verify_tls ? 2L : 0L);
    if (!config_.ca_file.empty()) curl_easy_setopt(curl_, CURLOPT_CAINFO, config_.ca_file.c_str());
    curl_easy_setopt(curl_, CURLOPT_VERBOSE, 1L);  // the debug function keeps the server's last reply
    curl_easy_setopt(curl_, CURLOPT_DEBUGFUNCTION, on_debug);
    curl_easy_setopt(curl_, CURLOPT_DEBUGDATA, reply);
    if (!config_.username.empty()) {
      curl_easy_setopt(curl_, CURLOPT_USERNAME, config_.username.c_str());
      curl_easy_setopt(curl_, CURLOPT_PASSWORD, config_.password.c_str());
    }
  }
  std::string failure(CURLcode rc, const std::string& reply) const {
    std::string e = config_.url + ": " + (errbuf_[0] ? std::string(errbuf_) : curl_easy_strerror(rc));
    if (!reply.empty()) e += " (server: " + reply + ")";
    // The URL may hold a token or user:pass@, the server's text anything: neither reaches a log.
    return printable_text(redact_secrets(e, config_.url, config_.password));
  }
  bool refusal_is_permanent() const override { return permanent_; }
  ChannelConfig config_;
  bool permanent_ = false;  ///< the last failure was a permanent refusal (smtp/http_refusal_permanent)
  CURL* curl_ = nullptr;
  char errbuf_[CURL_ERROR_SIZE] = {};
};

class SmtpChannel : public CurlChannel {
 public:
  using CurlChannel::CurlChannel;
  std::size_t deliver(const std::vector<OutMessage>& batch, std::string* error) override {
    std::size_t done = 0;
    for (const auto& m : batch) {
      std::string reply;
      prepare(&reply);
      Upload up{text(m)};
      const std::string from = "<" + config_.from + ">", to = "<" + m.to + ">";
      curl_slist* rcpt = curl_slist_append(nullptr, to.c_str());
      curl_easy_setopt(curl_, CURLOPT_MAIL_FROM, from.c_str());
      curl_easy_setopt(curl_, CURLOPT_MAIL_RCPT, rcpt);
      curl_easy_setopt(curl_, CURLOPT_READFUNCTION, on_read);
      curl_easy_setopt(curl_, CURLOPT_READDATA, &up);
      curl_easy_setopt(curl_, CURLOPT_UPLOAD, 1L);
      curl_easy_setopt(curl_, CURLOPT_USE_SSL, config_.starttls ? static_cast<long>(CURLUSESSL_ALL) : static_cast<long>(CURLUSESSL_NONE));
      const CURLcode rc = curl_easy_perform(curl_);
      curl_slist_free_all(rcpt);
      if (rc != CURLE_OK) {
        *error = failure(rc, reply);
        permanent_ = smtp_refusal_permanent(reply);
        break;
      }
      ++done;
    }
    return done;
  }

 private:
  std::string text(const OutMessage& m) const {
    char date[64];
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&now, &tm);
    std::strftime(date, sizeof date, "%a, %d %b %Y %H:%M:%S +0000", &tm);
    return mail_text({date, config_.from, m.to, m.subject, m.id, m.recipient, m.body});
  }
};

class WebhookChannel : public CurlChannel {
 public:
  using CurlChannel::CurlChannel;
  std::size_t deliver(const std::vector<OutMessage>& batch, std::string* error) override {
    std::size_t done = 0;
    for (const auto& m : batch) {
      std::string reply, body;
      prepare(&reply);
      curl_slist* headers = curl_slist_append(nullptr, "Content-Type: application/json");
      const std::string key = "Idempotency-Key: " + m.id;
      headers = curl_slist_append(headers, key.c_str());
      headers = curl_slist_append(headers, "Expect:");  // no 100-continue round trip
      curl_easy_setopt(curl_, CURLOPT_HTTPHEADER, headers);
      curl_easy_setopt(curl_, CURLOPT_POST, 1L);
      curl_easy_setopt(curl_, CURLOPT_POSTFIELDS, m.body.c_str());
      curl_easy_setopt(curl_, CURLOPT_POSTFIELDSIZE, static_cast<long>(m.body.size()));
      curl_easy_setopt(curl_, CURLOPT_WRITEFUNCTION, on_body);
      curl_easy_setopt(curl_, CURLOPT_WRITEDATA, &body);
      const CURLcode rc = curl_easy_perform(curl_);
      curl_slist_free_all(headers);
      long status = 0;
      curl_easy_getinfo(curl_, CURLINFO_RESPONSE_CODE, &status);
      if (rc != CURLE_OK) {
        *error = failure(rc, reply);
        break;
      }
      if (status < 200 || status >= 300) {
        permanent_ = http_refusal_permanent(status);
        *error = printable_text(redact_secrets(config_.url + ": HTTP " + std::to_string(status) + (body.empty() ? "" : ": " + body),
                                               config_.url, config_.password));
        break;
      }
      ++done;
    }
    return done;
  }
};

}  // namespace

std::unique_ptr<Channel> make_smtp_channel(const ChannelConfig& config) { return std::make_unique<SmtpChannel>(config); }
std::unique_ptr<Channel> make_webhook_channel(const ChannelConfig& config) { return std::make_unique<WebhookChannel>(config); }

std::unique_ptr<Channel> make_channel(const ChannelConfig& config) {
  switch (config.type) {
    case ChannelType::Smtp: return make_smtp_channel(config);
    case ChannelType::Webhook: return make_webhook_channel(config);
    case ChannelType::Mqtt: return make_mqtt_channel(config);
  }
  return nullptr;
}

}  // namespace rocking_monitor::notify
