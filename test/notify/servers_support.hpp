#pragma once
// Real servers for the notifier's tests, started and killed by the tests on loopback: test/notify/servers.py
// (SMTP via aiosmtpd, an HTTP webhook receiver) and Debian's mosquitto broker; an MQTT subscriber over
// libmosquitto that records what it receives. Waits are on conditions (a "ready" line, a port that
// answers, a log line), each with a deadline so that a broken server fails the test instead of hanging it.
#include <arpa/inet.h>
#include <mosquitto.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <functional>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

namespace notify_test {

/// A port nobody listens on now (the kernel's choice); the servers bind it with SO_REUSEADDR.
inline int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(fd);
  return ntohs(a.sin_port);
}

/// Polls `condition` every few ms until it holds or `timeout_s` passes; returns whether it held.
inline bool wait_for(const std::function<bool()>& condition, double timeout_s = 20.0) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!condition()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

inline bool port_open(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const bool ok = ::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  ::close(fd);
  return ok;
}

/// A child process; killed (SIGKILL) when it goes out of scope.
class Process {
 public:
  Process() = default;
  /// Starts argv; with `ready_line`, waits until its stdout says "ready".
  explicit Process(const std::vector<std::string>& argv, bool ready_line) { start(argv, ready_line); }
  ~Process() { kill(); }
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;
  void start(const std::vector<std::string>& argv, bool ready_line) {
    int fds[2];
    if (::pipe(fds) != 0) throw std::runtime_error("pipe");
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(fds[1], 1);
      ::close(fds[0]);
      std::vector<char*> args;
      for (const auto& s : argv) args.push_back(const_cast<char*>(s.c_str()));
      args.push_back(nullptr);
      ::execvp(args[0], args.data());
      std::perror(args[0]);
      ::_exit(127);
    }
    ::close(fds[1]);
    FILE* out = ::fdopen(fds[0], "r");
    if (ready_line) {
      char line[256] = {};
      // Blocks until the server has bound its port (or died: EOF).
      if (!std::fgets(line, sizeof line, out) || std::string(line).rfind("ready", 0) != 0)
        throw std::runtime_error("server did not start: " + argv[1] + " " + argv[2]);
    }
    out_ = out;
  }
  /// SIGTERM, then waits for it to exit (a broker that saves its retained state as it stops).
  void terminate() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      ::waitpid(pid_, nullptr, 0);
      pid_ = -1;
    }
    kill();
  }
  void kill() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
      pid_ = -1;
    }
    if (out_) {
      std::fclose(out_);
      out_ = nullptr;
    }
  }
  /// Whether it exited on its own (a server that died on purpose, --die-at).
  bool exited() {
    if (pid_ <= 0) return true;
    if (::waitpid(pid_, nullptr, WNOHANG) == pid_) {
      pid_ = -1;
      return true;
    }
    return false;
  }

 private:
  pid_t pid_ = -1;
  FILE* out_ = nullptr;
};

/// test/notify/servers.py smtp|http on `port`, logging to `log`, with extra options.
inline std::unique_ptr<Process> start_server(const std::string& kind, int port, const std::string& log,
                                             const std::vector<std::string>& options = {}) {
  std::vector<std::string> argv{"/usr/bin/python3", ROCKING_NOTIFY_SERVERS, kind, std::to_string(port), log};
  argv.insert(argv.end(), options.begin(), options.end());
  return std::make_unique<Process>(argv, true);
}

/// mosquitto on `port` with its retained state saved on every change in `dir` (it survives a kill).
inline std::unique_ptr<Process> start_mosquitto(int port, const std::string& dir) {
  const std::string conf = dir + "/mosquitto.conf";
  std::ofstream(conf) << "listener " << port << " 127.0.0.1\nallow_anonymous true\npersistence true\n"
                      << "persistence_location " << dir << "/\nautosave_on_changes true\nautosave_interval 1\n"
                      << "log_dest none\n" << (::geteuid() == 0 ? "user root\n" : "");  // as root it would run as user mosquitto, who cannot write dir
  auto p = std::make_unique<Process>(std::vector<std::string>{"/usr/sbin/mosquitto", "-c", conf}, false);
  if (!wait_for([&] { return port_open(port); })) throw std::runtime_error("mosquitto did not start on " + std::to_string(port));
  return p;
}

/// mosquitto with a plain listener on `port` (the test's subscriber) and a TLS one on `tls_port` under
/// `cert` and `key` (the notifier's), in `dir`. Waits until both ports answer.
inline std::unique_ptr<Process> start_mosquitto_tls(int port, int tls_port, const std::string& dir, const std::string& cert,
                                                    const std::string& key) {
  const std::string conf = dir + "/mosquitto_tls.conf";
  std::ofstream(conf) << "per_listener_settings false\nallow_anonymous true\nlog_dest none\n"
                      << (::geteuid() == 0 ? "user root\n" : "")
                      << "listener " << port << " 127.0.0.1\n"
                      << "listener " << tls_port << " 127.0.0.1\ncertfile " << cert << "\nkeyfile " << key << "\n";
  auto p = std::make_unique<Process>(std::vector<std::string>{"/usr/sbin/mosquitto", "-c", conf}, false);
  if (!wait_for([&] { return port_open(port) && port_open(tls_port); }))
    throw std::runtime_error("mosquitto did not start on " + std::to_string(port) + " and " + std::to_string(tls_port));
  return p;
}

/// The JSON lines of a server log (what the server accepted). Only complete lines: the server may
/// be writing the last one while the test reads (a cut line was a parse error, found in a CI run);
/// the tests poll, so it is read whole the next time.
inline std::vector<nlohmann::json> read_log(const std::string& path) {
  std::vector<nlohmann::json> out;
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::size_t start = 0;
  for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
    if (end > start) out.push_back(nlohmann::json::parse(text.substr(start, end - start)));
  return out;
}

/// An MQTT subscriber to `filter`, recording topic -> payloads received (retained ones too).
class MqttRecorder {
 public:
  MqttRecorder(int port, const std::string& filter) {
    mosquitto_lib_init();
    m_ = mosquitto_new(nullptr, true, this);
    filter_ = filter;
    mosquitto_connect_callback_set(m_, [](mosquitto* m, void* self, int) {
      mosquitto_subscribe(m, nullptr, static_cast<MqttRecorder*>(self)->filter_.c_str(), 1);
    });
    mosquitto_message_callback_set(m_, [](mosquitto*, void* self, const mosquitto_message* msg) {
      auto* me = static_cast<MqttRecorder*>(self);
      std::lock_guard<std::mutex> l(me->mutex_);
      me->got_[msg->topic].push_back(std::string(static_cast<const char*>(msg->payload), msg->payloadlen));
    });
    mosquitto_connect(m_, "127.0.0.1", port, 30);
    mosquitto_loop_start(m_);
  }
  ~MqttRecorder() {
    mosquitto_disconnect(m_);
    mosquitto_loop_stop(m_, true);
    mosquitto_destroy(m_);
  }
  std::map<std::string, std::vector<std::string>> got() {
    std::lock_guard<std::mutex> l(mutex_);
    return got_;
  }

 private:
  mosquitto* m_ = nullptr;
  std::string filter_;
  std::mutex mutex_;
  std::map<std::string, std::vector<std::string>> got_;
};

}  // namespace notify_test
