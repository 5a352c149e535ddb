#pragma once

// The last SeedLink sequence number of each station, kept in a small text file so that a restarted
// bridge resumes where the last one stopped (one line per station: "<NET_STA> <6 hex digits>").

#include <cstdint>
#include <map>
#include <string>

namespace rocking_monitor::feeds {

/// Reads the file; an absent file is an empty map. Throws std::runtime_error "<file>:<line>: ..."
/// for a line that is not "<NET_STA> <hex>" with a number below 2^24.
std::map<std::string, std::uint32_t> read_sequence_state(const std::string& path);

/// Writes the map to a fresh "<path>.tmp.XXXXXX" (mkostemp: 0600, never a planted link) and renames it
/// over the file (never a half-written file).
/// Throws std::runtime_error naming the file when it cannot be written.
void write_sequence_state(const std::string& path, const std::map<std::string, std::uint32_t>& state);

}  // namespace rocking_monitor::feeds
