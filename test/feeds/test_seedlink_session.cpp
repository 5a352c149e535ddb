// The client against a scripted server on a real localhost TCP socket: the exact command bytes of
// the handshake, packets handed on in order, INFO / malformed / repeated packets counted and
// dropped, and after the server drops the connection a reconnect that resumes at last + 1.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <mutex>
#include <thread>

#include "rocking_monitor/feeds/mseed_writer.hpp"
#include "rocking_monitor/feeds/seedlink_session.hpp"

namespace rocking_monitor::feeds {
namespace {

// A listening socket on an ephemeral localhost port.
struct Listener {
  int fd = -1;
  std::uint16_t port = 0;
  Listener() {
    fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
    ::listen(fd, 4);
    socklen_t len = sizeof a;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
    port = ntohs(a.sin_port);
  }
  ~Listener() { ::close(fd); }
};

std::string read_line(int fd) {
  std::string line;
  char c = 0;
  while (::recv(fd, &c, 1, 0) == 1) {
    line += c;
    if (c == '\n') break;
  }
  return line;
}

void send_str(int fd, const std::string& s) { ::send(fd, s.data(), s.size(), MSG_NOSIGNAL); }

std::string packet(const char* header8, const std::string& record) { return std::string(header8, 8) + record; }

TEST(SeedLinkSession, HandshakePacketsAndResume) {
  ChannelSeries s;
  s.network = "CI";
  s.station = "RIN";
  s.channel = "HNZ";
  s.start_us = 1000000000LL * 1000000;
  s.sample_rate = 100.0;
  for (int i = 0; i < 2000; ++i) s.counts.push_back(i * 37 % 1001 - 500);
  PackOptions po;
  po.max_samples = 100;
  const std::vector<std::string> recs = pack_channel(s, po);
  ASSERT_GE(recs.size(), 6u);
  std::string info(512, ' ');

  Listener l;
  std::vector<std::string> commands1, commands2;
  std::thread server([&] {
    auto handshake = [&](int c, std::vector<std::string>& seen) {
      for (;;) {
        const std::string line = read_line(c);
        if (line.empty()) return;
        seen.push_back(line);
        if (line == "HELLO\r\n") send_str(c, "SeedLink v3.1 (test) :: SLPROTO:3.1\r\nrocking_monitor test\r\n");
        else if (line == "END\r\n") return;
        else send_str(c, "OK\r\n");
      }
    };
    int c = ::accept(l.fd, nullptr, nullptr);
    handshake(c, commands1);
    send_str(c, packet("SL000001", recs[0]));
    send_str(c, packet("SLINFO *", info));
    send_str(c, packet("SLINFO  ", info));
    send_str(c, packet("SL000002", recs[1]));
    send_str(c, packet("SL0000Z2", recs[2]));  // malformed header: dropped
    send_str(c, packet("SL000002", recs[1]));  // repeated number: dropped
    send_str(c, packet("SL000003", recs[2]));
    ::close(c);  // the server goes away
    c = ::accept(l.fd, nullptr, nullptr);
    handshake(c, commands2);
    send_str(c, packet("SL000004", recs[3]));
    send_str(c, packet("SL000007", recs[4]));  // 5 and 6 never come
    ::shutdown(c, SHUT_WR);
    read_line(c);
    ::close(c);
  });

  SessionConfig cfg;
  cfg.host = "127.0.0.1";
  cfg.port = l.port;
  cfg.streams = {StreamSpec{"CI", "RIN", {"HN?"}}};
  cfg.backoff_min_s = 0.05;
  cfg.backoff_max_s = 0.1;
  cfg.connect_timeout_s = 5.0;
  std::atomic<bool> stop{false};
  std::vector<std::uint32_t> got;
  std::vector<std::string> got_records;
  SeedLinkSession session(
      cfg,
      [&](std::size_t stream, std::uint32_t seq, const char* rec, std::size_t len) {
        EXPECT_EQ(stream, 0u);
        got.push_back(seq);
        got_records.emplace_back(rec, len);
        if (got.size() == 5) stop = true;
      },
      [](SeedLinkSession::Level, const std::string&) {});
  std::thread client([&] { session.run(stop); });
  for (int i = 0; i < 200 && !stop.load(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(25));
  stop = true;
  client.join();
  server.join();

  const std::vector<std::string> expected1 = {"HELLO\r\n", "STATION RIN CI\r\n", "SELECT HN?\r\n", "DATA\r\n", "END\r\n"};
  const std::vector<std::string> expected2 = {"HELLO\r\n", "STATION RIN CI\r\n", "SELECT HN?\r\n", "DATA 000004\r\n", "END\r\n"};
  EXPECT_EQ(commands1, expected1);
  EXPECT_EQ(commands2, expected2);
  EXPECT_EQ(got, (std::vector<std::uint32_t>{1, 2, 3, 4, 7}));
  ASSERT_EQ(got_records.size(), 5u);
  EXPECT_EQ(got_records[2], recs[2]);
  EXPECT_EQ(got_records[4], recs[4]);
  const SessionCounters& k = session.counters();
  EXPECT_EQ(k.info_packets.load(), 2u);
  EXPECT_EQ(k.malformed.load(), 1u);
  EXPECT_EQ(k.repeated_sequence.load(), 1u);
  EXPECT_EQ(k.sequence_jumps.load(), 1u);
  EXPECT_EQ(k.skipped_sequence.load(), 2u);
  EXPECT_EQ(k.connects.load(), 2u);
  EXPECT_GE(k.disconnects.load(), 1u);
  EXPECT_EQ(*session.last_sequence(0), 7u);
}

TEST(SeedLinkSession, KeepAliveWhenIdleAndReconnectWhenSilent) {
  Listener l;
  std::vector<std::string> lines;
  std::atomic<int> accepted{0};
  std::thread server([&] {
    // First connection: answers the keep-alive with one INFO packet, then stays silent: the client
    // must give up after its idle timeout and come back.
    for (int round = 0; round < 2; ++round) {
      const int c = ::accept(l.fd, nullptr, nullptr);
      ++accepted;
      for (;;) {
        const std::string line = read_line(c);
        if (line.empty()) break;
        if (round == 0) lines.push_back(line);
        if (line == "HELLO\r\n") send_str(c, "SeedLink v3.1 (test)\r\ntest\r\n");
        else if (line == "INFO ID\r\n") {
          if (round == 0 && lines.size() == 6) send_str(c, packet("SLINFO  ", std::string(512, ' ')));
        } else if (line != "END\r\n") send_str(c, "OK\r\n");
        if (round == 1 && line == "END\r\n") break;
      }
      ::close(c);
    }
  });
  SessionConfig cfg;
  cfg.host = "127.0.0.1";
  cfg.port = l.port;
  cfg.streams = {StreamSpec{"CI", "RIN", {"HN?"}}};
  cfg.keepalive_s = 0.1;
  cfg.idle_timeout_s = 0.5;
  cfg.backoff_min_s = 0.05;
  std::atomic<bool> stop{false};
  std::mutex log_mutex;
  std::string log;
  SeedLinkSession session(cfg, [](std::size_t, std::uint32_t, const char*, std::size_t) {},
                          [&](SeedLinkSession::Level, const std::string& what) {
                            std::lock_guard<std::mutex> lock(log_mutex);
                            log += what + "\n";
                          });
  std::thread client([&] { session.run(stop); });
  for (int i = 0; i < 1000 && accepted.load() < 2; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  stop = true;
  client.join();
  server.join();
  ASSERT_GE(lines.size(), 6u);
  EXPECT_EQ(lines[5], "INFO ID\r\n");
  EXPECT_EQ(session.counters().info_packets.load(), 1u);
  EXPECT_GE(session.counters().keepalives.load(), 2u);
  EXPECT_EQ(session.counters().connects.load(), 2u);
  EXPECT_NE(log.find("nothing received for 0.5"), std::string::npos) << log;
}

TEST(SeedLinkSession, RefusedConnectionBacksOffAndSaysWhy) {
  Listener l;
  const std::uint16_t port = l.port;
  ::close(l.fd);  // nothing listens there any more
  l.fd = -1;
  SessionConfig cfg;
  cfg.host = "127.0.0.1";
  cfg.port = port;
  cfg.streams = {StreamSpec{"CI", "RIN", {"HN?"}}};
  cfg.backoff_min_s = 0.02;
  cfg.backoff_max_s = 0.04;
  std::atomic<bool> stop{false};
  SeedLinkSession session(cfg, [](std::size_t, std::uint32_t, const char*, std::size_t) {},
                          [](SeedLinkSession::Level, const std::string&) {});
  std::thread client([&] { session.run(stop); });
  while (session.counters().connect_failures.load() < 3) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  stop = true;
  client.join();
  EXPECT_NE(session.last_error().find("connect to 127.0.0.1:" + std::to_string(port)), std::string::npos) << session.last_error();
  EXPECT_EQ(session.counters().connects.load(), 0u);
}

}  // namespace
}  // namespace rocking_monitor::feeds

namespace rocking_monitor::feeds {
namespace {

// Six consecutive 100-sample records of CI.RIN.HNZ, 1 s apart in record time.
std::vector<std::string> six_records() {
  ChannelSeries s;
  s.network = "CI";
  s.station = "RIN";
  s.channel = "HNZ";
  s.start_us = 1700000000LL * 1000000;
  s.sample_rate = 100.0;
  for (int i = 0; i < 600; ++i) s.counts.push_back(i % 200 - 100);
  PackOptions po;
  po.max_samples = 100;
  return pack_channel(s, po);
}

// Answers a handshake (OK to everything), recording the commands; returns at END.
void restart_test_handshake(int c, std::vector<std::string>& seen) {
  for (;;) {
    const std::string line = read_line(c);
    if (line.empty()) return;
    seen.push_back(line);
    if (line == "HELLO\r\n") send_str(c, "SeedLink v3.1 (test) :: SLPROTO:3.1\r\ntest\r\n");
    else if (line == "END\r\n") return;
    else send_str(c, "OK\r\n");
  }
}

// What a session handed on and logged.
struct RestartRun {
  std::vector<std::uint32_t> got;
  std::string log;
  std::mutex log_mutex;
};

// Runs the session until its record handler sets `stop` (or 10 s passed: the test then fails on what it got).
void run_until_stopped(SeedLinkSession& session, std::atomic<bool>& stop) {
  std::thread client([&] { session.run(stop); });
  for (int i = 0; i < 1000 && !stop.load(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  stop = true;
  client.join();
}

// A session that stops itself once `want` packets were handed on.
SeedLinkSession restart_session(std::uint16_t port, std::atomic<bool>& stop, std::size_t want, RestartRun& run) {
  SessionConfig cfg;
  cfg.host = "127.0.0.1";
  cfg.port = port;
  cfg.streams = {StreamSpec{"CI", "RIN", {"HN?"}}};
  cfg.backoff_min_s = 0.05;
  cfg.backoff_max_s = 0.1;
  return SeedLinkSession(
      cfg,
      [&run, &stop, want](std::size_t, std::uint32_t seq, const char*, std::size_t) {
        run.got.push_back(seq);
        if (run.got.size() == want) stop = true;
      },
      [&run](SeedLinkSession::Level, const std::string& what) {
        std::lock_guard<std::mutex> lock(run.log_mutex);
        run.log += what + "\n";
      });
}

}  // namespace

// Issue 54: a server that restarts numbers its packets from low values again. Its records are newer
// than any handed on: accepted, counted and said, while a true repeat (an old record) is still dropped.
TEST(SeedLinkSession, ServerThatRestartsItsNumberingIsFollowedByRecordTime) {
  const std::vector<std::string> recs = six_records();
  ASSERT_EQ(recs.size(), 6u);
  Listener l;
  std::vector<std::string> commands1, commands2;
  std::thread server([&] {
    int c = ::accept(l.fd, nullptr, nullptr);
    restart_test_handshake(c, commands1);
    send_str(c, packet("SL000100", recs[0]));
    send_str(c, packet("SL000101", recs[1]));
    send_str(c, packet("SL000102", recs[2]));
    ::close(c);  // the server restarts
    c = ::accept(l.fd, nullptr, nullptr);
    restart_test_handshake(c, commands2);
    send_str(c, packet("SL000101", recs[1]));  // a true repeat: an old record, dropped
    send_str(c, packet("SL000001", recs[3]));  // the restarted server's numbers
    send_str(c, packet("SL000002", recs[4]));
    send_str(c, packet("SL000001", recs[3]));  // repeated after the restart: dropped
    send_str(c, packet("SL000003", recs[5]));
    ::shutdown(c, SHUT_WR);
    read_line(c);
    ::close(c);
  });
  std::atomic<bool> stop{false};
  RestartRun run;
  SeedLinkSession session = restart_session(l.port, stop, 6, run);
  run_until_stopped(session, stop);
  server.join();
  EXPECT_EQ(run.got, (std::vector<std::uint32_t>{0x100, 0x101, 0x102, 1, 2, 3}));
  ASSERT_EQ(commands2.size(), 5u);
  EXPECT_EQ(commands2[3], "DATA 000103\r\n");
  const SessionCounters& k = session.counters();
  EXPECT_EQ(k.server_restarts.load(), 1u);
  EXPECT_EQ(k.repeated_sequence.load(), 2u);
  EXPECT_EQ(*session.last_sequence(0), 3u);
  EXPECT_NE(run.log.find("CI_RIN: packet 000001 is numbered at or before the last one (000102) but its record is newer: "
                         "the server restarted its numbering; resynchronised"),
            std::string::npos)
      << run.log;
}

// A bridge restarted with its state file knows the number (0x102) but no record time. The server,
// asked for 000103, answers with 000001: it no longer holds 000103, it renumbered.
TEST(SeedLinkSession, LowerNumberAnsweringAResumeFromTheStateFileIsAServerRestart) {
  const std::vector<std::string> recs = six_records();
  Listener l;
  std::vector<std::string> commands;
  std::thread server([&] {
    const int c = ::accept(l.fd, nullptr, nullptr);
    restart_test_handshake(c, commands);
    send_str(c, packet("SL000001", recs[3]));
    send_str(c, packet("SL000002", recs[4]));
    ::shutdown(c, SHUT_WR);
    read_line(c);
    ::close(c);
  });
  std::atomic<bool> stop{false};
  RestartRun run;
  SeedLinkSession session = restart_session(l.port, stop, 2, run);
  session.resume_after(0, 0x102);
  run_until_stopped(session, stop);
  server.join();
  ASSERT_EQ(commands.size(), 5u);
  EXPECT_EQ(commands[3], "DATA 000103\r\n");
  EXPECT_EQ(run.got, (std::vector<std::uint32_t>{1, 2}));
  EXPECT_EQ(session.counters().server_restarts.load(), 1u);
  EXPECT_EQ(session.counters().repeated_sequence.load(), 0u);
}

}  // namespace rocking_monitor::feeds

#include <poll.h>

#include "rocking_monitor/feeds/tcp_connection.hpp"

namespace rocking_monitor::feeds {
namespace {

// Sends `bytes` one at a time, ~10 ms apart, until all went or the peer closed its end; true
// when the peer closed first. The pace only sets how slow the drip is: no verdict depends on it.
bool drip_until_closed(int c, const std::string& bytes) {
  for (const char b : bytes) {
    if (::send(c, &b, 1, MSG_NOSIGNAL) != 1) return true;
    pollfd p{c, POLLIN, 0};
    if (::poll(&p, 1, 10) > 0) {
      char x = 0;
      if (::recv(c, &x, 1, 0) <= 0) return true;
    }
  }
  return false;
}

}  // namespace

// Issue 54: a reply line's timeout is for the whole line. A server dripping a byte every 10 ms
// kept the old per-byte timeout happy until the line grew too long (~10 s); now: Timeout.
TEST(TcpConnection, ReplyLineDrippingByteByByteTimesOutAsAWhole) {
  Listener l;
  std::atomic<bool> peer_closed{false};
  std::thread server([&] {
    const int c = ::accept(l.fd, nullptr, nullptr);
    peer_closed = drip_until_closed(c, std::string(2000, 'O'));
    ::close(c);
  });
  TcpConnection tcp;
  ASSERT_EQ(tcp.open("127.0.0.1", l.port, 5.0), TcpConnection::Status::Ok);
  std::string line;
  EXPECT_EQ(tcp.read_line(line, 0.3), TcpConnection::Status::Timeout) << tcp.error();
  EXPECT_EQ(tcp.error(), "no whole reply line within 0.300000 s");
  EXPECT_LT(line.size(), 1024u);
  tcp.close();
  server.join();
  EXPECT_TRUE(peer_closed.load());  // the client hung up before the drip ended
}

// A packet dripping in is given up after ~record_timeout s from its first byte: counted, said, and
// the session reconnects (the old idle timeout per byte never fired while bytes trickled).
TEST(SeedLinkSession, PacketDrippingSlowerThanItsDeadlineIsGivenUp) {
  const std::vector<std::string> recs = six_records();
  Listener l;
  std::atomic<int> handshakes{0};
  std::atomic<bool> first_closed_by_client{false};
  std::thread server([&] {
    std::vector<std::string> seen;
    int c = ::accept(l.fd, nullptr, nullptr);
    restart_test_handshake(c, seen);
    ++handshakes;
    first_closed_by_client = drip_until_closed(c, packet("SL000001", recs[0]) + packet("SL000002", recs[1]));
    ::close(c);
    c = ::accept(l.fd, nullptr, nullptr);
    restart_test_handshake(c, seen);
    ++handshakes;
    read_line(c);  // until the client stops
    ::close(c);
  });
  SessionConfig cfg;
  cfg.host = "127.0.0.1";
  cfg.port = l.port;
  cfg.streams = {StreamSpec{"CI", "RIN", {"HN?"}}};
  cfg.record_timeout_s = 0.3;
  cfg.backoff_min_s = 0.05;
  std::atomic<bool> stop{false};
  RestartRun run;
  SeedLinkSession session(cfg, [&run](std::size_t, std::uint32_t seq, const char*, std::size_t) { run.got.push_back(seq); },
                          [&run](SeedLinkSession::Level, const std::string& what) {
                            std::lock_guard<std::mutex> lock(run.log_mutex);
                            run.log += what + "\n";
                          });
  std::thread client([&] { session.run(stop); });
  for (int i = 0; i < 2000 && handshakes.load() < 2; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  stop = true;
  client.join();
  server.join();
  EXPECT_TRUE(first_closed_by_client.load());
  EXPECT_TRUE(run.got.empty());
  EXPECT_EQ(session.counters().slow_packets.load(), 1u);
  EXPECT_EQ(session.counters().connects.load(), 2u);
  EXPECT_NE(run.log.find("a packet did not come whole within 0.300000 s (~record_timeout): the link drips; reconnecting"),
            std::string::npos)
      << run.log;
}

}  // namespace rocking_monitor::feeds

namespace rocking_monitor::feeds {

// Issue 54: a server's reply reaches logs and last_error() (hence /diagnostics) without control
// characters and as valid UTF-8, whatever bytes it held.
TEST(SeedLinkSession, ServerTextInLogsHasNoControlCharactersAndIsValidUtf8) {
  Listener l;
  std::atomic<bool> refused{false};
  std::thread server([&] {
    const int c = ::accept(l.fd, nullptr, nullptr);
    for (;;) {
      const std::string line = read_line(c);
      if (line.empty()) break;
      if (line == "HELLO\r\n") send_str(c, "SeedLink v3.1 (test)\r\ntest\r\n");
      else if (line.rfind("STATION", 0) == 0) {
        send_str(c, "ERROR \x1B[31mno\x07\xFF\r\n");
        refused = true;
      }
    }
    ::close(c);
  });
  SessionConfig cfg;
  cfg.host = "127.0.0.1";
  cfg.port = l.port;
  cfg.streams = {StreamSpec{"CI", "RIN", {"HN?"}}};
  cfg.backoff_min_s = 10.0;  // one attempt is enough
  std::atomic<bool> stop{false};
  RestartRun run;
  SeedLinkSession session(cfg, [](std::size_t, std::uint32_t, const char*, std::size_t) {},
                          [&run, &stop](SeedLinkSession::Level, const std::string& what) {
                            std::lock_guard<std::mutex> lock(run.log_mutex);
                            run.log += what + "\n";
                            if (what.find("accepted none") != std::string::npos) stop = true;
                          });
  run_until_stopped(session, stop);
  server.join();
  EXPECT_TRUE(refused.load());
  EXPECT_NE(run.log.find("STATION RIN CI refused: 'ERROR \\x1B[31mno\\x07\xEF\xBF\xBD'"), std::string::npos) << run.log;
  for (const char c : run.log) EXPECT_TRUE(c == '\n' || static_cast<unsigned char>(c) >= 0x20) << int(c);
  EXPECT_EQ(session.last_error().find('\x1B'), std::string::npos);
}

}  // namespace rocking_monitor::feeds
