// rocking_sim: runs one body through one ground-motion record (or two: its x and y rocking
// planes, uncoupled) with the ROS-free core.
// Thin command-line layer: parse, read, simulate, print. All physics lives in the core library.
// The parts, one job each: rocking_sim_options.* (the command line, the body and the records),
// rocking_sim_output.* (one plane's run, the JSON and text output), rocking_sim_ensemble.* (--samples),
// rocking_sim_solid.* (the 3-D model, --solid-model).
#include <iostream>
#include <optional>

#include <CLI/CLI.hpp>

#include "command_line.hpp"
#include "rocking_sim_ensemble.hpp"
#include "rocking_sim_options.hpp"
#include "rocking_sim_output.hpp"
#include "rocking_sim_solid.hpp"

namespace rm = rocking_monitor::core;
namespace sim = rocking_monitor::tools::sim;

int main(int argc, char** argv) {
  CLI::App app{
      "rocking_sim: rocking and overturning of a free-standing (optionally eccentric) rigid body "
      "under horizontal and vertical ground acceleration (Boroschek & Romo). With --depth the item "
      "rocks in two uncoupled principal planes: x-z (width, --record) and y-z (depth, --record-y)."};
  sim::CommandLine c;
  sim::add_options(app, c);
  if (const auto status = rocking_monitor::tools::parse_command_line(app, argc, argv, "rocking_sim")) return *status;

  try {
    const sim::Setup s = sim::resolve(app, c);
    const sim::Motions m = sim::read_motions(c, s.two_planes);

    // Two planes with friction share one budget (docs/model.md), as the node steps them.
    std::optional<sim::PlaneRun> x, y;
    if (s.body_y && sim::planes_share_friction(c.opt, c.body)) {
      auto pair = sim::run_plane_pair(c.opt, c.body, *s.body_y, m.x, *m.y, c.history_path, c.history_y_path);
      x = std::move(pair.first);
      y = std::move(pair.second);
    } else {
      x = sim::run_plane(c.opt, c.body, m.x, c.history_path);
      if (s.body_y) y = sim::run_plane(c.opt, *s.body_y, *m.y, c.history_y_path);
    }
    if (s.derived_history_y)  // said once it is written, so a failed run still prints one error line
      std::cerr << "rocking_sim: note: the y plane's history is in " << c.history_y_path
                << " (--history-y to choose)\n";
    const rm::ItemVerdict item = rm::combine(x->levels, y ? &y->levels : nullptr);
    std::optional<sim::SolidRun> solid;
    if (s.solid_item)
      solid = sim::run_solid(c.opt, *s.solid_item, s.solid_choice, c.bidirectional_ratio, m.x, m.y ? &*m.y : nullptr,
                             c.history_3d_path);
    std::optional<sim::EnsembleRun> ensemble;
    if (c.samples > 0)
      ensemble = sim::run_ensemble(c.opt, s.item_entry->uncertain, c.samples, c.ensemble_seed, c.alarm_probability,
                                   m.x, m.y ? &*m.y : nullptr);
    sim::print_result(c.as_json, *x, y ? &*y : nullptr, item, s.item_entry ? &*s.item_entry : nullptr,
                      ensemble ? &*ensemble : nullptr, solid ? &*solid : nullptr);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "rocking_sim: error: " << e.what() << "\n";
    return 2;
  }
}
