// Parsing one UDP datagram into a sample: the text form "time,ax,ay,az" and the 48-byte binary form
// (layout in udp_datagram.hpp). Little-endian is decoded byte by byte, so the host's byte order
// does not matter; strict numbers (std::from_chars, whole field), nothing allocated.
#include "rocking_monitor/feeds/udp_datagram.hpp"

#include <charconv>
#include <cmath>
#include <cstring>
#include <system_error>

namespace rocking_monitor::feeds {

namespace {

std::uint64_t le_u64(const unsigned char* p) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

double le_f64(const unsigned char* p) {
  const std::uint64_t bits = le_u64(p);
  double d = 0.0;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}

void put_u64(std::uint64_t v, unsigned char* p) {
  for (int i = 0; i < 8; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}

bool is_blank(char c) { return c == ' ' || c == '\t'; }

/// One text field (blanks around it allowed) as a double; false when it is not a whole number.
bool parse_field(const char* b, const char* e, double& out) {
  while (b < e && is_blank(*b)) ++b;
  while (e > b && is_blank(e[-1])) --e;
  if (b == e) return false;
  if (*b == '+') ++b;  // from_chars does not take a leading '+'
  const auto r = std::from_chars(b, e, out, std::chars_format::general);
  return r.ec == std::errc() && r.ptr == e;
}

}  // namespace

const char* to_string(DatagramError error) {
  switch (error) {
    case DatagramError::None:
      return "none";
    case DatagramError::Empty:
      return "empty datagram";
    case DatagramError::BinarySize:
      return "binary: not 48 bytes";
    case DatagramError::BinaryVersion:
      return "binary: unknown version";
    case DatagramError::TextFields:
      return "text: not 4 comma-separated fields (time,ax,ay,az)";
    case DatagramError::TextNumber:
      return "text: a field is not a number";
    case DatagramError::NonFinite:
      return "a value is NaN or infinite";
  }
  return "unknown";
}

DatagramError parse_datagram(const char* data, std::size_t size, AccelSample& out) {
  if (size == 0) return DatagramError::Empty;
  const auto* u = reinterpret_cast<const unsigned char*>(data);
  if (size >= 4 && std::memcmp(data, kBinaryMagic, 4) == 0) {
    if (size != kBinarySize) return DatagramError::BinarySize;
    const unsigned version = static_cast<unsigned>(u[4]) | (static_cast<unsigned>(u[5]) << 8);
    if (version != kBinaryVersion) return DatagramError::BinaryVersion;
    AccelSample s;
    s.has_sequence = true;
    s.sequence = le_u64(u + 8);
    s.time_s = le_f64(u + 16);
    for (int k = 0; k < 3; ++k) s.accel[k] = le_f64(u + 24 + 8 * k);
    if (!std::isfinite(s.time_s) || !std::isfinite(s.accel[0]) || !std::isfinite(s.accel[1]) ||
        !std::isfinite(s.accel[2])) {
      return DatagramError::NonFinite;
    }
    out = s;
    return DatagramError::None;
  }
  // text: drop one trailing line break
  std::size_t n = size;
  if (n > 0 && data[n - 1] == '\n') --n;
  if (n > 0 && data[n - 1] == '\r') --n;
  double v[4];
  std::size_t field = 0;
  const char* b = data;
  const char* end = data + n;
  for (const char* p = data;; ++p) {
    if (p == end || *p == ',') {
      if (field == 4) return DatagramError::TextFields;
      if (!parse_field(b, p, v[field])) {
        // NaN / inf are numbers to from_chars: tell them apart from garbage below
        return DatagramError::TextNumber;
      }
      ++field;
      b = p + 1;
      if (p == end) break;
    } else if (*p == '\n' || *p == '\r' || *p == '\0') {
      return DatagramError::TextFields;  // one sample per datagram
    }
  }
  if (field != 4) return DatagramError::TextFields;
  for (double x : v) {
    if (!std::isfinite(x)) return DatagramError::NonFinite;
  }
  out = AccelSample{};
  out.time_s = v[0];
  out.accel[0] = v[1];
  out.accel[1] = v[2];
  out.accel[2] = v[3];
  return DatagramError::None;
}

void encode_binary(std::uint64_t sequence, double time_s, const double accel[3], unsigned char* buffer) {
  std::memcpy(buffer, kBinaryMagic, 4);
  buffer[4] = static_cast<unsigned char>(kBinaryVersion & 0xff);
  buffer[5] = static_cast<unsigned char>(kBinaryVersion >> 8);
  buffer[6] = 0;
  buffer[7] = 0;
  put_u64(sequence, buffer + 8);
  const double values[4] = {time_s, accel[0], accel[1], accel[2]};
  for (int k = 0; k < 4; ++k) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &values[k], sizeof bits);
    put_u64(bits, buffer + 16 + 8 * k);
  }
}

}  // namespace rocking_monitor::feeds
