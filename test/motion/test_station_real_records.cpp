// Tests of stations (src/motion/station_*.cpp) and the sensor-frame mapping (src/motion/sensor_frame.cpp)
// on the real records of $ROCKING_RECORDS_DIR: StationRecords* (grouping counts against MANIFEST.csv and
// the records README, file-name grouping against the manifest, rotations of real pairs). Skipped with a
// notice when the records directory is absent.

#include "station_test_helpers.hpp"

namespace rocking_monitor::core {
namespace {

namespace fs = std::filesystem;

bool records_available() {
  return fs::exists(fs::path(ROCKING_RECORDS_DIR) / "MANIFEST.csv");
}

#define SKIP_WITHOUT_RECORDS()                                                                              \
  do {                                                                                                      \
    if (!records_available()) {                                                                             \
      std::cout << "NOTICE: records directory " << ROCKING_RECORDS_DIR << " not found; skipping" << std::endl; \
      GTEST_SKIP() << "records directory " << ROCKING_RECORDS_DIR << " not found";                          \
    }                                                                                                       \
  } while (0)

// ------------------------------------------------------------------ real records

TEST(StationRecordsManifest, GroupingCountsMatchTheRecordsReadme) {
  SKIP_WITHOUT_RECORDS();
  const StationListing l = list_stations(ROCKING_RECORDS_DIR);
  EXPECT_EQ(l.source, StationSource::Manifest);
  ASSERT_EQ(l.stations.size(), 158u);
  std::size_t components = 0;
  std::size_t three = 0;
  std::set<std::string> ids;
  struct Count {
    int stations = 0, pairs = 0, three = 0, one_h = 0;
  };
  std::map<std::string, Count> per_event;
  for (const StationInfo& s : l.stations) {
    components += s.component_count();
    ids.insert(s.id);
    Count& c = per_event[s.event];
    ++c.stations;
    if (s.horizontals.size() == 2) ++c.pairs;
    if (s.horizontals.size() == 2 && s.verticals.size() == 1) {
      ++three;
      ++c.three;
    }
    if (s.horizontals.size() == 1) ++c.one_h;
    EXPECT_GE(s.horizontals.size(), 1u) << s.id;
  }
  EXPECT_EQ(components, 300u);
  EXPECT_EQ(three, 37u);
  EXPECT_EQ(ids.size(), 158u) << "ids must be unique";
  // the README's table: stations, H pairs, 3-comp, only one H
  const std::map<std::string, std::array<int, 4>> table = {
      {"chichi_1999", {34, 19, 0, 15}},       {"northridge_1994", {24, 16, 10, 8}},
      {"landers_1992", {31, 30, 23, 1}},      {"loma_prieta_1989", {18, 11, 1, 7}},
      {"imperial_valley_1979", {18, 10, 1, 8}}, {"kobe_1995", {11, 4, 0, 7}},
      {"kocaeli_1999", {9, 7, 0, 2}},         {"san_fernando_1971", {4, 2, 2, 2}},
      {"whittier_narrows_1987", {4, 4, 0, 0}}, {"north_palm_springs_1986", {2, 2, 0, 0}},
      {"kern_county_1952", {1, 0, 0, 1}},     {"borrego_mountain_1968", {1, 0, 0, 1}},
      {"morgan_hill_1984", {1, 0, 0, 1}}};
  EXPECT_EQ(per_event.size(), table.size());
  for (const auto& [event, row] : table) {
    const Count& c = per_event[event];
    EXPECT_EQ(c.stations, row[0]) << event;
    EXPECT_EQ(c.pairs, row[1]) << event;
    EXPECT_EQ(c.three, row[2]) << event;
    EXPECT_EQ(c.one_h, row[3]) << event;
  }
  // a station name with commas (the SMC station) survived the CSV quoting
  const StationInfo& sf = find_station(l, "San Francisco, 1295 Shafter, F");
  EXPECT_EQ(sf.event, "loma_prieta_1989");
  EXPECT_EQ(sf.horizontals.size(), 2u);
  EXPECT_EQ(sf.verticals.size(), 1u);
}

TEST(StationRecordsManifest, FindStationByIdNameFileAndSubstring) {
  SKIP_WITHOUT_RECORDS();
  const StationListing l = list_stations(ROCKING_RECORDS_DIR);
  EXPECT_EQ(find_station(l, "northridge_1994/rinaldi_receiving_sta").station, "Rinaldi Receiving Sta");
  EXPECT_EQ(find_station(l, "rinaldi receiving sta").station, "Rinaldi Receiving Sta");
  EXPECT_EQ(find_station(l, "RinaldiUP.AT2").station, "Rinaldi Receiving Sta");
  EXPECT_EQ(find_station(l, "Takatori").event, "kobe_1995");
  EXPECT_EQ(find_station(l, "CHY002").horizontals.size(), 2u);
  const std::string ambiguous = station_error([&] { find_station(l, "El Centro Array"); });
  EXPECT_NE(ambiguous.find("stations match 'El Centro Array', give one of:"), std::string::npos) << ambiguous;
  EXPECT_NE(station_error([&] { find_station(l, "Atlantis"); }).find("no station matches 'Atlantis'"), std::string::npos);
}

TEST(StationRecordsFileNames, GroupingByFileNameReproducesTheManifest) {
  SKIP_WITHOUT_RECORDS();
  const StationListing manifest = list_stations(ROCKING_RECORDS_DIR);
  StationListOptions o;
  o.ignore_manifest = true;
  const StationListing names = list_stations(ROCKING_RECORDS_DIR, o);
  EXPECT_EQ(names.source, StationSource::FileNames);
  EXPECT_EQ(names.stations.size(), manifest.stations.size());
  // compare as sets of "file|V" per station
  auto key = [](const StationInfo& s) {
    std::set<std::string> k;
    for (const auto& c : s.horizontals) k.insert(fs::path(c.file).lexically_normal().string() + "|H");
    for (const auto& c : s.verticals) k.insert(fs::path(c.file).lexically_normal().string() + "|V");
    return k;
  };
  std::set<std::set<std::string>> a;
  std::set<std::set<std::string>> b;
  for (const auto& s : manifest.stations) a.insert(key(s));
  for (const auto& s : names.stations) b.insert(key(s));
  for (const auto& k : a) EXPECT_EQ(b.count(k), 1u) << "manifest station not reproduced by file names: " << *k.begin();
  EXPECT_EQ(names.ignored_files.size(), 2u);  // MANIFEST.csv and README.md
}

TEST(StationRecordsLoad, HorizontalsAreOrderedRightHandedAndChiChiHeadersWin) {
  SKIP_WITHOUT_RECORDS();
  const StationListing l = list_stations(ROCKING_RECORDS_DIR);
  int pairs = 0;
  for (const StationInfo& s : l.stations) {
    if (s.horizontals.size() != 2) continue;
    const StationRecord r = load_station(s);
    const auto a0 = label_azimuth_deg(r.horizontals[0].label);
    const auto a1 = label_azimuth_deg(r.horizontals[1].label);
    ASSERT_TRUE(a0 && a1) << s.id;
    // horizontals[1] is 90 deg counter-clockwise of horizontals[0] (Lucerne: 85 deg, the only exception)
    const double ccw = std::remainder(*a0 - *a1, 360.0);
    if (s.id == "landers_1992/lucerne") {
      EXPECT_EQ(r.horizontals[0].label, "345");
      EXPECT_EQ(r.horizontals[1].label, "260");
      ASSERT_EQ(r.notes.size(), 1u);
      EXPECT_NE(r.notes[0].find("85 deg apart, not orthogonal"), std::string::npos) << r.notes[0];
    } else {
      EXPECT_NEAR(ccw, 90.0, 1e-9) << s.id << " " << r.horizontals[0].label << "/" << r.horizontals[1].label;
    }
    ++pairs;
  }
  EXPECT_EQ(pairs, 105);
  // The three Chi-Chi files named -E whose header says W: positive west in the manifest and header.
  for (const char* name : {"CHY071", "TAP034", "TCU081"}) {
    const StationRecord r = load_station(find_station(l, std::string("chichi_1999/") + name));
    bool west = false;
    for (const Component& c : r.horizontals) west = west || (c.file.find("-E.AT2") != std::string::npos && c.label == "W");
    EXPECT_TRUE(west) << name;
    EXPECT_TRUE(r.notes.empty()) << name << ": " << (r.notes.empty() ? "" : r.notes[0]);
  }
}

TEST(StationRecordsRotate, RealPairsRotateExactlyPreserveNormAndInvert) {
  SKIP_WITHOUT_RECORDS();
  const StationListing l = list_stations(ROCKING_RECORDS_DIR);
  // N/W (Chi-Chi), 000/090 (Kobe), 228/318 (Rinaldi), N-S/E-W in one BBP file, 021/291/DWN (Castaic).
  for (const char* name : {"chichi_1999/chy002", "kobe_1995/takatori", "northridge_1994/rinaldi_receiving_sta", "landers_1992/lucerne_bbp_id_luc",
                           "san_fernando_1971/castaic_old_ridge_route"}) {
    SCOPED_TRACE(name);
    const StationRecord r = load_station(find_station(l, name));
    ASSERT_EQ(r.horizontals.size(), 2u);
    const Component& a = r.horizontals[0];
    const Component& b = r.horizontals[1];  // 90 deg left of a
    const double az = *label_azimuth_deg(a.label);
    RotatedPair p = rotate(a, b, az);  // by 0: reproduces
    EXPECT_EQ(p.along.accel, a.accel);
    EXPECT_EQ(p.left.accel, b.accel);
    p = rotate(a, b, az + 90.0);  // by 90: permutes (along = -b, left = a)
    EXPECT_EQ(p.along.accel, negated(b.accel));
    EXPECT_EQ(p.left.accel, a.accel);
    p = rotate(a, b, az + 180.0);  // by 180: negates
    EXPECT_EQ(p.along.accel, negated(a.accel));
    EXPECT_EQ(p.left.accel, negated(b.accel));
    for (double theta : {13.7, 45.0, 123.456, -77.0, 300.25}) {
      SCOPED_TRACE(theta);
      const RotatedPair q = rotate(a, b, az + theta);
      double worst_norm = 0.0;
      for (std::size_t i = 0; i < a.accel.size(); ++i) {
        const double n0 = std::hypot(a.accel[i], b.accel[i]);
        const double n1 = std::hypot(q.along.accel[i], q.left.accel[i]);
        worst_norm = std::max(worst_norm, std::fabs(n1 - n0) / std::max(n0, 1e-300));
      }
      EXPECT_LT(worst_norm, 4e-15) << "vector norm not preserved";
      // theta then -theta: back to the original azimuth
      const RotatedPair back = rotate(q.along, q.left, az);
      double worst = 0.0;
      double peak = 0.0;
      for (std::size_t i = 0; i < a.accel.size(); ++i) {
        worst = std::max({worst, std::fabs(back.along.accel[i] - a.accel[i]), std::fabs(back.left.accel[i] - b.accel[i])});
        peak = std::max({peak, std::fabs(a.accel[i]), std::fabs(b.accel[i])});
      }
      EXPECT_LT(worst, 2e-15 * peak) << "rotating back does not restore the components";
    }
  }
}

TEST(StationRecordsRotate, LucerneNonOrthogonalPairIsResolvedExactly) {
  SKIP_WITHOUT_RECORDS();
  const StationListing l = list_stations(ROCKING_RECORDS_DIR);
  const StationRecord r = load_station(find_station(l, "landers_1992/lucerne"));
  const Component& a = r.horizontals[0];  // 345
  const Component& b = r.horizontals[1];  // 260
  double peak = 0.0;
  for (std::size_t i = 0; i < a.accel.size(); ++i) peak = std::max({peak, std::fabs(a.accel[i]), std::fabs(b.accel[i])});
  // Projecting the resolved motion back on each sensor axis gives that sensor's record.
  const RotatedPair on_a = rotate(a, b, 345.0);
  const RotatedPair on_b = rotate(a, b, 260.0);
  const RotatedPair mid = rotate(a, b, 37.0);
  const RotatedPair mid_back = rotate(mid.along, mid.left, 345.0);  // now an orthogonal pair
  for (std::size_t i = 0; i < a.accel.size(); ++i) {
    ASSERT_NEAR(on_a.along.accel[i], a.accel[i], 1e-14 * peak) << i;
    ASSERT_NEAR(on_b.along.accel[i], b.accel[i], 1e-14 * peak) << i;
    ASSERT_NEAR(mid_back.along.accel[i], a.accel[i], 1e-14 * peak) << i;
    // the resolved vector has the same norm whatever the output azimuth
    ASSERT_NEAR(std::hypot(mid.along.accel[i], mid.left.accel[i]), std::hypot(on_a.along.accel[i], on_a.left.accel[i]), 1e-14 * peak);
  }
  const SensorFrameMotion m = to_sensor_frame(r);
  EXPECT_EQ(m.ground[0], a.accel);  // x = the 345 channel as recorded
  for (std::size_t i = 0; i < a.accel.size(); ++i) ASSERT_NEAR(m.ground[1][i], on_a.left.accel[i], 0.0);
  EXPECT_NE(m.source[1].find("not orthogonal"), std::string::npos) << m.source[1];
  Component c = b;
  c.label = "350";  // 5 deg from a: refused
  const std::string msg = station_error([&] { rotate(a, c, 0.0); });
  EXPECT_NE(msg.find("nearly parallel (5 deg apart)"), std::string::npos) << msg;
}

TEST(StationRecordsSensorFrame, EveryMultiComponentStationMapsWithCountedPadding) {
  SKIP_WITHOUT_RECORDS();
  const StationListing l = list_stations(ROCKING_RECORDS_DIR);
  int mapped = 0;
  int padded = 0;
  for (const StationInfo& s : l.stations) {
    if (s.component_count() < 2) continue;
    const StationRecord r = load_station(s);
    const SensorFrameMotion m = to_sensor_frame(r);
    std::size_t longest = 0;
    for (const auto& c : r.horizontals) longest = std::max(longest, c.accel.size());
    if (r.vertical) longest = std::max(longest, r.vertical->accel.size());
    EXPECT_EQ(m.size(), longest) << s.id;
    EXPECT_EQ(m.ground[0].size(), m.ground[2].size());
    for (const auto& n : m.notes) padded += n.rfind("padded ", 0) == 0 ? 1 : 0;
    ++mapped;
  }
  EXPECT_EQ(mapped, 105);
  EXPECT_GT(padded, 0) << "the records have pairs of unequal length (e.g. El Centro #10: 7411 and 7403)";
}

}  // namespace
}  // namespace rocking_monitor::core

#undef SKIP_WITHOUT_RECORDS  // unity batches: a later test file of the batch defines its own
