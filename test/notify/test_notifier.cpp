// The notifier's core without servers: deduplication, the outbox across restarts, grouping, retries.
// The channel here is a recording double whose failures the test switches; the same logic against real
// servers is in test_notify_servers.cpp.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>

#include <nlohmann/json.hpp>

#include "rocking_monitor/notify/channels.hpp"
#include "rocking_monitor/notify/compose.hpp"
#include "rocking_monitor/notify/notifier.hpp"
#include "rocking_monitor/notify/redact.hpp"

using namespace rocking_monitor::notify;

namespace {

const char* kConfig = R"(
window: 10.0
retry: {initial: 0.01, factor: 2.0, max: 0.05}
channels:
  mail: {type: smtp, url: "smtp://127.0.0.1:1", from: monitor@museum.example}
  bms: {type: mqtt, host: 127.0.0.1, topic_prefix: museum}
recipients:
  - {name: curator, channel: mail, to: curator@museum.example, items: ["vase_*"]}
  - {name: facilities, channel: mail, to: facilities@museum.example, levels: [OVERTURNED]}
  - {name: building, channel: bms}
)";

struct Recorded {
  std::mutex mutex;
  std::vector<OutMessage> delivered;
  std::atomic<int> fail_next{0};   // deliveries to refuse, with a server's reply
  std::atomic<int> refuse_next{0};  // deliveries to refuse for good (550), issue 54
  std::atomic<int> attempts{0};     // deliver() calls
  std::vector<OutMessage> of(const std::string& recipient) {
    std::lock_guard<std::mutex> l(mutex);
    std::vector<OutMessage> out;
    for (const auto& m : delivered)
      if (m.recipient == recipient) out.push_back(m);
    return out;
  }
};

class RecordingChannel : public Channel {
 public:
  explicit RecordingChannel(Recorded* r) : r_(r) {}
  std::size_t deliver(const std::vector<OutMessage>& batch, std::string* error) override {
    ++r_->attempts;
    permanent_ = false;
    if (r_->refuse_next > 0) {
      --r_->refuse_next;
      *error = "550 5.1.1 <nobody@museum.example>: Recipient address rejected";
      permanent_ = true;
      return 0;
    }
    if (r_->fail_next > 0) {
      --r_->fail_next;
      *error = "451 4.3.0 mailbox temporarily unavailable";
      return 0;
    }
    std::lock_guard<std::mutex> l(r_->mutex);
    r_->delivered.insert(r_->delivered.end(), batch.begin(), batch.end());
    return batch.size();
  }
  bool refusal_is_permanent() const override { return permanent_; }
  Recorded* r_;
  bool permanent_ = false;
};

NotifyAlarm alarm(const std::string& source, const std::string& item, int level, double t, std::uint64_t seq,
                  const std::string& event = "2026-11-27T10:00:00.000Z/1") {
  NotifyAlarm a;
  a.source = source;
  a.item = item;
  a.description = "item " + item;
  a.level = level;
  a.event_time = t;
  a.stamp_ns = static_cast<std::int64_t>(std::llround(t * 1e9));
  a.event_id = event;
  a.sequence = seq;
  return a;
}

struct NotifierCore : ::testing::Test {
  std::string dir, outbox;
  Recorded rec;
  NotifyConfig config = parse_notify_config(kConfig, "test.yaml");
  void SetUp() override {
    dir = ::testing::TempDir() + "notify_" + std::to_string(::getpid()) + "_" +
          ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::filesystem::remove_all(dir);
    outbox = dir + "/outbox.jsonl";
  }
  void TearDown() override { std::filesystem::remove_all(dir); }
  std::unique_ptr<Notifier> start(double now) {
    return std::make_unique<Notifier>(config, outbox, [this](const ChannelConfig&) { return std::make_unique<RecordingChannel>(&rec); }, now);
  }
};

}  // namespace

TEST(NotifyBackoff, DoublesUpToTheMaximum) {
  NotifyConfig c;
  c.retry_initial = 0.5;
  c.retry_factor = 2.0;
  c.retry_max = 30.0;
  EXPECT_DOUBLE_EQ(backoff_delay(c, 1), 0.5);
  EXPECT_DOUBLE_EQ(backoff_delay(c, 2), 1.0);
  EXPECT_DOUBLE_EQ(backoff_delay(c, 6), 16.0);
  EXPECT_DOUBLE_EQ(backoff_delay(c, 7), 30.0);
  EXPECT_DOUBLE_EQ(backoff_delay(c, 70), 30.0);
}

TEST_F(NotifierCore, FirstCommittedAtOnceTheRestGroupedPerWindow) {
  auto n = start(1000.0);
  // BEYOND_TIPPING alone waits for the window; the COMMITTED that follows takes it along at once.
  EXPECT_EQ(n->accept(alarm("/m", "vase_1", kBeyondTipping, 100.0, 1), 1000.0), Notifier::Accepted::Routed);
  ASSERT_EQ(n->tick(1000.0), "");
  EXPECT_DOUBLE_EQ(n->next_due(), 1010.0);
  n->accept(alarm("/m", "vase_1", kCommitted, 100.2, 2), 1000.2);
  ASSERT_EQ(n->tick(1000.2), "");
  ASSERT_TRUE(n->wait_idle(10));
  auto curator = rec.of("curator");
  ASSERT_EQ(curator.size(), 1u);
  EXPECT_EQ(curator[0].alarms.size(), 2u);
  EXPECT_NE(curator[0].subject.find("1 item COMMITTED, 1 item BEYOND_TIPPING"), std::string::npos) << curator[0].subject;
  EXPECT_NE(curator[0].body.find(instructions(kCommitted)), std::string::npos);
  // Within the window: grouped, sent when the window since the last message ends.
  n->accept(alarm("/m", "vase_2", kCommitted, 101.0, 3), 1001.0);
  n->accept(alarm("/m", "vase_1", kOverturned, 101.5, 4), 1001.5);
  n->accept(alarm("/m", "amphora", kOverturned, 101.6, 5), 1001.6);
  ASSERT_EQ(n->tick(1005.0), "");
  ASSERT_TRUE(n->wait_idle(10));
  EXPECT_EQ(rec.of("curator").size(), 1u);
  EXPECT_EQ(rec.of("facilities").size(), 1u);  // facilities' first OVERTURNED went at once
  EXPECT_DOUBLE_EQ(n->next_due(), 1010.2);     // the curator's group: 10 s after its last message
  ASSERT_EQ(n->tick(1010.1), "");
  ASSERT_TRUE(n->wait_idle(10));
  EXPECT_EQ(rec.of("curator").size(), 1u);
  ASSERT_EQ(n->tick(1010.2), "");
  ASSERT_TRUE(n->wait_idle(10));
  curator = rec.of("curator");
  ASSERT_EQ(curator.size(), 2u);
  EXPECT_EQ(curator[1].alarms.size(), 2u);
  EXPECT_EQ(rec.of("facilities").size(), 1u);
  EXPECT_EQ(rec.of("facilities")[0].alarms.size(), 2u);  // vase_1 and amphora OVERTURNED
  // MQTT: each alarm at once, two retained publications (level topic, state).
  const auto bms = rec.of("building");
  ASSERT_EQ(bms.size(), 10u);
  EXPECT_EQ(bms[2].topic, "museum/vase_1/COMMITTED");
  EXPECT_EQ(bms[3].topic, "museum/vase_1/state");
  EXPECT_EQ(bms[3].body, "COMMITTED");
  EXPECT_TRUE(bms[3].retain);
}

TEST_F(NotifierCore, RepeatsAndThePairsCopiesAreOneAlarm) {
  config.recipients.resize(2);  // the e-mail recipients: an item that is no vase and not OVERTURNED goes to nobody
  auto n = start(1000.0);
  EXPECT_EQ(n->accept(alarm("/a", "vase_1", kCommitted, 100.0, 7), 1000.0), Notifier::Accepted::Routed);
  // a re-sends its journal (restart): same event id and sequence
  EXPECT_EQ(n->accept(alarm("/a", "vase_1", kCommitted, 100.0, 7), 1000.1), Notifier::Accepted::Repeat);
  // b numbers its journal differently; same item, level and stamp within the window
  EXPECT_EQ(n->accept(alarm("/b", "vase_1", kCommitted, 100.004, 3, "2026-11-27T10:00:01.000Z/1"), 1000.1),
            Notifier::Accepted::Merged);
  EXPECT_EQ(n->accept(alarm("/b", "nothing_routes_here", kCommitted, 100.0, 4), 1000.1), Notifier::Accepted::Unrouted);
  ASSERT_EQ(n->tick(1000.2), "");
  ASSERT_TRUE(n->wait_idle(10));
  EXPECT_EQ(rec.of("curator").size(), 1u);
  const auto c = n->counts();
  EXPECT_EQ(c.accepted, 1u);
  EXPECT_EQ(c.repeats, 1u);
  EXPECT_EQ(c.merged, 1u);
  EXPECT_EQ(c.unrouted, 1u);
}

TEST_F(NotifierCore, RestartSendsWhatWasNotAcknowledgedAndRemembersWhatWas) {
  {
    rec.fail_next = 1000000;  // the server refuses everything: nothing acknowledged
    auto n = start(1000.0);
    n->accept(alarm("/a", "vase_1", kCommitted, 100.0, 1), 1000.0);
    ASSERT_EQ(n->tick(1000.0), "");
    n->accept(alarm("/a", "vase_2", kCommitted, 100.5, 2), 1000.5);  // waits for the window: not in a message yet
    ASSERT_EQ(n->tick(1000.5), "");
    // the refusal is reported with the server's reason
    auto mail = [&] {
      for (const auto& s : n->status())
        if (s.name == "mail") return s;
      return Notifier::ChannelStatus{};
    };
    // waits (on the condition, at most 10 s) for the mail channel's first refusal
    for (int i = 0; i < 1000 && mail().failures == 0; ++i) n->wait_idle(0.01);
    EXPECT_NE(mail().last_error.find("451 4.3.0"), std::string::npos) << mail().last_error;
    EXPECT_EQ(mail().queued, 1u);
  }  // "killed": the notifier goes; its outbox stays
  EXPECT_TRUE(rec.of("curator").empty());
  rec.fail_next = 0;
  {
    auto n = start(1001.0);
    // the monitor re-sends its open event to the new subscriber: repeats
    EXPECT_EQ(n->accept(alarm("/a", "vase_1", kCommitted, 100.0, 1), 1001.0), Notifier::Accepted::Repeat);
    EXPECT_EQ(n->accept(alarm("/a", "vase_2", kCommitted, 100.5, 2), 1001.0), Notifier::Accepted::Repeat);
    ASSERT_EQ(n->tick(1001.0), "");
    ASSERT_TRUE(n->wait_idle(10));
    EXPECT_EQ(rec.of("curator").size(), 1u);  // the first message, sent again from the outbox
    ASSERT_EQ(n->tick(1010.0), "");          // the second alarm's group: window after the first message
    ASSERT_TRUE(n->wait_idle(10));
    const auto curator = rec.of("curator");
    ASSERT_EQ(curator.size(), 2u);
    EXPECT_NE(curator[1].body.find("vase_2"), std::string::npos);
    EXPECT_EQ(curator[1].body.find("vase_1"), std::string::npos);
  }
  const std::size_t before = rec.delivered.size();
  {
    auto n = start(1020.0);  // everything acknowledged: a third start sends nothing
    EXPECT_EQ(n->accept(alarm("/a", "vase_1", kCommitted, 100.0, 1), 1020.0), Notifier::Accepted::Repeat);
    ASSERT_EQ(n->tick(1040.0), "");
    ASSERT_TRUE(n->wait_idle(10));
  }
  EXPECT_EQ(rec.delivered.size(), before);
}

TEST_F(NotifierCore, RetriesUntilTheServerTakesIt) {
  rec.fail_next = 3;
  auto n = start(1000.0);
  n->accept(alarm("/a", "vase_1", kOverturned, 100.0, 1), 1000.0);
  ASSERT_EQ(n->tick(1000.0), "");
  ASSERT_TRUE(n->wait_idle(10));
  EXPECT_EQ(rec.of("curator").size(), 1u);
  EXPECT_EQ(rec.of("facilities").size(), 1u);
  std::uint64_t failures = 0;
  for (const auto& s : n->status()) failures += s.failures;
  EXPECT_EQ(failures, 3u);
}

TEST_F(NotifierCore, BurstOfTenThousandItemsIsBoundedPerRecipientAndWindow) {
  config.recipients.resize(2);  // the e-mail recipients
  config.recipients[0].items = {"*"};
  auto n = start(1000.0);
  // 10,000 items over 30 s of shaking, each to COMMITTED then OVERTURNED, ticks every 0.05 s.
  const int items = 10000;
  double now = 1000.0;
  std::uint64_t seq = 0;
  for (int step = 0; step <= 600; ++step, now += 0.05) {
    for (int i = step * items / 600; i < (step + 1) * items / 600 && i < items; ++i) {
      n->accept(alarm("/a", "item_" + std::to_string(i), kCommitted, now - 900, ++seq), now);
      n->accept(alarm("/a", "item_" + std::to_string(i), kOverturned, now - 899.99, ++seq), now);
    }
    ASSERT_EQ(n->tick(now), "");
  }
  ASSERT_EQ(n->tick(now + 10.0), "");
  ASSERT_TRUE(n->wait_idle(30));
  for (const char* r : {"curator", "facilities"}) {
    const auto got = rec.of(r);
    std::size_t alarms = 0;
    for (const auto& m : got) alarms += m.alarms.size();
    // 40 s from the first alarm to the last flush: at most one message per 10 s window, and every alarm in one.
    EXPECT_LE(got.size(), 5u) << r;
    EXPECT_GE(got.size(), 3u) << r;
    EXPECT_EQ(alarms, std::string(r) == "curator" ? 2u * items : 1u * items) << r;
    for (std::size_t k = 1; k < got.size(); ++k) EXPECT_GE(got[k].created - got[k - 1].created, 10.0 - 1e-9);
    EXPECT_NE(got[1].body.find("more (every item is on the dashboard)"), std::string::npos);
  }
}

TEST_F(NotifierCore, CutLastLineIsDroppedWithAWarning) {
  {
    auto n = start(1000.0);
    n->accept(alarm("/a", "vase_1", kCommitted, 100.0, 1), 1000.0);
    ASSERT_EQ(n->tick(1000.0), "");
    ASSERT_TRUE(n->wait_idle(10));
  }
  std::ofstream(outbox, std::ios::app) << R"({"t":"alarm","n":2,"ala)";
  auto n = start(1001.0);
  ASSERT_EQ(n->warnings().size(), 1u);
  EXPECT_NE(n->warnings()[0].find("outbox.jsonl:"), std::string::npos);
  EXPECT_EQ(n->accept(alarm("/a", "vase_1", kCommitted, 100.0, 1), 1001.0), Notifier::Accepted::Repeat);
}

TEST_F(NotifierCore, CorruptOutboxIsAClearError) {
  std::filesystem::create_directories(dir);
  std::ofstream(outbox) << "{\"t\":\"outbox\",\"token\":\"ab\"}\nnot json\n";
  try {
    start(1000.0);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("outbox.jsonl:2: corrupt outbox line"), std::string::npos) << e.what();
  }
}

TEST_F(NotifierCore, MessagesOfARemovedChannelAreDroppedAndSaid) {
  rec.fail_next = 1000000;
  {
    auto n = start(1000.0);
    n->accept(alarm("/a", "vase_1", kOverturned, 100.0, 1), 1000.0);
    ASSERT_EQ(n->tick(1000.0), "");
  }
  rec.fail_next = 0;
  config.channels.erase("bms");
  config.recipients.pop_back();
  auto n = start(1001.0);
  const auto w = n->warnings();
  ASSERT_EQ(w.size(), 2u);  // the two publications of the building's MQTT recipient
  EXPECT_NE(w[0].find("for channel 'bms', no longer configured, dropped"), std::string::npos) << w[0];
  ASSERT_TRUE(n->wait_idle(10));
  EXPECT_EQ(rec.of("curator").size(), 1u);
  EXPECT_EQ(rec.of("facilities").size(), 1u);
  EXPECT_TRUE(rec.of("building").empty());
}

TEST(NotifyCompose, ProbabilityAlarmIsNoItemState) {
  const NotifyConfig c = parse_notify_config(kConfig, "test.yaml");
  OutboxAlarm a;
  a.number = 7;
  a.alarm = alarm("/a", "vase/1", kCommitted, 100.0, 1);
  const auto det = compose_mqtt(c.channels.at("bms"), c.recipients[2], a, kCommitted);
  ASSERT_EQ(det.size(), 2u);
  EXPECT_EQ(det[0].topic, "museum/vase_1/COMMITTED");  // a '/' in an item id is no topic level
  EXPECT_EQ(det[1].topic, "museum/vase_1/state");
  a.alarm.probability = true;
  const auto prob = compose_mqtt(c.channels.at("bms"), c.recipients[2], a, 0);
  ASSERT_EQ(prob.size(), 1u);
  EXPECT_EQ(prob[0].topic, "museum/vase_1/probability/COMMITTED");
}

// Issue 54: an alarm from a topic may carry any bytes. Invalid UTF-8 in its item id or description
// is replaced (U+FFFD) on the outbox's JSON and in the messages, never thrown in the notifier.
TEST_F(NotifierCore, InvalidUtf8InAnAlarmIsReplacedNeverThrown) {
  const std::string bad_id = "vase_\xFF", replaced_id = "vase_\xEF\xBF\xBD";
  NotifyAlarm a = alarm("/m", bad_id, kCommitted, 100.0, 1);
  a.description = "Ming \xC3(";
  std::string line;
  ASSERT_NO_THROW(line = to_json(a));
  EXPECT_NE(line.find(replaced_id), std::string::npos) << line;
  EXPECT_NE(line.find("Ming \xEF\xBF\xBD("), std::string::npos) << line;
  auto n = start(1000.0);
  EXPECT_EQ(n->accept(a, 1000.0), Notifier::Accepted::Routed);
  ASSERT_EQ(n->tick(1000.0), "");
  ASSERT_TRUE(n->wait_idle(10));
  const auto mqtt = rec.of("building");
  ASSERT_FALSE(mqtt.empty());
  EXPECT_NE(mqtt[0].body.find(replaced_id), std::string::npos) << mqtt[0].body;
  ASSERT_EQ(rec.of("curator").size(), 1u);
  n.reset();  // the outbox written above reads back after a restart
  auto again = start(1001.0);
  EXPECT_EQ(again->accept(a, 1001.0), Notifier::Accepted::Repeat);
}

// Issue 54: secrets stay out of errors. The token in a webhook URL's path or query and a
// user:pass@ are redacted, here and in what a failed delivery says (a real connection refused).
TEST(NotifyRedact, UrlsLoseUserInformationPathAndQuery) {
  EXPECT_EQ(redact_url("https://user:pw@hooks.example:8443/services/T0/B0/secret?token=y"), "https://***@hooks.example:8443/***");
  EXPECT_EQ(redact_url("smtp://alice:hunter2@mail.example:587"), "smtp://***@mail.example:587");
  EXPECT_EQ(redact_url("smtps://mail.example:465/"), "smtps://mail.example:465");
  EXPECT_EQ(redact_url("http://127.0.0.1:8080?key=abc"), "http://127.0.0.1:8080/***");
  EXPECT_EQ(redact_url("not a url"), "***");
  EXPECT_EQ(redact_secrets("x https://h/t0k3n y pw", "https://h/t0k3n", "pw"), "x https://h/*** y ***");
}

TEST(NotifyRedact, FailedWebhookDeliverySaysNoToken) {
  // A port nothing listens on: bind one, note it, close it.
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(fd);
  ChannelConfig c;
  c.type = ChannelType::Webhook;
  c.url = "http://ops:s3cr3t@127.0.0.1:" + std::to_string(ntohs(a.sin_port)) + "/hooks/T0/B0/t0k3n?token=abc";
  c.timeout = 5.0;
  OutMessage m;
  m.id = "m1";
  m.body = "{}";
  std::string error;
  EXPECT_EQ(make_webhook_channel(c)->deliver({m}, &error), 0u);
  EXPECT_EQ(error.rfind("http://***@127.0.0.1:" + std::to_string(ntohs(a.sin_port)) + "/***: ", 0), 0u) << error;
  for (const char* secret : {"s3cr3t", "t0k3n", "abc", "ops"}) EXPECT_EQ(error.find(secret), std::string::npos) << error;
}

// Issue 54: a permanent refusal (550) is not retried: the message is closed as failed in the outbox
// (with the reason), said in the channel's status, and the recipient's next message goes out.
TEST_F(NotifierCore, PermanentRefusalIsMarkedFailedAndNotRetried) {
  config.recipients.resize(2);  // the mail channel alone: the refusal is the curator's first message
  rec.refuse_next = 1;
  {
    auto n = start(1000.0);
    n->accept(alarm("/m", "vase_1", kCommitted, 100.0, 1), 1000.0);
    ASSERT_EQ(n->tick(1000.0), "");
    ASSERT_TRUE(n->wait_idle(10));  // the refused message left the queue: no backoff, no retry
    EXPECT_TRUE(rec.of("curator").empty());
    const int attempts_after_refusal = rec.attempts.load();
    n->accept(alarm("/m", "vase_2", kOverturned, 200.0, 2, "2026-11-27T10:05:00.000Z/1"), 1100.0);
    ASSERT_EQ(n->tick(1100.0), "");
    ASSERT_TRUE(n->wait_idle(10));
    ASSERT_EQ(rec.of("curator").size(), 1u);  // the next message was not held up
    EXPECT_NE(rec.of("curator")[0].subject.find("OVERTURNED"), std::string::npos);
    EXPECT_GT(rec.attempts.load(), attempts_after_refusal);
    std::uint64_t refused = 0;
    std::string last_error;
    for (const auto& s : n->status())
      if (s.name == "mail") refused = s.refused, last_error = s.last_error;
    EXPECT_EQ(refused, 1u);
    EXPECT_NE(last_error.find("refused for good, not retried: message "), std::string::npos) << last_error;
    EXPECT_NE(last_error.find("to curator: 550 5.1.1"), std::string::npos) << last_error;
  }
  std::ifstream in(outbox);
  std::string line, failed_line;
  int failed_lines = 0;
  while (std::getline(in, line))
    if (line.find("\"t\":\"failed\"") != std::string::npos) ++failed_lines, failed_line = line;
  EXPECT_EQ(failed_lines, 1);
  EXPECT_NE(failed_line.find("Recipient address rejected"), std::string::npos) << failed_line;
  // After a restart the failed message is not sent again.
  const std::size_t curator_before = rec.of("curator").size();
  auto again = start(1200.0);
  ASSERT_TRUE(again->wait_idle(10));
  EXPECT_EQ(rec.of("curator").size(), curator_before);
}

// Issue 51: an item that slid off its plinth is OVERTURNED (routing reads the level) and every message
// says why: the e-mail's subject and line, the webhook's text and its alarm's "cause", the MQTT alarm.
// An item that overturned by rocking says nothing of a support ("cause": "rocking").
TEST(NotifyCompose, AnItemThatFellOffItsSupportSaysSoInEveryMessage) {
  const NotifyConfig c = parse_notify_config(R"(
channels:
  mail: {type: smtp, url: "smtp://127.0.0.1:1", from: monitor@museum.example}
  chat: {type: webhook, url: "http://127.0.0.1:8080/hook"}
  bms: {type: mqtt, host: 127.0.0.1, topic_prefix: museum}
recipients:
  - {name: curator, channel: mail, to: curator@museum.example}
  - {name: chat, channel: chat}
  - {name: building, channel: bms}
)", "cause.yaml");
  OutboxAlarm off, rocked;
  off.number = 1;
  off.alarm = alarm("/a", "bust", kOverturned, 100.0, 1);
  off.alarm.cause = rocking_monitor::core::AlarmCause::FellOffSupport;
  rocked.number = 2;
  rocked.alarm = alarm("/a", "amphora", kOverturned, 101.0, 2);

  const OutMessage mail = compose_group(c, c.recipients[0], {&off});
  EXPECT_EQ(mail.subject, "[" + c.site + "] 1 item OVERTURNED: bust (fell off its support)");
  EXPECT_NE(mail.body.find("  - bust (item bust) at 1970-01-01T00:01:40.000Z: fell off its support (slid or tipped "
                           "over the edge of its plinth, shelf or pedestal"),
            std::string::npos)
      << mail.body;
  const OutMessage both = compose_group(c, c.recipients[0], {&off, &rocked});
  EXPECT_NE(both.body.find("  - amphora (item amphora) at 1970-01-01T00:01:41.000Z\n"), std::string::npos) << both.body;

  const nlohmann::json hook = nlohmann::json::parse(compose_group(c, c.recipients[1], {&off, &rocked}).body);
  ASSERT_EQ(hook.at("alarms").size(), 2u);
  EXPECT_EQ(hook["alarms"][0].at("item"), "bust");
  EXPECT_EQ(hook["alarms"][0].at("level"), "OVERTURNED");
  EXPECT_EQ(hook["alarms"][0].at("cause"), "fell_off_support");
  EXPECT_EQ(hook["alarms"][1].at("cause"), "rocking");
  EXPECT_NE(hook.at("text").get<std::string>().find("bust (item bust) at 1970-01-01T00:01:40.000Z: fell off its support"),
            std::string::npos);
  EXPECT_EQ(hook.at("text").get<std::string>().find("amphora (item amphora) at 1970-01-01T00:01:41.000Z: fell"),
            std::string::npos);

  const auto mqtt = compose_mqtt(c.channels.at("bms"), c.recipients[2], off, kOverturned);
  ASSERT_EQ(mqtt.size(), 2u);
  EXPECT_EQ(mqtt[0].topic, "museum/bust/OVERTURNED");  // the same topics: subscribers keep working
  EXPECT_EQ(nlohmann::json::parse(mqtt[0].body).at("cause"), "fell_off_support");
  EXPECT_EQ(mqtt[1].body, "OVERTURNED");
}

// The cause of an alarm still waiting for its group is in the outbox: a notifier restarted before the
// group is sent still says the item fell off its support.
TEST_F(NotifierCore, TheCauseOfAWaitingAlarmSurvivesARestart) {
  {
    auto n = start(1000.0);
    n->accept(alarm("/m", "amphora", kOverturned, 100.0, 1), 1000.0);  // facilities' first: at once
    ASSERT_EQ(n->tick(1000.0), "");
    ASSERT_TRUE(n->wait_idle(10));
    NotifyAlarm off = alarm("/m", "bust", kOverturned, 100.5, 2);
    off.cause = rocking_monitor::core::AlarmCause::FellOffSupport;
    n->accept(off, 1000.5);  // waits for the window
    ASSERT_EQ(n->tick(1000.5), "");
    ASSERT_TRUE(n->wait_idle(10));
  }
  ASSERT_EQ(rec.of("facilities").size(), 1u);
  EXPECT_EQ(rec.of("facilities")[0].body.find("fell off"), std::string::npos);
  auto n = start(1001.0);
  ASSERT_EQ(n->tick(1010.0), "");
  ASSERT_TRUE(n->wait_idle(10));
  const auto facilities = rec.of("facilities");
  ASSERT_EQ(facilities.size(), 2u);
  EXPECT_NE(facilities[1].body.find("  - bust (item bust) at 1970-01-01T00:01:40.500Z: fell off its support"),
            std::string::npos)
      << facilities[1].body;
}
