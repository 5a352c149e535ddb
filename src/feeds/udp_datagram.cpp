// Parsing one UDP datagram into a sample: the text form "time,ax,ay,az", the 48-byte binary form and
// its 80-byte authenticated version 2 (layouts in udp_datagram.hpp). Little-endian is decoded byte by
// byte, so the host's byte order does not matter; strict numbers (std::from_chars, whole field).
#include "rocking_monitor/feeds/udp_datagram.hpp"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>

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

unsigned le_u16(const unsigned char* p) { return static_cast<unsigned>(p[0]) | (static_cast<unsigned>(p[1]) << 8); }

/// Bytes 8-47 of either binary version: sequence, time, accelerations.
DatagramError decode_binary_body(const unsigned char* u, AccelSample& out) {
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

/// Version 2: the size, then the tag (constant-time comparison: a forger learns nothing from the
/// time a wrong tag takes), then the body.
DatagramError decode_authenticated(const unsigned char* u, std::size_t size, const DatagramKey& key,
                                   AccelSample& out) {
  if (key.size == 0) return DatagramError::NoKey;
  if (size != kAuthSize) return DatagramError::AuthSize;
  unsigned char tag[kTagSize];
  if (!hmac_sha256(key, u, kBinarySize, tag)) return DatagramError::BadTag;
  if (CRYPTO_memcmp(tag, u + kBinarySize, kTagSize) != 0) return DatagramError::BadTag;
  return decode_binary_body(u, out);
}

DatagramError parse_text(const char* data, std::size_t size, AccelSample& out) {
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

void encode_version(std::uint64_t sequence, double time_s, const double accel[3], std::uint16_t version,
                    unsigned char* buffer) {
  std::memcpy(buffer, kBinaryMagic, 4);
  buffer[4] = static_cast<unsigned char>(version & 0xff);
  buffer[5] = static_cast<unsigned char>(version >> 8);
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

}  // namespace

bool hmac_sha256(const DatagramKey& key, const unsigned char* data, std::size_t size, unsigned char* tag) {
  if (key.size == 0 || key.size > static_cast<std::size_t>(INT32_MAX)) return false;  // OpenSSL takes an int
  unsigned int tag_len = 0;
  const unsigned char* md = HMAC(EVP_sha256(), key.data, static_cast<int>(key.size), data, size, tag, &tag_len);
  return md != nullptr && tag_len == kTagSize;
}

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
    case DatagramError::AuthSize:
      return "binary v2: not 80 bytes (48 + a 32-byte tag)";
    case DatagramError::Unauthenticated:
      return "unauthenticated: text or binary v1 while ~key_file is set";
    case DatagramError::BadTag:
      return "binary v2: bad HMAC tag (wrong key or altered)";
    case DatagramError::NoKey:
      return "binary v2: authenticated, but no ~key_file to verify it";
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
  return parse_datagram(data, size, DatagramKey{}, out);
}

DatagramError parse_datagram(const char* data, std::size_t size, const DatagramKey& key, AccelSample& out) {
  if (size == 0) return DatagramError::Empty;
  const auto* u = reinterpret_cast<const unsigned char*>(data);
  if (size >= 4 && std::memcmp(data, kBinaryMagic, 4) == 0) {
    if (size < 8) return DatagramError::BinarySize;  // not even the header
    const unsigned version = le_u16(u + 4);
    if (version == kBinaryVersionAuth) return decode_authenticated(u, size, key, out);
    if (version != kBinaryVersion) return DatagramError::BinaryVersion;
    if (key.size > 0) return DatagramError::Unauthenticated;
    if (size != kBinarySize) return DatagramError::BinarySize;
    return decode_binary_body(u, out);
  }
  if (key.size > 0) return DatagramError::Unauthenticated;
  return parse_text(data, size, out);
}


void encode_binary(std::uint64_t sequence, double time_s, const double accel[3], unsigned char* buffer) {
  encode_version(sequence, time_s, accel, kBinaryVersion, buffer);
}

bool encode_binary_auth(std::uint64_t sequence, double time_s, const double accel[3], const DatagramKey& key,
                        unsigned char* buffer) {
  encode_version(sequence, time_s, accel, kBinaryVersionAuth, buffer);
  return hmac_sha256(key, buffer, kBinarySize, buffer + kBinarySize);
}

}  // namespace rocking_monitor::feeds
