// record_to_mseed on a real station (Rinaldi 318, 228, UP): libmseed reads back every channel as
// the record's samples x gain rounded to counts (so within half a count of the AT2 values), at the
// record's times, interleaved by record end time; bad options give one error line.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

#include "rocking_monitor/feeds/mseed_record.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "test_helpers.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kRecords = fs::path(ROCKING_RECORDS_DIR) / "northridge_1994";

rocking_monitor::core::testing::CommandResult run(const std::string& args) {
  return rocking_monitor::core::testing::run_command(std::string(RECORD_TO_MSEED_EXE) + " " + args + " 2>&1");
}

std::string station_files() {
  return " --file " + (kRecords / "Rinaldi318.AT2").string() + " --file " + (kRecords / "Rinaldi228.AT2").string() +
         " --file " + (kRecords / "RinaldiUP.AT2").string();
}

TEST(RecordToMseed, ReadsBackAsTheRecordInCounts) {
  if (!fs::exists(kRecords / "Rinaldi318.AT2")) GTEST_SKIP() << "records not found: " << kRecords;
  const double gain = 427000.0;
  const auto a318 = rocking_monitor::core::read_record((kRecords / "Rinaldi318.AT2").string()).at(0).accel;
  const auto a228 = rocking_monitor::core::read_record((kRecords / "Rinaldi228.AT2").string()).at(0).accel;
  const auto aup = rocking_monitor::core::read_record((kRecords / "RinaldiUP.AT2").string()).at(0).accel;
  const fs::path out = fs::temp_directory_path() / ("record_to_mseed_" + std::to_string(getpid()) + ".mseed");
  for (int length : {512, 4096}) {
    const auto r = run(station_files() + " -o " + out.string() + " --gain 427000 --network CI --station RIN --orientation 12" +
                       " --record-length " + std::to_string(length));
    ASSERT_EQ(r.status, 0) << r.out;
    std::ifstream f(out, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    ASSERT_EQ(bytes.size() % static_cast<std::size_t>(length), 0u);
    rocking_monitor::feeds::MseedDecoder d;
    rocking_monitor::feeds::DecodedRecord rec;
    std::map<std::string, std::vector<double>> counts;
    std::int64_t last_end = 0;
    for (std::size_t at = 0; at < bytes.size(); at += static_cast<std::size_t>(length)) {
      ASSERT_EQ(d.decode(bytes.data() + at, static_cast<std::size_t>(length), rec), rocking_monitor::feeds::MseedDecoder::Result::Ok)
          << d.error();
      EXPECT_EQ(rec.network, "CI");
      EXPECT_EQ(rec.station, "RIN");
      EXPECT_EQ(rec.encoding, 11);
      auto& c = counts[rec.channel];
      EXPECT_EQ(rec.start_us, 1000000000LL * 1000000 + static_cast<std::int64_t>(c.size()) * 10000) << rec.channel;
      const std::int64_t end = rec.start_us + static_cast<std::int64_t>(rec.samples.size()) * 10000;
      EXPECT_GE(end, last_end) << "records not in the order of their end times";
      last_end = end;
      c.insert(c.end(), rec.samples.begin(), rec.samples.end());
    }
    ASSERT_EQ(counts.size(), 3u);
    ASSERT_EQ(counts["HN1"].size(), a318.size());
    ASSERT_EQ(counts["HN2"].size(), a228.size());
    ASSERT_EQ(counts["HNZ"].size(), aup.size());
    // HN1 = the 318 deg component; HN2 points 90 deg clockwise of it (048 deg) = -(228 deg component).
    for (std::size_t i = 0; i < a318.size(); ++i) {
      ASSERT_EQ(counts["HN1"][i], std::nearbyint(a318[i] * gain)) << i;
      ASSERT_EQ(counts["HN2"][i], std::nearbyint(-a228[i] * gain)) << i;
      ASSERT_EQ(counts["HNZ"][i], std::nearbyint(aup[i] * gain)) << i;
      ASSERT_LE(std::fabs(counts["HN1"][i] / gain - a318[i]), 0.5 / gain);
    }
  }
  fs::remove(out);
}

TEST(RecordToMseed, BadOptionsAreOneErrorLine) {
  if (!fs::exists(kRecords / "Rinaldi318.AT2")) GTEST_SKIP() << "records not found: " << kRecords;
  const std::string out = " -o " + (fs::temp_directory_path() / "never_written.mseed").string();
  auto r = run(station_files() + out);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("record_to_mseed: error: --gain is required"), std::string::npos) << r.out;
  r = run(station_files() + out + " --gain 1e9");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("beyond +-2^29 (lower --gain)"), std::string::npos) << r.out;
  r = run(" --file " + (kRecords / "Rinaldi318.AT2").string() + out + " --gain 1000");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("three components"), std::string::npos) << r.out;
  r = run(station_files() + out + " --gain 1000 --azimuth 10");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("--azimuth is for --orientation 12"), std::string::npos) << r.out;
}

}  // namespace
