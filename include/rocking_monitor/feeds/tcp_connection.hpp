#pragma once

// A plain POSIX TCP client connection with timeouts on every call (poll()), for the SeedLink
// client. Never blocks longer than the timeout it is given; a stop flag ends waits early.
// A read's timeout bounds the whole read, not the wait for each byte (issue 54): a server or a
// half-dead link that drips one byte at a time cannot keep a read, hence a session, alive forever.

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

namespace rocking_monitor::feeds {

/// "host:port" -> host, port; throws std::invalid_argument naming the text.
void parse_host_port(const std::string& text, std::string& host, std::uint16_t& port);

class TcpConnection {
 public:
  enum class Status { Ok, Timeout, Closed, Error, Stopped };
  using Deadline = std::chrono::steady_clock::time_point;

  TcpConnection() = default;
  ~TcpConnection();
  TcpConnection(const TcpConnection&) = delete;
  TcpConnection& operator=(const TcpConnection&) = delete;

  /// Resolves and connects within timeout_s; on failure `error()` says why.
  Status open(const std::string& host, std::uint16_t port, double timeout_s);
  void close();
  bool is_open() const { return fd_ >= 0; }

  Status send_all(const std::string& bytes, double timeout_s);
  /// Reads exactly n bytes, all within timeout_s (Timeout when they did not all come in time).
  Status read_exact(char* out, std::size_t n, double timeout_s);
  /// Reads one line ending in '\n' (or "\r" alone, as old servers do), terminator stripped; the
  /// whole line within timeout_s.
  Status read_line(std::string& line, double timeout_s, std::size_t max_length = 1024);
  /// Waits until a byte can be read; Timeout when none came within timeout_s.
  Status wait_readable(double timeout_s);

  void set_stop_flag(const std::atomic<bool>* stop) { stop_ = stop; }
  const std::string& error() const { return error_; }

 private:
  Status wait(short events, double timeout_s);
  Status wait_until(short events, Deadline deadline);
  Status read_exact_until(char* out, std::size_t n, Deadline deadline);
  int fd_ = -1;
  const std::atomic<bool>* stop_ = nullptr;
  std::string error_;
  char pending_ = 0;  ///< a byte read ahead after a bare "\r" line end
  bool has_pending_ = false;
};

}  // namespace rocking_monitor::feeds
