// The notifier killed (SIGKILL) at random points while it delivers, and started again on the same
// outbox, against real servers (issue 44 "a notifier killed mid-event and restarted sends nothing twice
// and nothing is lost"). Each notifier runs in a child process: it is given every alarm of the event
// (as the monitor re-sends its open event to a new subscriber), forms one e-mail and one webhook POST
// per alarm (10 s of notifier time apart), and delivers them. Checked at the servers' logs: every
// message id of the run arrived and each alarm is in exactly one of them. A kill between the server's
// acknowledgement and the outbox's fsync of it makes that message arrive twice, with the same id
// (Message-ID, Idempotency-Key): counted and printed, never more than one per kill and channel.
// Runs: 3 (ROCKING_NOTIFY_KILL_RUNS=20 for the measurement).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <set>

#include "rocking_monitor/notify/channels.hpp"
#include "servers_support.hpp"

using namespace rocking_monitor::notify;
using namespace notify_test;

namespace {

constexpr int kAlarms = 16;

[[noreturn]] void notifier_child(const NotifyConfig& config, const std::string& outbox) {
  try {
    Notifier n(config, outbox, make_channel, 1000.0);
    for (int k = 0; k < kAlarms; ++k) {
      NotifyAlarm a;
      a.source = "/rocking_monitor";
      a.item = "item_" + std::to_string(k);
      a.level = kCommitted;
      a.event_time = 100.0 + k;
      a.stamp_ns = static_cast<std::int64_t>((100.0 + k) * 1e9);
      a.event_id = "2026-11-27T10:00:00.000Z/1";
      a.sequence = static_cast<std::uint64_t>(k + 1);
      n.accept(a, 1000.0 + 10.0 * k);
      if (!n.tick(1000.0 + 10.0 * k).empty()) ::_exit(3);
    }
    if (!n.tick(1000.0 + 10.0 * kAlarms + 10.0).empty()) ::_exit(3);
    ::_exit(n.wait_idle(60) ? 0 : 4);
  } catch (...) {
    ::_exit(5);
  }
}

}  // namespace

TEST(NotifyKill, KilledAtRandomPointsAndRestartedLosesNothing) {
  const char* env = std::getenv("ROCKING_NOTIFY_KILL_RUNS");
  const int runs = env ? std::atoi(env) : 3;
  const std::string dir = ::testing::TempDir() + "notify_kill_" + std::to_string(::getpid());
  std::mt19937 rng(20261127);
  int duplicates = 0, kills = 0;
  for (int run = 0; run < runs; ++run) {
    SCOPED_TRACE("run " + std::to_string(run));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const int smtp_port = free_port(), http_port = free_port();
    const std::string smtp_log = dir + "/smtp.jsonl", http_log = dir + "/http.jsonl", outbox = dir + "/outbox.jsonl";
    auto smtp = start_server("smtp", smtp_port, smtp_log);
    auto http = start_server("http", http_port, http_log);
    const NotifyConfig config = parse_notify_config(
        "window: 10\nretry: {initial: 0.02, factor: 2, max: 0.2}\nchannels:\n"
        "  mail: {type: smtp, url: 'smtp://127.0.0.1:" + std::to_string(smtp_port) + "', from: monitor@test.example}\n"
        "  hook: {type: webhook, url: 'http://127.0.0.1:" + std::to_string(http_port) + "/hook'}\n"
        "recipients:\n  - {name: curator, channel: mail, to: curator@test.example}\n  - {name: ops, channel: hook}\n",
        "kill.yaml");
    // Two kills at random numbers of e-mails received, then a run to the end.
    std::vector<int> points{static_cast<int>(rng() % kAlarms), static_cast<int>(rng() % kAlarms)};
    std::sort(points.begin(), points.end());
    for (int point : points) {
      const pid_t child = ::fork();
      ASSERT_GE(child, 0);
      if (child == 0) notifier_child(config, outbox);
      // killed once the SMTP server holds `point` messages (or the child is done)
      int status = 0;
      const bool done = !wait_for([&] {
        return read_log(smtp_log).size() >= static_cast<std::size_t>(point) || ::waitpid(child, &status, WNOHANG) == child;
      });
      ASSERT_FALSE(done) << "the servers never received " << point << " messages";
      // then 0-20 ms on: a random spot in the stream, not always just after a message was stored
      // (where the notifier is always between the server's acknowledgement and its fsync of it).
      std::this_thread::sleep_for(std::chrono::microseconds(rng() % 20000));
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      ++kills;
    }
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) notifier_child(config, outbox);
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "last notifier: status " << status;
    for (const auto& log : {smtp_log, http_log}) {
      const auto got = read_log(log);
      std::set<std::string> ids;
      std::multiset<std::string> items;
      for (const auto& m : got) {
        if (!ids.insert(m["id"].get<std::string>()).second) {
          ++duplicates;
          continue;  // the same message again (same id): a receiver drops it by its id
        }
        if (m.contains("alarms")) {
          for (const auto& a : m["alarms"]) items.insert(a["item"].get<std::string>());
        } else {
          const std::string body = m["body"];
          for (auto at = body.find("  - item_"); at != std::string::npos; at = body.find("  - item_", at + 1))
            items.insert(body.substr(at + 4, body.find(' ', at + 4) - at - 4));
        }
      }
      EXPECT_EQ(ids.size(), static_cast<std::size_t>(kAlarms)) << log << ": one message per alarm, none lost";
      for (int k = 0; k < kAlarms; ++k) EXPECT_EQ(items.count("item_" + std::to_string(k)), 1u) << log << " item_" << k;
      EXPECT_LE(got.size() - ids.size(), points.size()) << log;
    }
  }
  std::printf("[ measured ] %d runs, %d kills: 0 messages lost, %d delivered twice (same id)\n", runs, kills, duplicates);
  std::filesystem::remove_all(dir);
}
