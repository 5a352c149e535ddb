// SeedLink 3 bytes: commands, replies, packet headers and sequence arithmetic, byte-exact.
#include <gtest/gtest.h>

#include <cstring>
#include <optional>

#include "rocking_monitor/feeds/seedlink_protocol.hpp"
#include "rocking_monitor/feeds/stream_list.hpp"

namespace rocking_monitor::feeds {
namespace {

TEST(SeedLinkProtocol, CommandsAreTheSpecifiedBytes) {
  EXPECT_EQ(hello_command(), "HELLO\r\n");
  EXPECT_EQ(station_command("CI", "RIN"), "STATION RIN CI\r\n");
  EXPECT_EQ(select_command("HN?"), "SELECT HN?\r\n");
  EXPECT_EQ(select_command("00HN?.D"), "SELECT 00HN?.D\r\n");
  EXPECT_EQ(data_command(std::nullopt), "DATA\r\n");
  EXPECT_EQ(data_command(0x00A3F1), "DATA 00A3F1\r\n");
  EXPECT_EQ(data_command(0), "DATA 000000\r\n");
  EXPECT_EQ(end_command(), "END\r\n");
  EXPECT_EQ(keepalive_command(), "INFO ID\r\n");
  EXPECT_THROW(station_command("CIX", "RIN"), std::invalid_argument);
  EXPECT_THROW(station_command("CI", "RINALDI"), std::invalid_argument);
  EXPECT_THROW(station_command("CI", "R N"), std::invalid_argument);
  EXPECT_THROW(data_command(0x1000000), std::invalid_argument);
}

TEST(SeedLinkProtocol, PacketHeaders) {
  PacketHeader h = parse_packet_header("SL00001A");
  EXPECT_EQ(h.kind, PacketHeader::Kind::Data);
  EXPECT_EQ(h.sequence, 26u);
  h = parse_packet_header("SLFFFFFF");
  EXPECT_EQ(h.kind, PacketHeader::Kind::Data);
  EXPECT_EQ(h.sequence, 0xFFFFFFu);
  h = parse_packet_header("SLINFO *");
  EXPECT_EQ(h.kind, PacketHeader::Kind::Info);
  EXPECT_TRUE(h.more_info);
  h = parse_packet_header("SLINFO  ");
  EXPECT_EQ(h.kind, PacketHeader::Kind::Info);
  EXPECT_FALSE(h.more_info);
  EXPECT_EQ(parse_packet_header("SL0000G1").kind, PacketHeader::Kind::Malformed);
  EXPECT_EQ(parse_packet_header("SL 00001").kind, PacketHeader::Kind::Malformed);
  EXPECT_EQ(parse_packet_header("SLINFOXX").kind, PacketHeader::Kind::Malformed);
  EXPECT_EQ(parse_packet_header("000001D ").kind, PacketHeader::Kind::OutOfSync);
}

TEST(SeedLinkProtocol, Replies) {
  EXPECT_EQ(classify_reply("OK"), Reply::Ok);
  EXPECT_EQ(classify_reply("OK\r"), Reply::Ok);
  EXPECT_EQ(classify_reply("ERROR"), Reply::Error);
  EXPECT_EQ(classify_reply("ERROR ARGUMENTS station not found"), Reply::Error);
  EXPECT_EQ(classify_reply("SeedLink v3.1"), Reply::Other);
  EXPECT_DOUBLE_EQ(*hello_version("SeedLink v3.1 (2020.075 RingServer) :: SLPROTO:3.1 CAP EXTREPLY"), 3.1);
  EXPECT_DOUBLE_EQ(*hello_version("SeedLink v3 (test)"), 3.0);
  EXPECT_FALSE(hello_version("HTTP/1.1 400 Bad Request"));
}

TEST(SeedLinkProtocol, SequenceNumbersWrapAt24Bits) {
  EXPECT_EQ(sequence_step(5, 6).kind, SequenceStep::Kind::Next);
  EXPECT_EQ(sequence_step(0xFFFFFF, 0).kind, SequenceStep::Kind::Next);
  EXPECT_EQ(next_sequence(0xFFFFFF), 0u);
  EXPECT_EQ(sequence_step(5, 5).kind, SequenceStep::Kind::Repeat);
  EXPECT_EQ(sequence_step(5, 3).kind, SequenceStep::Kind::Repeat);
  EXPECT_EQ(sequence_step(2, 0xFFFFFE).kind, SequenceStep::Kind::Repeat);  // behind, across the wrap
  const SequenceStep j = sequence_step(5, 9);
  EXPECT_EQ(j.kind, SequenceStep::Kind::Jump);
  EXPECT_EQ(j.skipped, 3u);
  EXPECT_EQ(sequence_step(0xFFFFFE, 1).skipped, 2u);  // FFFFFF and 000000 missing
}

TEST(SeedLinkProtocol, StationOfARecordHeader) {
  // SEED fixed header: sequence "000001", quality 'D', reserved ' ', station (5), location (2),
  // channel (3), network (2).
  char r[64];
  std::memset(r, 0, sizeof r);
  std::memcpy(r, "000001D RIN  00HN1CI", 20);
  std::string net, sta;
  ASSERT_TRUE(record_station(r, sizeof r, net, sta));
  EXPECT_EQ(net, "CI");
  EXPECT_EQ(sta, "RIN");
  std::memcpy(r, "SLINFO *", 8);
  EXPECT_FALSE(record_station(r, sizeof r, net, sta));
}

// Issue 54: the record time that tells a restarted server's new numbers from repeats.
TEST(SeedLinkProtocol, StartTimeOfARecordHeaderInEitherByteOrder) {
  char r[64];
  std::memset(r, 0, sizeof r);
  std::memcpy(r, "000001D RIN  00HN1CI", 20);
  // 2024, day 60 (29 February), 12:34:56.7890: 1709210096.789 s since 1970
  const unsigned char big[10] = {0x07, 0xE8, 0x00, 0x3C, 12, 34, 56, 0, 0x1E, 0xD2};
  std::memcpy(r + 20, big, 10);
  EXPECT_EQ(record_start_us(r, sizeof r), std::optional<std::int64_t>(1709210096789000LL));
  const unsigned char little[10] = {0xE8, 0x07, 0x3C, 0x00, 12, 34, 56, 0, 0xD2, 0x1E};
  std::memcpy(r + 20, little, 10);
  EXPECT_EQ(record_start_us(r, sizeof r), std::optional<std::int64_t>(1709210096789000LL));
  r[24] = 24;  // hour 24: no time
  EXPECT_EQ(record_start_us(r, sizeof r), std::nullopt);
  std::memcpy(r, "SLINFO *", 8);  // no data record
  EXPECT_EQ(record_start_us(r, sizeof r), std::nullopt);
}

TEST(StreamList, ItemsAndTheirErrors) {
  const StreamSpec s = parse_stream("CI_RIN:HN? 00HNZ.D");
  EXPECT_EQ(s.network, "CI");
  EXPECT_EQ(s.station, "RIN");
  ASSERT_EQ(s.selectors.size(), 2u);
  EXPECT_EQ(s.selectors[1], "00HNZ.D");
  EXPECT_EQ(s.name(), "CI_RIN");
  auto message = [](const std::string& item) {
    try {
      parse_stream(item);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("CIRIN:HN?").find("no '_'"), std::string::npos);
  EXPECT_NE(message("CI_RIN").find("no ':'"), std::string::npos);
  EXPECT_NE(message("CI_RIN:").find("no channel selector"), std::string::npos);
  EXPECT_NE(message("CI_TOOLONG:HN?").find("station code"), std::string::npos);
  try {
    parse_streams({"CI_RIN:HN?", "CI_RIN:HL?"});
    ADD_FAILURE() << "the same station twice was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("already given by 'CI_RIN:HN?'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_streams({}), std::invalid_argument);
}

}  // namespace
}  // namespace rocking_monitor::feeds
