#include "rocking_monitor/notify/notify_alarm.hpp"

#include <algorithm>
#include <cctype>

namespace rocking_monitor::notify {

std::string level_name(int level) {
  switch (level) {
    case kBeyondTipping: return "BEYOND_TIPPING";
    case kCommitted: return "COMMITTED";
    case kOverturned: return "OVERTURNED";
  }
  return "LEVEL_" + std::to_string(level);
}

int level_code(const std::string& name) {
  std::string up = name;
  std::transform(up.begin(), up.end(), up.begin(), [](unsigned char ch) { return std::toupper(ch); });
  for (int code : {kBeyondTipping, kCommitted, kOverturned})
    if (up == level_name(code)) return code;
  return 0;
}

}  // namespace rocking_monitor::notify
