// An e-mail's text with headers that outside text cannot add to (mail_text.hpp).
#include "rocking_monitor/notify/mail_text.hpp"

#include <algorithm>

#include "rocking_monitor/safe_text.hpp"

namespace rocking_monitor::notify {
namespace {

bool ascii(std::string_view s) {
  return std::all_of(s.begin(), s.end(), [](unsigned char ch) { return ch < 128; });
}

std::string base64(std::string_view s) {
  static const char* b64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  const auto byte = [&](std::size_t k) { return static_cast<unsigned>(static_cast<unsigned char>(s[k])); };
  for (; i + 2 < s.size(); i += 3) {
    const unsigned v = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
    out += {b64[v >> 18], b64[(v >> 12) & 63], b64[(v >> 6) & 63], b64[v & 63]};
  }
  if (i + 1 == s.size()) {
    const unsigned v = byte(i) << 16;
    out += {b64[v >> 18], b64[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == s.size()) {
    const unsigned v = byte(i) << 16 | byte(i + 1) << 8;
    out += {b64[v >> 18], b64[(v >> 12) & 63], b64[(v >> 6) & 63], '='};
  }
  return out;
}

// "\n" line ends as CRLF, bare CRs dropped: SMTP's line ends, and no CR that a server might read as one.
std::string crlf(const std::string& text) {
  std::string out;
  out.reserve(text.size() + text.size() / 40);
  for (char ch : text) {
    if (ch == '\n') out += "\r\n";
    else if (ch != '\r') out += ch;
  }
  return out;
}

}  // namespace

std::string header_line(std::string_view text) {
  std::string out = valid_utf8(text);
  std::replace_if(out.begin(), out.end(), [](char ch) {
    const auto c = static_cast<unsigned char>(ch);
    return c < 0x20 || c == 0x7F;
  }, ' ');
  return out;
}

std::string header_text(std::string_view text) {
  const std::string line = header_line(text);
  if (ascii(line)) return line;
  // 45 bytes make 60 base64 characters: "=?UTF-8?B?" + 60 + "?=" = 72 <= 75 (RFC 2047 section 2).
  // A word ends between characters (a UTF-8 sequence is never split across two words, section 5).
  constexpr std::size_t kWordBytes = 45;
  std::string out;
  for (std::size_t at = 0; at < line.size();) {
    std::size_t end = std::min(line.size(), at + kWordBytes);
    while (end < line.size() && (static_cast<unsigned char>(line[end]) & 0xC0) == 0x80) --end;  // continuation byte
    if (!out.empty()) out += "\r\n ";
    out += "=?UTF-8?B?" + base64(std::string_view(line).substr(at, end - at)) + "?=";
    at = end;
  }
  return out;
}

std::string mail_text(const MailFields& m) {
  // The header values go in after crlf() has run over the rest: header_text's folds are CRLF already
  // and header_line leaves no line end to convert.
  std::string head = "Date: " + header_line(m.date) + "\r\nFrom: " + header_line(m.from) + "\r\nTo: " +
                     header_line(m.to) + "\r\nSubject: " + header_text(m.subject) + "\r\nMessage-ID: <" +
                     header_line(m.id) + "@rocking-monitor>\r\nMIME-Version: 1.0\r\nContent-Type: text/plain; " +
                     "charset=utf-8\r\nContent-Transfer-Encoding: 8bit\r\nX-Rocking-Monitor-Recipient: " +
                     header_text(m.recipient) + "\r\n\r\n";
  return head + crlf(m.body);
}

}  // namespace rocking_monitor::notify
