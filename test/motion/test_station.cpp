// Tests of stations (src/motion/station_*.cpp), the sensor-frame mapping (src/motion/sensor_frame.cpp) and
// the synthetic signals (src/motion/synthetic_motion.cpp) on small synthetic inputs, always run:
// StationLabels / StationManifestParsing / StationFileNamesSynthetic / StationRotateSynthetic /
// StationSensorFrame / SyntheticMotion. The real records: test_station_real_records.cpp.

#include "station_test_helpers.hpp"

namespace rocking_monitor::core {
namespace {

namespace fs = std::filesystem;

class StationTempDir {
 public:
  StationTempDir() {
    static std::atomic<int> counter{0};
    path_ = fs::temp_directory_path() / ("rocking_station_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~StationTempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  StationTempDir(const StationTempDir&) = delete;
  StationTempDir& operator=(const StationTempDir&) = delete;
  std::string write(const std::string& name, const std::string& content) const {
    const fs::path p = path_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << content;
    return p.string();
  }
  std::string str() const { return path_.string(); }

 private:
  fs::path path_;
};

/// A PEER NGA AT2 file holding `values` (in g) with the given header component label.
std::string at2_text(const std::string& station, const std::string& label, const std::vector<double>& values, double dt = 0.01) {
  char line4[128];
  std::snprintf(line4, sizeof line4, "NPTS=  %zu, DT=  %.4f SEC,\n", values.size(), dt);
  std::string s = "PEER NGA STRONG MOTION DATABASE RECORD\nTest Quake, 1/2/2003, " + station + ", " + label +
                  "\nACCELERATION TIME SERIES IN UNITS OF G\n" + line4;
  char buf[32];
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::snprintf(buf, sizeof buf, " %.7E", values[i]);
    s += buf;
    if (i % 5 == 4 || i + 1 == values.size()) s += "\n";
  }
  return s;
}

Component make_component(const std::string& file, const std::string& label, std::vector<double> accel, double dt = 0.01) {
  Component c;
  c.file = file;
  c.label = label;
  c.vertical = label_is_vertical(label);
  c.dt = dt;
  c.accel = std::move(accel);
  return c;
}

std::vector<double> ramp(std::size_t n, double a, double b) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = a * std::sin(0.37 * static_cast<double>(i) + b) + 0.1 * b;
  return v;
}

// ------------------------------------------------------------------ labels

TEST(StationLabels, AzimuthFromEveryLabelStyle) {
  const std::map<std::string, double> expected = {
      {"000", 0.0},  {"0", 0.0},    {"090", 90.0}, {"90", 90.0}, {"228", 228.0}, {"360", 0.0},
      {"37.5", 37.5}, {"N", 0.0},   {"-N", 0.0},   {"E", 90.0},  {"-E", 90.0},   {"S", 180.0},
      {"W", 270.0},  {"-W", 270.0}, {"N-S", 0.0},  {"E-W", 90.0}, {"n", 0.0},    {" 180 ", 180.0}};
  for (const auto& [label, az] : expected) {
    const auto got = label_azimuth_deg(label);
    ASSERT_TRUE(got.has_value()) << label;
    EXPECT_EQ(*got, az) << label;
  }
  for (const char* none : {"UP", "DWN", "-UP", "U-D", "up", "V", "H", "", "L", "T", "N45E", "1.2.3"}) {
    EXPECT_FALSE(label_azimuth_deg(none).has_value()) << none;
  }
  EXPECT_EQ(format_azimuth_label(90.0), "090");
  EXPECT_EQ(format_azimuth_label(-90.0), "270");
  EXPECT_EQ(format_azimuth_label(360.0), "000");
  EXPECT_EQ(format_azimuth_label(37.5), "37.5");
  EXPECT_EQ(*label_azimuth_deg(format_azimuth_label(123.456)), 123.456);
  EXPECT_EQ(slugify("Gilroy - Gavilan Coll."), "gilroy_gavilan_coll");
  EXPECT_EQ(slugify("San Francisco, 1295 Shafter, F"), "san_francisco_1295_shafter_f");
}

// ------------------------------------------------------------------ manifest parsing

const char* kManifestHeader = "event,year,station,component,file,format,units,dt_s,npts,pga_g,source_repo,source_path,notes\n";

TEST(StationManifestParsing, QuotedNamesWithCommasAndQuotes) {
  StationTempDir dir;
  std::string m = kManifestHeader;
  m += "ev,1999,\"San Francisco, 1295 Shafter, F\",H:360,ev/a.smc,USGS_SMC_V2,cm/s2,0.005,6001,0.1,r,p,\n";
  m += "ev,1999,\"San Francisco, 1295 Shafter, F\",V:up,ev/b.smc,USGS_SMC_V2,cm/s2,0.005,6002,0.1,r,p,\"a note, with \"\"quotes\"\"\"\n";
  m += "ev,1999,\"San Francisco, 1295 Shafter, F\",H:270,ev/c.smc,USGS_SMC_V2,cm/s2,0.005,6004,0.1,r,p,\n";
  m += "ev,1999,Other,H:N,ev/RSN1_EV_OTH-N.AT2,PEER_AT2_NGA,g,0.01,5,0.1,r,p,\"multi\nline note\"\n";
  m += "ev,1999,Other,H:W,ev/RSN1_EV_OTH-E.AT2,PEER_AT2_NGA,g,0.01,5,0.1,r,p,\n";
  dir.write("MANIFEST.csv", m);
  const StationListing l = list_stations(dir.str());
  EXPECT_EQ(l.source, StationSource::Manifest);
  ASSERT_EQ(l.stations.size(), 2u);
  EXPECT_EQ(l.stations[0].station, "San Francisco, 1295 Shafter, F");
  EXPECT_EQ(l.stations[0].id, "ev/san_francisco_1295_shafter_f");
  EXPECT_EQ(l.stations[0].horizontals.size(), 2u);
  ASSERT_EQ(l.stations[0].verticals.size(), 1u);
  EXPECT_EQ(l.stations[0].verticals[0].label, "up");
  EXPECT_EQ(l.stations[0].verticals[0].manifest_line, 3u);
  EXPECT_EQ(l.stations[0].verticals[0].manifest_npts, 6002u);
  EXPECT_EQ(l.stations[0].horizontals[1].manifest_dt, 0.005);
  EXPECT_EQ(l.stations[1].station, "Other");
  // the quoted note spans two lines: the next record starts on line 7
  EXPECT_EQ(l.stations[1].horizontals[1].manifest_line, 7u);
  EXPECT_EQ(l.stations[1].horizontals[1].label, "W");
  EXPECT_EQ(fs::path(l.stations[1].horizontals[1].file).filename(), "RSN1_EV_OTH-E.AT2");
}

TEST(StationManifestParsing, ErrorsNameTheManifestLine) {
  struct Case {
    std::string rows;
    std::size_t line;
    std::string part;
  };
  const std::vector<Case> cases = {
      {"ev,1,A,H:N,f.AT2,x,g,0.01,5,0.1,r,p,\nev,1,\"B, C,H:N,f.AT2,x,g,0.01,5,0.1,r,p,\n", 3, "unterminated quoted field"},
      {"ev,1,San Francisco, 1295 Shafter,H:N,f.AT2,x,g,0.01,5,0.1,r,p,\n", 2, "expected 13 fields"},
      {"ev,1,A,X:N,f.AT2,x,g,0.01,5,0.1,r,p,\n", 2, "must start with 'H:'"},
      {"ev,1,A,H:UP,f.AT2,x,g,0.01,5,0.1,r,p,\n", 2, "label says vertical"},
      {"ev,1,A,H:N,f.AT2,x,g,abc,5,0.1,r,p,\n", 2, "non-numeric dt_s 'abc'"},
      {"ev,1,A,H:N,f.AT2,x,g,0.01,5,0.1,r,p,\nev,1,A,H:E,g.AT2,x,g,0.01,5,0.1,r,p,\nev,1,A,H:W,h.AT2,x,g,0.01,5,0.1,r,p,\n", 4,
       "more than 2 horizontal components: f.AT2 [N], g.AT2 [E], h.AT2 [W]"},
      {"ev,1,A,V:UP,f.AT2,x,g,0.01,5,0.1,r,p,\nev,1,A,V:DWN,g.AT2,x,g,0.01,5,0.1,r,p,\n", 3, "more than 1 vertical"},
      {"ev,1,A,H:N,f.AT2,x,g,0.01,5,0.1,r,p,\nev,1,A,H:N,f.AT2,x,g,0.01,5,0.1,r,p,\n", 3, "listed twice"},
      {"ev,1,\"A\"x,H:N,f.AT2,x,g,0.01,5,0.1,r,p,\n", 2, "after a quoted field"},
      {"ev,1,A\"B,H:N,f.AT2,x,g,0.01,5,0.1,r,p,\n", 2, "inside an unquoted field"},
  };
  for (const Case& c : cases) {
    StationTempDir dir;
    const std::string manifest = dir.write("MANIFEST.csv", std::string(kManifestHeader) + c.rows);
    const std::string msg = station_error([&] { list_stations(dir.str()); });
    const std::string prefix = manifest + ":" + std::to_string(c.line) + ": ";
    EXPECT_EQ(msg.rfind(prefix, 0), 0u) << "expected prefix " << prefix << " in: " << msg;
    EXPECT_NE(msg.find(c.part), std::string::npos) << "missing '" << c.part << "' in: " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  StationTempDir dir;
  dir.write("MANIFEST.csv", "event,station,file\nev,A,f.AT2\n");
  EXPECT_NE(station_error([&] { list_stations(dir.str()); }).find(":1: missing column 'component'"), std::string::npos);
  EXPECT_NE(station_error([&] { list_stations(dir.str() + "/nope"); }).find("not a directory"), std::string::npos);
}

// ------------------------------------------------------------------ file-name grouping (synthetic)

TEST(StationFileNamesSynthetic, GroupsByRsnAndCodeAndUsesTheHeaderLabel) {
  StationTempDir dir;
  const std::vector<double> v = {0.01, 0.02, -0.01, 0.0, 0.005};
  dir.write("quake/RSN7_QUAKE.A_A-STA-N.AT2", at2_text("Sta", "N", v));
  dir.write("quake/RSN7_QUAKE.A_A-STA-E.AT2", at2_text("Sta", "W", v));  // named -E, header says W (Chi-Chi style)
  dir.write("quake/RSN7_QUAKE.A_A-STA-UP.AT2", at2_text("Sta", "UP", v));
  dir.write("quake/RSN8_QUAKE.A_B-XYZ000.AT2", at2_text("Xyz", "000", v));
  dir.write("quake/RSN8_QUAKE.A_B-XYZ090.AT2", at2_text("Xyz", "090", v));
  dir.write("quake/RSN8_QUAKE.A_B-XYZDWN.AT2", at2_text("Xyz", "DWN", v));
  dir.write("quake/Rinaldi228.AT2", at2_text("R", "228", v));
  dir.write("quake/Rinaldi318.AT2", at2_text("R", "318", v));
  dir.write("quake/notes.txt", "not a record\n");
  const StationListing l = list_stations(dir.str());
  EXPECT_EQ(l.source, StationSource::FileNames);
  ASSERT_EQ(l.stations.size(), 3u);
  ASSERT_EQ(l.ignored_files.size(), 1u);
  EXPECT_EQ(fs::path(l.ignored_files[0]).filename(), "notes.txt");
  std::map<std::string, const StationInfo*> by_name;
  for (const auto& s : l.stations) by_name[s.station] = &s;
  ASSERT_EQ(by_name.count("A-STA"), 1u);
  ASSERT_EQ(by_name.count("B-XYZ"), 1u);
  ASSERT_EQ(by_name.count("Rinaldi"), 1u);
  EXPECT_EQ(by_name["A-STA"]->horizontals.size(), 2u);
  EXPECT_EQ(by_name["A-STA"]->verticals.size(), 1u);
  EXPECT_EQ(by_name["A-STA"]->event, "quake");
  EXPECT_EQ(by_name["B-XYZ"]->verticals.at(0).label, "DWN");
  EXPECT_EQ(by_name["Rinaldi"]->horizontals.size(), 2u);

  // Loading uses the header: the "-E" file is positive west; ordered so that y = x - 90 deg.
  const StationRecord r = load_station(*by_name["A-STA"]);
  ASSERT_EQ(r.horizontals.size(), 2u);
  EXPECT_EQ(r.horizontals[0].label, "N");
  EXPECT_EQ(r.horizontals[1].label, "W");
  ASSERT_EQ(r.notes.size(), 1u) << r.notes.size();
  EXPECT_NE(r.notes[0].find("file name says 'E', header says 'W'"), std::string::npos) << r.notes[0];
  const StationRecord x = load_station(*by_name["B-XYZ"]);
  EXPECT_EQ(x.horizontals[0].label, "090");  // (090, 000, up) = (E, N, U)
  EXPECT_EQ(x.horizontals[1].label, "000");
  ASSERT_TRUE(x.vertical.has_value());
  EXPECT_DOUBLE_EQ(x.vertical->accel[0], -0.01 * kGravity);  // DWN flipped to positive up
}

TEST(StationFromFiles, AdHocStationFromFilesNotesMixedStations) {
  StationTempDir dir;
  const std::vector<double> v = {0.01, 0.02, -0.01, 0.0, 0.005};
  const std::string n = dir.write("a-N.AT2", at2_text("Alpha", "N", v));
  const std::string e = dir.write("a-E.AT2", at2_text("Alpha", "E", v));
  const std::string up = dir.write("b-UP.AT2", at2_text("Beta", "UP", v));
  const StationInfo info = station_from_files({n, e, up});
  EXPECT_EQ(info.source, StationSource::Files);
  EXPECT_EQ(info.station, "Alpha");
  EXPECT_EQ(info.id, "test_quake/alpha");
  EXPECT_EQ(info.horizontals.size(), 2u);
  EXPECT_EQ(info.verticals.size(), 1u);
  const StationRecord r = load_station(info);
  EXPECT_EQ(r.horizontals[0].label, "E");  // (E, N, up)
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_NE(r.notes[0].find("the headers name different stations: 'Alpha' (a-N.AT2) and 'Beta' (b-UP.AT2)"), std::string::npos) << r.notes[0];
  const std::string three = station_error([&] { station_from_files({n, e, n}); });
  EXPECT_NE(three.find("listed twice"), std::string::npos) << three;
  EXPECT_THROW(station_from_files({dir.str() + "/missing.AT2"}), RecordError);
}

// ------------------------------------------------------------------ rotation (synthetic)

TEST(StationRotateSynthetic, ZeroNinetyOneEightyAreExact) {
  const Component n = make_component("n.AT2", "N", ramp(257, 1.3, 0.2));
  const Component e = make_component("e.AT2", "E", ramp(257, 0.7, 1.1));
  // (E, N) is the right-handed order: left of east is north.
  RotatedPair r = rotate(e, n, 90.0);
  EXPECT_EQ(r.along.accel, e.accel);
  EXPECT_EQ(r.left.accel, n.accel);
  EXPECT_EQ(r.along.label, "090");
  EXPECT_EQ(r.left.label, "000");
  r = rotate(n, e, 0.0);  // order of the inputs does not matter
  EXPECT_EQ(r.along.accel, n.accel);
  EXPECT_EQ(r.left.accel, negated(e.accel));  // left of north is west
  r = rotate(e, n, 180.0);
  EXPECT_EQ(r.along.accel, negated(n.accel));  // south
  EXPECT_EQ(r.left.accel, e.accel);            // left of south is east
  r = rotate(e, n, 270.0);
  EXPECT_EQ(r.along.accel, negated(e.accel));
  EXPECT_EQ(r.left.accel, negated(n.accel));
  r = rotate(e, n, -270.0);  // = 90
  EXPECT_EQ(r.along.accel, e.accel);
  // 45 deg: along = (n + e)/sqrt(2)
  r = rotate(e, n, 45.0);
  for (std::size_t i = 0; i < n.accel.size(); ++i) {
    EXPECT_NEAR(r.along.accel[i], (n.accel[i] + e.accel[i]) / std::sqrt(2.0), 1e-15);
    EXPECT_NEAR(r.left.accel[i], (n.accel[i] - e.accel[i]) / std::sqrt(2.0), 1e-15);  // toward NW
  }
}

TEST(StationRotateSynthetic, ErrorsNameBothFiles) {
  const Component a = make_component("dir/first.AT2", "000", ramp(100, 1.0, 0.0));
  Component b = make_component("dir/second.AT2", "090", ramp(99, 1.0, 0.5));
  std::string msg = station_error([&] { rotate(a, b, 30.0); });
  EXPECT_NE(msg.find("first.AT2 [000] and second.AT2 [090]"), std::string::npos) << msg;
  EXPECT_NE(msg.find("different lengths (100 and 99 samples)"), std::string::npos) << msg;
  b = make_component("dir/second.AT2", "090", ramp(100, 1.0, 0.5), 0.02);
  msg = station_error([&] { rotate(a, b, 30.0); });
  EXPECT_NE(msg.find("first.AT2 [000] and second.AT2 [090]: different sample intervals"), std::string::npos) << msg;
  b = make_component("dir/second.AT2", "175", ramp(100, 1.0, 0.5));
  EXPECT_NE(station_error([&] { rotate(a, b, 30.0); }).find("nearly parallel"), std::string::npos);
  b = make_component("dir/second.AT2", "UP", ramp(100, 1.0, 0.5));
  EXPECT_NE(station_error([&] { rotate(a, b, 30.0); }).find("only horizontal"), std::string::npos);
  b = make_component("dir/second.csv", "H", ramp(100, 1.0, 0.5));
  EXPECT_NE(station_error([&] { rotate(a, b, 30.0); }).find("label 'H' carries no azimuth"), std::string::npos);
}

// ------------------------------------------------------------------ sensor frame (synthetic)

StationRecord synthetic_station(std::size_t n0, std::size_t n1, std::size_t nv) {
  StationRecord r;
  r.info.id = "test/sta";
  r.horizontals.push_back(make_component("x.AT2", "090", ramp(n0, 1.0, 0.1)));
  r.horizontals.push_back(make_component("y.AT2", "000", ramp(n1, 2.0, 0.7)));
  if (nv > 0) r.vertical = make_component("z.AT2", "UP", ramp(nv, 0.5, 1.9));
  return r;
}

TEST(StationSensorFrame, GravityOnZAndExactStamps) {
  StationRecord st = synthetic_station(300, 300, 300);
  for (auto* c : {&st.horizontals[0], &st.horizontals[1], &*st.vertical}) c->t0 = 1.5;
  const SensorFrameMotion m = to_sensor_frame(st);
  ASSERT_EQ(m.size(), 300u);
  EXPECT_EQ(m.ground[0], st.horizontals[0].accel);
  EXPECT_EQ(m.ground[1], st.horizontals[1].accel);
  EXPECT_EQ(m.ground[2], st.vertical->accel);
  EXPECT_EQ(*m.x_azimuth_deg, 90.0);
  for (std::size_t i = 0; i < m.size(); ++i) {
    const AccelerometerSample s = m.sample(i);
    EXPECT_EQ(s.time_ns, 1'500'000'000 + static_cast<std::int64_t>(i) * 10'000'000);
    EXPECT_EQ(s.specific_force[0], st.horizontals[0].accel[i]);
    EXPECT_EQ(s.specific_force[1], st.horizontals[1].accel[i]);
    EXPECT_EQ(s.specific_force[2], st.vertical->accel[i] + kGravity);
    EXPECT_EQ(s.ground[2], st.vertical->accel[i]);
  }
  EXPECT_TRUE(m.notes.empty());
  // no vertical: z reads exactly g; one horizontal: y is zeros and flagged
  StationRecord one = synthetic_station(50, 50, 0);
  one.horizontals.pop_back();
  const SensorFrameMotion m1 = to_sensor_frame(one);
  EXPECT_TRUE(m1.recorded[0]);
  EXPECT_FALSE(m1.recorded[1]);
  EXPECT_FALSE(m1.recorded[2]);
  EXPECT_EQ(m1.source[1], "none (zeros)");
  for (std::size_t i = 0; i < m1.size(); ++i) {
    EXPECT_EQ(m1.sample(i).specific_force[1], 0.0);
    EXPECT_EQ(m1.sample(i).specific_force[2], kGravity);
  }
  // scale multiplies the ground motion, not gravity
  SensorFrameOptions o;
  o.scale = 2.0;
  const SensorFrameMotion m2 = to_sensor_frame(st, o);
  EXPECT_EQ(m2.sample(7).specific_force[2], 2.0 * st.vertical->accel[7] + kGravity);
}

TEST(StationSensorFrame, LengthMismatchPoliciesCountWhatTheyChange) {
  const StationRecord st = synthetic_station(300, 296, 303);
  SensorFrameOptions o;
  o.length_mismatch = LengthMismatch::Error;
  const std::string msg = station_error([&] { to_sensor_frame(st, o); });
  EXPECT_NE(msg.find("y.AT2 [000] and z.AT2 [UP]: different lengths (296 and 303 samples)"), std::string::npos) << msg;

  o.length_mismatch = LengthMismatch::Pad;
  const SensorFrameMotion p = to_sensor_frame(st, o);
  ASSERT_EQ(p.size(), 303u);
  ASSERT_EQ(p.notes.size(), 2u);
  EXPECT_NE(p.notes[0].find("padded x.AT2 [090] with 3 zero samples"), std::string::npos) << p.notes[0];
  EXPECT_NE(p.notes[1].find("padded y.AT2 [000] with 7 zero samples"), std::string::npos) << p.notes[1];
  EXPECT_EQ(p.ground[1][295], st.horizontals[1].accel[295]);
  EXPECT_EQ(p.ground[1][296], 0.0);

  o.length_mismatch = LengthMismatch::Truncate;
  const SensorFrameMotion t = to_sensor_frame(st, o);
  ASSERT_EQ(t.size(), 296u);
  ASSERT_EQ(t.notes.size(), 2u);
  EXPECT_NE(t.notes[0].find("truncated x.AT2 [090] from 300 to 296 samples (dropped the last 4"), std::string::npos) << t.notes[0];
  EXPECT_NE(t.notes[1].find("truncated z.AT2 [UP] from 303 to 296 samples (dropped the last 7"), std::string::npos) << t.notes[1];
}

TEST(StationSensorFrame, AzimuthRotatesAndBadInputIsRefused) {
  const StationRecord st = synthetic_station(120, 120, 120);
  SensorFrameOptions o;
  o.azimuth_deg = 30.0;
  const SensorFrameMotion m = to_sensor_frame(st, o);
  const RotatedPair r = rotate(st.horizontals[0], st.horizontals[1], 30.0);
  EXPECT_EQ(m.ground[0], r.along.accel);
  EXPECT_EQ(m.ground[1], r.left.accel);
  EXPECT_EQ(*m.x_azimuth_deg, 30.0);
  o.azimuth_deg = 0.0;  // x = north (h1), y = west (-h0)
  const SensorFrameMotion n = to_sensor_frame(st, o);
  EXPECT_EQ(n.ground[0], st.horizontals[1].accel);
  EXPECT_EQ(n.ground[1], negated(st.horizontals[0].accel));

  StationRecord one = st;
  one.horizontals.pop_back();
  o.azimuth_deg = 45.0;
  EXPECT_NE(station_error([&] { to_sensor_frame(one, o); }).find("an azimuth needs two horizontal components, the station has 1"),
            std::string::npos);
  o.azimuth_deg = 90.0;  // already along 090: allowed, nothing rotated
  EXPECT_EQ(to_sensor_frame(one, o).ground[0], one.horizontals[0].accel);

  StationRecord bad_dt = st;
  bad_dt.vertical->dt = 0.02;
  EXPECT_NE(station_error([&] { to_sensor_frame(bad_dt, {}); }).find("x.AT2 [090] and z.AT2 [UP]: different sample intervals"),
            std::string::npos);
  StationRecord bad_t0 = st;
  bad_t0.horizontals[1].t0 = 0.5;
  EXPECT_NE(station_error([&] { to_sensor_frame(bad_t0, {}); }).find("different start times"), std::string::npos);
  EXPECT_THROW(parse_length_mismatch("chop"), std::invalid_argument);
  EXPECT_EQ(parse_length_mismatch("pad"), LengthMismatch::Pad);
}

// ------------------------------------------------------------------ synthetic signals

TEST(SyntheticMotion, RickerSinePulseAndSeededNoise) {
  EXPECT_EQ(ricker(2.0, 3.0, 1.5, 2.0), 3.0);
  const double side = std::sqrt(1.5) / (kPi * 1.5);
  EXPECT_NEAR(ricker(2.0 + side, 3.0, 1.5, 2.0), -2.0 * 3.0 * std::exp(-1.5), 1e-12);
  EXPECT_NEAR(ricker(2.0 + 1.0 / (kPi * 1.5 * std::sqrt(2.0)), 3.0, 1.5, 2.0), 0.0, 1e-12);  // zero crossing
  EXPECT_EQ(sine_pulse(0.15, 4.0, 0.6, 0.0, 1.0), 4.0);
  EXPECT_EQ(sine_pulse(0.61, 4.0, 0.6, 0.0, 1.0), 0.0);
  EXPECT_EQ(sine_pulse(-0.01, 4.0, 0.6, 0.0, 1.0), 0.0);
  EXPECT_EQ(synthetic_sample_count(8.0, 0.005), 1601u);
  EXPECT_THROW(synthetic_sample_count(8.0, 0.0), std::invalid_argument);

  GaussianNoise a(0.005, 42);
  GaussianNoise b(0.005, 42);
  GaussianNoise c(0.005, 43);
  double sum = 0.0;
  double sum2 = 0.0;
  bool differs = false;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double x = a.next();
    EXPECT_EQ(x, b.next());
    differs = differs || x != c.next();
    sum += x;
    sum2 += x * x;
  }
  EXPECT_TRUE(differs);
  EXPECT_NEAR(sum / n, 0.0, 4.0 * 0.005 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.005, 0.005 * 0.01);
}

}  // namespace
}  // namespace rocking_monitor::core
