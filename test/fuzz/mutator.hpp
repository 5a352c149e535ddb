#pragma once
// Seeded mutations of a parser's input (test/fuzz/fuzz_parsers.cpp): the faults a real file shows.

#include <cstdint>
#include <random>
#include <string>

namespace rocking_monitor::fuzz {

/// 1 to 4 mutations of `in`: byte flips, truncation, a number replaced by a huge/tiny/NaN/Inf/Fortran
/// D-exponent/malformed text, CRLF or lone CR line ends, a UTF-8 BOM, a line duplicated or deleted.
/// `binary` (miniSEED) aims half of the byte flips at the records' 64-byte fixed headers instead.
std::string mutate(const std::string& in, std::mt19937_64& rng, bool binary);

}  // namespace rocking_monitor::fuzz
