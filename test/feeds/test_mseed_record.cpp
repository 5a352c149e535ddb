// miniSEED 2 records written by libmseed (steim2, steim1, int32) decode to the same counts and
// times; a record with an unknown encoding and a damaged one are told apart.
#include <gtest/gtest.h>

#include <cmath>

#include "rocking_monitor/feeds/mseed_record.hpp"
#include "rocking_monitor/feeds/mseed_writer.hpp"

namespace rocking_monitor::feeds {
namespace {

ChannelSeries sine_series(std::size_t n) {
  ChannelSeries s;
  s.network = "CI";
  s.station = "RIN";
  s.location = "00";
  s.channel = "HNZ";
  s.start_us = 1000000000LL * 1000000 + 5000;  // 2001-09-09T01:46:40.005Z
  s.sample_rate = 200.0;
  for (std::size_t i = 0; i < n; ++i)
    s.counts.push_back(static_cast<std::int32_t>(std::lround(400000.0 * std::sin(0.05 * static_cast<double>(i)) + (i % 7) * 13)));
  return s;
}

TEST(MseedRecord, RoundTripOfEveryIntegerEncoding) {
  const ChannelSeries s = sine_series(3000);
  for (int encoding : {11, 10, 3}) {
    PackOptions o;
    o.encoding = encoding;
    const std::vector<std::string> records = pack_channel(s, o);
    ASSERT_GT(records.size(), 3u);
    MseedDecoder d;
    DecodedRecord r;
    std::size_t at = 0;
    for (const std::string& rec : records) {
      ASSERT_EQ(rec.size(), 512u);
      ASSERT_EQ(d.decode(rec.data(), rec.size(), r), MseedDecoder::Result::Ok) << d.error();
      EXPECT_EQ(r.network, "CI");
      EXPECT_EQ(r.station, "RIN");
      EXPECT_EQ(r.location, "00");
      EXPECT_EQ(r.channel, "HNZ");
      EXPECT_EQ(r.encoding, encoding);
      EXPECT_DOUBLE_EQ(r.sample_rate, 200.0);
      EXPECT_EQ(r.start_us, s.start_us + static_cast<std::int64_t>(at) * 5000) << "record at sample " << at;
      for (std::size_t i = 0; i < r.samples.size(); ++i) ASSERT_EQ(r.samples[i], s.counts[at + i]) << at + i;
      at += r.samples.size();
    }
    EXPECT_EQ(at, s.counts.size()) << "encoding " << encoding;
  }
}

TEST(MseedRecord, ShortRecordsHoldAtMostTheGivenSamples) {
  PackOptions o;
  o.max_samples = 50;
  const std::vector<std::string> records = pack_channel(sine_series(260), o);
  ASSERT_EQ(records.size(), 6u);
  MseedDecoder d;
  DecodedRecord r;
  ASSERT_EQ(d.decode(records.back().data(), 512, r), MseedDecoder::Result::Ok);
  EXPECT_EQ(r.samples.size(), 10u);
}

TEST(MseedRecord, UnknownEncodingAndDamageAreReported) {
  std::string rec = pack_channel(sine_series(100)).front();
  // Blockette 1000 follows the 48-byte fixed header: type (2), next (2), encoding (1), ...
  ASSERT_EQ(static_cast<unsigned char>(rec[48]), 0x03);
  ASSERT_EQ(static_cast<unsigned char>(rec[49]), 0xE8);
  std::string unknown = rec;
  unknown[52] = 99;
  MseedDecoder d;
  DecodedRecord r;
  EXPECT_EQ(d.decode(unknown.data(), unknown.size(), r), MseedDecoder::Result::UnknownEncoding);
  EXPECT_EQ(r.encoding, 99);
  EXPECT_NE(d.error().find("encoding 99"), std::string::npos) << d.error();
  std::string damaged = rec;
  damaged[6] = 'X';  // quality indicator: no longer a data record
  EXPECT_EQ(d.decode(damaged.data(), damaged.size(), r), MseedDecoder::Result::Malformed);
  std::string garbage(512, 'Z');
  EXPECT_EQ(d.decode(garbage.data(), garbage.size(), r), MseedDecoder::Result::Malformed);
  // Still good afterwards.
  EXPECT_EQ(d.decode(rec.data(), rec.size(), r), MseedDecoder::Result::Ok) << d.error();
}

}  // namespace
}  // namespace rocking_monitor::feeds
