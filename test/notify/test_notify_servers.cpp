// The notifier's core against real servers it starts on loopback (issue 44 part 4): an SMTP server
// (aiosmtpd), an HTTP webhook receiver and the mosquitto broker. Servers killed in the middle of a
// delivery and restarted get every message exactly once; refusals are reported with the server's
// reason and hold up no other recipient; a burst of 10,000 items is a bounded number of e-mails.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <algorithm>
#include <set>

#include "rocking_monitor/notify/channels.hpp"
#include "rocking_monitor/notify/compose.hpp"
#include "servers_support.hpp"

using namespace rocking_monitor::notify;
using namespace notify_test;

namespace {

NotifyAlarm alarm(const std::string& item, int level, double t, std::uint64_t seq) {
  NotifyAlarm a;
  a.source = "/rocking_monitor";
  a.item = item;
  a.description = "Ming vase, shelf 3";
  a.level = level;
  a.event_time = t;
  a.stamp_ns = static_cast<std::int64_t>(std::llround(t * 1e9));
  a.event_id = "2026-11-27T10:00:00.000Z/1";
  a.sequence = seq;
  return a;
}

struct NotifyServers : ::testing::Test {
  std::string dir;
  int smtp_port = free_port(), http_port = free_port(), mqtt_port = free_port();
  std::string smtp_log, http_log;
  void SetUp() override {
    dir = ::testing::TempDir() + "notify_servers_" + std::to_string(::getpid()) + "_" +
          ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    smtp_log = dir + "/smtp.jsonl";
    http_log = dir + "/http.jsonl";
  }
  void TearDown() override { std::filesystem::remove_all(dir); }
  NotifyConfig config(const std::string& extra_recipients = "") const {
    return parse_notify_config(
        "site: Test store\ndashboard_url: http://127.0.0.1:8080/\nwindow: 10\n"
        "retry: {initial: 0.02, factor: 2, max: 0.2}\nchannels:\n"
        "  mail: {type: smtp, url: 'smtp://127.0.0.1:" + std::to_string(smtp_port) + "', from: monitor@test.example, timeout: 5}\n"
        "  hook: {type: webhook, url: 'http://127.0.0.1:" + std::to_string(http_port) + "/hook', timeout: 5}\n"
        "  bms: {type: mqtt, host: 127.0.0.1, port: " + std::to_string(mqtt_port) + ", topic_prefix: store, timeout: 5}\n"
        "recipients:\n"
        "  - {name: curator, channel: mail, to: curator@test.example}\n"
        "  - {name: ops, channel: hook}\n"
        "  - {name: building, channel: bms}\n" + extra_recipients,
        "test.yaml");
  }
  std::string channel_error(const Notifier& n, const std::string& channel) const {
    for (const auto& s : n.status())
      if (s.name == channel) return s.failing_attempts > 0 ? s.last_error : "";
    return "";
  }
};

double wall() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace

TEST_F(NotifyServers, DeliversToEachChannel) {
  auto smtp = start_server("smtp", smtp_port, smtp_log);
  auto http = start_server("http", http_port, http_log);
  auto broker = start_mosquitto(mqtt_port, dir);
  Notifier n(config(), dir + "/outbox.jsonl", make_channel, wall());
  const double t0 = wall();
  n.accept(alarm("vase_1", kCommitted, 100.0, 1), t0);
  ASSERT_EQ(n.tick(t0), "");
  ASSERT_TRUE(wait_for([&] { return read_log(smtp_log).size() == 1 && read_log(http_log).size() == 1; }));
  std::printf("[ measured ] first COMMITTED alarm to the SMTP and HTTP servers' logs: %.3f s\n", wall() - t0);
  const auto mail = read_log(smtp_log)[0];
  EXPECT_EQ(mail["to"], nlohmann::json::array({"curator@test.example"}));
  EXPECT_EQ(mail["from"], "monitor@test.example");
  EXPECT_EQ(mail["subject"], "[Test store] 1 item COMMITTED: vase_1");
  const std::string body = mail["body"];
  EXPECT_NE(body.find("vase_1 (Ming vase, shelf 3)"), std::string::npos) << body;
  EXPECT_NE(body.find("Do not try to catch it."), std::string::npos) << body;
  EXPECT_NE(body.find("Dashboard: http://127.0.0.1:8080/"), std::string::npos) << body;
  const auto hook = read_log(http_log)[0];
  EXPECT_EQ(hook["recipient"], "ops");
  EXPECT_EQ(hook["counts"]["COMMITTED"], 1);
  EXPECT_EQ(hook["path"], "/hook");
  EXPECT_NE(std::string(hook["id"]).find(".ops"), std::string::npos);
  EXPECT_EQ(std::string(mail["id"]).find("<" + std::string(hook["id"]).substr(0, std::string(hook["id"]).find('.'))), 0u)
      << "one outbox token names both messages";
  ASSERT_TRUE(n.wait_idle(20));
  // A subscriber that comes later gets the retained state.
  MqttRecorder sub(mqtt_port, "store/#");
  ASSERT_TRUE(wait_for([&] { return sub.got().size() == 2; }));
  const auto got = sub.got();
  EXPECT_EQ(got.at("store/vase_1/state").back(), "COMMITTED");
  EXPECT_EQ(nlohmann::json::parse(got.at("store/vase_1/COMMITTED").back())["item"], "vase_1");
}

// Issue 52 item 6: an alarm from a topic may carry any text. A CR/LF in its item id must not add an
// e-mail header (a Bcc, a Content-Type) nor end the headers early; "\r\n.\r\n" in the text must not end
// SMTP's DATA early; '/' and a line end must not add MQTT topic levels. Through real servers: what
// Python's e-mail parser and a subscriber see.
TEST_F(NotifyServers, TextFromAnAlarmAddsNoHeaderNoTopicLevelAndDoesNotEndTheMail) {
  auto smtp = start_server("smtp", smtp_port, smtp_log);
  auto http = start_server("http", http_port, http_log);
  auto broker = start_mosquitto(mqtt_port, dir);
  Notifier n(config(), dir + "/outbox.jsonl", make_channel, wall());
  const std::string item = "vase_1\r\nBcc: intruder@evil.example\r\nContent-Type: text/html\r\n\r\n<b>x";
  NotifyAlarm a = alarm(item, kCommitted, 100.0, 1);
  a.description = "<script>alert(1)</script>\r\n.\r\nafter the dot";
  const double t0 = wall();
  n.accept(a, t0);
  ASSERT_EQ(n.tick(t0), "");
  ASSERT_TRUE(wait_for([&] { return read_log(smtp_log).size() == 1 && read_log(http_log).size() == 1; }));
  const auto mail = read_log(smtp_log)[0];
  EXPECT_EQ(mail["to"], nlohmann::json::array({"curator@test.example"}));
  EXPECT_EQ(mail["headers"], nlohmann::json::array({"Date", "From", "To", "Subject", "Message-ID", "MIME-Version",
                                                    "Content-Type", "Content-Transfer-Encoding",
                                                    "X-Rocking-Monitor-Recipient"}));
  EXPECT_EQ(mail["content_type"], "text/plain");
  EXPECT_EQ(mail["subject"],
            "[Test store] 1 item COMMITTED: vase_1  Bcc: intruder@evil.example  Content-Type: text/html    <b>x");
  std::string body = mail["body"];
  body.erase(std::remove(body.begin(), body.end(), '\r'), body.end());  // the parser keeps SMTP's CRLF
  EXPECT_NE(body.find("<script>alert(1)</script>\n.\nafter the dot"), std::string::npos) << body;
  EXPECT_NE(body.find("Dashboard: http://127.0.0.1:8080/"), std::string::npos) << "the mail ended early:\n" << body;
  const auto hook = read_log(http_log)[0];
  EXPECT_EQ(hook["alarms"][0]["item"], item) << "JSON carries the text as it is, escaped";
  ASSERT_TRUE(n.wait_idle(20));
  MqttRecorder sub(mqtt_port, "store/#");
  ASSERT_TRUE(wait_for([&] { return sub.got().size() == 2; }));
  const std::string level = "vase_1__Bcc: intruder@evil.example__Content-Type: text_html____<b>x";
  const auto got = sub.got();
  EXPECT_EQ(got.count("store/" + level + "/state"), 1u);
  EXPECT_EQ(got.count("store/" + level + "/COMMITTED"), 1u);
  for (const auto& [topic, payloads] : got) EXPECT_EQ(std::count(topic.begin(), topic.end(), '/'), 2) << topic;
}

TEST_F(NotifyServers, ServerKilledMidDeliveryAndRestartedGetsEveryMessageOnce) {
  // Three kill points per server; each run: 12 steps 10 s of notifier time apart, one COMMITTED item
  // per step, so each step is one e-mail, one POST and two MQTT publications.
  for (int die_at : {1, 4, 9}) {
    SCOPED_TRACE("die_at " + std::to_string(die_at));
    std::filesystem::remove(smtp_log);
    std::filesystem::remove(http_log);
    std::filesystem::remove(dir + "/outbox.jsonl");
    auto smtp = start_server("smtp", smtp_port, smtp_log, {"--die-at", std::to_string(die_at)});
    auto http = start_server("http", http_port, http_log, {"--die-at", std::to_string(die_at + 1)});
    auto broker = start_mosquitto(mqtt_port, dir);
    Notifier n(config(), dir + "/outbox.jsonl", make_channel, 1000.0);
    const int steps = 12;
    bool smtp_back = false, http_back = false, broker_killed = false;
    for (int k = 0; k < steps; ++k) {
      const double now = 1000.0 + 10.0 * k;
      n.accept(alarm("item_" + std::to_string(k), kCommitted, 100.0 + k, k + 1), now);
      ASSERT_EQ(n.tick(now), "");
      // The broker: stopped while the notifier publishes. SIGTERM: mosquitto writes its retained state
      // as it stops; after a SIGKILL it can lose a publication it had already acknowledged (its own
      // durability: it saves at most once per change batch), which no client can tell.
      if (!broker_killed && k == die_at) {
        broker->terminate();
        broker_killed = true;
        ASSERT_TRUE(wait_for([&] { return !channel_error(n, "bms").empty(); }));
        broker = start_mosquitto(mqtt_port, dir);
      }
      // A server that died mid-delivery: the notifier says so, with a reason; then it is restarted.
      if (!smtp_back && smtp->exited()) {
        ASSERT_TRUE(wait_for([&] { return !channel_error(n, "mail").empty(); }));
        EXPECT_NE(channel_error(n, "mail").find("smtp://127.0.0.1:"), std::string::npos);
        smtp = start_server("smtp", smtp_port, smtp_log);
        smtp_back = true;
      }
      if (!http_back && http->exited()) {
        ASSERT_TRUE(wait_for([&] { return !channel_error(n, "hook").empty(); }));
        http = start_server("http", http_port, http_log);
        http_back = true;
      }
    }
    // the last kills may come after the last step
    ASSERT_TRUE(wait_for([&] { return smtp_back || smtp->exited(); }));
    if (!smtp_back) smtp = start_server("smtp", smtp_port, smtp_log);
    ASSERT_TRUE(wait_for([&] { return http_back || http->exited(); }));
    if (!http_back) http = start_server("http", http_port, http_log);
    ASSERT_TRUE(n.wait_idle(30));
    for (const auto& log : {smtp_log, http_log}) {
      const auto got = read_log(log);
      std::multiset<std::string> ids;
      for (const auto& m : got) ids.insert(m["id"].get<std::string>());
      EXPECT_EQ(got.size(), static_cast<std::size_t>(steps)) << log;
      EXPECT_EQ(std::set<std::string>(ids.begin(), ids.end()).size(), got.size()) << log << ": a message twice";
    }
    // Every item's retained state, after a broker killed and restarted: nothing lost.
    MqttRecorder sub(mqtt_port, "store/#");
    const bool all = wait_for([&] { return sub.got().size() == 2u * steps; }, 5.0);
    for (int k = 0; k < steps; ++k)
      for (const char* t : {"/state", "/COMMITTED"})
        if (!sub.got().count("store/item_" + std::to_string(k) + t)) std::printf("missing store/item_%d%s\n", k, t);
    ASSERT_TRUE(all);
    for (int k = 0; k < steps; ++k) EXPECT_EQ(sub.got().at("store/item_" + std::to_string(k) + "/state").back(), "COMMITTED");
    const auto s = n.status();
    std::uint64_t failures = 0;
    for (const auto& c : s) failures += c.failures;
    EXPECT_GE(failures, 3u);
  }
}

TEST_F(NotifyServers, RefusalsAreReportedWithTheServersReason) {
  auto smtp = start_server("smtp", smtp_port, smtp_log, {"--reject", "nobody"});
  auto http = start_server("http", http_port, http_log, {"--fail-first", "2"});
  auto broker = start_mosquitto(mqtt_port, dir);
  // The curator's address is refused; facilities, on the same server, get theirs all the same.
  NotifyConfig c = config("  - {name: facilities, channel: mail, to: facilities@test.example}\n");
  c.recipients[0].to = "nobody@test.example";
  Notifier n(c, dir + "/outbox.jsonl", make_channel, 1000.0);
  n.accept(alarm("vase_1", kOverturned, 100.0, 1), 1000.0);
  ASSERT_EQ(n.tick(1000.0), "");
  auto mail = [&] {
    for (const auto& s : n.status())
      if (s.name == "mail") return s;
    return Notifier::ChannelStatus{};
  };
  // The refusal (550: permanent, issue 54) closes the message as failed, with the server's reason;
  // it is not retried.
  ASSERT_TRUE(wait_for([&] { return mail().refused == 1u; }));
  EXPECT_NE(mail().last_error.find("refused for good, not retried"), std::string::npos) << mail().last_error;
  EXPECT_NE(mail().last_error.find("550 5.1.1 <nobody@test.example>: Recipient address rejected"), std::string::npos)
      << mail().last_error;
  ASSERT_TRUE(wait_for([&] { return read_log(smtp_log).size() == 1; }));
  EXPECT_EQ(read_log(smtp_log)[0]["to"], nlohmann::json::array({"facilities@test.example"}));
  // facilities' message acknowledged, nothing waits
  EXPECT_TRUE(wait_for([&] { return mail().queued == 0u; })) << mail().queued;
  EXPECT_EQ(mail().refused, 1u);
  // The webhook's receiver refuses twice with a reason, then takes it.
  ASSERT_TRUE(wait_for([&] { return read_log(http_log).size() == 1; }));
  std::uint64_t hook_failures = 0;
  for (const auto& s : n.status())
    if (s.name == "hook") {
      hook_failures = s.failures;
      EXPECT_NE(s.last_error.find("HTTP 503: receiver in maintenance"), std::string::npos) << s.last_error;
    }
  EXPECT_EQ(hook_failures, 2u);
}

TEST_F(NotifyServers, BurstOfTenThousandItemsIsAFewEmails) {
  auto smtp = start_server("smtp", smtp_port, smtp_log);
  auto http = start_server("http", http_port, http_log);
  NotifyConfig c = config();
  c.recipients.resize(2);  // e-mail and webhook
  Notifier n(c, dir + "/outbox.jsonl", make_channel, 1000.0);
  // 10,000 items COMMITTED within 20 s of shaking, the notifier ticking every 0.05 s.
  const int items = 10000, ticks = 400;
  double now = 1000.0;
  for (int k = 0; k <= ticks; ++k, now += 0.05) {
    for (int i = k * items / ticks; i < (k + 1) * items / ticks && i < items; ++i)
      n.accept(alarm("item_" + std::to_string(i), kCommitted, now - 900.0, static_cast<std::uint64_t>(i + 1)), now);
    ASSERT_EQ(n.tick(now), "");
  }
  ASSERT_EQ(n.tick(now + 10.0), "");
  ASSERT_TRUE(n.wait_idle(30));
  const auto mail = read_log(smtp_log), hook = read_log(http_log);
  std::printf("[ measured ] 10,000 items in 20 s: %zu e-mails, %zu webhook POSTs\n", mail.size(), hook.size());
  // 30 s from the first alarm to the last flush, one message per 10 s window at most.
  EXPECT_LE(mail.size(), 4u);
  EXPECT_LE(hook.size(), 4u);
  int posted = 0;
  for (const auto& h : hook) posted += static_cast<int>(h["alarms"].size());
  EXPECT_EQ(posted, items);
  int listed = 0;
  for (const auto& m : mail) {
    const std::string body = m["body"];
    const auto more = body.find("... and ");
    listed += more == std::string::npos ? 0 : std::stoi(body.substr(more + 8));
    for (auto at = body.find("  - item_"); at != std::string::npos; at = body.find("  - item_", at + 1)) ++listed;
  }
  EXPECT_EQ(listed, items) << "every item listed or counted";
}

TEST_F(NotifyServers, StartTlsAndLogin) {
  // A self-signed certificate for the test's SMTP server (openssl), so verify_tls: false.
  const std::string cert = dir + "/cert.pem", key = dir + "/key.pem";
  const std::string cmd = "openssl req -x509 -newkey rsa:2048 -nodes -subj /CN=127.0.0.1 -days 1 -keyout " + key +
                          " -out " + cert + " >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  auto smtp = start_server("smtp", smtp_port, smtp_log, {"--starttls", cert, key, "--login", "monitor:s3cret"});
  const std::string yaml = "channels:\n  mail: {type: smtp, url: 'smtp://127.0.0.1:" + std::to_string(smtp_port) +
                           "', from: monitor@test.example, starttls: true, verify_tls: false, username: monitor, "
                           "password: PASSWORD}\nretry: {initial: 0.02, max: 0.1}\n"
                           "recipients:\n  - {name: curator, channel: mail, to: curator@test.example}\n";
  {  // the wrong password: refused, with the server's reason
    auto bad = yaml;
    bad.replace(bad.find("PASSWORD"), 8, "wrong");
    Notifier n(parse_notify_config(bad, "tls.yaml"), dir + "/outbox_bad.jsonl", make_channel, 1000.0);
    n.accept(alarm("vase_1", kCommitted, 100.0, 1), 1000.0);
    ASSERT_EQ(n.tick(1000.0), "");
    ASSERT_TRUE(wait_for([&] { return !channel_error(n, "mail").empty(); }));
    EXPECT_NE(channel_error(n, "mail").find("535"), std::string::npos) << channel_error(n, "mail");
    std::printf("[ refused  ] %s\n", channel_error(n, "mail").c_str());
    EXPECT_TRUE(read_log(smtp_log).empty());
  }
  auto good = yaml;
  good.replace(good.find("PASSWORD"), 8, "s3cret");
  Notifier n(parse_notify_config(good, "tls.yaml"), dir + "/outbox.jsonl", make_channel, 1000.0);
  n.accept(alarm("vase_1", kCommitted, 100.0, 1), 1000.0);
  ASSERT_EQ(n.tick(1000.0), "");
  ASSERT_TRUE(wait_for([&] { return read_log(smtp_log).size() == 1; }));
  const auto mail = read_log(smtp_log)[0];
  EXPECT_EQ(mail["tls"], true);
  EXPECT_EQ(mail["authenticated"], true);
  EXPECT_EQ(mail["subject"], "[rocking monitor] 1 item COMMITTED: vase_1");
}

namespace {

// A certificate authority made for the test (openssl) in dir: ca.pem signed server.pem (key server.key)
// for 127.0.0.1; other_ca.pem is another CA, which did not. Whether the command succeeded.
bool make_test_ca(const std::string& dir) {
  std::ofstream(dir + "/san.ext") << "subjectAltName=IP:127.0.0.1\n";
  const std::string q = " >/dev/null 2>&1 && ";
  const std::string make =
      "cd " + dir + " && openssl req -x509 -newkey rsa:2048 -nodes -subj '/CN=rocking test CA' -days 1 -keyout ca.key -out ca.pem" + q +
      "openssl req -x509 -newkey rsa:2048 -nodes -subj '/CN=another CA' -days 1 -keyout other_ca.key -out other_ca.pem" + q +
      "openssl req -newkey rsa:2048 -nodes -subj /CN=127.0.0.1 -keyout server.key -out server.csr" + q +
      "openssl x509 -req -in server.csr -CA ca.pem -CAkey ca.key -CAcreateserial -days 1 -extfile san.ext -out server.pem >/dev/null 2>&1";
  return std::system(make.c_str()) == 0;
}

}  // namespace

// Issue 52 item 5: TLS checked against a certificate authority the test makes (openssl): the HTTPS
// webhook and SMTP STARTTLS deliver with the CA that signed the server's certificate in ca_file, and
// refuse with a clear error under another CA (nothing reaches the server).
TEST_F(NotifyServers, TlsIsCheckedAgainstTheCaFile) {
  const std::string ca = dir + "/ca.pem", other_ca = dir + "/other_ca.pem", cert = dir + "/server.pem", key = dir + "/server.key";
  ASSERT_TRUE(make_test_ca(dir));
  auto http = start_server("http", http_port, http_log, {"--tls", cert, key});
  auto smtp = start_server("smtp", smtp_port, smtp_log, {"--starttls", cert, key});
  auto yaml = [&](const std::string& ca_file) {
    return "channels:\n  hook: {type: webhook, url: 'https://127.0.0.1:" + std::to_string(http_port) + "/hook', ca_file: " +
           ca_file + ", timeout: 5}\n  mail: {type: smtp, url: 'smtp://127.0.0.1:" + std::to_string(smtp_port) +
           "', from: monitor@test.example, starttls: true, ca_file: " + ca_file + ", timeout: 5}\n"
           "retry: {initial: 0.02, max: 0.1}\nrecipients:\n  - {name: ops, channel: hook}\n"
           "  - {name: curator, channel: mail, to: curator@test.example}\n";
  };
  {
    const NotifyConfig c = parse_notify_config(yaml(other_ca), "tls.yaml");
    EXPECT_TRUE(c.warnings.empty());
    Notifier n(c, dir + "/outbox_other.jsonl", make_channel, 1000.0);
    n.accept(alarm("vase_1", kCommitted, 100.0, 1), 1000.0);
    ASSERT_EQ(n.tick(1000.0), "");
    ASSERT_TRUE(wait_for([&] { return !channel_error(n, "hook").empty() && !channel_error(n, "mail").empty(); }));
    for (const char* ch : {"hook", "mail"}) {
      EXPECT_NE(channel_error(n, ch).find("SSL certificate problem"), std::string::npos) << channel_error(n, ch);
      std::printf("[ refused  ] %s\n", channel_error(n, ch).c_str());
    }
    EXPECT_TRUE(read_log(http_log).empty());
    EXPECT_TRUE(read_log(smtp_log).empty());
  }
  Notifier n(parse_notify_config(yaml(ca), "tls.yaml"), dir + "/outbox.jsonl", make_channel, 1000.0);
  n.accept(alarm("vase_1", kCommitted, 100.0, 1), 1000.0);
  ASSERT_EQ(n.tick(1000.0), "");
  ASSERT_TRUE(wait_for([&] { return read_log(http_log).size() == 1 && read_log(smtp_log).size() == 1; }));
  EXPECT_EQ(read_log(http_log)[0]["alarms"][0]["item"], "vase_1");
  EXPECT_EQ(read_log(smtp_log)[0]["tls"], true);
}

// Issue 52 item 5, the two paths left: smtps:// (TLS from the first byte, aiosmtpd with an SSL context)
// and MQTT over TLS (mosquitto's TLS listener), under the test's CA. Another CA is refused with the
// TLS library's reason and nothing reaches either server; the right one delivers.
TEST_F(NotifyServers, SmtpsAndMqttOverTlsAreCheckedAgainstTheCaFile) {
  const std::string ca = dir + "/ca.pem", other_ca = dir + "/other_ca.pem", cert = dir + "/server.pem", key = dir + "/server.key";
  ASSERT_TRUE(make_test_ca(dir));
  const int tls_port = free_port();
  auto smtp = start_server("smtp", smtp_port, smtp_log, {"--smtps", cert, key});
  auto broker = start_mosquitto_tls(mqtt_port, tls_port, dir, cert, key);
  MqttRecorder rec(mqtt_port, "store/#");  // over the plain listener: what the broker received
  auto yaml = [&](const std::string& ca_file, const std::string& outbox) {
    return "channels:\n  mail: {type: smtp, url: 'smtps://127.0.0.1:" + std::to_string(smtp_port) +
           "', from: monitor@test.example, ca_file: " + ca_file + ", timeout: 5}\n"
           "  bms: {type: mqtt, host: 127.0.0.1, port: " + std::to_string(tls_port) + ", tls: true, ca_file: " + ca_file +
           ", topic_prefix: store, client_id: " + outbox + ", timeout: 5}\n"
           "retry: {initial: 0.02, max: 0.1}\nrecipients:\n  - {name: curator, channel: mail, to: curator@test.example}\n"
           "  - {name: building, channel: bms}\n";
  };
  {
    const NotifyConfig c = parse_notify_config(yaml(other_ca, "other"), "tls.yaml");
    EXPECT_TRUE(c.warnings.empty());
    Notifier n(c, dir + "/outbox_other.jsonl", make_channel, 1000.0);
    n.accept(alarm("vase_1", kCommitted, 100.0, 1), 1000.0);
    ASSERT_EQ(n.tick(1000.0), "");
    ASSERT_TRUE(wait_for([&] { return !channel_error(n, "mail").empty() && !channel_error(n, "bms").empty(); }));
    EXPECT_NE(channel_error(n, "mail").find("SSL certificate problem"), std::string::npos) << channel_error(n, "mail");
    EXPECT_NE(channel_error(n, "bms").find("certificate verify failed"), std::string::npos) << channel_error(n, "bms");
    for (const char* ch : {"mail", "bms"}) std::printf("[ refused  ] %s\n", channel_error(n, ch).c_str());
    EXPECT_TRUE(read_log(smtp_log).empty());
  }
  Notifier n(parse_notify_config(yaml(ca, "right"), "tls.yaml"), dir + "/outbox.jsonl", make_channel, 1000.0);
  n.accept(alarm("vase_1", kCommitted, 100.0, 1), 1000.0);
  ASSERT_EQ(n.tick(1000.0), "");
  ASSERT_TRUE(wait_for([&] { return read_log(smtp_log).size() == 1 && rec.got().count("store/vase_1/state") == 1; }));
  EXPECT_EQ(read_log(smtp_log)[0]["tls"], true);
  EXPECT_EQ(rec.got()["store/vase_1/state"], std::vector<std::string>{"COMMITTED"}) << "the wrong CA's attempt published nothing";
  EXPECT_EQ(channel_error(n, "bms"), "");
}

// MQTT's verify_tls: false: TLS without checking (the test's CA is in no system store), said at start.
TEST_F(NotifyServers, MqttOverTlsWithoutVerificationDeliversAndWarns) {
  const std::string cert = dir + "/server.pem", key = dir + "/server.key";
  ASSERT_TRUE(make_test_ca(dir));
  const int tls_port = free_port();
  auto broker = start_mosquitto_tls(mqtt_port, tls_port, dir, cert, key);
  MqttRecorder rec(mqtt_port, "store/#");
  const NotifyConfig c = parse_notify_config(
      "channels:\n  bms: {type: mqtt, host: 127.0.0.1, port: " + std::to_string(tls_port) +
          ", tls: true, verify_tls: false, topic_prefix: store, timeout: 5}\n"
          "retry: {initial: 0.02, max: 0.1}\nrecipients:\n  - {name: building, channel: bms}\n",
      "tls.yaml");
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("verify_tls: false"), std::string::npos) << c.warnings[0];
  {  // and without tls: true it is plain MQTT: verify_tls there is refused, not silently ignored
    const std::string plain = "channels:\n  bms: {type: mqtt, host: 127.0.0.1, verify_tls: false}\n"
                              "recipients:\n  - {name: building, channel: bms}\n";
    try {
      parse_notify_config(plain, "plain.yaml");
      ADD_FAILURE() << "verify_tls without tls accepted";
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find("only with tls: true"), std::string::npos) << e.what();
    }
  }
  Notifier n(c, dir + "/outbox.jsonl", make_channel, 1000.0);
  n.accept(alarm("vase_1", kCommitted, 100.0, 1), 1000.0);
  ASSERT_EQ(n.tick(1000.0), "");
  ASSERT_TRUE(wait_for([&] { return rec.got().count("store/vase_1/state") == 1; }));
}

// The host name is checked too: a certificate from the right CA but issued for another name is refused.
TEST_F(NotifyServers, MqttOverTlsRefusesACertificateForAnotherHost) {
  ASSERT_TRUE(make_test_ca(dir));
  std::ofstream(dir + "/other.ext") << "subjectAltName=DNS:other.example\n";
  const std::string make = "cd " + dir + " && openssl req -newkey rsa:2048 -nodes -subj /CN=other.example -keyout other.key "
                           "-out other.csr >/dev/null 2>&1 && openssl x509 -req -in other.csr -CA ca.pem -CAkey ca.key "
                           "-CAcreateserial -days 1 -extfile other.ext -out other.pem >/dev/null 2>&1";
  ASSERT_EQ(std::system(make.c_str()), 0) << make;
  const int tls_port = free_port();
  auto broker = start_mosquitto_tls(mqtt_port, tls_port, dir, dir + "/other.pem", dir + "/other.key");
  MqttRecorder rec(mqtt_port, "store/#");
  Notifier n(parse_notify_config("channels:\n  bms: {type: mqtt, host: 127.0.0.1, port: " + std::to_string(tls_port) +
                                     ", tls: true, ca_file: " + dir + "/ca.pem, topic_prefix: store, timeout: 5}\n"
                                     "retry: {initial: 0.02, max: 0.1}\nrecipients:\n  - {name: building, channel: bms}\n",
                                 "tls.yaml"),
             dir + "/outbox.jsonl", make_channel, 1000.0);
  n.accept(alarm("vase_1", kCommitted, 100.0, 1), 1000.0);
  ASSERT_EQ(n.tick(1000.0), "");
  ASSERT_TRUE(wait_for([&] { return !channel_error(n, "bms").empty(); }));
  EXPECT_NE(channel_error(n, "bms").find("host name verification failed"), std::string::npos) << channel_error(n, "bms");
  std::printf("[ refused  ] %s\n", channel_error(n, "bms").c_str());
  EXPECT_TRUE(rec.got().empty());
}
