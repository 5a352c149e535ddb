#pragma once
// rocking_experiments' specimens: the catalogue's items as the members the model runs (the node's
// ensemble for an item with distributions), grouped by the outcome column they are scored against.

#include <string>
#include <vector>

#include "experiments_options.hpp"
#include "rocking_monitor/monitoring/catalogue.hpp"
#include "rocking_monitor/physics/base_body.hpp"
#include "rocking_monitor/physics/body.hpp"
#include "rocking_monitor/study/shaking_table_experiments.hpp"

namespace rocking_monitor::tools::experiments {

namespace rm = rocking_monitor::core;

/// One model run per test: the planar body, the 3-D body (when the 3-D model runs), the table's
/// azimuth in the member's frame (rad) and the member's input gain.
struct Member {
  rm::BodyParameters planar;
  rm::BaseBodyParameters solid;
  double azimuth;
  double gain;
};

/// The members scored against one outcome column (SP1: the items SP1, SP1#0, SP1#1, ...).
struct Specimen {
  std::string id;
  std::vector<Member> members;
  int column;
};

/// --model: 3d, planar, or auto (3d when every item has its 3-D description).
bool uses_solid_model(const Options& o, const std::vector<rm::CatalogueItem>& items);

/// Every item's members, grouped by specimen in catalogue order; prints each specimen's pivots (and
/// its members' input_gain range) on stdout as it is first met. Throws naming the item at fault.
std::vector<Specimen> load_specimens(const Options& o, const rm::MeasuredOutcomes& outcomes,
                                     const std::vector<rm::CatalogueItem>& items, bool solid);

}  // namespace rocking_monitor::tools::experiments
