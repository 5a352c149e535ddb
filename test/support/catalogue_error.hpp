#pragma once
// The message parse_catalogue_items gives for one catalogue item ("" when it is accepted): the tests
// of refused fields read it for the item's and the field's names.

#include <string>

#include <nlohmann/json.hpp>

#include "rocking_monitor/monitoring/catalogue.hpp"

namespace rocking_monitor::core::testing {

inline std::string catalogue_item_error(const nlohmann::json& entry) {
  try {
    parse_catalogue_items(nlohmann::json::array({entry}));
  } catch (const CatalogueError& e) {
    return e.what();
  }
  return "";
}

}  // namespace rocking_monitor::core::testing
