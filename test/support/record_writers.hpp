#pragma once
// Writers of the record formats the shared records directory lacks (miniSEED, COSMOS V2, K-NET),
// used by the format tests (test/motion/test_record_formats.cpp) and the fuzzer's seeds
// (test/fuzz/seed_records.cpp): one writer, so a fix to a format reaches both.
// No GoogleTest here: the fuzzer links without it; a writer that fails throws.

#include <libmseed.h>

#include <string>
#include <vector>

#include "rocking_monitor/motion/record_reader.hpp"

namespace rocking_monitor::core::testing {

// ------------------------------------------------------------------ miniSEED (packed by libmseed)

/// The Rinaldi records' start, 1994-01-17T12:31:01Z (hptime: microseconds).
inline const hptime_t kRinaldiStart = MS_EPOCH2HPTIME(758809861);
/// A 24-bit logger with a +-2 g sensor: 2^23 counts / (2 g), in counts per m/s^2.
double logger_gain();

/// One channel packed into miniSEED records by libmseed (samples as int32 for integer encodings,
/// float32/float64 otherwise); returns the records. Throws std::runtime_error when libmseed packs
/// no record or not every sample.
std::vector<std::string> pack_channel(const std::string& chan, double rate, hptime_t start,
                                      const std::vector<double>& values, int encoding, int reclen,
                                      const std::string& sta = "RRS");

/// The channels' records interleaved (one record of each in turn), as a recorder writes them.
std::string interleave(const std::vector<std::vector<std::string>>& channels);

/// The component's samples in counts at `gain` counts per m/s^2, rounded to whole counts.
std::vector<double> counts(const Component& c, double gain);

// ------------------------------------------------------------------ COSMOS V2

/// A value as Fortran's Ew.d edit descriptor prints it: 0.ddddddE+ee, right-aligned in w columns,
/// the leading 0 dropped when the value would not fit ("-.123457E+01"); `exp` is 'E' or 'D'.
std::string fortran_e(double v, int w, int d, char exp = 'E');

struct CosmosChannel {
  const Component* comp;
  int orientation;  // integer header #54
  double dt;        // real header #34
  std::string units = "cm/sec2(04)";
  char real_exp = 'E';  // 'D': the real header in Fortran D exponents
  /// Real-world quirks: trailing blanks on every other line and a velocity block after the
  /// acceleration. Off: the plainest file the v1.20 description allows.
  bool quirks = true;
};

/// One channel of a COSMOS V2 file after the v1.20 description: 13 text lines, 100 integers (10I8),
/// 100 reals (5E16.7 or 5D16.7), one comment, the acceleration in (6E13.6) (negative values touch:
/// "-0.123456E+01-0.234567E+01"), [a short velocity block,] End-of-data.
std::string cosmos_channel(const CosmosChannel& ch, int number, const std::string& eol);

// ------------------------------------------------------------------ K-NET / KiK-net ASCII

struct KnetFile {
  std::string text;
  std::vector<long long> counts;
  double gal_per_count;
};

/// A K-NET ASCII file after NIED's description: 17 header lines (name in columns 1-18), counts 8
/// per line in 9 columns, the logger's offset added to every count, Max. Acc. of the record with
/// its mean removed (as NIED defines it). `old_names`: "Long."/"Max. Acc." (older files) rather than
/// "Lon."/"Max Acc."; `trailing_blanks`: two blanks after every third data line (a quirk).
KnetFile knet_file(const Component& c, const std::string& dir_field, long long offset, const std::string& eol,
                   bool old_names, const std::string& scale = "3920(gal)/6182761", bool trailing_blanks = true);

}  // namespace rocking_monitor::core::testing
