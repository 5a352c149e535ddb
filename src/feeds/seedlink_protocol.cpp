// SeedLink 3 command strings, replies and packet headers (see the header for the byte layouts).
#include "rocking_monitor/feeds/seedlink_protocol.hpp"

#include <cstdio>
#include <stdexcept>

namespace rocking_monitor::feeds {
namespace {

// A code goes into a blank-separated command line: blanks or control bytes would split or end it.
void check_code(std::string_view code, std::size_t max, const char* what) {
  if (code.empty() || code.size() > max)
    throw std::invalid_argument(std::string(what) + " code '" + std::string(code) + "' must have 1 to " +
                                std::to_string(max) + " characters");
  for (char c : code) {
    if (c <= ' ' || c > '~')
      throw std::invalid_argument(std::string(what) + " code '" + std::string(code) + "' holds a blank or control character");
  }
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r' || s.back() == '\n' || s.back() == '\0'))
    s.remove_suffix(1);
  return s;
}

}  // namespace

std::string hello_command() { return "HELLO\r\n"; }

std::string station_command(std::string_view network, std::string_view station) {
  check_code(network, 2, "network");
  check_code(station, 5, "station");
  return "STATION " + std::string(station) + " " + std::string(network) + "\r\n";
}

std::string select_command(std::string_view selector) {
  // [LL]CCC[.T]: 3 to 7 characters (location 2, channel 3, ".T" 2).
  check_code(selector, 8, "selector");
  if (selector.size() < 3) throw std::invalid_argument("selector '" + std::string(selector) + "' must name a channel (CCC, ? wildcards)");
  return "SELECT " + std::string(selector) + "\r\n";
}

std::string data_command(std::optional<std::uint32_t> from_sequence) {
  if (!from_sequence) return "DATA\r\n";
  if (*from_sequence >= kSequenceModulus) throw std::invalid_argument("sequence number beyond 24 bits");
  char buf[32];
  std::snprintf(buf, sizeof buf, "DATA %06X\r\n", static_cast<unsigned>(*from_sequence));
  return buf;
}

std::string end_command() { return "END\r\n"; }

std::string keepalive_command() { return "INFO ID\r\n"; }

Reply classify_reply(std::string_view line) {
  line = trim(line);
  if (line == "OK") return Reply::Ok;
  if (line.substr(0, 5) == "ERROR") return Reply::Error;  // SeedLink 3.1 may add a code and text
  return Reply::Other;
}

std::optional<double> hello_version(std::string_view line) {
  const std::size_t at = line.find("SeedLink v");
  if (at == std::string_view::npos) return std::nullopt;
  std::string digits;
  for (std::size_t i = at + 10; i < line.size() && ((line[i] >= '0' && line[i] <= '9') || line[i] == '.'); ++i)
    digits += line[i];
  if (digits.empty() || digits.front() == '.') return std::nullopt;
  return std::strtod(digits.c_str(), nullptr);
}

PacketHeader parse_packet_header(const char* b) {
  PacketHeader h;
  if (b[0] != 'S' || b[1] != 'L') {
    h.kind = PacketHeader::Kind::OutOfSync;
    return h;
  }
  if (b[2] == 'I' && b[3] == 'N' && b[4] == 'F' && b[5] == 'O' && b[6] == ' ' && (b[7] == ' ' || b[7] == '*')) {
    h.kind = PacketHeader::Kind::Info;
    h.more_info = b[7] == '*';
    return h;
  }
  std::uint32_t seq = 0;
  for (int i = 2; i < 8; ++i) {
    const int d = hex_digit(b[i]);
    if (d < 0) {
      h.kind = PacketHeader::Kind::Malformed;
      return h;
    }
    seq = seq * 16 + static_cast<std::uint32_t>(d);
  }
  h.kind = PacketHeader::Kind::Data;
  h.sequence = seq;
  return h;
}

bool record_station(const char* r, std::size_t length, std::string& network, std::string& station) {
  if (length < 48) return false;
  for (int i = 0; i < 6; ++i) {
    if (!((r[i] >= '0' && r[i] <= '9') || r[i] == ' ' || r[i] == '\0')) return false;
  }
  if (r[6] != 'D' && r[6] != 'R' && r[6] != 'Q' && r[6] != 'M') return false;
  station = std::string(trim(std::string_view(r + 8, 5)));
  network = std::string(trim(std::string_view(r + 18, 2)));
  return !station.empty();
}

namespace {
// Days from 1970-01-01 to the first of January of `year` (proleptic Gregorian).
std::int64_t slproto_days_to_year(int year) {
  std::int64_t days = 0;
  for (int y = 1970; y < year; ++y) days += (y % 4 == 0 && (y % 100 != 0 || y % 400 == 0)) ? 366 : 365;
  for (int y = year; y < 1970; ++y) days -= (y % 4 == 0 && (y % 100 != 0 || y % 400 == 0)) ? 366 : 365;
  return days;
}
std::uint16_t slproto_u16(const char* p, bool big_endian) {
  const auto b0 = static_cast<unsigned char>(p[0]), b1 = static_cast<unsigned char>(p[1]);
  return static_cast<std::uint16_t>(big_endian ? (b0 << 8) | b1 : (b1 << 8) | b0);
}
}  // namespace

std::optional<std::int64_t> record_start_us(const char* r, std::size_t length) {
  std::string net, sta;
  if (!record_station(r, length, net, sta)) return std::nullopt;
  const char* t = r + 20;
  // The record's byte order is not said before blockette 1000: the one giving a plausible year wins.
  const bool big = slproto_u16(t, true) >= 1900 && slproto_u16(t, true) <= 2500;
  const int year = slproto_u16(t, big), day = slproto_u16(t + 2, big);
  const int hour = static_cast<unsigned char>(t[4]), minute = static_cast<unsigned char>(t[5]);
  const int second = static_cast<unsigned char>(t[6]), tenth_ms = slproto_u16(t + 8, big);
  if (year < 1900 || year > 2500 || day < 1 || day > 366 || hour > 23 || minute > 59 || second > 60 || tenth_ms > 9999)
    return std::nullopt;
  const std::int64_t s = (slproto_days_to_year(year) + day - 1) * 86400 + hour * 3600 + minute * 60 + second;
  return s * 1000000 + static_cast<std::int64_t>(tenth_ms) * 100;
}

SequenceStep sequence_step(std::uint32_t last, std::uint32_t got) {
  const std::uint32_t ahead = (got - last) & (kSequenceModulus - 1);
  SequenceStep s;
  if (ahead == 1) return s;
  // Half the sequence space decides: behind by less than 2^23 is a repeat, not a huge jump.
  if (ahead == 0 || ahead >= kSequenceModulus / 2) {
    s.kind = SequenceStep::Kind::Repeat;
    return s;
  }
  s.kind = SequenceStep::Kind::Jump;
  s.skipped = ahead - 1;
  return s;
}

std::uint32_t next_sequence(std::uint32_t seq) { return (seq + 1) & (kSequenceModulus - 1); }

}  // namespace rocking_monitor::feeds
