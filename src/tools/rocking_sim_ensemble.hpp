#pragma once
// rocking_sim --samples: a catalogue item's ensemble through the record(s).

#include <cstdint>
#include <string>
#include <vector>

#include "rocking_monitor/monitoring/item_ensemble.hpp"
#include "rocking_sim_output.hpp"

namespace rocking_monitor::tools::sim {

struct EnsembleRun {
  json out;
  std::vector<std::string> lines;
};

// --samples: the item's ensemble (the live node's members: draw_members() with the same seed, each
// an ItemMonitor) through the record(s); P(level) with its Wilson interval and the threshold crossings.
// `my` (the y plane's motion) may be null.
EnsembleRun run_ensemble(const RunOptions& opt, const rm::UncertainItemSpec& spec, int samples, std::uint64_t seed,
                         double threshold, const rm::GroundMotion& mx, const rm::GroundMotion* my);

}  // namespace rocking_monitor::tools::sim
