// The network parsers under the fuzzer (see the header).
#include "network_parsers.hpp"

#include <cmath>
#include <exception>
#include <optional>
#include <cstring>
#include <sstream>

#include "rocking_monitor/feeds/mseed_record.hpp"
#include "rocking_monitor/feeds/seedlink_protocol.hpp"
#include "rocking_monitor/feeds/udp_datagram.hpp"

namespace rocking_monitor::fuzz {
namespace {

namespace rf = rocking_monitor::feeds;

// Parsed without a key and with kFuzzDatagramKey (issue 52, version 2); rejected when both refuse.
// Accepted with the key means: 80 bytes whose last 32 are the HMAC of the first 48.
std::string fuzz_check_datagram(const std::string& bytes, bool& rejected) {
  rf::AccelSample s;
  const rf::DatagramError plain = rf::parse_datagram(bytes.data(), bytes.size(), s);
  const rf::DatagramKey key{reinterpret_cast<const unsigned char*>(kFuzzDatagramKey), sizeof kFuzzDatagramKey - 1};
  rf::AccelSample keyed;
  const rf::DatagramError e = rf::parse_datagram(bytes.data(), bytes.size(), key, keyed);
  if (e == rf::DatagramError::None) {
    unsigned char tag[rf::kTagSize];
    const auto* u = reinterpret_cast<const unsigned char*>(bytes.data());
    if (bytes.size() != rf::kAuthSize || !rf::hmac_sha256(key, u, rf::kBinarySize, tag) ||
        std::memcmp(tag, u + rf::kBinarySize, rf::kTagSize) != 0)
      return "accepted with the key without a valid tag";
    if (plain == rf::DatagramError::None) return "a version-2 datagram accepted without a key";
    s = keyed;
  }
  rejected = plain != rf::DatagramError::None && e != rf::DatagramError::None;
  if (rejected) return std::string(rf::to_string(plain)).empty() || std::string(rf::to_string(e)).empty()
                           ? "a refusal without a reason" : "";
  if (!std::isfinite(s.time_s)) return "parsed with a non-finite time";
  for (double a : s.accel)
    if (!std::isfinite(a)) return "parsed with a non-finite acceleration";
  return "";
}

// A packet (header + record, however long the input) and every line of the input as a reply;
// refused when it is neither a data packet of a station nor holds a reply the client knows.
std::string fuzz_check_seedlink(const std::string& bytes, bool& rejected) {
  rejected = true;
  if (bytes.size() >= rf::kSeedLinkHeaderBytes) {
    const rf::PacketHeader h = rf::parse_packet_header(bytes.data());
    if (h.kind == rf::PacketHeader::Kind::Data && h.sequence >= rf::kSequenceModulus) return "a sequence number above 24 bits";
    const char* record = bytes.data() + rf::kSeedLinkHeaderBytes;
    const std::size_t length = bytes.size() - rf::kSeedLinkHeaderBytes;
    std::string net, sta;
    if (rf::record_station(record, length, net, sta)) {
      if (net.size() > 2 || sta.empty() || sta.size() > 5) return "station codes of impossible length";
      if (h.kind == rf::PacketHeader::Kind::Data) rejected = false;
    }
    (void)rf::record_start_us(record, length);
  }
  std::istringstream lines(bytes);
  for (std::string line; std::getline(lines, line, '\n');) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (rf::classify_reply(line) != rf::Reply::Other) rejected = false;
    if (const std::optional<double> v = rf::hello_version(line)) {
      if (!std::isfinite(*v)) return "a non-finite protocol version";
      rejected = false;
    }
  }
  return "";
}

std::string fuzz_check_mseed(const std::string& bytes, bool& rejected) {
  static rf::MseedDecoder decoder;  // reused, as the bridge reuses it between records
  rf::DecodedRecord r;
  const rf::MseedDecoder::Result result = decoder.decode(bytes.data(), bytes.size(), r);
  rejected = result != rf::MseedDecoder::Result::Ok;
  if (rejected) return decoder.error().empty() ? "a refusal without a reason" : "";
  if (!(std::isfinite(r.sample_rate) && r.sample_rate > 0.0)) return "decoded with sample rate " + std::to_string(r.sample_rate);
  for (std::size_t i = 0; i < r.samples.size(); ++i)
    if (!std::isfinite(r.samples[i])) return "decoded with a non-finite sample " + std::to_string(i);
  return "";
}

}  // namespace

bool is_network_target(const std::string& target) {
  return target == "udp_datagram" || target == "seedlink" || target == "mseed_record";
}

std::string check_network(const std::string& target, const std::string& bytes, bool& rejected) {
  try {
    if (target == "udp_datagram") return fuzz_check_datagram(bytes, rejected);
    if (target == "seedlink") return fuzz_check_seedlink(bytes, rejected);
    return fuzz_check_mseed(bytes, rejected);
  } catch (const std::exception& e) {
    return std::string("exception from a network parser: ") + e.what();
  } catch (...) {
    return "non-std exception from a network parser";
  }
}

}  // namespace rocking_monitor::fuzz
