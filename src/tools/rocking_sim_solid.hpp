#pragma once
// rocking_sim --solid-model: the item as one rigid body on its base polygon (the 3-D model,
// docs/rocking_3d.md), stepped exactly as the live node steps it: an ItemMonitor with the node's
// ~solid_model rule under the x and y horizontals and the shared vertical.

#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rocking_monitor/monitoring/item_monitor.hpp"
#include "rocking_monitor/physics/item_verdict.hpp"
#include "rocking_sim_options.hpp"

namespace rocking_monitor::tools::sim {

struct SolidRun {
  nlohmann::json out;
  std::vector<std::string> lines;
  rm::LevelTimes levels;                     ///< the item's alarms, as the node raises them
  std::array<const char*, 3> by{"", "", ""};  ///< per level: "3d", "x" or "y"
  bool decided = false;                      ///< the 3-D model was in charge at some sample
};

/// The item through the motions (my may be null: no y horizontal), `history_path` (may be empty) the
/// 3-D history CSV. Throws std::invalid_argument for an item the 3-D model cannot run.
SolidRun run_solid(const RunOptions& opt, const rm::ItemSpec& spec, rm::SolidChoice choice,
                   double bidirectional_ratio, const rm::GroundMotion& mx, const rm::GroundMotion* my,
                   const std::string& history_path);

/// The ItemMonitor options of rocking_sim's flags (the node's ~fidelity, ~tol, ...; the scene from
/// both planes' records).
rm::ItemMonitor::Options monitor_options(const RunOptions& opt, const rm::GroundMotion& mx,
                                         const rm::GroundMotion* my);

}  // namespace rocking_monitor::tools::sim
