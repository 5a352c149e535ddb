// The margin of a shaking-table test (issue 41): the grid and bisection of table_test_margin on
// predicates with known thresholds, and the input gain of the experiments equal to the record
// scaled by hand (planar and 3-D: the same outcome to the bit).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/physics/base_body.hpp"
#include "rocking_monitor/study/shaking_table_experiments.hpp"
#include "rocking_monitor/study/table_test_margin.hpp"

namespace rocking_monitor::core {
namespace {

TEST(TableTestMargin, BracketsAKnownThresholdToTheBisectionsResolution) {
  for (double threshold : {0.3, 0.77, 1.0001, 1.3, 3.9}) {
    std::vector<double> calls;
    const TestMargin m = table_test_margin([&](double s) { calls.push_back(s); return s >= threshold; });
    EXPECT_EQ(m.censored, 0) << threshold;
    EXPECT_FALSE(m.chaotic);
    EXPECT_EQ(m.runs, 14);  // 9 grid scales + 5 halvings
    ASSERT_EQ(calls.size(), 14u);
    EXPECT_LT(m.bracket_lo, threshold);
    EXPECT_GE(m.bracket_hi, threshold);
    // the grid step is a factor sqrt 2; five halvings of its log leave a factor 2^(1/64)
    EXPECT_NEAR(std::log(m.bracket_hi / m.bracket_lo), std::log(2.0) / 64.0, 1e-12);
    EXPECT_NEAR(m.scale, std::sqrt(m.bracket_lo * m.bracket_hi), 1e-15);
    // the grid: 0.25 (4^(k/8)), 1 exactly among them
    EXPECT_EQ(calls[0], 0.25);
    EXPECT_EQ(calls[4], 1.0);
    EXPECT_EQ(calls[8], 4.0);
  }
  EXPECT_EQ(table_test_margin([](double s) { return s >= 1.3; }).pattern, "000001111");
}

TEST(TableTestMargin, CensoredAndChaoticCasesAreSaidSo) {
  const TestMargin always = table_test_margin([](double) { return true; });
  EXPECT_EQ(always.censored, -1);
  EXPECT_EQ(always.scale, 0.25);
  EXPECT_EQ(always.runs, 9);
  const TestMargin never = table_test_margin([](double) { return false; });
  EXPECT_EQ(never.censored, 1);
  EXPECT_EQ(never.scale, 4.0);
  EXPECT_EQ(never.pattern, "000000000");
  // overturns only in a window: not monotone in the scale; the margin is the window's lower edge
  const TestMargin window = table_test_margin([](double s) { return s >= 0.6 && s <= 1.2; });
  EXPECT_TRUE(window.chaotic);
  EXPECT_EQ(window.pattern, "000110000");
  EXPECT_LT(window.bracket_lo, 0.6);
  EXPECT_GE(window.bracket_hi, 0.6);
  MarginSearch bad;
  bad.hi = 0.1;
  EXPECT_THROW(table_test_margin([](double) { return true; }, bad), std::invalid_argument);
  bad = MarginSearch{};
  bad.grid = 1;
  EXPECT_THROW(validate(bad), std::invalid_argument);
}

// A 1.2 Hz, two-cycle sine table record (m/s^2), then rest; dt 1/800 s as the granite tests.
TableTest sine_test(double amp) {
  TableTest t;
  t.number = 7;
  t.dt = 1.0 / 800.0;
  for (int i = 0; i < 4000; ++i) {
    const double time = i * t.dt;
    t.accel_mps2.push_back(time < 2.0 / 1.2 ? amp * std::sin(2.0 * kPi * 1.2 * time) : 0.0);
  }
  return t;
}

TEST(TableTestMargin, TheInputGainIsTheRecordScaledByHand) {
  BodyParameters b;
  b.width = 0.2;
  b.cg_height = 0.4;
  const BaseBodyParameters solid = box_base_body(b, 0.3, 0.5, std::nan(""));
  ExperimentSettings gained;
  gained.input_gain = 1.7;
  const TableTest raw = sine_test(2.0);
  TableTest scaled = raw;
  for (double& a : scaled.accel_mps2) a *= 1.7;
  const TestPrediction p3 = predict_table_test_3d(solid, "box", raw, gained);
  const TestPrediction q3 = predict_table_test_3d(solid, "box", scaled, ExperimentSettings{});
  ASSERT_GT(q3.impacts, 0) << "the box must rock, or the test proves little";
  EXPECT_EQ(p3.predicted, q3.predicted);
  EXPECT_EQ(p3.impacts, q3.impacts);
  EXPECT_EQ(p3.max_rotation_ratio, q3.max_rotation_ratio);
  const TestPrediction p2 = predict_table_test(b, "box", raw, gained);
  const TestPrediction q2 = predict_table_test(b, "box", scaled, ExperimentSettings{});
  ASSERT_GT(q2.impacts, 0);
  EXPECT_EQ(p2.impacts, q2.impacts);
  EXPECT_EQ(p2.max_rotation_ratio, q2.max_rotation_ratio);
  // and the margin of the box under this record: it stands at the bracket's lower end, overturns at
  // its upper end, with the gain applied the same way
  const TestMargin m = table_test_margin([&](double s) {
    ExperimentSettings e;
    e.input_gain = s;
    return predict_table_test_3d(solid, "box", raw, e).predicted;
  });
  ASSERT_EQ(m.censored, 0) << m.pattern;
  ExperimentSettings at_lo, at_hi;
  at_lo.input_gain = m.bracket_lo;
  at_hi.input_gain = m.bracket_hi;
  EXPECT_FALSE(predict_table_test_3d(solid, "box", raw, at_lo).predicted);
  EXPECT_TRUE(predict_table_test_3d(solid, "box", raw, at_hi).predicted);
  std::printf("[ measured ] box 0.2 x 0.3 x 0.8 m under a 2 m/s^2 1.2 Hz two-cycle sine: margin %.4f (%s)\n",
              m.scale, m.pattern.c_str());
}

}  // namespace
}  // namespace rocking_monitor::core
