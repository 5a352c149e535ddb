#pragma once
// The fuzzer's seeds: real records from the shared records directory, and the formats it lacks
// (miniSEED, COSMOS V2, K-NET, CSV) written here from the real Rinaldi 228 record, by the writers the
// format tests use (test/support/record_writers.hpp).

#include <string>
#include <vector>

namespace rocking_monitor::fuzz {

struct Seed {
  std::string file_name;  ///< name the mutated input is written under (detection reads the extension too)
  std::string bytes;
};

/// One parser and its seeds. `records_dir` is ROCKING_RECORDS_DIR, `config_dir` the package's config/.
struct Target {
  std::string name;  ///< at2, bbp, smc, csv, miniseed, cosmos, knet, catalogue, catalogue_items, and the
                     ///< network parsers (network_parsers.hpp): udp_datagram, seedlink, mseed_record
  bool binary = false;
  std::vector<Seed> seeds;
};

/// Every target; throws std::runtime_error naming a missing seed file.
std::vector<Target> make_targets(const std::string& records_dir, const std::string& config_dir);

/// Counts per m/s^2 the miniSEED seed is written with (the reader is given it: no channel table).
double miniseed_gain();

}  // namespace rocking_monitor::fuzz
