// The notifier's routing configuration: the shipped example parses to what its comments say, and each
// kind of bad value is one error naming the file, the line and the field.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "rocking_monitor/notify/notify_config.hpp"
#include "rocking_monitor/notify/notify_alarm.hpp"

using namespace rocking_monitor::notify;

namespace {

const char* kGood = R"(
site: Museum store
window: 10.0
channels:
  mail: {type: smtp, url: "smtp://127.0.0.1:2525", from: monitor@museum.example}
  chat: {type: webhook, url: "http://127.0.0.1:8080/hook"}
  bms: {type: mqtt, host: 127.0.0.1, port: 1883, topic_prefix: museum/rocking}
recipients:
  - {name: curator, channel: mail, to: curator@museum.example, items: ["vase_*"], levels: [COMMITTED, OVERTURNED]}
  - {name: facilities, channel: mail, to: facilities@museum.example, levels: [OVERTURNED]}
  - {name: officer, channel: mail, to: safety@museum.example, digest: true, digest_window: 120}
  - {name: chat, channel: chat}
  - {name: building, channel: bms}
)";

// The error text of parsing `yaml` (empty if it parses).
std::string error_of(const std::string& yaml) {
  try {
    parse_notify_config(yaml, "notify.yaml");
  } catch (const NotifyConfigError& e) {
    return e.what();
  }
  return "";
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

}  // namespace

TEST(NotifyConfig, ParsesChannelsAndRouting) {
  const NotifyConfig c = parse_notify_config(kGood, "notify.yaml");
  EXPECT_EQ(c.site, "Museum store");
  ASSERT_EQ(c.channels.size(), 3u);
  EXPECT_EQ(c.channels.at("bms").type, ChannelType::Mqtt);
  EXPECT_EQ(c.channels.at("bms").topic_prefix, "museum/rocking");
  EXPECT_EQ(channel_host(c.channels.at("mail")), "127.0.0.1");
  ASSERT_EQ(c.recipients.size(), 5u);
  const auto& curator = c.recipients[0];
  EXPECT_TRUE(curator.wants("vase_ming", kCommitted, false));
  EXPECT_FALSE(curator.wants("vase_ming", kBeyondTipping, false));
  EXPECT_FALSE(curator.wants("amphora_1", kOverturned, false));
  EXPECT_TRUE(c.recipients[1].wants("amphora_1", kOverturned, true));
  EXPECT_FALSE(c.recipients[1].wants("amphora_1", kCommitted, false));
  EXPECT_TRUE(c.recipients[2].digest);
  EXPECT_DOUBLE_EQ(c.recipients[2].digest_window, 120.0);
  EXPECT_TRUE(c.recipients[3].wants("anything", kBeyondTipping, false));
}

TEST(NotifyConfig, ShippedExampleParses) {
  const NotifyConfig c = load_notify_config(std::string(ROCKING_SOURCE_DIR) + "/config/notify.yaml");
  EXPECT_FALSE(c.recipients.empty());
  EXPECT_EQ(c.channels.size(), 3u);
}

TEST(NotifyConfig, BadValuesNameFileLineAndField) {
  struct Case {
    std::string from, to, expected;
  } cases[] = {
      {"channel: mail, to: facilities", "channel: mial, to: facilities", "notify.yaml:10: recipients[1].channel: unknown channel 'mial' (defined: bms, chat, mail)"},
      {"to: curator@museum.example", "to: curator.museum.example", "notify.yaml:9: recipients[0].to: bad e-mail address 'curator.museum.example'"},
      {"from: monitor@museum.example", "from: monitor@", "notify.yaml:5: channels.mail.from: bad e-mail address 'monitor@'"},
      {"type: webhook, url: \"http://127.0.0.1:8080/hook\"", "type: webhook, url: \"ftp://x/hook\"", "notify.yaml:6: channels.chat.url: bad URL 'ftp://x/***'"},
      {"type: mqtt", "type: mqtq", "notify.yaml:7: channels.bms.type: unknown channel type 'mqtq' (smtp, webhook or mqtt)"},
      {"port: 1883", "port: 99999", "notify.yaml:7: channels.bms.port: must be 1..65535, got 99999"},
      {"levels: [OVERTURNED]", "levels: [FALLEN]", "notify.yaml:10: recipients[1].levels[0]: unknown level 'FALLEN'"},
      {"window: 10.0", "window: -1", "notify.yaml:3: window: must be a positive number of seconds"},
      {"window: 10.0", "windw: 10.0", "notify.yaml:3: windw: unknown key"},
      {"digest: true", "digest: maybe", "notify.yaml:11: recipients[2].digest: not a boolean (true/false): 'maybe'"},
      {"{name: chat, channel: chat}", "{name: chat, channel: chat, to: a@b.c}", "notify.yaml:12: recipients[3].to: only for an smtp channel ('chat' is webhook)"},
      {"{name: building, channel: bms}", "{name: chat, channel: bms}", "notify.yaml:13: recipients[4].name: 'chat' is used twice"},
  };
  for (const auto& c : cases) {
    const std::string e = error_of(replaced(kGood, c.from, c.to));
    EXPECT_EQ(e.rfind(c.expected, 0), 0u) << "expected: " << c.expected << "\n     got: " << e;
  }
  EXPECT_NE(error_of("channels: {}\n").find("channels: missing or empty"), std::string::npos) << error_of("channels: {}\n");
  EXPECT_NE(error_of("site: [unclosed\n").find("notify.yaml:"), std::string::npos);
}

TEST(NotifyConfig, UnknownHostIsAnErrorNamingTheField) {
  NotifyConfig c = parse_notify_config(replaced(kGood, "host: 127.0.0.1", "host: no-such-broker.invalid"), "notify.yaml");
  try {
    check_hosts(c);
    FAIL() << "no error for an unresolvable host";
  } catch (const NotifyConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("notify.yaml: channels.bms.host: host 'no-such-broker.invalid' not found", 0), 0u) << e.what();
  }
  EXPECT_NO_THROW(check_hosts(parse_notify_config(kGood, "notify.yaml")));
}

// Issue 52 item 5: a password comes from a file only its owner can read, or from the environment;
// inline it works but is said at every start, as verify_tls: false is. Each refusal names the file,
// the line and the field, and says why.
TEST(NotifyConfig, PasswordsFromAPrivateFileOrTheEnvironment) {
  const std::string dir = ::testing::TempDir() + "notify_secrets_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  const std::string secret = dir + "/smtp_password", open_secret = dir + "/open_password";
  std::ofstream(secret) << "s3cret word\n";
  std::ofstream(open_secret) << "s3cret\n";
  std::filesystem::permissions(secret, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
  std::filesystem::permissions(open_secret, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write |
                                                std::filesystem::perms::group_read | std::filesystem::perms::others_read);
  const std::string mail = "from: monitor@museum.example}";
  const std::string config = dir + "/notify.yaml";  // relative paths are beside the configuration
  auto parsed = [&](const std::string& keys) { return parse_notify_config(replaced(kGood, mail, "from: monitor@museum.example, " + keys + "}"), config); };

  EXPECT_EQ(parsed("username: m, password_file: " + secret).channels.at("mail").password, "s3cret word");
  EXPECT_EQ(parsed("username: m, password_file: smtp_password").channels.at("mail").password, "s3cret word");
  EXPECT_TRUE(parsed("password_file: smtp_password").warnings.empty());
  ::setenv("ROCKING_TEST_SMTP_PASSWORD", "from the environment", 1);
  EXPECT_EQ(parsed("password_env: ROCKING_TEST_SMTP_PASSWORD").channels.at("mail").password, "from the environment");
  const NotifyConfig inline_password = parsed("password: typed");
  EXPECT_EQ(inline_password.channels.at("mail").password, "typed");
  ASSERT_EQ(inline_password.warnings.size(), 1u);
  EXPECT_EQ(inline_password.warnings[0], config + ": channels.mail.password: inline in the configuration: prefer "
                                          "password_file (mode 0600) or password_env");

  auto refusal = [&](const std::string& keys) {
    try {
      parsed(keys);
    } catch (const NotifyConfigError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(refusal("password_file: " + open_secret), config + ":5: channels.mail.password_file: password file '" +
                                                          open_secret + "' is accessible to group or others (mode 0644): chmod 600 it");
  EXPECT_EQ(refusal("password_file: missing"), config + ":5: channels.mail.password_file: password file '" + dir +
                                                   "/missing': No such file or directory");
  ::unsetenv("ROCKING_TEST_NO_SUCH_VARIABLE");
  EXPECT_EQ(refusal("password_env: ROCKING_TEST_NO_SUCH_VARIABLE"),
            config + ":5: channels.mail.password_env: environment variable 'ROCKING_TEST_NO_SUCH_VARIABLE' is not set or empty");
  EXPECT_EQ(refusal("password: a, password_file: smtp_password"),
            config + ":5: channels.mail.password_file: give one of password, password_file, password_env, not password too");
  std::ofstream(secret) << "two\nlines\n";
  EXPECT_EQ(refusal("password_file: smtp_password"),
            config + ":5: channels.mail.password_file: password file '" + secret + "' has more than one line");
  std::filesystem::remove_all(dir);
}

TEST(NotifyConfig, VerifyTlsFalseIsSaidAndAMissingCaFileRefused) {
  const NotifyConfig c = parse_notify_config(replaced(kGood, "url: \"http://127.0.0.1:8080/hook\"",
                                                      "url: \"https://127.0.0.1:8443/hook\", verify_tls: false"),
                                             "notify.yaml");
  EXPECT_FALSE(c.channels.at("chat").verify_tls);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0], "notify.yaml: channels.chat.verify_tls: false: the server's certificate is not checked, so "
                           "anyone between here and the server can read and change the alarms");
  EXPECT_TRUE(parse_notify_config(kGood, "notify.yaml").warnings.empty());
  EXPECT_EQ(error_of(replaced(kGood, "url: \"http://127.0.0.1:8080/hook\"", "url: \"https://h:1/x\", ca_file: /no/such/ca.pem")),
            "notify.yaml:6: channels.chat.ca_file: cannot read '/no/such/ca.pem'");
}
