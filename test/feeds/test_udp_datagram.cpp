// Tests of the shaking-table datagrams (src/feeds/udp_datagram.cpp): the binary layout byte by byte
// (written by hand here, not by encode_binary), the text form with its quirks, and every error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>
#include <limits>
#include <string>

#include "rocking_monitor/feeds/datagram_key.hpp"
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
  e[4] = 3;
  EXPECT_EQ(fd::parse_datagram(reinterpret_cast<const char*>(e), 48, s), fd::DatagramError::BinaryVersion);
  e[4] = 2;  // version 2 without a key cannot be verified: refused, whatever its size
  EXPECT_EQ(fd::parse_datagram(reinterpret_cast<const char*>(e), 48, s), fd::DatagramError::NoKey);
  e[4] = 1;
  EXPECT_EQ(fd::parse_datagram(reinterpret_cast<const char*>(e), 7, s), fd::DatagramError::BinarySize);
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

// --- Authenticated datagrams (version 2, issue 52) ---

namespace {

std::vector<unsigned char> from_hex(const std::string& hex) {
  std::vector<unsigned char> out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) out.push_back(static_cast<unsigned char>(std::stoi(hex.substr(i, 2), nullptr, 16)));
  return out;
}

// The known-answer vector, computed outside this code base by Python's standard library:
//   key = b'shaking-table-key-0123456789abcd'
//   body = struct.pack('<4sHHQdddd', b'RMAC', 2, 0, 0x0102030405060708, 1.5, -2.0, 0.25, 9.80665)
//   hmac.new(key, body, hashlib.sha256).hexdigest()
const std::string kAuthKey = "shaking-table-key-0123456789abcd";
const char* const kAuthTagHex = "db0ab8b918b0c33023d32eed406509483bd32e88b55285699fc212f05cc0040d";

fd::DatagramKey auth_key() {
  return fd::DatagramKey{reinterpret_cast<const unsigned char*>(kAuthKey.data()), kAuthKey.size()};
}

// The 80 bytes written by hand: header, body as in BinaryLayoutIsLittleEndianAsDocumented, tag.
std::vector<unsigned char> known_v2_datagram() {
  std::vector<unsigned char> b = {'R', 'M', 'A', 'C', 2, 0, 0, 0, 8, 7, 6, 5, 4, 3, 2, 1};
  auto put = [&](std::uint64_t bits) {
    for (int i = 0; i < 8; ++i) b.push_back(static_cast<unsigned char>(bits >> (8 * i)));
  };
  const double g = 9.80665;
  std::uint64_t gbits = 0;
  std::memcpy(&gbits, &g, 8);
  put(0x3FF8000000000000ull);
  put(0xC000000000000000ull);
  put(0x3FD0000000000000ull);
  put(gbits);
  for (unsigned char c : from_hex(kAuthTagHex)) b.push_back(c);
  return b;
}

fd::DatagramError parse_v2(const std::vector<unsigned char>& b, const fd::DatagramKey& key, fd::AccelSample& s) {
  return fd::parse_datagram(reinterpret_cast<const char*>(b.data()), b.size(), key, s);
}

}  // namespace

TEST(UdpDatagramAuth, HmacIsRfc4231TestCase2) {
  const std::string key = "Jefe", data = "what do ya want for nothing?";
  unsigned char tag[fd::kTagSize];
  ASSERT_TRUE(fd::hmac_sha256(fd::DatagramKey{reinterpret_cast<const unsigned char*>(key.data()), key.size()},
                              reinterpret_cast<const unsigned char*>(data.data()), data.size(), tag));
  EXPECT_EQ(std::vector<unsigned char>(tag, tag + 32),
            from_hex("5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843"));
}

TEST(UdpDatagramAuth, PythonKnownAnswerIsAcceptedAndEncodedAlike) {
  const auto b = known_v2_datagram();
  ASSERT_EQ(b.size(), fd::kAuthSize);
  fd::AccelSample s;
  ASSERT_EQ(parse_v2(b, auth_key(), s), fd::DatagramError::None);
  EXPECT_TRUE(s.has_sequence);
  EXPECT_EQ(s.sequence, 0x0102030405060708ull);
  EXPECT_EQ(s.time_s, 1.5);
  EXPECT_EQ(s.accel[0], -2.0);
  EXPECT_EQ(s.accel[1], 0.25);
  EXPECT_EQ(s.accel[2], 9.80665);
  unsigned char e[fd::kAuthSize];
  const double a[3] = {-2.0, 0.25, 9.80665};
  ASSERT_TRUE(fd::encode_binary_auth(0x0102030405060708ull, 1.5, a, auth_key(), e));
  EXPECT_EQ(std::vector<unsigned char>(e, e + fd::kAuthSize), b);
}

TEST(UdpDatagramAuth, EveryFlippedBitIsRefused) {
  const auto good = known_v2_datagram();
  fd::AccelSample s;
  for (std::size_t byte = 0; byte < good.size(); ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      auto b = good;
      b[byte] ^= static_cast<unsigned char>(1u << bit);
      const fd::DatagramError e = parse_v2(b, auth_key(), s);
      // Bytes 6-79 (reserved, body, tag): the tag no longer matches. Bytes 0-5 (magic, version):
      // no longer a version-2 datagram, refused as such.
      if (byte >= 6)
        EXPECT_EQ(e, fd::DatagramError::BadTag) << "byte " << byte << " bit " << bit;
      else
        EXPECT_NE(e, fd::DatagramError::None) << "byte " << byte << " bit " << bit;
    }
  }
}

TEST(UdpDatagramAuth, WrongKeyLengthAndFormsAreTold) {
  const auto good = known_v2_datagram();
  fd::AccelSample s;
  std::string other = kAuthKey;
  other.back() = 'e';  // one byte off
  EXPECT_EQ(parse_v2(good, fd::DatagramKey{reinterpret_cast<const unsigned char*>(other.data()), other.size()}, s),
            fd::DatagramError::BadTag);
  const std::string shorter = kAuthKey.substr(0, 31);  // a key missing its last byte (a stripped newline?)
  EXPECT_EQ(parse_v2(good, fd::DatagramKey{reinterpret_cast<const unsigned char*>(shorter.data()), 31}, s),
            fd::DatagramError::BadTag);
  auto truncated = good;
  truncated.pop_back();  // 79 bytes: the tag cut short
  EXPECT_EQ(parse_v2(truncated, auth_key(), s), fd::DatagramError::AuthSize);
  EXPECT_EQ(parse_v2(std::vector<unsigned char>(good.begin(), good.begin() + 48), auth_key(), s),
            fd::DatagramError::AuthSize);  // no tag at all
  auto padded = good;
  padded.push_back(0);
  EXPECT_EQ(parse_v2(padded, auth_key(), s), fd::DatagramError::AuthSize);
  EXPECT_STREQ(fd::to_string(fd::DatagramError::AuthSize), "binary v2: not 80 bytes (48 + a 32-byte tag)");
  // Without a key: version 2 cannot be verified.
  EXPECT_EQ(parse_v2(good, fd::DatagramKey{}, s), fd::DatagramError::NoKey);
  // With a key: version 1 and text carry no tag.
  unsigned char v1[48];
  const double a[3] = {1, 2, 3};
  fd::encode_binary(7, 0.0, a, v1);
  EXPECT_EQ(fd::parse_datagram(reinterpret_cast<const char*>(v1), 48, auth_key(), s), fd::DatagramError::Unauthenticated);
  EXPECT_EQ(fd::parse_datagram("1,2,3,4\n", 8, auth_key(), s), fd::DatagramError::Unauthenticated);
  EXPECT_EQ(fd::parse_datagram("", 0, auth_key(), s), fd::DatagramError::Empty);
  // The tag covers the body, not only the header: a NaN in a well-tagged datagram is still refused.
  const double nan[3] = {1, std::numeric_limits<double>::quiet_NaN(), 3};
  unsigned char e[fd::kAuthSize];
  ASSERT_TRUE(fd::encode_binary_auth(7, 0.0, nan, auth_key(), e));
  EXPECT_EQ(fd::parse_datagram(reinterpret_cast<const char*>(e), fd::kAuthSize, auth_key(), s),
            fd::DatagramError::NonFinite);
}

namespace {

std::string write_key_file(const std::string& name, const std::string& bytes, mode_t mode) {
  const std::string path = testing::TempDir() + "rocking_key_" + std::to_string(::getpid()) + "_" + name;
  { std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes; }
  ::chmod(path.c_str(), mode);
  return path;
}

}  // namespace

TEST(DatagramKeyFile, ReadsRawBytesStrippingOneNewline) {
  std::vector<unsigned char> key;
  std::string error;
  const std::string raw("\x00\x01\xff\n\n", 5);
  ASSERT_TRUE(fd::read_key_file(write_key_file("raw", raw, 0600), key, error)) << error;
  EXPECT_EQ(key, std::vector<unsigned char>({0x00, 0x01, 0xff, '\n'}));  // one newline stripped, not two
  ASSERT_TRUE(fd::read_key_file(write_key_file("ro", "secret", 0400), key, error)) << error;
  EXPECT_EQ(std::string(key.begin(), key.end()), "secret");
  EXPECT_EQ(error, "");
}

TEST(DatagramKeyFile, RefusalsNameTheFileAndTheReason) {
  std::vector<unsigned char> key = {42};
  std::string error;
  const std::string missing = testing::TempDir() + "rocking_key_does_not_exist";
  EXPECT_FALSE(fd::read_key_file(missing, key, error));
  EXPECT_EQ(error, "key file '" + missing + "': No such file or directory");
  const std::string empty = write_key_file("empty", "", 0600);
  EXPECT_FALSE(fd::read_key_file(empty, key, error));
  EXPECT_EQ(error, "key file '" + empty + "' is empty");
  const std::string newline = write_key_file("newline", "\n", 0600);
  EXPECT_FALSE(fd::read_key_file(newline, key, error));
  EXPECT_EQ(error, "key file '" + newline + "' is empty (after its trailing newline)");
  const std::string group = write_key_file("group", "secret", 0640);
  EXPECT_FALSE(fd::read_key_file(group, key, error));
  EXPECT_EQ(error, "key file '" + group + "' is accessible to group or others (mode 0640): chmod 600 it");
  const std::string world = write_key_file("world", "secret", 0604);
  EXPECT_FALSE(fd::read_key_file(world, key, error));
  EXPECT_EQ(error, "key file '" + world + "' is accessible to group or others (mode 0604): chmod 600 it");
  const std::string big = write_key_file("big", std::string(fd::kMaxKeyBytes + 1, 'k'), 0600);
  EXPECT_FALSE(fd::read_key_file(big, key, error));
  EXPECT_EQ(error, "key file '" + big + "' is larger than 4096 bytes: not a key");
  EXPECT_FALSE(fd::read_key_file(testing::TempDir(), key, error));
  EXPECT_EQ(error, "key file '" + testing::TempDir() + "' is not a regular file");
  EXPECT_EQ(key, std::vector<unsigned char>({42}));  // untouched on refusal
}
