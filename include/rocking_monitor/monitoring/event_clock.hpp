#pragma once

// Times as the people who act on an alarm read them: seconds since the first sample of the event,
// and the wall-clock time (UTC) of the sample's stamp, instead of raw epoch seconds.

#include <string>

namespace rocking_monitor::core {

/// ISO 8601 UTC of a time in seconds since the Unix epoch, to the millisecond:
/// 1000000000.2051 -> "2001-09-09T01:46:40.205Z". Non-finite or negative times give "unknown time".
std::string iso8601_utc(double t);

/// "1.205 s after the first sample (2001-09-09T01:46:41.205Z)".
std::string event_time_text(double t, double t_first);

}  // namespace rocking_monitor::core
