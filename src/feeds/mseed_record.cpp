// miniSEED 2 record -> DecodedRecord with libmseed 2 (msr_unpack).
#include "rocking_monitor/feeds/mseed_record.hpp"

#include <libmseed.h>

#include <cstring>
#include <mutex>

namespace rocking_monitor::feeds {
namespace {

// libmseed prints its errors; the decoder returns them instead (thread_local: one per decoder thread).
thread_local std::string last_libmseed_message;
void capture(char* message) {
  last_libmseed_message = message;
  while (!last_libmseed_message.empty() && last_libmseed_message.back() == '\n') last_libmseed_message.pop_back();
}
void quiet_libmseed() {
  static std::once_flag once;
  std::call_once(once, [] { ms_loginit(capture, nullptr, capture, nullptr); });
}

std::string trimmed(const char* s) {
  std::string t(s);
  while (!t.empty() && t.back() == ' ') t.pop_back();
  return t;
}

// The record's samples as doubles; false for a sample type that is not numeric.
bool copy_samples(const MSRecord* m, std::vector<double>& samples) {
  const auto n = static_cast<std::size_t>(m->numsamples);
  samples.resize(n);
  switch (m->sampletype) {
    case 'i': {
      const auto* s = static_cast<const std::int32_t*>(m->datasamples);
      for (std::size_t i = 0; i < n; ++i) samples[i] = s[i];
      return true;
    }
    case 'f': {
      const auto* s = static_cast<const float*>(m->datasamples);
      for (std::size_t i = 0; i < n; ++i) samples[i] = s[i];
      return true;
    }
    case 'd': {
      const auto* s = static_cast<const double*>(m->datasamples);
      for (std::size_t i = 0; i < n; ++i) samples[i] = s[i];
      return true;
    }
    default:
      return false;
  }
}

}  // namespace

MseedDecoder::MseedDecoder() {
  quiet_libmseed();
  msr_ = msr_init(nullptr);
}

MseedDecoder::~MseedDecoder() {
  auto* m = static_cast<MSRecord*>(msr_);
  msr_free(&m);
}

bool MseedDecoder::supported_encoding(int e) {
  return e == DE_INT16 || e == DE_INT32 || e == DE_FLOAT32 || e == DE_FLOAT64 || e == DE_STEIM1 || e == DE_STEIM2;
}

MseedDecoder::Result MseedDecoder::unpack_header(const char* record, std::size_t length, DecodedRecord& out) {
  if (length < 128 || length > (1u << 20)) {
    error_ = "record of " + std::to_string(length) + " bytes (miniSEED records are 128 bytes to 1 MiB)";
    return Result::Malformed;
  }
  if (buffer_.size() < length) buffer_.resize(length);
  std::memcpy(buffer_.data(), record, length);
  auto* m = static_cast<MSRecord*>(msr_);
  last_libmseed_message.clear();
  if (MS_ISVALIDHEADER(buffer_.data()) == 0) {
    error_ = "not a miniSEED data record header";
    return Result::Malformed;
  }
  const int r = msr_unpack(buffer_.data(), static_cast<int>(length), &m, 0, 0);
  msr_ = m;
  if (r != MS_NOERROR) {
    error_ = std::string("miniSEED header: ") + ms_errorstr(r) + (last_libmseed_message.empty() ? "" : ": " + last_libmseed_message);
    return Result::Malformed;
  }
  if (m->Blkt1000 == nullptr) {
    error_ = "miniSEED record without blockette 1000 (encoding and length unknown)";
    return Result::Malformed;
  }
  out.encoding = m->encoding;
  if (!supported_encoding(m->encoding)) {
    error_ = "data encoding " + std::to_string(m->encoding) + " (" + ms_encodingstr(static_cast<char>(m->encoding)) +
             ") is not one of int16, int32, float32, float64, steim1, steim2";
    return Result::UnknownEncoding;
  }
  if (m->reclen != static_cast<int>(length)) {
    error_ = "blockette 1000 gives a record length of " + std::to_string(m->reclen) + " bytes, the packet holds " +
             std::to_string(length);
    return Result::Malformed;
  }
  return Result::Ok;
}

MseedDecoder::Result MseedDecoder::unpack_data(const char* record, std::size_t length) {
  auto* m = static_cast<MSRecord*>(msr_);
  std::memcpy(buffer_.data(), record, length);  // the header pass may have swapped bytes in place
  last_libmseed_message.clear();
  const int r = msr_unpack(buffer_.data(), static_cast<int>(length), &m, 1, 0);
  msr_ = m;
  if (r != MS_NOERROR || m->numsamples != m->samplecnt) {
    error_ = std::string("miniSEED data: ") + (r != MS_NOERROR ? ms_errorstr(r) : "sample count mismatch") +
             (last_libmseed_message.empty() ? "" : ": " + last_libmseed_message);
    return Result::Malformed;
  }
  return Result::Ok;
}

MseedDecoder::Result MseedDecoder::decode(const char* record, std::size_t length, DecodedRecord& out) {
  error_.clear();
  // The header first: an unknown encoding is its own finding, not a decoding failure.
  if (const Result r = unpack_header(record, length, out); r != Result::Ok) return r;
  if (const Result r = unpack_data(record, length); r != Result::Ok) return r;
  auto* m = static_cast<MSRecord*>(msr_);
  const double rate = msr_samprate(m);
  if (!(rate > 0.0)) {
    error_ = "sample rate " + std::to_string(rate) + " Hz (a data record needs a positive rate)";
    return Result::Malformed;
  }
  out.network = trimmed(m->network);
  out.station = trimmed(m->station);
  out.location = trimmed(m->location);
  out.channel = trimmed(m->channel);
  out.start_us = msr_starttime(m);  // hptime_t: microseconds (HPTMODULUS 1000000)
  out.sample_rate = rate;
  out.record_length = static_cast<std::uint32_t>(m->reclen);
  if (!copy_samples(m, out.samples)) {
    error_ = std::string("sample type '") + m->sampletype + "' is not numeric";
    return Result::Malformed;
  }
  return Result::Ok;
}

}  // namespace rocking_monitor::feeds
