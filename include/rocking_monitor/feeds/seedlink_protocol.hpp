#pragma once

// The bytes of the SeedLink 3 protocol (client side): the commands a client sends, the server's
// one-line replies, and the 8-byte header in front of every 512-byte miniSEED record.
//
//   client                         server
//   HELLO<cr><lf>                  two lines: "SeedLink v3.1 (...)" and the organisation
//   STATION <sta> <net><cr><lf>    OK | ERROR          (multi-station mode, one per station)
//   SELECT <LLCCC.T><cr><lf>       OK | ERROR          (per selector of that station)
//   DATA [<seq hex6>]<cr><lf>      OK | ERROR          (resume at packet <seq> of that station)
//   END<cr><lf>                    (no reply) packets: "SL" + 6 upper-case hex digits + record
//   INFO ID<cr><lf>                "SLINFO *" / "SLINFO  " + 512-byte log records (keep-alive)
//
// Sequence numbers are 24-bit, per station, and wrap. No ROS, no sockets: bytes in, values out.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace rocking_monitor::feeds {

constexpr std::size_t kSeedLinkHeaderBytes = 8;    ///< "SL" + 6 hex digits, or "SLINFO" + 2
constexpr std::size_t kSeedLinkRecordBytes = 512;  ///< SeedLink 3 carries 512-byte miniSEED records
constexpr std::size_t kSeedLinkPacketBytes = kSeedLinkHeaderBytes + kSeedLinkRecordBytes;
constexpr std::uint32_t kSequenceModulus = 0x1000000;  ///< 24-bit sequence numbers

std::string hello_command();
/// "STATION <sta> <net>\r\n"; throws std::invalid_argument for codes that are empty, too long
/// (station 5, network 2 characters) or hold a blank or control character.
std::string station_command(std::string_view network, std::string_view station);
/// "SELECT <selector>\r\n"; the selector is [LL]CCC[.T] with ? wildcards (e.g. "HN?.D").
std::string select_command(std::string_view selector);
/// "DATA\r\n" (from the next packet) or "DATA 00A3F1\r\n" (from that packet on).
std::string data_command(std::optional<std::uint32_t> from_sequence);
std::string end_command();
/// The keep-alive: a server answers it with INFO packets, which the client reads and drops.
std::string keepalive_command();

/// What the server answered to a command (one line, terminator stripped).
enum class Reply { Ok, Error, Other };
Reply classify_reply(std::string_view line);

/// The first line of the answer to HELLO, e.g. "SeedLink v3.1 (2020.075) :: SLPROTO:3.1": the
/// protocol version (3.1 -> 3.1), or nothing when the line does not name one.
std::optional<double> hello_version(std::string_view line);

/// An 8-byte packet header.
struct PacketHeader {
  enum class Kind {
    Data,       ///< "SL" + 6 hex digits: `sequence` holds them
    Info,       ///< "SLINFO" + ' ' + ('*': more INFO packets follow | ' ': the last one)
    Malformed,  ///< starts "SL" but neither of the above: the record behind it is skipped
    OutOfSync,  ///< does not even start with "SL": the byte stream lost its framing
  };
  Kind kind = Kind::Malformed;
  std::uint32_t sequence = 0;  ///< Data: 0 .. 0xFFFFFF
  bool more_info = false;      ///< Info: another INFO packet follows
};
PacketHeader parse_packet_header(const char* bytes8);

/// Network and station codes of a miniSEED 2 record (fixed header bytes 8-12 and 18-19), blanks
/// trimmed; false when the first 20 bytes are not a data record header (sequence digits, quality
/// indicator D/R/Q/M).
bool record_station(const char* record, std::size_t length, std::string& network, std::string& station);

/// Start time of a miniSEED 2 record (fixed header BTIME, bytes 20-29, either byte order), in
/// microseconds since the epoch (UTC); nothing when the header is no data record or the time is no
/// date (year 1900..2500, day 1..366, hour < 24, minute < 60, second <= 60); as stamped, without
/// the header's time correction (ordering records needs no more). Used to tell a server
/// that renumbered its packets after a restart from one that repeats old ones.
std::optional<std::int64_t> record_start_us(const char* record, std::size_t length);

/// Where packet `got` stands after the station's `last` one (24-bit wrap): the next one, a repeat
/// or older one (to drop), or a jump forward by `skipped` + 1 (packets missing in between).
struct SequenceStep {
  enum class Kind { Next, Repeat, Jump };
  Kind kind = Kind::Next;
  std::uint32_t skipped = 0;  ///< Jump: how many sequence numbers were never received
};
SequenceStep sequence_step(std::uint32_t last, std::uint32_t got);
/// The sequence number after `seq` (24-bit wrap).
std::uint32_t next_sequence(std::uint32_t seq);

}  // namespace rocking_monitor::feeds
