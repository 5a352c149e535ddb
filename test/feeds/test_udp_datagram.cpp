// Tests of the shaking-table datagrams (src/feeds/udp_datagram.cpp): the binary layout byte by byte
// (written by hand here, not by encode_binary), the text form with its quirks, and every error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "rocking_monitor/feeds/udp_datagram.hpp"

namespace fd = rocking_monitor::feeds;

namespace {

fd::DatagramError parse(const std::string& s, fd::AccelSample& out) {
  return fd::parse_datagram(s.data(), s.size(), out);
}

}  // namespace

TEST(UdpDatagram, BinaryLayoutIsLittleEndianAsDocumented) {
  // sequence 0x0102030405060708, time 1.5 (0x3FF8000000000000), ax -2 (0xC000000000000000),
  // ay 0.25 (0x3FD0000000000000), az 9.80665 (bits from memcpy, written low byte first)
  unsigned char b[48] = {'R', 'M', 'A', 'C', 1, 0, 0, 0, 8, 7, 6, 5, 4, 3, 2, 1};
  auto put = [&](int offset, std::uint64_t bits) {
    for (int i = 0; i < 8; ++i) b[offset + i] = static_cast<unsigned char>(bits >> (8 * i));
  };
  put(16, 0x3FF8000000000000ull);
  put(24, 0xC000000000000000ull);
  put(32, 0x3FD0000000000000ull);
  const double g = 9.80665;
  std::uint64_t gbits = 0;
  std::memcpy(&gbits, &g, 8);
  put(40, gbits);
  fd::AccelSample s;
  ASSERT_EQ(fd::parse_datagram(reinterpret_cast<const char*>(b), 48, s), fd::DatagramError::None);
  EXPECT_TRUE(s.has_sequence);
  EXPECT_EQ(s.sequence, 0x0102030405060708ull);
  EXPECT_EQ(s.time_s, 1.5);
  EXPECT_EQ(s.accel[0], -2.0);
  EXPECT_EQ(s.accel[1], 0.25);
  EXPECT_EQ(s.accel[2], g);
  // encode_binary writes the same bytes
  unsigned char e[48];
  const double a[3] = {-2.0, 0.25, g};
  fd::encode_binary(0x0102030405060708ull, 1.5, a, e);
  EXPECT_EQ(std::memcmp(b, e, 48), 0);
}

TEST(UdpDatagram, BinaryErrors) {
  unsigned char e[49];
  const double a[3] = {1, 2, 3};
  fd::encode_binary(7, 0.0, a, e);
  fd::AccelSample s;
  EXPECT_EQ(fd::parse_datagram(reinterpret_cast<const char*>(e), 47, s), fd::DatagramError::BinarySize);
  EXPECT_EQ(fd::parse_datagram(reinterpret_cast<const char*>(e), 49, s), fd::DatagramError::BinarySize);
  e[4] = 2;
  EXPECT_EQ(fd::parse_datagram(reinterpret_cast<const char*>(e), 48, s), fd::DatagramError::BinaryVersion);
  e[4] = 1;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double b[3] = {1, nan, 3};
  fd::encode_binary(7, 0.0, b, e);
  EXPECT_EQ(fd::parse_datagram(reinterpret_cast<const char*>(e), 48, s), fd::DatagramError::NonFinite);
  EXPECT_STREQ(fd::to_string(fd::DatagramError::BinarySize), "binary: not 48 bytes");
}

TEST(UdpDatagram, TextFormsAndErrors) {
  fd::AccelSample s;
  ASSERT_EQ(parse("12.345,0.1,-0.02,3e-3\n", s), fd::DatagramError::None);
  EXPECT_FALSE(s.has_sequence);
  EXPECT_EQ(s.time_s, 12.345);
  EXPECT_EQ(s.accel[0], 0.1);
  EXPECT_EQ(s.accel[1], -0.02);
  EXPECT_EQ(s.accel[2], 0.003);
  ASSERT_EQ(parse(" 1 , +2,3 ,4\r\n", s), fd::DatagramError::None);  // blanks, '+', CRLF
  EXPECT_EQ(s.accel[0], 2.0);
  ASSERT_EQ(parse("0,0,0,0", s), fd::DatagramError::None);  // no line break
  EXPECT_EQ(parse("", s), fd::DatagramError::Empty);
  EXPECT_EQ(parse("1,2,3\n", s), fd::DatagramError::TextFields);
  EXPECT_EQ(parse("1,2,3,4,5\n", s), fd::DatagramError::TextFields);
  EXPECT_EQ(parse("1,2,3,4\n5,6,7,8\n", s), fd::DatagramError::TextFields);  // two samples in one datagram
  EXPECT_EQ(parse("1,2,x,4\n", s), fd::DatagramError::TextNumber);
  EXPECT_EQ(parse("1,2,3.0.1,4\n", s), fd::DatagramError::TextNumber);
  EXPECT_EQ(parse("1,,3,4\n", s), fd::DatagramError::TextNumber);
  EXPECT_EQ(parse("1,2,nan,4\n", s), fd::DatagramError::NonFinite);
  EXPECT_EQ(parse("1,inf,3,4\n", s), fd::DatagramError::NonFinite);
  EXPECT_EQ(parse("1,2,1e999,4\n", s), fd::DatagramError::TextNumber);  // out of range
}
