// Operator times: ISO 8601 UTC against known epochs (independent: the calendar), rounding carries.
#include <gtest/gtest.h>

#include <limits>

#include "rocking_monitor/monitoring/event_clock.hpp"

using rocking_monitor::core::event_time_text;
using rocking_monitor::core::iso8601_utc;

TEST(EventClock, Iso8601UtcOfKnownEpochs) {
  EXPECT_EQ(iso8601_utc(0.0), "1970-01-01T00:00:00.000Z");
  EXPECT_EQ(iso8601_utc(1000000000.0), "2001-09-09T01:46:40.000Z");
  EXPECT_EQ(iso8601_utc(951782400.0), "2000-02-29T00:00:00.000Z");            // leap day
  EXPECT_EQ(iso8601_utc(790378800.25), "1995-01-17T21:40:00.250Z");  // as Python datetime.utcfromtimestamp
  EXPECT_EQ(iso8601_utc(59.9996), "1970-01-01T00:01:00.000Z");               // rounding carries into the minute
  EXPECT_EQ(iso8601_utc(1.0004), "1970-01-01T00:00:01.000Z");
  EXPECT_EQ(iso8601_utc(-1.0), "unknown time");
  EXPECT_EQ(iso8601_utc(std::numeric_limits<double>::quiet_NaN()), "unknown time");
}

TEST(EventClock, EventTimeIsRelativeToTheFirstSample) {
  EXPECT_EQ(event_time_text(1000000001.205, 1000000000.0), "1.205 s after the first sample (2001-09-09T01:46:41.205Z)");
  EXPECT_EQ(event_time_text(5.0, 5.0), "0.000 s after the first sample (1970-01-01T00:00:05.000Z)");
}
