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
