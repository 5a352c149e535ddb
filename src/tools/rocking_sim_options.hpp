#pragma once
// rocking_sim's command line: every flag, what the flags resolve to (the body, the y plane, the
// catalogue item) and the record(s) read into ground motions. src/tools/rocking_sim.cpp runs them.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rocking_monitor/model/adaptive_model.hpp"
#include "rocking_monitor/monitoring/catalogue_file.hpp"
#include "rocking_monitor/monitoring/plane_monitor.hpp"
#include "rocking_monitor/physics/base_body.hpp"
#include "rocking_monitor/motion/ground_motion.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "rocking_monitor/physics/principal_planes.hpp"

namespace rocking_monitor::tools::sim {

namespace rm = rocking_monitor::core;

// What both planes share: solver, fidelity and its settings, the scale.
struct RunOptions {
  rm::SolverSettings settings;
  rm::Fidelity fidelity = rm::Fidelity::Adaptive;
  std::string scene_text;
  rm::ContactSettings contact;
  double hold_time_s = rm::AdaptiveSettings{}.hold_time_s;
  double linearized_max_alpha = 0.0;
  double scale = 1.0;
};

/// Every flag's value as parsed (defaults as --help shows them).
struct CommandLine {
  std::string record, record_y, vertical_file, units_text, history_path, history_y_path,
      method_text = "dopri5", model_text = "nonlinear";
  RunOptions opt;
  rm::BodyParameters body;
  rm::DepthParameters depth;
  bool as_json = false;
  rm::ReadOptions options;
  std::string catalogue_file, item_id;
  int samples = 0;
  std::uint64_t ensemble_seed = 1;
  double alarm_probability = 0.5;
  std::string fidelity_text = "adaptive";
  std::string solid_model_text = "auto", history_3d_path;  ///< --solid-model, --history-3d
  double bidirectional_ratio = 0.3;
};

/// Declares every flag on `app`, bound to `c`.
void add_options(CLI::App& app, CommandLine& c);

/// What the flags resolve to before any record is read.
struct Setup {
  std::optional<rm::CatalogueItem> item_entry;  ///< --catalogue/--item
  bool two_planes = false;                      ///< --depth (or the item's depth)
  std::optional<rm::BodyParameters> body_y;     ///< the y plane's body when two_planes
  bool derived_history_y = false;               ///< --history-y derived from --history
  /// The item the 3-D model runs (--solid-model): a catalogue item with a base polygon, or the box of
  /// --width/--depth with --solid-model 3d; empty: planes only.
  std::optional<rm::ItemSpec> solid_item;
  rm::SolidChoice solid_choice = rm::SolidChoice::Auto;
};

/// Checks the flags together and settles the solver, the body (from the flags or the catalogue item)
/// and the y plane; fills c.history_y_path when derived. Throws naming the flag at fault.
Setup resolve(const CLI::App& app, CommandLine& c);

/// The ground motion along x and, with two planes, along y (same dt and length; the shared vertical).
struct Motions {
  rm::GroundMotion x;
  std::optional<rm::GroundMotion> y;
};

/// Reads --record (--vertical, --record-y) into ground motions, with notes on stderr. Throws
/// rm::RecordError naming the file.
Motions read_motions(CommandLine& c, bool two_planes);

/// --scene: "auto" (the record's own peaks), "unknown", or "H,V" (m/s^2). Throws std::invalid_argument.
rm::SceneEnvelope parse_scene(const std::string& text, const rm::GroundMotion& motion);

}  // namespace rocking_monitor::tools::sim
