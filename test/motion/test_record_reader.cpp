// Tests of the strong-motion record readers (src/motion/record_reader.cpp and one *_reader.cpp per format)
// on well-formed files: RecordReaderAt2/Bbp/Smc/Csv/Detect read small synthetic files written to a
// temp dir (known values in -> known SI values out). They run without the records directory.
// Corrupted files: test_record_reader_errors.cpp; the real records: test_record_reader_real_data.cpp.

#include "record_reader_fixtures.hpp"

// =================================================================== PEER AT2

TEST(RecordReaderAt2, NgaHeaderWithoutComma) {
  TempDir tmp;
  const auto p = tmp.write("a.AT2", at2_seven("NPTS=      7  DT=   .0050 SEC,   4 POLE @    30.00000 HZ"));
  const auto comps = read_record(p);
  ASSERT_EQ(comps.size(), 1u);
  const Component& c = comps[0];
  expect_values(c, kSevenG, kGravity);
  EXPECT_DOUBLE_EQ(c.dt, 0.005);
  EXPECT_EQ(c.t0, 0.0);
  EXPECT_EQ(c.file, p);
  EXPECT_EQ(c.event, "Test Event");
  EXPECT_EQ(c.station, "Some Station");
  EXPECT_EQ(c.label, "090");
  EXPECT_FALSE(c.vertical);
  EXPECT_NEAR(c.duration(), 6 * 0.005, 1e-15);
}

TEST(RecordReaderAt2, NgaHeaderWithComma) {
  TempDir tmp;
  const auto p = tmp.write("b.AT2", at2_seven("NPTS=      7, DT=   .0100 SEC,   0 POLE @    30.00000 HZ,  -5 POLE"));
  const auto c = read_record(p).at(0);
  expect_values(c, kSevenG, kGravity);
  EXPECT_DOUBLE_EQ(c.dt, 0.01);
}

TEST(RecordReaderAt2, Peer1999Header) {
  TempDir tmp;
  const auto text = at2("PEER STRONG MOTION DATABASE RECORD. PROCESSING BY PACIFIC ENGINEERING.",
                        "IMPERIAL VALLEY 10/15/79 2316, EL CENTRO ARRAY #12, 140 (USGS STATION 931)",
                        "ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.1 Hz LP=40.0 Hz",
                        "NPTS=  7, DT= .00500 SEC",
                        {"  -.2556093E-02   .1000000E+00  0.795256E-03  -.5000000E-01   1.0000000E+00",
                         "   .2500000E-00  -.1234567E-05"});
  const auto p = tmp.write("H-E12140.at2", text);
  EXPECT_EQ(detect_format(p), RecordFormat::PeerAt2);
  const auto c = read_record(p).at(0);
  expect_values(c, kSevenG, kGravity);
  EXPECT_DOUBLE_EQ(c.dt, 0.005);
  EXPECT_EQ(c.event, "IMPERIAL VALLEY");
  EXPECT_EQ(c.station, "EL CENTRO ARRAY #12");
  EXPECT_EQ(c.label, "140");
}

TEST(RecordReaderAt2, OldNgaHeaderCountThenDt) {
  TempDir tmp;
  const auto text = at2(kNgaTitle, "KOBE 01/16/95 2046, NISHI-AKASHI, 090 (CUE)                ",
                        "ACCELERATION TIME HISTORY IN UNITS OF G", "7    0.0050    NPTS, DT",
                        {"   -.2556093E-02   0.100000E+00   0.795256E-03  -0.500000E-01   0.100000E+01",
                         "   0.250000E+00  -0.1234567E-05"});
  const auto p = tmp.write("NIS090.AT2", text);
  const auto c = read_record(p).at(0);
  expect_values(c, kSevenG, kGravity);
  EXPECT_DOUBLE_EQ(c.dt, 0.005);
  EXPECT_EQ(c.event, "KOBE");
  EXPECT_EQ(c.station, "NISHI-AKASHI");
  EXPECT_EQ(c.label, "090");
}

TEST(RecordReaderAt2, CrlfAndValuesAfterNptsIgnored) {
  TempDir tmp;
  // NPTS = 5 but 7 values (+ a text pad) follow: exactly 5 are read, the rest is ignored.
  const auto p = tmp.write("c.AT2", at2_seven("NPTS=      5, DT=   .0100 SEC", "\r\n") + "  .0  trailing-junk\r\n");
  const auto c = read_record(p).at(0);
  ASSERT_EQ(c.accel.size(), 5u);
  expect_values(c, std::vector<double>(kSevenG.begin(), kSevenG.begin() + 5), kGravity);
  EXPECT_EQ(c.station, "Some Station");  // no '\r' left in metadata
  EXPECT_EQ(c.label, "090");
}

TEST(RecordReaderAt2, TitleVariantsAndStationWithCommas) {
  struct Case {
    std::string line2, event, station, label;
  };
  const std::vector<Case> cases = {
      {"Loma Prieta, 10/18/1989, Emeryville; Pacific Park #2, Free Field, 260", "Loma Prieta",
       "Emeryville; Pacific Park #2, Free Field", "260"},
      {"NORTHRIDGE EQ 1/17/94, 12:31, BURBANK - HOWARD, 330 (USC STATION 90059)", "NORTHRIDGE EQ", "BURBANK - HOWARD",
       "330"},
      {"NORTHRIDGE, 1/17/94 12:31, VASQUEZ ROCKS PARK, 090 (CDMG STATION 24047)", "NORTHRIDGE", "VASQUEZ ROCKS PARK",
       "090"},
      {"LOMA PRIETA 10/18/89 00:05, GILROY GAVILAN COLL, 067 (CDMG STATION 47006)", "LOMA PRIETA",
       "GILROY GAVILAN COLL", "067"},
      {"Kobe Japan, 1/16/1995, Port Island (0 m), 0", "Kobe Japan", "Port Island (0 m)", "0"},
  };
  TempDir tmp;
  int k = 0;
  for (const auto& cs : cases) {
    SCOPED_TRACE(cs.line2);
    const auto p = tmp.write("t" + std::to_string(k++) + ".AT2",
                             at2(kNgaTitle, cs.line2, kNgaUnits, "NPTS= 2, DT= .01 SEC", {" .1E-01 -.2E-01"}));
    const auto c = read_record(p).at(0);
    EXPECT_EQ(c.event, cs.event);
    EXPECT_EQ(c.station, cs.station);
    EXPECT_EQ(c.label, cs.label);
  }
}

TEST(RecordReaderAt2, VerticalDwnIsFlippedToPositiveUp) {
  TempDir tmp;
  const auto dwn = tmp.write("x_DWN.AT2", at2(kNgaTitle, "San Fernando, 2/9/1971, Lake Hughes #1, DWN", kNgaUnits,
                                              "NPTS=  3, DT= .0100 SEC", {"  .1000000E+00  -.2000000E+00  .5E-01"}));
  const auto up = tmp.write("x_UP.AT2", at2(kNgaTitle, "Northridge-01, 1/17/1994, Rinaldi Receiving Sta, UP",
                                            kNgaUnits, "NPTS=  3, DT= .0100 SEC", {"  .1000000E+00  -.2000000E+00  .5E-01"}));
  const auto d = read_record(dwn).at(0);
  const auto u = read_record(up).at(0);
  EXPECT_TRUE(d.vertical);
  EXPECT_TRUE(u.vertical);
  EXPECT_EQ(d.label, "DWN");  // label kept as written
  EXPECT_EQ(u.label, "UP");
  expect_values(d, {-0.1, 0.2, -0.05}, kGravity);  // positive down in the file -> negated
  expect_values(u, {0.1, -0.2, 0.05}, kGravity);
  EXPECT_TRUE(rocking_monitor::core::label_is_positive_down("DWN"));
  EXPECT_TRUE(rocking_monitor::core::label_is_positive_down("down"));
  EXPECT_FALSE(rocking_monitor::core::label_is_positive_down("UP"));
  EXPECT_FALSE(rocking_monitor::core::label_is_positive_down("U-D"));
  EXPECT_TRUE(rocking_monitor::core::label_is_vertical("-UP"));
  EXPECT_TRUE(rocking_monitor::core::label_is_vertical("up"));
  EXPECT_TRUE(rocking_monitor::core::label_is_vertical("U-D"));
  EXPECT_TRUE(rocking_monitor::core::label_is_vertical("V"));
  EXPECT_FALSE(rocking_monitor::core::label_is_vertical("090"));
  EXPECT_FALSE(rocking_monitor::core::label_is_vertical("N-S"));
  EXPECT_FALSE(rocking_monitor::core::label_is_vertical("W"));
}

TEST(RecordReaderAt2, FortranDExponentAccepted) {
  TempDir tmp;
  const auto p = tmp.write("d.AT2", at2(kNgaTitle, "E, 1/1/2000, S, 0", kNgaUnits, "NPTS= 3, DT= .01 SEC",
                                        {"  .25D-01  -1.5d+00  +2.0E-3"}));
  expect_values(read_record(p).at(0), {0.025, -1.5, 0.002}, kGravity);
}

// =================================================================== SCEC BBP

TEST(RecordReaderBbp, ThreeComponentsCmPerS2ToSi) {
  TempDir tmp;
  const std::string rows =
      "5.000000e-01\t1.000000e+00\t-2.000000e+00\t3.000000e+00\n"
      "5.100000e-01\t-4.000000e+00\t5.000000e+00\t-6.000000e+00\n"
      "5.200000e-01\t7.000000e+00\t-8.000000e+00\t9.000000e+00\n";
  const auto p = tmp.write("tst01.bbp", std::string(kBbpHeader) + rows);
  EXPECT_EQ(detect_format(p), RecordFormat::Bbp);
  const auto comps = read_record(p);
  ASSERT_EQ(comps.size(), 3u);
  const char* labels[3] = {"N-S", "E-W", "U-D"};
  const std::vector<std::vector<double>> expect = {{1, -4, 7}, {-2, 5, -8}, {3, -6, 9}};
  for (int k = 0; k < 3; ++k) {
    const Component& c = comps[static_cast<std::size_t>(k)];
    SCOPED_TRACE(labels[k]);
    EXPECT_EQ(c.label, labels[k]);
    EXPECT_EQ(c.vertical, k == 2);
    EXPECT_NEAR(c.dt, 0.01, 1e-12);
    EXPECT_DOUBLE_EQ(c.t0, 0.5);
    EXPECT_EQ(c.station, "tst01");
    EXPECT_EQ(c.event, "1992 Landers EQ");
    EXPECT_EQ(c.file, p);
    expect_values(c, expect[static_cast<std::size_t>(k)], 0.01);  // U-D "+ is upward": not flipped
  }
}

TEST(RecordReaderBbp, LabelOnlyHeaderMixedSeparatorsAndRoundedTimes) {
  TempDir tmp;
  // gmsvtoolkit style header; rows switch from tab-separated %e to space-separated %f like the
  // Landers files; the printed time stamps carry rounding (3.000260e-02 ... 10.000000).
  std::string text = "#    time(sec)      N-S(cm/s/s)      E-W(cm/s/s)      U-D(cm/s/s)\r\n";
  const int n = 2001;
  for (int i = 0; i < n; ++i) {
    const double t = 0.0300026 + 0.005 * i;
    char buf[160];
    if (t < 5.0) {
      std::snprintf(buf, sizeof buf, "%.6e\t%.6e\t%.6e\t%.6e\r\n", t, 1.0 * i, -2.0, 0.5);
    } else {
      std::snprintf(buf, sizeof buf, " %.6f        %.4f          -2.0000          0.5000\r\n", t, 1.0 * i);
    }
    text += buf;
  }
  const auto p = tmp.write("2009-XYZ.bbp", text);
  const auto comps = read_record(p);
  ASSERT_EQ(comps.size(), 3u);
  EXPECT_EQ(comps[0].station, "2009-XYZ");  // no "# Station:" line: BBP id = file name
  EXPECT_EQ(comps[0].event, "");
  EXPECT_EQ(comps[0].accel.size(), static_cast<std::size_t>(n));
  EXPECT_NEAR(comps[0].dt, 0.005, 1e-9);
  EXPECT_NEAR(comps[0].t0, 0.0300026, 1e-12);
  EXPECT_NEAR(comps[0].accel[1234], 12.34, 1e-12);
  EXPECT_NEAR(comps[2].accel[2000], 0.005, 1e-15);
}

TEST(RecordReaderBbp, RejectsVelocityFileAndWrongColumnCount) {
  TempDir tmp;
  const auto vel = tmp.write("v.bbp",
                             "#    time(sec)      N-S(cm/s)      E-W(cm/s)      U-D(cm/s)\n"
                             "0.0 1 2 3\n0.01 1 2 3\n");
  expect_record_error(vel, 1, {"not an acceleration file"});
  const auto cols = tmp.write("c.bbp", std::string(kBbpHeader) + "0.0 1 2 3\n0.01 1 2\n0.02 1 2 3\n");
  expect_record_error(cols, 10, {"expected 4 columns", "found 3"});
}

// =================================================================== USGS SMC V2

TEST(RecordReaderSmc, TouchingFixedWidthFields) {
  TempDir tmp;
  // first data line as in 0111a.smc: the fields touch, so whitespace splitting would fail
  std::vector<std::string> f = {" 1.5057E+0", "-2.2223E+0", "-1.9234E+0", "-3.1562E+0", "-3.2440E+0",
                                "-3.5638E+0", "-5.1941E+0", "-5.7933E+0", "-5.0138E-1", " 1.9171E+0"};
  const auto p = tmp.write("0111a.smc", smc(f, 10, 200.0, 3));
  EXPECT_EQ(detect_format(p), RecordFormat::UsgsSmc);
  const auto comps = read_record(p);
  ASSERT_EQ(comps.size(), 1u);
  const Component& c = comps[0];
  expect_values(c, {1.5057, -2.2223, -1.9234, -3.1562, -3.2440, -3.5638, -5.1941, -5.7933, -0.50138, 1.9171}, 0.01);
  EXPECT_DOUBLE_EQ(c.dt, 0.005);
  EXPECT_EQ(c.t0, 0.0);
  EXPECT_EQ(c.station, "San Francisco, 1295 Shafter, F");
  EXPECT_EQ(c.label, "360");
  EXPECT_EQ(c.event, "Loma Prieta, CA");
  EXPECT_FALSE(c.vertical);
}

TEST(RecordReaderSmc, CrlfVerticalUpAndDown) {
  TempDir tmp;
  const auto up = tmp.write("b.smc", smc(smc_fields20(), 20, 100.0, 2, "up", "\r\n"));
  const auto c = read_record(up).at(0);
  EXPECT_TRUE(c.vertical);
  EXPECT_EQ(c.label, "up");
  EXPECT_DOUBLE_EQ(c.dt, 0.01);
  expect_values(c, smc_values20(), 0.01);
  const auto down = tmp.write("d.smc", smc(smc_fields20(), 20, 100.0, 2, "down"));
  const auto d = read_record(down).at(0);
  EXPECT_TRUE(d.vertical);
  expect_values(d, smc_values20(), -0.01);
}

TEST(RecordReaderSmc, ValuesAfterNptsIgnored) {
  TempDir tmp;
  const auto p = tmp.write("e.smc", smc(smc_fields20(), 13, 50.0, 0));
  const auto c = read_record(p).at(0);
  const auto all = smc_values20();
  expect_values(c, std::vector<double>(all.begin(), all.begin() + 13), 0.01);
  EXPECT_DOUBLE_EQ(c.dt, 0.02);
}

// =================================================================== CSV / whitespace

TEST(RecordReaderCsv, TwoColumnsCommaHeaderInG) {
  TempDir tmp;
  const auto p = tmp.write("rec.csv", "time_s,accel_g\n0.00,0.10\n0.01,-0.20\n0.02, 0.05\n\n");
  ReadOptions o;
  o.csv_units = AccelUnits::G;
  const auto comps = read_record(p, o);
  ASSERT_EQ(comps.size(), 1u);
  EXPECT_EQ(comps[0].label, "H");
  EXPECT_FALSE(comps[0].vertical);
  EXPECT_NEAR(comps[0].dt, 0.01, 1e-15);
  EXPECT_EQ(comps[0].t0, 0.0);
  expect_values(comps[0], {0.10, -0.20, 0.05}, kGravity);
}

TEST(RecordReaderCsv, ThreeColumnsWhitespaceCmPerS2WithOffsetStart) {
  TempDir tmp;
  const auto p = tmp.write("rec.txt", "  2.50  \t 10.0   -5.0\r\n  2.52  20.0  -10.0\r\n  2.54\t30.0\t-15.0\r\n");
  ReadOptions o;
  o.csv_units = AccelUnits::CentimetersPerSecond2;
  EXPECT_EQ(detect_format(p), RecordFormat::Csv);
  const auto comps = read_record(p, o);
  ASSERT_EQ(comps.size(), 2u);
  EXPECT_EQ(comps[1].label, "V");
  EXPECT_TRUE(comps[1].vertical);
  EXPECT_DOUBLE_EQ(comps[0].t0, 2.5);
  EXPECT_DOUBLE_EQ(comps[1].t0, 2.5);
  EXPECT_NEAR(comps[0].dt, 0.02, 1e-12);
  expect_values(comps[0], {10, 20, 30}, 0.01);
  expect_values(comps[1], {-5, -10, -15}, 0.01);
}

TEST(RecordReaderCsv, DefaultUnitsAreSi) {
  TempDir tmp;
  const auto p = tmp.write("si.csv", "0.0 , 1.5\n0.5 , -2.5\n1.0 , 3e-1\n");
  const auto c = read_record(p).at(0);
  expect_values(c, {1.5, -2.5, 0.3}, 1.0);
  EXPECT_DOUBLE_EQ(c.dt, 0.5);
}

// =================================================================== detection

TEST(RecordReaderDetect, ContentBeforeExtension) {
  TempDir tmp;
  const auto a = tmp.write("at2_content.txt", at2_seven("NPTS=      7, DT=   .0100 SEC"));
  const auto b = tmp.write("bbp_content.dat", std::string(kBbpHeader) + "0.0 1 2 3\n0.01 1 2 3\n");
  const auto s = tmp.write("smc_content.csv", smc(smc_fields20(), 20, 100.0, 1));
  const auto c = tmp.write("csv_content.foo", "t,a\n0,1\n0.1,2\n");
  EXPECT_EQ(detect_format(a), RecordFormat::PeerAt2);
  EXPECT_EQ(detect_format(b), RecordFormat::Bbp);
  EXPECT_EQ(detect_format(s), RecordFormat::UsgsSmc);
  EXPECT_EQ(detect_format(c), RecordFormat::Csv);
  EXPECT_EQ(read_record(a).size(), 1u);
  EXPECT_EQ(read_record(b).size(), 3u);
  EXPECT_EQ(read_record(s).size(), 1u);
  EXPECT_EQ(read_record(c).size(), 1u);
  // unknown content: the extension decides
  const auto ext = tmp.write("odd.AT2", "hello\nworld\n");
  EXPECT_EQ(detect_format(ext), RecordFormat::PeerAt2);
  EXPECT_STREQ(rocking_monitor::core::to_string(RecordFormat::UsgsSmc), "usgs_smc");
}

TEST(RecordReaderDetect, UnknownFormatAndForcedFormat) {
  TempDir tmp;
  const auto u = tmp.write("notes.xyz", "just some text\nnothing numeric here\n");
  EXPECT_EQ(detect_format(u), RecordFormat::Auto);
  expect_record_error(u, 0, {"unknown record format"});
  // a CSV forced to be read as AT2 fails on its header, not with a crash
  const auto c = tmp.write("forced.csv", "0,1\n0.1,2\n0.2,3\n");
  ReadOptions o;
  o.format = RecordFormat::PeerAt2;
  expect_record_error(c, 3, {"bad header"}, o);
  o.format = RecordFormat::Csv;
  EXPECT_EQ(read_record(c, o).at(0).accel.size(), 3u);
}
