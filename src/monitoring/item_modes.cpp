#include "rocking_monitor/monitoring/item_modes.hpp"

#include <cstring>

namespace rocking_monitor::core {

const char* to_string(ItemMode mode) {
  switch (mode) {
    case ItemMode::Rest: return "REST";
    case ItemMode::Rocking: return "ROCKING";
    case ItemMode::BeyondTipping: return "BEYOND_TIPPING";
    case ItemMode::Committed: return "COMMITTED";
    case ItemMode::Overturned: return "OVERTURNED";
  }
  return "UNKNOWN";
}

const char* to_string(AlarmCause cause) {
  switch (cause) {
    case AlarmCause::Rocking: return "rocking";
    case AlarmCause::FellOffSupport: return "fell_off_support";
  }
  return "unknown";
}

bool parse_alarm_cause(const char* name, AlarmCause& cause) {
  for (AlarmCause c : {AlarmCause::Rocking, AlarmCause::FellOffSupport})
    if (std::strcmp(name, to_string(c)) == 0) {
      cause = c;
      return true;
    }
  return false;
}

const char* to_string(CriterionId id) {
  switch (id) {
    case CriterionId::Housner: return "housner";
    case CriterionId::Ishiyama: return "ishiyama";
    case CriterionId::IshiyamaEquivalent: return "ishiyama_equivalent";
    case CriterionId::Proposed: return "proposed";
    case CriterionId::FreeFlight: return "free_flight";
    case CriterionId::SlideFromRest: return "slide_from_rest";
    case CriterionId::SlideAtUplift: return "slide_at_uplift";
    case CriterionId::SlideWhileRocking: return "slide_while_rocking";
  }
  return "unknown";
}

}  // namespace rocking_monitor::core
