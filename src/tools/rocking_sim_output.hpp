#pragma once
// rocking_sim's output: one plane through its record (its single-plane JSON and text lines), and the
// whole answer printed as JSON or text, one plane or two (with the item's verdict and the ensemble).

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

#include "rocking_monitor/physics/item_verdict.hpp"
#include "rocking_sim_options.hpp"

namespace rocking_monitor::tools::sim {

using nlohmann::json;

// One plane's answer: the single-plane JSON of its fidelity, its text summary lines and its level
// times for combine().
struct PlaneRun {
  json out;
  std::vector<std::string> lines;
  rm::LevelTimes levels;
};

struct EnsembleRun;  // rocking_sim_ensemble.hpp
struct SolidRun;     // rocking_sim_solid.hpp

/// NaN (never) as JSON null.
json nullable(double v);

/// The levels every model's JSON block reports alike: overturned, committed, beyond_tipping, their
/// times and the uplift time (null: never), max_rotation_ratio and impacts (RockingOutcome,
/// AdaptiveOutcome).
template <class Outcome>
json outcome_json(const Outcome& o) {
  return {{"overturned", o.overturned},
          {"committed", o.committed},
          {"beyond_tipping", o.beyond_tipping},
          {"max_rotation_ratio", o.max_rotation_ratio},
          {"impacts", o.impacts},
          {"uplift_time_s", nullable(o.uplift_time)},
          {"beyond_tipping_time_s", nullable(o.beyond_tipping_time)},
          {"committed_time_s", nullable(o.committed_time)},
          {"overturn_time_s", nullable(o.overturn_time)}};
}

/// printf into a std::string (lines up to 1023 characters).
std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

// One plane through its record, exactly as the single-plane tool: simulate() for --fidelity rocking,
// the AdaptiveModel loop for contact / adaptive.
PlaneRun run_plane(const RunOptions& opt, const rm::BodyParameters& params,
                   const rm::GroundMotion& motion, const std::string& history_path);
/// Whether an item's two planes share one friction budget (the adaptive or contact model with a
/// friction coefficient): then run_plane_pair, as the node steps them.
bool planes_share_friction(const RunOptions& opt, const rm::BodyParameters& x);
/// The x and y planes stepped together under one friction budget (monitoring/friction_share.hpp); the
/// records of equal length and interval (std::invalid_argument otherwise).
std::pair<PlaneRun, PlaneRun> run_plane_pair(const RunOptions& opt, const rm::BodyParameters& x,
                                             const rm::BodyParameters& y, const rm::GroundMotion& mx,
                                             const rm::GroundMotion& my, const std::string& history_x,
                                             const std::string& history_y);

/// Prints the answer: with --json one object (the top level is the x plane's single-plane output, then
/// "planes", "item", "solid" and "ensemble"); else the planes' lines ([x]/[y] with two), the 3-D
/// model's ([3d]), the item line and the ensemble's lines. With `solid` the item's verdict is the 3-D
/// run's (the node's alarms: by the 3-D model or, before it took over, a plane). `y`, `item_entry`,
/// `ensemble` and `solid` may be null.
void print_result(bool as_json, const PlaneRun& x, const PlaneRun* y, const rm::ItemVerdict& item,
                  const rm::CatalogueItem* item_entry, const EnsembleRun* ensemble, const SolidRun* solid = nullptr);

}  // namespace rocking_monitor::tools::sim
