// ~allowed_senders of udp_accel_bridge (include/rocking_monitor/feeds/sender_filter.hpp).
#include "rocking_monitor/feeds/sender_filter.hpp"

#include <cctype>
#include <utility>

namespace rocking_monitor::feeds {

namespace {

// Digits only, at most `max_digits`, value <= max_value: no sign, spaces or hex, so that an
// entry such as "10.0.0.1 " or "0x7f.0.0.1" is refused rather than read as something else.
std::optional<unsigned long> parse_decimal(const std::string& text, std::size_t max_digits,
                                           unsigned long max_value) {
  if (text.empty() || text.size() > max_digits) return std::nullopt;
  unsigned long value = 0;
  for (char c : text) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
    value = value * 10 + static_cast<unsigned long>(c - '0');
  }
  if (value > max_value) return std::nullopt;
  return value;
}

std::uint32_t prefix_mask(int prefix) {
  // Shifting a 32-bit value by 32 is undefined: /0 is handled apart.
  return prefix == 0 ? 0u : ~std::uint32_t{0} << (32 - prefix);
}

}  // namespace

std::optional<std::uint32_t> parse_ipv4(const std::string& text) {
  std::uint32_t address = 0;
  std::size_t start = 0;
  for (int octet = 0; octet < 4; ++octet) {
    const std::size_t dot = text.find('.', start);
    const bool last = octet == 3;
    if (last != (dot == std::string::npos)) return std::nullopt;
    const std::string part = text.substr(start, last ? std::string::npos : dot - start);
    const auto value = parse_decimal(part, 3, 255);
    if (!value) return std::nullopt;
    address = (address << 8) | static_cast<std::uint32_t>(*value);
    start = dot + 1;
  }
  return address;
}

std::string format_ipv4(std::uint32_t a) {
  return std::to_string(a >> 24) + "." + std::to_string((a >> 16) & 0xFF) + "." +
         std::to_string((a >> 8) & 0xFF) + "." + std::to_string(a & 0xFF);
}

std::string format_endpoint(std::uint32_t address, std::uint16_t port) {
  return format_ipv4(address) + ":" + std::to_string(port);
}

std::vector<std::string> split_sender_list(const std::string& text) {
  std::vector<std::string> entries;
  std::string piece;
  for (char c : text + ",") {
    if (c == ',' || std::isspace(static_cast<unsigned char>(c))) {
      if (!piece.empty()) entries.push_back(piece);
      piece.clear();
    } else {
      piece += c;
    }
  }
  return entries;
}

std::optional<SenderRule> parse_sender_rule(const std::string& entry, std::string& error) {
  const std::string quoted = "allowed_senders entry '" + entry + "'";
  const std::size_t colon = entry.find(':');
  const std::size_t slash = entry.find('/');
  if (colon != std::string::npos && slash != std::string::npos) {
    error = quoted + ": give either a port (a.b.c.d:port) or a range (a.b.c.d/nn), not both";
    return std::nullopt;
  }
  const std::size_t split = colon != std::string::npos ? colon : slash;
  const auto address = parse_ipv4(entry.substr(0, split));
  if (!address) {
    error = quoted + ": not an IPv4 address a.b.c.d (each part 0-255)";
    return std::nullopt;
  }
  SenderRule rule;
  if (colon != std::string::npos) {
    const auto port = parse_decimal(entry.substr(colon + 1), 5, 65535);
    if (!port || *port == 0) {
      error = quoted + ": the port must be a number 1-65535";
      return std::nullopt;
    }
    rule.port = static_cast<std::uint16_t>(*port);
  }
  if (slash != std::string::npos) {
    const auto prefix = parse_decimal(entry.substr(slash + 1), 2, 32);
    if (!prefix) {
      error = quoted + ": the prefix length after '/' must be a number 0-32";
      return std::nullopt;
    }
    rule.prefix = static_cast<int>(*prefix);
  }
  rule.mask = prefix_mask(rule.prefix);
  // A range written with host bits set ("10.0.0.5/24") is refused: it usually means the author
  // meant one host, and accepting the whole range silently would widen who may feed the monitor.
  if ((*address & ~rule.mask) != 0) {
    error = quoted + ": host bits are set beyond /" + std::to_string(rule.prefix) + " (the range is " +
            format_ipv4(*address & rule.mask) + "/" + std::to_string(rule.prefix) + ")";
    return std::nullopt;
  }
  rule.network = *address;
  return rule;
}

bool SenderFilter::configure(const std::vector<std::string>& entries, std::string& error) {
  std::vector<SenderRule> rules;
  for (const auto& entry : entries) {
    auto rule = parse_sender_rule(entry, error);
    if (!rule) return false;
    rules.push_back(*rule);
  }
  rules_ = std::move(rules);
  return true;
}

bool SenderFilter::allows(std::uint32_t address, std::uint16_t port) const {
  if (rules_.empty()) return true;
  for (const auto& rule : rules_) {
    if ((address & rule.mask) != rule.network) continue;
    if (rule.port && *rule.port != port) continue;
    return true;
  }
  return false;
}

bool SenderTally::admit(const SenderFilter& filter, std::uint32_t address, std::uint16_t port) {
  const bool ok = filter.allows(address, port);
  if (!ok) ++dropped_total_;
  auto& listed = ok ? admitted_ : dropped_;
  const Key key = (static_cast<Key>(address) << 16) | port;
  const auto it = listed.find(key);
  if (it != listed.end())
    ++it->second;
  else if (listed.size() < kMaxListed)
    listed.emplace(key, 1);
  else
    ++(ok ? unlisted_admitted_ : unlisted_dropped_);
  return ok;
}

std::string SenderTally::describe(const std::map<Key, std::uint64_t>& sources) {
  std::string text;
  for (const auto& [key, count] : sources) {
    if (!text.empty()) text += ", ";
    text += format_endpoint(static_cast<std::uint32_t>(key >> 16), static_cast<std::uint16_t>(key & 0xFFFF)) +
            " (" + std::to_string(count) + ")";
  }
  return text.empty() ? "none" : text;
}

}  // namespace rocking_monitor::feeds
