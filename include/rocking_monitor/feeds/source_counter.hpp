#pragma once

// Datagrams of one kind of refusal (issue 52: unauthenticated, bad tag, ...) counted per source
// address:port, so that /diagnostics can name who sent them. Bounded like SenderTally: beyond
// kMaxListed distinct sources the datagrams are still counted, as "others".

#include <cstdint>
#include <map>
#include <string>

#include "rocking_monitor/feeds/sender_filter.hpp"

namespace rocking_monitor::feeds {

class SourceCounter {
 public:
  static constexpr std::size_t kMaxListed = SenderTally::kMaxListed;

  /// Counts one datagram from address:port (host order). Allocates only for a new source.
  void add(std::uint32_t address, std::uint16_t port) {
    ++total_;
    const SenderTally::Key key = (static_cast<SenderTally::Key>(address) << 16) | port;
    const auto it = listed_.find(key);
    if (it != listed_.end())
      ++it->second;
    else if (listed_.size() < kMaxListed)
      listed_.emplace(key, 1);
    else
      ++unlisted_;
  }
  std::uint64_t total() const { return total_; }
  /// "a.b.c.d:port (n), ..., others (m)", or "none".
  std::string describe() const {
    std::string text = SenderTally::describe(listed_);
    if (unlisted_ > 0) text += ", others (" + std::to_string(unlisted_) + ")";
    return text;
  }

 private:
  std::map<SenderTally::Key, std::uint64_t> listed_;
  std::uint64_t total_ = 0, unlisted_ = 0;
};

}  // namespace rocking_monitor::feeds
