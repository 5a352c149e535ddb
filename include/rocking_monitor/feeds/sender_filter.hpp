#pragma once

// Which hosts may feed ground motion to udp_accel_bridge (issue 52: only the real sensors feed the
// monitor). A UDP socket accepts a datagram from anyone who can reach it, so the bridge pins its
// senders: `~allowed_senders` is a list of entries, each
//
//   "a.b.c.d"        that IPv4 address, any source port
//   "a.b.c.d:port"   that address from that source port only (1-65535)
//   "a.b.c.d/nn"     a CIDR range, nn = 0..32 (/0 is everyone: allowed, but it must be written)
//
// Parsing refuses a bad entry with a message naming it; nothing is guessed. ROS-free, no sockets:
// addresses are host-order uint32 (a.b.c.d = a<<24 | b<<16 | c<<8 | d).

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace rocking_monitor::feeds {

/// One allowed sender: an address range and optionally one port.
struct SenderRule {
  std::uint32_t network = 0;  ///< host order, already masked
  std::uint32_t mask = 0;     ///< host order, e.g. 0xFFFFFF00 for /24
  int prefix = 32;            ///< 0..32
  std::optional<std::uint16_t> port;  ///< unset: any source port
};

/// Parses "a.b.c.d" (each 0..255, decimal, no sign, no leading '+'), host order.
std::optional<std::uint32_t> parse_ipv4(const std::string& text);

/// "a.b.c.d" of a host-order address.
std::string format_ipv4(std::uint32_t address);

/// "a.b.c.d:port".
std::string format_endpoint(std::uint32_t address, std::uint16_t port);

/// A list given as one string (a launch argument): entries separated by commas and/or spaces;
/// empty pieces are skipped, so "" is no list.
std::vector<std::string> split_sender_list(const std::string& text);

/// One entry of `~allowed_senders`; on failure returns nullopt and sets `error` to a sentence that
/// names the entry and what is wrong with it.
std::optional<SenderRule> parse_sender_rule(const std::string& entry, std::string& error);

/// The whole list: every entry must parse (the first bad one is named in `error`).
class SenderFilter {
 public:
  /// Empty list: `pinned()` is false and `allows` accepts everyone (the bridge warns about it).
  bool configure(const std::vector<std::string>& entries, std::string& error);

  bool pinned() const { return !rules_.empty(); }
  bool allows(std::uint32_t address, std::uint16_t port) const;
  const std::vector<SenderRule>& rules() const { return rules_; }

 private:
  std::vector<SenderRule> rules_;
};

/// Who sent the datagrams, per source address:port: those admitted and those dropped by the
/// filter, each with a count, so that nothing is dropped uncounted and /diagnostics can name them.
/// A flood from many spoofed sources must not grow memory without bound: beyond kMaxListed
/// distinct sources per kind the datagrams are still counted, in `unlisted`.
class SenderTally {
 public:
  static constexpr std::size_t kMaxListed = 32;
  using Key = std::uint64_t;  ///< address << 16 | port

  /// Counts the datagram; true when the filter admits it. Allocates only for a new source.
  bool admit(const SenderFilter& filter, std::uint32_t address, std::uint16_t port);

  const std::map<Key, std::uint64_t>& admitted() const { return admitted_; }
  const std::map<Key, std::uint64_t>& dropped() const { return dropped_; }
  std::uint64_t dropped_total() const { return dropped_total_; }
  std::uint64_t unlisted_admitted() const { return unlisted_admitted_; }
  std::uint64_t unlisted_dropped() const { return unlisted_dropped_; }
  /// Distinct admitted sources (listed, plus 1 if any went unlisted: at least that many).
  std::size_t admitted_sources() const { return admitted_.size() + (unlisted_admitted_ > 0 ? 1 : 0); }

  /// "a.b.c.d:port (n), ..." of a map, for /diagnostics.
  static std::string describe(const std::map<Key, std::uint64_t>& sources);

 private:
  std::map<Key, std::uint64_t> admitted_, dropped_;
  std::uint64_t dropped_total_ = 0, unlisted_admitted_ = 0, unlisted_dropped_ = 0;
};

}  // namespace rocking_monitor::feeds
