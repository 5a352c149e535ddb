// POSIX TCP with poll() timeouts (see the header). Waits are cut into 100 ms slices so that a stop
// request ends them promptly.
#include "rocking_monitor/feeds/tcp_connection.hpp"

#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

namespace rocking_monitor::feeds {

void parse_host_port(const std::string& text, std::string& host, std::uint16_t& port) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size())
    throw std::invalid_argument("server '" + text + "': expected host:port, e.g. localhost:18000");
  host = text.substr(0, colon);
  const std::string p = text.substr(colon + 1);
  char* end = nullptr;
  const long v = std::strtol(p.c_str(), &end, 10);
  if (end != p.c_str() + p.size() || v < 1 || v > 65535)
    throw std::invalid_argument("server '" + text + "': port '" + p + "' is not a number in 1..65535");
  port = static_cast<std::uint16_t>(v);
}

TcpConnection::~TcpConnection() { close(); }

void TcpConnection::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  has_pending_ = false;
}

namespace {
TcpConnection::Deadline tcp_deadline_in(double timeout_s) {
  return std::chrono::steady_clock::now() +
         std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(timeout_s));
}
}  // namespace

TcpConnection::Status TcpConnection::wait(short events, double timeout_s) {
  const Status s = wait_until(events, tcp_deadline_in(timeout_s));
  if (s == Status::Timeout) error_ = "timed out after " + std::to_string(timeout_s) + " s";
  return s;
}

TcpConnection::Status TcpConnection::wait_until(short events, Deadline until) {
  using clock = std::chrono::steady_clock;
  for (;;) {
    if (stop_ != nullptr && stop_->load()) return Status::Stopped;
    const double left = std::chrono::duration<double>(until - clock::now()).count();
    if (left <= 0.0) {
      error_ = "timed out";
      return Status::Timeout;
    }
    pollfd p{fd_, events, 0};
    const int ms = static_cast<int>(std::min(left, 0.1) * 1000.0) + 1;
    const int r = ::poll(&p, 1, ms);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) {
      error_ = std::string("poll: ") + std::strerror(errno);
      return Status::Error;
    }
    if (r > 0) return Status::Ok;
  }
}

TcpConnection::Status TcpConnection::open(const std::string& host, std::uint16_t port, double timeout_s) {
  close();
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* res = nullptr;
  const int g = ::getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &res);
  if (g != 0) {
    error_ = "cannot resolve '" + host + "': " + ::gai_strerror(g);
    return Status::Error;
  }
  Status st = Status::Error;
  for (addrinfo* a = res; a != nullptr; a = a->ai_next) {
    fd_ = ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
    if (fd_ < 0) continue;
    const int flags = ::fcntl(fd_, F_GETFL, 0);
    ::fcntl(fd_, F_SETFL, flags | O_NONBLOCK);
    int r = ::connect(fd_, a->ai_addr, a->ai_addrlen);
    if (r < 0 && errno == EINPROGRESS) {
      st = wait(POLLOUT, timeout_s);
      if (st == Status::Ok) {
        int err = 0;
        socklen_t len = sizeof err;
        ::getsockopt(fd_, SOL_SOCKET, SO_ERROR, &err, &len);
        r = err == 0 ? 0 : -1;
        errno = err;
      } else {
        r = -1;
      }
    }
    if (r == 0) {
      const int one = 1;
      ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
      ::freeaddrinfo(res);
      return Status::Ok;
    }
    if (st != Status::Timeout && st != Status::Stopped) error_ = "connect to " + host + ":" + std::to_string(port) + ": " + std::strerror(errno);
    ::close(fd_);
    fd_ = -1;
    if (st == Status::Stopped) break;
  }
  ::freeaddrinfo(res);
  return st == Status::Ok ? Status::Error : st;
}

TcpConnection::Status TcpConnection::send_all(const std::string& bytes, double timeout_s) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const Status w = wait(POLLOUT, timeout_s);
    if (w != Status::Ok) return w;
    const ssize_t n = ::send(fd_, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) continue;
    if (n < 0) {
      error_ = std::string("send: ") + std::strerror(errno);
      return Status::Error;
    }
    done += static_cast<std::size_t>(n);
  }
  return Status::Ok;
}

TcpConnection::Status TcpConnection::wait_readable(double timeout_s) {
  if (has_pending_) return Status::Ok;
  return wait(POLLIN, timeout_s);
}

TcpConnection::Status TcpConnection::read_exact(char* out, std::size_t n, double timeout_s) {
  const Status s = read_exact_until(out, n, tcp_deadline_in(timeout_s));
  if (s == Status::Timeout) error_ = "not all of " + std::to_string(n) + " bytes came within " + std::to_string(timeout_s) + " s";
  return s;
}

TcpConnection::Status TcpConnection::read_exact_until(char* out, std::size_t n, Deadline deadline) {
  std::size_t done = 0;
  if (n > 0 && has_pending_) {
    out[done++] = pending_;
    has_pending_ = false;
  }
  while (done < n) {
    const Status w = wait_until(POLLIN, deadline);
    if (w != Status::Ok) return w;
    const ssize_t r = ::recv(fd_, out + done, n - done, 0);
    if (r < 0 && (errno == EAGAIN || errno == EINTR)) continue;
    if (r < 0) {
      error_ = std::string("recv: ") + std::strerror(errno);
      return Status::Error;
    }
    if (r == 0) {
      error_ = "the server closed the connection";
      return Status::Closed;
    }
    done += static_cast<std::size_t>(r);
  }
  return Status::Ok;
}

TcpConnection::Status TcpConnection::read_line(std::string& line, double timeout_s, std::size_t max_length) {
  line.clear();
  const Deadline deadline = tcp_deadline_in(timeout_s);  // for the whole line, not each byte
  for (;;) {
    char c = 0;
    const Status s = read_exact_until(&c, 1, deadline);
    if (s == Status::Timeout) error_ = "no whole reply line within " + std::to_string(timeout_s) + " s";
    if (s != Status::Ok) return s;
    if (c == '\n') return Status::Ok;
    if (c == '\r') {
      // "\r\n" or a bare "\r": peek at the next byte if one is there already.
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 50) > 0) {
        char next = 0;
        if (::recv(fd_, &next, 1, 0) == 1 && next != '\n') {
          pending_ = next;
          has_pending_ = true;
        }
      }
      return Status::Ok;
    }
    line += c;
    if (line.size() > max_length) {
      error_ = "reply line longer than " + std::to_string(max_length) + " bytes";
      return Status::Error;
    }
  }
}

}  // namespace rocking_monitor::feeds
