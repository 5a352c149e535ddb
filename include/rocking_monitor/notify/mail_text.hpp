#pragma once

// An e-mail as the SMTP channel sends it (issue 52 item 6, issue 54): headers and body with CRLF line
// ends. Header values carry text from outside (an item id from an alarm topic, a site name): a CR or
// LF in one would end its header and start another (a forged Bcc, Content-Type or an early body), so
// every header value is one line of valid UTF-8, and non-ASCII text is RFC 2047 encoded words.

#include <string>
#include <string_view>

namespace rocking_monitor::notify {

/// A header value on one line: invalid UTF-8 replaced (U+FFFD), every control character (C0 with CR,
/// LF and TAB, and DEL) a space. For addresses and ids, which stay as they are otherwise.
std::string header_line(std::string_view text);

/// Free text for a header (subject, a name): header_line(), then, when not ASCII, RFC 2047 "B" encoded
/// words of at most 75 characters each, cut between characters, folded onto continuation lines ("\r\n ").
std::string header_text(std::string_view text);

struct MailFields {
  std::string date;       ///< RFC 5322 date, e.g. "Sun, 29 Nov 2026 08:00:00 +0000"
  std::string from, to;   ///< addresses
  std::string subject;    ///< free text
  std::string id;         ///< the outbox's message id (Message-ID <id@rocking-monitor>)
  std::string recipient;  ///< the recipient's name in the routing (X-Rocking-Monitor-Recipient)
  std::string body;       ///< plain text, UTF-8; "\n" line ends
};

/// The message as uploaded: the headers (each value through header_line or header_text), a blank
/// line, the body; every line end CRLF, no bare CR.
std::string mail_text(const MailFields& m);

}  // namespace rocking_monitor::notify
