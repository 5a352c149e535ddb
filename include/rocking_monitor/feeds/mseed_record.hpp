#pragma once

// One miniSEED 2 data record decoded with libmseed (Debian libmseed-dev): its codes, start time,
// rate and samples (counts). Integer (int16, int32, steim1, steim2) and float (float32, float64)
// encodings are decoded; any other encoding is reported as such, never guessed.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rocking_monitor::feeds {

struct DecodedRecord {
  std::string network, station, location, channel;  ///< blanks trimmed
  std::int64_t start_us = 0;   ///< time of the first sample, microseconds since the epoch (UTC)
  double sample_rate = 0.0;    ///< Hz
  int encoding = 0;            ///< SEED data encoding code (blockette 1000)
  std::uint32_t record_length = 0;  ///< bytes
  std::vector<double> samples;  ///< counts; sized to the record's sample count (capacity kept)
};

class MseedDecoder {
 public:
  enum class Result {
    Ok,
    Malformed,        ///< not a miniSEED data record, or its data do not decode
    UnknownEncoding,  ///< a valid header whose encoding is not one of the six above
  };
  MseedDecoder();
  ~MseedDecoder();
  MseedDecoder(const MseedDecoder&) = delete;
  MseedDecoder& operator=(const MseedDecoder&) = delete;

  /// Decodes `length` bytes; `out` keeps its capacity between calls (no allocation once grown).
  Result decode(const char* record, std::size_t length, DecodedRecord& out);
  /// Why the last decode was not Ok.
  const std::string& error() const { return error_; }

  static bool supported_encoding(int encoding);

 private:
  // decode()'s passes: the header (length, blockette 1000, encoding) into out.encoding, then the data.
  Result unpack_header(const char* record, std::size_t length, DecodedRecord& out);
  Result unpack_data(const char* record, std::size_t length);

  void* msr_ = nullptr;       ///< MSRecord*, reused between records
  std::vector<char> buffer_;  ///< libmseed unpacks in place (byte swapping): a private copy
  std::string error_;
};

}  // namespace rocking_monitor::feeds
