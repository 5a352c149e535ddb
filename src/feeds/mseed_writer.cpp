// One channel of counts -> miniSEED 2 records with libmseed's msr_pack (see the header).
#include "rocking_monitor/feeds/mseed_writer.hpp"

#include <libmseed.h>

#include <cstring>
#include <stdexcept>

namespace rocking_monitor::feeds {
namespace {

void copy_code(char* dst, std::size_t size, const std::string& code, std::size_t max, const char* what) {
  if (code.size() > max) throw std::invalid_argument(std::string(what) + " code '" + code + "' is longer than " + std::to_string(max));
  std::memset(dst, 0, size);
  std::memcpy(dst, code.data(), code.size());
}

void collect(char* record, int length, void* out) {
  static_cast<std::vector<std::string>*>(out)->emplace_back(record, static_cast<std::size_t>(length));
}

}  // namespace

std::vector<std::string> pack_channel(const ChannelSeries& s, const PackOptions& o) {
  if (o.encoding != DE_STEIM2 && o.encoding != DE_STEIM1 && o.encoding != DE_INT32)
    throw std::invalid_argument("encoding " + std::to_string(o.encoding) + " is not one of 11 (steim2), 10 (steim1), 3 (int32)");
  if (o.record_length < 256 || o.record_length > 8192 || (o.record_length & (o.record_length - 1)) != 0)
    throw std::invalid_argument("record length " + std::to_string(o.record_length) + " is not a power of two in 256..8192");
  if (!(s.sample_rate > 0.0)) throw std::invalid_argument("sample rate must be > 0 Hz");
  if (s.channel.size() != 3) throw std::invalid_argument("channel code '" + s.channel + "' must have 3 characters");
  if (s.station.empty()) throw std::invalid_argument("station code is empty");
  std::vector<std::string> records;
  const std::size_t step = o.max_samples == 0 ? s.counts.size() : o.max_samples;
  const std::int64_t period_us = static_cast<std::int64_t>(1e6 / s.sample_rate + 0.5);
  std::int32_t sequence = 1;
  for (std::size_t at = 0; at < s.counts.size(); at += step) {
    const std::size_t n = std::min(step, s.counts.size() - at);
    MSRecord* msr = msr_init(nullptr);
    copy_code(msr->network, sizeof msr->network, s.network, 2, "network");
    copy_code(msr->station, sizeof msr->station, s.station, 5, "station");
    copy_code(msr->location, sizeof msr->location, s.location, 2, "location");
    copy_code(msr->channel, sizeof msr->channel, s.channel, 3, "channel");
    msr->dataquality = 'D';
    msr->starttime = s.start_us + static_cast<std::int64_t>(at) * period_us;
    msr->samprate = s.sample_rate;
    msr->reclen = o.record_length;
    msr->encoding = static_cast<std::int8_t>(o.encoding);
    msr->byteorder = 1;  // big-endian, as SEED prescribes
    msr->sequence_number = sequence;
    std::vector<std::int32_t> chunk(s.counts.begin() + static_cast<std::ptrdiff_t>(at),
                                    s.counts.begin() + static_cast<std::ptrdiff_t>(at + n));
    msr->datasamples = chunk.data();
    msr->numsamples = static_cast<std::int64_t>(n);
    msr->sampletype = 'i';
    std::int64_t packed = 0;
    const std::size_t before = records.size();
    const int r = msr_pack(msr, collect, &records, &packed, 1, 0);
    msr->datasamples = nullptr;  // ours, not libmseed's to free
    msr_free(&msr);
    if (r < 0 || packed != static_cast<std::int64_t>(n))
      throw std::runtime_error("libmseed could not pack " + s.channel + " samples " + std::to_string(at) + ".." + std::to_string(at + n));
    sequence += static_cast<std::int32_t>(records.size() - before);
  }
  return records;
}

}  // namespace rocking_monitor::feeds
