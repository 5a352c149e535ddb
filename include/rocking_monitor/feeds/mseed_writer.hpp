#pragma once

// Writes one channel of integer counts as miniSEED 2 records with libmseed (msr_pack), for
// record_to_mseed and the tests: what an instrument would send over SeedLink.

#include <cstdint>
#include <string>
#include <vector>

namespace rocking_monitor::feeds {

struct ChannelSeries {
  std::string network, station, location, channel;  ///< SEED codes (2, 5, 2, 3 characters at most)
  std::int64_t start_us = 0;  ///< time of the first sample, microseconds since the epoch (UTC)
  double sample_rate = 0.0;   ///< Hz
  std::vector<std::int32_t> counts;
};

struct PackOptions {
  int encoding = 11;           ///< SEED code: 11 steim2 (default), 10 steim1, 3 int32
  int record_length = 512;     ///< bytes, a power of two in 256..8192
  /// Largest number of samples per record (0: as many as fit). Smaller values make records of
  /// shorter duration, as recorders configured for low latency send.
  std::size_t max_samples = 0;
};

/// The records, in time order, each exactly record_length bytes (big-endian, blockette 1000 and
/// 1001). Throws std::invalid_argument for bad codes or options, std::runtime_error if libmseed fails.
std::vector<std::string> pack_channel(const ChannelSeries& series, const PackOptions& options = {});

}  // namespace rocking_monitor::feeds
