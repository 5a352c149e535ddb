// Outside text in e-mail headers and MQTT topics (issue 52 item 6, issue 54): one line per header
// whatever the text, RFC 2047 words within 75 characters that decode to the text, and one topic
// level per item id. The same through real servers: test_notify_servers.cpp.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rocking_monitor/notify/compose.hpp"
#include "rocking_monitor/notify/mail_text.hpp"

using namespace rocking_monitor::notify;

namespace {

std::vector<std::string> lines(const std::string& text) {  // split at CRLF
  std::vector<std::string> out;
  std::size_t at = 0;
  for (std::size_t end; (end = text.find("\r\n", at)) != std::string::npos; at = end + 2) out.push_back(text.substr(at, end - at));
  out.push_back(text.substr(at));
  return out;
}

std::string unbase64(const std::string& s) {
  const std::string b64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  unsigned v = 0;
  int bits = 0;
  for (char ch : s) {
    if (ch == '=') break;
    v = (v << 6) | static_cast<unsigned>(b64.find(ch));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += static_cast<char>((v >> bits) & 0xFF);
    }
  }
  return out;
}

MailFields fields(const std::string& subject) {
  return {"Sun, 29 Nov 2026 08:00:00 +0000", "monitor@museum.example", "curator@museum.example", subject,
          "1764403200.7", "curator", "line 1\nline 2\n"};
}

}  // namespace

TEST(MailText, ALineEndInASubjectAddsNoHeader) {
  const std::string text = mail_text(fields("[Museum] 1 item COMMITTED: vase\r\nBcc: x@evil.example\n\nbody?\rZ"));
  const auto l = lines(text);
  std::vector<std::string> names;
  std::size_t blank = 0;
  for (; blank < l.size() && !l[blank].empty(); ++blank) names.push_back(l[blank].substr(0, l[blank].find(':')));
  EXPECT_EQ(names, (std::vector<std::string>{"Date", "From", "To", "Subject", "Message-ID", "MIME-Version",
                                             "Content-Type", "Content-Transfer-Encoding", "X-Rocking-Monitor-Recipient"}));
  EXPECT_EQ(l[3], "Subject: [Museum] 1 item COMMITTED: vase  Bcc: x@evil.example  body? Z");
  ASSERT_EQ(l.size(), blank + 4);
  EXPECT_EQ(l[blank + 1], "line 1");
  EXPECT_EQ(l[blank + 2], "line 2");
  for (std::size_t i = 0; i < text.size(); ++i) {  // every CR begins a CRLF, every LF ends one
    if (text[i] == '\r') EXPECT_EQ(text[i + 1], '\n') << i;
    if (text[i] == '\n') EXPECT_EQ(text[i - 1], '\r') << i;
  }
}

TEST(MailText, HeaderLineKeepsOneLineOfValidUtf8) {
  EXPECT_EQ(header_line("a\tb\x7F" "c\x01"), "a b c ");
  EXPECT_EQ(header_line("vase_\xFF"), "vase_\xEF\xBF\xBD");
  EXPECT_EQ(header_line("curator@museum.example"), "curator@museum.example");
}

// A long non-ASCII subject: encoded words of at most 75 characters on folded lines, each word whole
// UTF-8 (no character cut between two words), and together the subject again.
TEST(MailText, NonAsciiSubjectIsEncodedWordsThatDecodeToIt) {
  std::string subject = "[Musée] 3 items COMMITTED: ";
  for (int i = 0; i < 20; ++i) subject += "vase_é€𝄞" + std::to_string(i) + " ";
  const std::string h = header_text(subject);
  const auto folded = lines(h);
  ASSERT_GT(folded.size(), 3u);
  std::string decoded;
  for (std::size_t i = 0; i < folded.size(); ++i) {
    std::string w = folded[i];
    if (i > 0) {
      ASSERT_EQ(w[0], ' ') << "a continuation line starts with white space";
      w = w.substr(1);
    }
    EXPECT_LE(w.size(), 75u) << w;
    ASSERT_EQ(w.rfind("=?UTF-8?B?", 0), 0u) << w;
    ASSERT_EQ(w.substr(w.size() - 2), "?=") << w;
    const std::string part = unbase64(w.substr(10, w.size() - 12));
    EXPECT_EQ(header_line(part), part) << "word " << i << " cuts a character";
    decoded += part;
  }
  EXPECT_EQ(decoded, subject);
  EXPECT_EQ(header_text("plain ASCII"), "plain ASCII");
  EXPECT_EQ(header_text("a\nb\xC3"), "=?UTF-8?B?" "YSBi77+9" "?=");  // "a b" + U+FFFD
}

TEST(MailText, AnMqttTopicLevelIsOneLevel) {
  EXPECT_EQ(mqtt_topic_level("vase_1"), "vase_1");
  EXPECT_EQ(mqtt_topic_level("a/b+c#d"), "a_b_c_d");
  EXPECT_EQ(mqtt_topic_level(std::string("nul\0x\r\n", 7)), "nul_x__");
  EXPECT_EQ(mqtt_topic_level("vase_\xFF"), "vase_\xEF\xBF\xBD");
  EXPECT_EQ(mqtt_topic_level(""), "_");
  EXPECT_EQ(mqtt_topic_level("Musée"), "Musée");
}
