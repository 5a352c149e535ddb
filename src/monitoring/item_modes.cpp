#include "rocking_monitor/monitoring/item_modes.hpp"

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
