#pragma once

// Text that came from outside (a catalogue, a topic, a server's reply) made safe for where it goes
// (issue 54): valid UTF-8 for JSON and ROS strings, no control characters for one-line logs and
// /diagnostics. One bad byte must never throw inside a callback nor rewrite a log's lines.
// Header-only and dependency-free so that every layer (feeds included) can use it.

#include <cstddef>
#include <string>
#include <string_view>

namespace rocking_monitor {

namespace safe_text_detail {
// Length of the well-formed UTF-8 sequence at s[i] (1..4), or 0 when it is not one (overlong forms,
// surrogates and code points above U+10FFFF are not well-formed, as RFC 3629 says).
inline std::size_t utf8_sequence_length(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  if (c < 0x80) return 1;
  std::size_t n = 0;
  unsigned char lo = 0x80, hi = 0xBF;  // the range of the second byte
  if (c >= 0xC2 && c <= 0xDF) n = 2;
  else if (c == 0xE0) n = 3, lo = 0xA0;
  else if (c >= 0xE1 && c <= 0xEC) n = 3;
  else if (c == 0xED) n = 3, hi = 0x9F;
  else if (c >= 0xEE && c <= 0xEF) n = 3;
  else if (c == 0xF0) n = 4, lo = 0x90;
  else if (c >= 0xF1 && c <= 0xF3) n = 4;
  else if (c == 0xF4) n = 4, hi = 0x8F;
  else return 0;
  if (i + n > s.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  return n;
}
}  // namespace safe_text_detail

/// True when the text is well-formed UTF-8.
inline bool is_valid_utf8(std::string_view s) {
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t n = safe_text_detail::utf8_sequence_length(s, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

/// The text with every byte that is not part of well-formed UTF-8 replaced by U+FFFD, as
/// nlohmann::json's error_handler_t::replace does: valid text comes back unchanged.
inline std::string valid_utf8(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t n = safe_text_detail::utf8_sequence_length(s, i);
    if (n == 0) {
      out += "\xEF\xBF\xBD";
      ++i;
    } else {
      out.append(s.data() + i, n);
      i += n;
    }
  }
  return out;
}

/// Server or user text for a log line or /diagnostics: valid UTF-8, each control character
/// (C0, DEL) written as \xNN so that it cannot forge a line, move a terminal's cursor or ring
/// its bell, and at most `max_bytes` bytes of the input kept ("..." says it was cut).
inline std::string printable_text(std::string_view s, std::size_t max_bytes = 512) {
  const bool cut = s.size() > max_bytes;
  const std::string valid = valid_utf8(cut ? s.substr(0, max_bytes) : s);
  static const char* const hex = "0123456789ABCDEF";
  std::string out;
  out.reserve(valid.size());
  for (const char ch : valid) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7F) {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 0xF];
    } else {
      out += ch;
    }
  }
  if (cut) out += "...";
  return out;
}

}  // namespace rocking_monitor
