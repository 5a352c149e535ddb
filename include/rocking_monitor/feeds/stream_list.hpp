#pragma once

// The stations a SeedLink client asks for, as users write them: "NET_STA:SELECTORS", e.g.
// "CI_RIN:HN?" or "IU_ANMO:00HN? 00HNZ" (selectors [LL]CCC[.T], blank-separated).

#include <string>
#include <vector>

namespace rocking_monitor::feeds {

struct StreamSpec {
  std::string network;                 ///< e.g. "CI" (1-2 characters)
  std::string station;                 ///< e.g. "RIN" (1-5 characters)
  std::vector<std::string> selectors;  ///< e.g. {"HN?"}; each sent as "SELECT <sel>"
  /// "<net>_<sta>", the station's name in topics and diagnostics.
  std::string name() const { return network + "_" + station; }
};

/// Parses one item; throws std::invalid_argument naming the item and what is wrong with it.
StreamSpec parse_stream(const std::string& item);

/// Parses a list; also refuses the same station twice (naming both items).
std::vector<StreamSpec> parse_streams(const std::vector<std::string>& items);

}  // namespace rocking_monitor::feeds
