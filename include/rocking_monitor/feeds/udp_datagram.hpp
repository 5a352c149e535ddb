#pragma once

// One acceleration sample per UDP datagram, as a shaking-table controller or a DAQ program sends
// it (udp_accel_bridge; README "Connect a shaking table"). Two forms, told apart by the first bytes:
//
//  * text: ASCII "time,ax,ay,az" (an optional trailing LF or CRLF), e.g. "12.345,0.1,-0.02,0.003\n":
//    time in seconds of the controller's clock, accelerations in m/s^2. No sequence number: the
//    bridge derives it from the time at the nominal rate.
//  * binary, 48 bytes, little-endian (kBinarySize):
//      offset  size  type     field
//           0     4  char[4]  magic "RMAC"
//           4     2  uint16   version = 1
//           6     2  uint16   reserved = 0
//           8     8  uint64   sequence number (consecutive, +1 per sample)
//          16     8  float64  time, s of the controller's clock
//          24     8  float64  ax, m/s^2
//          32     8  float64  ay, m/s^2
//          40     8  float64  az, m/s^2
//  * authenticated binary (version 2, issue 52), 80 bytes (kAuthSize): the 48 bytes above with
//    version = 2, then a 32-byte HMAC-SHA256 tag (RFC 2104, OpenSSL's libcrypto) over bytes 0-47
//    under the key of the bridge's ~key_file (datagram_key.hpp). With a key, only these are
//    accepted (text and version 1 are Unauthenticated); without one they cannot be verified and
//    are refused (NoKey). Replays carry a valid tag: the sequence window catches them.
//
// Parsing allocates nothing of its own (it runs once per sample; OpenSSL's HMAC may).

#include <cstddef>
#include <cstdint>

namespace rocking_monitor::feeds {

inline constexpr char kBinaryMagic[4] = {'R', 'M', 'A', 'C'};
inline constexpr std::uint16_t kBinaryVersion = 1;
inline constexpr std::size_t kBinarySize = 48;
inline constexpr std::uint16_t kBinaryVersionAuth = 2;
inline constexpr std::size_t kTagSize = 32;  ///< HMAC-SHA256
inline constexpr std::size_t kAuthSize = kBinarySize + kTagSize;

/// The shared key of version-2 datagrams, raw bytes (not owned). size 0: no key configured.
struct DatagramKey {
  const unsigned char* data = nullptr;
  std::size_t size = 0;
};

/// One sample from the controller.
struct AccelSample {
  bool has_sequence = false;  ///< binary datagrams carry one; text ones do not
  std::uint64_t sequence = 0;
  double time_s = 0.0;                ///< controller clock, s
  double accel[3] = {0.0, 0.0, 0.0};  ///< ax, ay, az, m/s^2
  /// Set by the sequencer (never by parsing): another datagram came with this sequence number and
  /// other values while this one was held (issue 52); the bridge marks it on the published Imu.
  bool conflict = false;
};

enum class DatagramError {
  None,
  Empty,
  BinarySize,     ///< starts with the magic but is not 48 bytes
  BinaryVersion,  ///< a version this bridge does not know
  AuthSize,         ///< version 2 but not 80 bytes (48 + the 32-byte tag): truncated or padded
  Unauthenticated,  ///< a key is configured, and this is text or version 1 (no tag)
  BadTag,           ///< version 2 whose tag is not the HMAC of its bytes under the key
  NoKey,            ///< version 2, but no key is configured to verify it
  TextFields,     ///< not four comma-separated fields
  TextNumber,     ///< a field that is not a number
  NonFinite,      ///< NaN or infinity
};

/// What went wrong, in a few words ("text: a field is not a number").
const char* to_string(DatagramError error);

/// Parses one datagram without a key (text or version 1). Returns DatagramError::None and fills
/// `out`, or the problem.
DatagramError parse_datagram(const char* data, std::size_t size, AccelSample& out);
/// The same with `key`: when key.size > 0 only version 2 with a valid tag is accepted; when 0,
/// as the overload above (version 2 is NoKey).
DatagramError parse_datagram(const char* data, std::size_t size, const DatagramKey& key, AccelSample& out);

/// HMAC-SHA256 of `data` under `key` (OpenSSL), into tag[kTagSize]. False if OpenSSL fails.
bool hmac_sha256(const DatagramKey& key, const unsigned char* data, std::size_t size, unsigned char* tag);

/// Writes the binary form of a sample into `buffer` (kBinarySize bytes); for senders and tests.
void encode_binary(std::uint64_t sequence, double time_s, const double accel[3], unsigned char* buffer);
/// The version-2 form (kAuthSize bytes): encode_binary with version 2, then the tag under `key`.
bool encode_binary_auth(std::uint64_t sequence, double time_s, const double accel[3], const DatagramKey& key,
                        unsigned char* buffer);

}  // namespace rocking_monitor::feeds
