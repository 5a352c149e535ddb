// Regression (issue 19 part 4, found by test/fuzz/fuzz_parsers): a record value that is finite as
// written but overflows after the unit conversion to m/s^2 (1.7e308 g x 9.80665) is a file:line
// error, not an infinite sample that the model rejects later without saying where it came from.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "rocking_monitor/motion/record_reader.hpp"
#include "temp_root.hpp"

namespace fs = std::filesystem;
namespace rm = rocking_monitor::core;

namespace {

const rm::testing::TempRoot& kOverflowTemp = rm::testing::TempRoot::registered("rocking_overflow_test_");

std::string write(const std::string& name, const std::string& text) {
  fs::create_directories(kOverflowTemp.path());
  const fs::path p = kOverflowTemp.path() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

std::string overflow_read_error(const std::string& path, const rm::ReadOptions& o = {}) {
  try {
    rm::read_record(path, o);
  } catch (const rm::RecordError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(RecordOverflow, At2ValueInGOverflowingAfterScalingNamesFileAndLine) {
  // PEER layout; the 7th value (line 6) is the largest double below the overflow of x g.
  const std::string text =
      "PEER NGA STRONG MOTION DATABASE RECORD\n"
      "Northridge-01, 1/17/1994, Rinaldi Receiving Sta, 228\n"
      "ACCELERATION TIME SERIES IN UNITS OF G\n"
      "NPTS=   10, DT=   .0100 SEC\n"
      "  -.2556093E-02  -.2534838E-02  -.2450926E-02  -.2152656E-02  -.1770125E-02\n"
      "  -.1455219E-02  1.7E+308  -.2736706E-02  -.3821358E-02  -.3397461E-02\n";
  const std::string path = write("overflow.AT2", text);
  const std::string err = overflow_read_error(path);
  EXPECT_EQ(err.rfind(path + ":6: value 1.7e+308 overflows after conversion to m/s^2 (x 9.80665", 0), 0u) << err;
  // 1.7e307 g is 1.67e308 m/s^2: finite, so it reads (the check is the overflow, not a size limit)
  std::string fits = text;
  fits.replace(fits.find("1.7E+308"), 8, "1.7E+307");
  const rm::Component c = rm::read_record(write("fits.AT2", fits)).at(0);
  EXPECT_DOUBLE_EQ(c.accel.at(6), 1.7e307 * 9.80665);
}

TEST(RecordOverflow, CsvInGOverflowingNamesFileAndLine) {
  const std::string path = write("overflow.csv", "time_s,accel_g\n0.00,0.1\n0.01,1e308\n0.02,0.2\n");
  rm::ReadOptions o;
  o.csv_units = rm::AccelUnits::G;
  const std::string err = overflow_read_error(path, o);
  EXPECT_EQ(err.rfind(path + ":3: value 1e+308 overflows after conversion to m/s^2", 0), 0u) << err;
}
