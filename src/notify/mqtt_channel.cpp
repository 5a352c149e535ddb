// The MQTT channel over libmosquitto (channels.hpp): publications at QoS 1 or 2, many in flight, each
// acknowledged by the broker (PUBACK / PUBCOMP). A lost connection is a new client on the next attempt,
// so the library never re-sends on its own what the outbox will send again.
#include <mosquitto.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <map>
#include <mutex>

#include "rocking_monitor/notify/channels.hpp"

namespace rocking_monitor::notify {
namespace {

class MqttChannel : public Channel {
 public:
  explicit MqttChannel(const ChannelConfig& c) : config_(c) {
    static std::once_flag once;
    std::call_once(once, [] { mosquitto_lib_init(); });
  }
  ~MqttChannel() override { drop(); }
  std::size_t batch_size() const override { return 200; }

  std::size_t deliver(const std::vector<OutMessage>& batch, std::string* error) override {
    const std::string where = std::string(config_.tls ? "mqtts://" : "mqtt://") + config_.host + ":" + std::to_string(config_.port);
    if (!mosq_ && !connect(error)) {
      *error = where + ": " + *error;
      return 0;
    }
    acked_.clear();
    std::map<int, std::size_t> index;  // mid -> position in batch
    for (std::size_t i = 0; i < batch.size(); ++i) {
      int mid = 0;
      const auto& m = batch[i];
      const int rc = mosquitto_publish(mosq_, &mid, m.topic.c_str(), static_cast<int>(m.body.size()), m.body.data(),
                                       config_.qos, m.retain);
      if (rc != MOSQ_ERR_SUCCESS) {
        *error = where + ": publish " + m.topic + ": " + mosquitto_strerror(rc);
        break;
      }
      index[mid] = i;
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(config_.timeout);
    while (acked_.size() < index.size()) {
      const int rc = mosquitto_loop(mosq_, 50, 1);
      if (rc != MOSQ_ERR_SUCCESS) {
        *error = where + ": " + (rc == MOSQ_ERR_ERRNO ? std::string("connection: ") + std::strerror(errno) : mosquitto_strerror(rc));
        break;
      }
      if (std::chrono::steady_clock::now() > deadline) {
        *error = where + ": no acknowledgement within " + std::to_string(config_.timeout) + " s";
        break;
      }
    }
    // The acknowledged prefix (the broker acknowledges in order; a gap ends it).
    std::size_t done = 0;
    std::vector<bool> ok(batch.size(), false);
    for (int mid : acked_)
      if (auto it = index.find(mid); it != index.end()) ok[it->second] = true;
    while (done < batch.size() && ok[done]) ++done;
    if (done < batch.size()) {
      if (error->empty()) *error = where + ": not acknowledged";
      drop();
    }
    return done;
  }

 private:
  bool connect(std::string* error) {
    mosq_ = mosquitto_new(config_.client_id.c_str(), true, this);
    if (!mosq_) {
      *error = "mosquitto_new failed";
      return false;
    }
    mosquitto_int_option(mosq_, MOSQ_OPT_PROTOCOL_VERSION, MQTT_PROTOCOL_V311);
    if (config_.tls && !set_tls(error)) {
      drop();
      return false;
    }
    if (!config_.username.empty())
      mosquitto_username_pw_set(mosq_, config_.username.c_str(), config_.password.empty() ? nullptr : config_.password.c_str());
    mosquitto_connect_callback_set(mosq_, [](mosquitto*, void* self, int rc) {
      auto* me = static_cast<MqttChannel*>(self);
      me->connack_ = true;
      me->connack_rc_ = rc;
    });
    mosquitto_publish_callback_set(mosq_, [](mosquitto*, void* self, int mid) { static_cast<MqttChannel*>(self)->acked_.push_back(mid); });
    connack_ = false;
    library_errors_.clear();
    int rc = mosquitto_connect(mosq_, config_.host.c_str(), config_.port, 30);
    if (rc != MOSQ_ERR_SUCCESS) {
      *error = std::string("connect: ") + (rc == MOSQ_ERR_ERRNO ? std::strerror(errno) : mosquitto_strerror(rc)) +
               library_errors_;
      drop();
      return false;
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(config_.timeout);
    while (!connack_) {
      rc = mosquitto_loop(mosq_, 50, 1);
      if (rc != MOSQ_ERR_SUCCESS || std::chrono::steady_clock::now() > deadline) {
        *error = std::string("connect: ") + (rc != MOSQ_ERR_SUCCESS ? mosquitto_strerror(rc) : "no CONNACK in time") +
                 library_errors_;
        drop();
        return false;
      }
    }
    if (connack_rc_ != 0) {
      *error = std::string("broker refused the connection: ") + mosquitto_connack_string(connack_rc_);
      drop();
      return false;
    }
    return true;
  }
  // TLS as the smtp and webhook channels have it: the server's certificate checked against ca_file or the
  // system's CAs, and its name against host, unless verify_tls is false. libmosquitto reports a failed
  // handshake as "A TLS error occurred." and logs OpenSSL's reason, so its error log is kept for the
  // error text ("certificate verify failed").
  bool set_tls(std::string* error) {
    int rc = MOSQ_ERR_SUCCESS;
    if (!config_.ca_file.empty()) rc = mosquitto_tls_set(mosq_, config_.ca_file.c_str(), nullptr, nullptr, nullptr, nullptr);
    else rc = mosquitto_int_option(mosq_, MOSQ_OPT_TLS_USE_OS_CERTS, 1);
    if (rc == MOSQ_ERR_SUCCESS) rc = mosquitto_tls_opts_set(mosq_, config_.verify_tls ? 1 : 0, nullptr, nullptr);  // SSL_VERIFY_PEER or NONE
    if (rc == MOSQ_ERR_SUCCESS) rc = mosquitto_tls_insecure_set(mosq_, !config_.verify_tls);  // the host name check
    if (rc != MOSQ_ERR_SUCCESS) {
      *error = std::string("TLS setup: ") + mosquitto_strerror(rc) +
               (config_.ca_file.empty() ? "" : " (ca_file '" + config_.ca_file + "')");
      return false;
    }
    mosquitto_log_callback_set(mosq_, [](mosquitto*, void* self, int level, const char* text) {
      if (level != MOSQ_LOG_ERR) return;
      auto* me = static_cast<MqttChannel*>(self);
      me->library_errors_ += std::string(": ") + text;
      // OpenSSL's reason names no certificate: say which check it was (the SSL object is gone by now).
      if (std::strstr(text, "certificate verify failed"))
        me->library_errors_ += " (the broker's certificate is not signed by " +
                               (me->config_.ca_file.empty() ? std::string("a CA this system trusts")
                                                            : "ca_file '" + me->config_.ca_file + "'") +
                               ", or not issued for host '" + me->config_.host + "')";
    });
    return true;
  }
  void drop() {
    if (!mosq_) return;
    mosquitto_disconnect(mosq_);
    mosquitto_destroy(mosq_);
    mosq_ = nullptr;
  }
  ChannelConfig config_;
  mosquitto* mosq_ = nullptr;
  bool connack_ = false;
  int connack_rc_ = 0;
  std::vector<int> acked_;
  std::string library_errors_;  // libmosquitto's error log of this connection attempt (OpenSSL's reasons)
};

}  // namespace

std::unique_ptr<Channel> make_mqtt_channel(const ChannelConfig& config) { return std::make_unique<MqttChannel>(config); }

}  // namespace rocking_monitor::notify
