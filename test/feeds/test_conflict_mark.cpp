// Tests of the conflict mark on sensor_msgs/Imu's linear_acceleration_covariance (issue 52 item 3,
// feeds/conflict_mark.hpp): what the bridge writes the monitor reads, and nothing else reads as it.
#include <gtest/gtest.h>

#include <array>
#include <limits>

#include "rocking_monitor/feeds/conflict_mark.hpp"

namespace fd = rocking_monitor::feeds;

TEST(ConflictMark, WhatTheBridgeWritesIsWhatTheMonitorReads) {
  std::array<double, 9> cov{};
  fd::mark_conflicting(cov, true, 1e-4);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(cov[4 * k], std::numeric_limits<double>::infinity()) << k;
  for (int i : {1, 2, 3, 5, 6, 7}) EXPECT_EQ(cov[i], 0.0) << i;  // no inf * 0 for a weighting consumer
  EXPECT_TRUE(fd::conflict_marked(cov));
  fd::mark_conflicting(cov, false, 1e-4);  // the bridge reuses its message: the next sample is clean
  for (int k = 0; k < 3; ++k) EXPECT_EQ(cov[4 * k], 1e-4) << k;
  EXPECT_FALSE(fd::conflict_marked(cov));
}

TEST(ConflictMark, OneAxisWithoutInformationMarksTheSample) {
  for (int k = 0; k < 3; ++k) {
    std::array<double, 9> cov{};
    cov[4 * k] = std::numeric_limits<double>::infinity();
    EXPECT_TRUE(fd::conflict_marked(cov)) << "axis " << k;
  }
}

TEST(ConflictMark, OtherCovariancesAreNotTheMark) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(fd::conflict_marked(std::array<double, 9>{}));                          // unknown (0)
  EXPECT_FALSE(fd::conflict_marked(std::array<double, 9>{-1.0}));                      // REP 145's "no data" flag
  EXPECT_FALSE(fd::conflict_marked(std::array<double, 9>{-inf, 0, 0, 0, -inf, 0, 0, 0, -inf}));
  EXPECT_FALSE(fd::conflict_marked(std::array<double, 9>{nan, 0, 0, 0, nan, 0, 0, 0, nan}));
  EXPECT_FALSE(fd::conflict_marked(std::array<double, 9>{1e300, 0, 0, 0, 1e300, 0, 0, 0, 1e300}));
  EXPECT_FALSE(fd::conflict_marked(std::array<double, 9>{0, inf, inf, inf, 0, inf, inf, inf, 0}));  // off-diagonal
}
