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
//
// Parsing allocates nothing (it runs once per sample).

#include <cstddef>
#include <cstdint>

namespace rocking_monitor::feeds {

inline constexpr char kBinaryMagic[4] = {'R', 'M', 'A', 'C'};
inline constexpr std::uint16_t kBinaryVersion = 1;
inline constexpr std::size_t kBinarySize = 48;

/// One sample from the controller.
struct AccelSample {
  bool has_sequence = false;  ///< binary datagrams carry one; text ones do not
  std::uint64_t sequence = 0;
  double time_s = 0.0;                ///< controller clock, s
  double accel[3] = {0.0, 0.0, 0.0};  ///< ax, ay, az, m/s^2
};

enum class DatagramError {
  None,
  Empty,
  BinarySize,     ///< starts with the magic but is not 48 bytes
  BinaryVersion,  ///< a version this bridge does not know
  TextFields,     ///< not four comma-separated fields
  TextNumber,     ///< a field that is not a number
  NonFinite,      ///< NaN or infinity
};

/// What went wrong, in a few words ("text: a field is not a number").
const char* to_string(DatagramError error);

/// Parses one datagram. Returns DatagramError::None and fills `out`, or the problem.
DatagramError parse_datagram(const char* data, std::size_t size, AccelSample& out);

/// Writes the binary form of a sample into `buffer` (kBinarySize bytes); for senders and tests.
void encode_binary(std::uint64_t sequence, double time_s, const double accel[3], unsigned char* buffer);

}  // namespace rocking_monitor::feeds
