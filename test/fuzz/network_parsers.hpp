#pragma once
// The fuzzer's network targets (issue 54): bytes a shaking-table controller, a SeedLink server or
// the wire can send, through the parsers the bridges run on them (parse_datagram, the SeedLink packet
// header and reply parsers, the miniSEED record decoder). Each input must be parsed into finite
// values or refused by the parser's own result; an exception, a non-finite value, a crash or a
// sanitizer report is a failure.

#include <string>

namespace rocking_monitor::fuzz {

/// The key the udp_datagram target's version-2 seed is tagged with and parsed under (issue 52).
inline constexpr char kFuzzDatagramKey[] = "fuzz-datagram-key";

/// Whether `target` is one of the network parsers' targets.
bool is_network_target(const std::string& target);

/// Runs the target's parsers on `bytes`: "" when the outcome is acceptable (`rejected` says whether
/// the parser refused the input), else what is wrong.
std::string check_network(const std::string& target, const std::string& bytes, bool& rejected);

}  // namespace rocking_monitor::fuzz
