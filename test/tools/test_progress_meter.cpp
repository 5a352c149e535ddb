// The tools' progress display (src/tools/progress_meter.*, issue 53): the line it draws from given
// counts and elapsed time (no clock read, so no verdict depends on the machine), and that it draws
// nothing when it is not shown.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "progress_meter.hpp"

namespace rt = rocking_monitor::tools;

namespace {

/// What a meter wrote to a temporary stream.
std::string written(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string text;
  char buf[256];
  while (std::fgets(buf, sizeof buf, f)) text += buf;
  return text;
}

}  // namespace

TEST(ProgressMeter, DurationsReadAsSecondsMinutesHours) {
  EXPECT_EQ(rt::duration_text(7.4), "7s");
  EXPECT_EQ(rt::duration_text(125.0), "2m05s");
  EXPECT_EQ(rt::duration_text(3720.0), "1h02m");
  EXPECT_EQ(rt::duration_text(-1.0), "--");
  EXPECT_EQ(rt::duration_text(NAN), "--");
}

TEST(ProgressMeter, LineGivesDoneTotalRateAndTimeLeft) {
  // 5 of 10 tests in 2 s: 2.5 tests/s, 5 left take 2 s; the bar half full (15 of 30 columns).
  EXPECT_EQ(rt::progress_line(5, 10, 2.0, "tests"),
            "[===============>              ]  50.0%  5/10 tests  2.5 tests/s  left 2s");
  // 900 of 1200 cases in 3 s: 300 cases/s, 300 left take 1 s.
  EXPECT_EQ(rt::progress_line(900, 1200, 3.0, "cases"),
            "[======================>       ]  75.0%  900/1200 cases  300 cases/s  left 1s");
  // a slow job (a margin search: 0.05 tests/s) keeps two decimals; 18 left take 6 min
  EXPECT_EQ(rt::progress_line(2, 20, 40.0, "tests"),
            "[===>                          ]  10.0%  2/20 tests  0.05 tests/s  left 6m00s");
  // nothing done yet: no rate, time left unknown
  EXPECT_EQ(rt::progress_line(0, 4, 0.0, "inputs"),
            "[>                             ]   0.0%  0/4 inputs  0 inputs/s  left --");
  EXPECT_EQ(rt::progress_line(4, 4, 8.0, "inputs"),
            "[==============================] 100.0%  4/4 inputs  0.50 inputs/s  left 0s");
}

TEST(ProgressMeter, NotShownWritesNothing) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  rt::ProgressMeter meter("tests", f, false);
  for (std::size_t k = 0; k <= 3; ++k) meter.update(k, 3);
  EXPECT_EQ(written(f), "");
  std::fclose(f);
}

TEST(ProgressMeter, ShownRedrawsOneLineAndEndsItWhenDone) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  rt::ProgressMeter meter("tests", f, true);
  meter.update(0, 3);  // the first report is always drawn
  meter.update(3, 3);  // and the last, with the newline
  meter.update(3, 3);  // nothing after the end
  const std::string text = written(f);
  ASSERT_EQ(text.front(), '\r');
  EXPECT_NE(text.find("0/3 tests"), std::string::npos) << text;
  EXPECT_NE(text.find("3/3 tests"), std::string::npos) << text;
  EXPECT_EQ(text.back(), '\n');
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\r'), 2) << text;
  std::fclose(f);
}

TEST(ProgressMeter, QuietIsNeverShown) {
  EXPECT_FALSE(rt::ProgressMeter("cases", true).shown());
}
