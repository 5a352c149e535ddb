// Tests of the strong-motion record readers on corrupted synthetic files
// (src/motion/record_reader.cpp and one *_reader.cpp per format): RecordReaderErrors, each file
// must throw RecordError naming the file, the line and the problem.

#include "record_reader_fixtures.hpp"

// =================================================================== errors (synthetic)

TEST(RecordReaderErrors, MissingFileAndDirectory) {
  TempDir tmp;
  const auto missing = tmp.path("does_not_exist.AT2");
  expect_record_error(missing, 0, {"does_not_exist.AT2", "cannot open"});
  EXPECT_NE(error_of([&] { detect_format(missing); }).find("cannot open"), std::string::npos);
  const auto dir = tmp.path("");
  EXPECT_FALSE(error_of([&] { read_record(dir); }).empty());
  const auto empty = tmp.write("empty.AT2", "");
  expect_record_error(empty, 0, {"empty file"});
}

TEST(RecordReaderErrors, At2FewerValuesThanNpts) {
  TempDir tmp;
  const auto p = tmp.write("short.AT2", at2_seven("NPTS=      9, DT=   .0050 SEC"));
  expect_record_error(p, 6, {"expected 9 values (NPTS), found 7"});
}

TEST(RecordReaderErrors, At2BadHeaderLine) {
  TempDir tmp;
  const auto garbage = tmp.write("g.AT2", at2_seven("NPTS=   x7y, DT=   .0050 SEC"));
  expect_record_error(garbage, 4, {"bad header", "NPTS", "'x7y'"});
  const auto partial = tmp.write("g2.AT2", at2_seven("NPTS=   7q, DT=   .0050 SEC"));
  expect_record_error(partial, 4, {"bad header", "NPTS"});
  const auto nodt = tmp.write("g3.AT2", at2_seven("NPTS=      7"));
  expect_record_error(nodt, 4, {"bad header", "missing DT"});
  const auto none = tmp.write("g4.AT2", at2_seven("@@@@ garbage ####"));
  expect_record_error(none, 4, {"bad header", "NPTS"});
  const auto baddt = tmp.write("g5.AT2", at2_seven("NPTS=      7, DT= .0.05 SEC"));
  expect_record_error(baddt, 4, {"bad header", "DT", "'.0.05'"});
  const auto units = tmp.write("g6.AT2", at2(kNgaTitle, "E, 1/1/2000, S, 0", "VELOCITY TIME SERIES IN UNITS OF CM/S",
                                             "NPTS= 2, DT= .01 SEC", {" .1 .2"}));
  expect_record_error(units, 3, {"bad header", "UNITS OF G"});
  const auto few = tmp.write("g7.AT2", "PEER NGA STRONG MOTION DATABASE RECORD\nonly two lines\n");
  expect_record_error(few, 2, {"bad header"});
}

TEST(RecordReaderErrors, At2NonPositiveDtAndEmptyData) {
  TempDir tmp;
  const auto zero = tmp.write("z.AT2", at2_seven("NPTS=      7, DT=   .0000 SEC"));
  expect_record_error(zero, 4, {"non-positive DT"});
  const auto neg = tmp.write("n.AT2", at2_seven("NPTS=      7, DT=   -.0100 SEC"));
  expect_record_error(neg, 4, {"non-positive DT"});
  const auto empty = tmp.write("e.AT2", at2_seven("NPTS=      0, DT=   .0100 SEC"));
  expect_record_error(empty, 4, {"empty data"});
}

TEST(RecordReaderErrors, NonNumericToken) {
  TempDir tmp;
  const auto p = tmp.write("bad.AT2", at2(kNgaTitle, "E, 1/1/2000, S, 0", kNgaUnits, "NPTS= 6, DT= .01 SEC",
                                          {" .1E-01  .2E-01  .3E-01", " .4E-01  1.2.3  .6E-01"}));
  expect_record_error(p, 6, {"non-numeric value '1.2.3'"});
  for (const std::string tok : {"0x10", "1e", "12abc", "--1", "1.0E+0x", "."}) {
    SCOPED_TRACE(tok);
    const auto q = tmp.write("tok.AT2", at2(kNgaTitle, "E, 1/1/2000, S, 0", kNgaUnits, "NPTS= 3, DT= .01 SEC",
                                            {" .1E-01 " + tok + " .3E-01"}));
    expect_record_error(q, 5, {"non-numeric value '" + tok + "'"});
  }
  const auto csv = tmp.write("bad.csv", "time,a\n0.0,1.0\n0.1,1.2.3\n");
  expect_record_error(csv, 3, {"non-numeric value '1.2.3'"});
}

TEST(RecordReaderErrors, NonFiniteValues) {
  TempDir tmp;
  for (const std::string tok : {"NaN", "nan", "-inf", "Infinity", "1e999"}) {
    SCOPED_TRACE(tok);
    const auto p = tmp.write("nan.AT2", at2(kNgaTitle, "E, 1/1/2000, S, 0", kNgaUnits, "NPTS= 3, DT= .01 SEC",
                                            {" .1E-01 .2E-01", " " + tok}));
    expect_record_error(p, 6, {"non-finite value '" + tok + "'"});
  }
  const auto bbp = tmp.write("nan.bbp", std::string(kBbpHeader) + "0.0 1 2 3\n0.01 1 NaN 3\n");
  expect_record_error(bbp, 10, {"non-finite value 'NaN'"});
  const auto csv = tmp.write("nan.csv", "0.0 1\n0.1 nan\n");
  expect_record_error(csv, 2, {"non-finite value 'nan'"});
  // underflow is not an error: the value is simply (nearly) zero
  const auto tiny = tmp.write("tiny.csv", "0.0 1e-400\n0.1 0\n");
  EXPECT_NEAR(read_record(tiny).at(0).accel[0], 0.0, 1e-300);
}

TEST(RecordReaderErrors, NonUniformTimeColumn) {
  TempDir tmp;
  const auto jump = tmp.write("jump.csv", "time_s,accel\n0.00,1\n0.01,2\n0.02,3\n0.04,4\n0.05,5\n");
  expect_record_error(jump, 5, {"non-uniform time step"});
  // small jitter beyond the printed-digit rounding
  const auto jitter = tmp.write("jitter.csv", "0.000000 1\n0.010000 2\n0.020000 3\n0.030200 4\n0.040000 5\n");
  expect_record_error(jitter, 4, {"non-uniform time step"});
  // a slow drift (each step within the tolerance, the grid not)
  std::string drift;
  for (int i = 0; i < 400; ++i) {
    char buf[64];
    // 5e-9 s extra per step after row 200: every step passes, the accumulated drift does not
    std::snprintf(buf, sizeof buf, "%.9f 0\n", i * 0.01 + (i > 200 ? (i - 200) * 5e-9 : 0.0));
    drift += buf;
  }
  const auto d = tmp.write("drift.csv", drift);
  expect_record_error(d, 201, {"non-uniform time step", "off the uniform grid"});
  const auto dup = tmp.write("dup.csv", "0.00 1\n0.01 2\n0.01 3\n0.02 4\n");
  expect_record_error(dup, 3, {"non-uniform time step", "not increasing"});
  // uniform, but dt = 1/300 s printed with 5 decimals: the rounding is not a reason to reject
  std::string coarse;
  for (int i = 0; i < 3000; ++i) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.5f,%d\n", i / 300.0, i % 7);
    coarse += buf;
  }
  const auto uc = read_record(tmp.write("coarse.csv", coarse)).at(0);
  EXPECT_NEAR(uc.dt, 1.0 / 300.0, 1e-8);
  const auto back = tmp.write("back.csv", "0.02 1\n0.01 2\n0.0 3\n");
  expect_record_error(back, 2, {"non-positive time step"});
  const auto bbp = tmp.write("gap.bbp", std::string(kBbpHeader) + "0.00 1 2 3\n0.01 1 2 3\n0.03 1 2 3\n");
  expect_record_error(bbp, 11, {"non-uniform time step"});
}

TEST(RecordReaderErrors, CsvShapeProblems) {
  TempDir tmp;
  expect_record_error(tmp.write("one.csv", "0.0\n0.1\n"), 1, {"expected 2 or 3 columns"});
  expect_record_error(tmp.write("cols.csv", "0.0 1 2\n0.1 1\n"), 2, {"expected 3 columns"});
  expect_record_error(tmp.write("gap.csv", "0.0,,1\n0.1,1,1\n"), 1, {"empty field"});
  expect_record_error(tmp.write("hdr2.csv", "time,a\nagain,b\n0,1\n"), 2, {"non-numeric value 'again'"});
  expect_record_error(tmp.write("onlyhdr.csv", "time,a\n\n"), 0, {"empty data"});
  expect_record_error(tmp.write("single.csv", "0.0,1\n"), 1, {"at least 2 samples"});
  expect_record_error(tmp.write("hdr.bbp", kBbpHeader), 0, {"empty data"});
}

TEST(RecordReaderErrors, SmcMissingOrDamagedLines) {
  TempDir tmp;
  const std::string good = smc(smc_fields20(), 20, 100.0, 2);
  std::string eol;
  const auto lines = split_lines_keep(good, &eol);
  ASSERT_EQ(lines.size(), 27u + 2u + 3u);

  auto without = [&](std::size_t line_no) {  // 1-based
    auto l = lines;
    l.erase(l.begin() + static_cast<long>(line_no - 1));
    return join_lines(l, eol);
  };
  // a missing data line (the middle one of three): 8 + 4 values left
  expect_record_error(tmp.write("m1.smc", without(31)), 31, {"expected 20 values (NPTS), found 12"});
  // the last data line missing
  expect_record_error(tmp.write("m2.smc", without(32)), 31, {"expected 20 values (NPTS), found 16"});
  // a missing comment line: the first data line is taken where a comment should be
  expect_record_error(tmp.write("m3.smc", without(29)), 29, {"expected comment line 2 of 2"});
  // a missing text header line shifts the integer block
  expect_record_error(tmp.write("m4.smc", without(5)), 17, {"bad header", "integer"});
  // a data line cut short in the middle of the data
  auto cut = lines;
  cut[29] = cut[29].substr(0, 50);
  expect_record_error(tmp.write("m5.smc", join_lines(cut, eol)), 30, {"short data line (5 of 8 values)"});
  // NPTS missing (-32768) and bad sampling rate
  expect_record_error(tmp.write("m6.smc", smc(smc_fields20(), -32768, 100.0, 2)), 14, {"missing NPTS"});
  expect_record_error(tmp.write("m7.smc", smc(smc_fields20(), 20, 0.0, 2)), 18, {"non-positive sampling rate"});
  // non-numeric field
  auto bad = lines;
  bad[29].replace(10, 10, "   1.2.3  ");
  expect_record_error(tmp.write("m8.smc", join_lines(bad, eol)), 30, {"non-numeric value '1.2.3'"});
  // V1 (uncorrected) is not read as V2
  auto v1 = lines;
  v1[0] = "1 UNCORRECTED ACCELEROGRAM";
  expect_record_error(tmp.write("m9.smc", join_lines(v1, eol)), 1, {"unsupported SMC file type"}, [] {
    ReadOptions o;
    o.format = RecordFormat::UsgsSmc;
    return o;
  }());
}

TEST(RecordReaderErrors, BinaryGarbageDoesNotCrash) {
  TempDir tmp;
  std::string junk;
  for (int i = 0; i < 5000; ++i) junk.push_back(static_cast<char>((i * 7919 + 13) % 256));
  const auto p = tmp.write("junk.AT2", junk);
  const std::string msg = error_of([&] { read_record(p); });
  EXPECT_FALSE(msg.empty());
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  for (RecordFormat f : {RecordFormat::Bbp, RecordFormat::UsgsSmc, RecordFormat::Csv}) {
    ReadOptions o;
    o.format = f;
    EXPECT_FALSE(error_of([&] { read_record(p, o); }).empty());
  }
}
