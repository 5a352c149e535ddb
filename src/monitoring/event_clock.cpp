#include "rocking_monitor/monitoring/event_clock.hpp"

#include <cmath>
#include <cstdio>
#include <ctime>

namespace rocking_monitor::core {

std::string iso8601_utc(double t) {
  if (!std::isfinite(t) || t < 0.0 || t > 253402300799.0) return "unknown time";  // past 9999-12-31
  // Whole milliseconds first, so that 1.9996 s prints as 2.000 and not 1.1000.
  const long long ms = std::llround(t * 1000.0);
  const std::time_t seconds = static_cast<std::time_t>(ms / 1000);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char buf[96];  // room for any int fields, so the compiler sees no truncation
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d.%03lldZ", utc.tm_year + 1900, utc.tm_mon + 1,
                utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec, ms % 1000);
  return buf;
}

std::string event_time_text(double t, double t_first) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3f s after the first sample (", t - t_first);
  return buf + iso8601_utc(t) + ")";
}

}  // namespace rocking_monitor::core
