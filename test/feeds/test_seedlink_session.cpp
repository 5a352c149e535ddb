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
