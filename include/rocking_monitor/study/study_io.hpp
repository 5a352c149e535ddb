#pragma once

// File formats of the study that need third-party libraries: the YAML body list (yaml-cpp) and the
// JSON summary (nlohmann-json), linked privately by the study layer (cmake/layers.cmake).

#include <cstddef>
#include <string>
#include <vector>

#include "rocking_monitor/study/study.hpp"

namespace rocking_monitor::core::study {

/// Reads bodies from a YAML file:
///
///     bodies:                       # or the list itself at the top level
///       - name: infusion_pump       # optional (default body<N>), must be unique
///         width: 0.45               # B, m (required)
///         cg_height: 0.70           # h, m (required)
///         nu1: 0.35                 # optional, default 0.5; a list [0.5, 0.35] gives one body each,
///                                   # named <name>_nu<value>, all with the same radius of gyration
///         radius_of_gyration: 0.25  # optional, m; default: homogeneous rectangle B x 2h
///         restitution: 0.9          # optional, measured angular-velocity ratio (default eq. 34)
///         mu_s: 0.5                 # optional, static friction (sliding onsets are reported)
///
///         depth: 0.40               # optional, m: the body is then a two-plane item (below)
///         eccentricity_y: 0.5       # optional with depth, default 0.5
///         radius_of_gyration_y: 0.2 # optional with depth, m; default y_plane_body()'s
///
/// or a monitor catalogue (config/catalogue_example.yaml), read by the node's own parser
/// (monitoring/catalogue_file.hpp: same keys, distributions and messages); the live node's sensor,
/// frame, pose and description have no meaning offline, nor has a top-level `sensors:` list. Items
/// with distributions keep their laws (StudyBody::uncertain) for the fragility.
///
/// A body with a depth is a two-plane item (study_items.hpp), the others are single-plane bodies
/// run per record component. Unknown keys are errors (a typo must not silently fall back to a
/// default). Throws StudyError "<file>: bodies[<i>] (<name>): <field>: <problem>" (items[<i>] (<id>)
/// for a catalogue) or "<file>:<line>:<col>: <YAML problem>".
struct BodyFile {
  std::vector<StudyBody> bodies;  ///< single-plane bodies, file order
  std::vector<StudyItem> items;   ///< two-plane items, file order
  std::vector<std::string> notes; ///< what of the file is not run as given (e.g. 3-D without a depth)
};
BodyFile load_body_file(const std::string& path);
/// The single-plane bodies of a file without two-plane items (throws StudyError if it has some).
std::vector<StudyBody> load_bodies_yaml(const std::string& path);

/// How a run was made (goes into summary.json under "run").
struct StudyRunInfo {
  std::string records_dir;
  bool from_manifest = false;
  std::string bodies_source;  ///< "paper grid" or the YAML path
  std::string method, model;
  double tol = 0.0;
  int substeps = 0;
  int threads = 0;
  std::string shard = "1/1";
  std::size_t case_begin = 0, case_end = 0, total_cases = 0;
  double wall_time_s = 0.0;   ///< negative: not measured (merged shards)
  std::vector<std::string> notes;
};

/// The rocking model every case of the study runs, named in summary.json's "run" (the live node
/// defaults to adaptive fidelity; the study deliberately runs the paper's model).
inline constexpr const char* kStudyRockingModel =
    "pure rocking (paper): no sliding, no free flight; contact onsets only reported";

/// summary.json: run info, the symmetric-body headline, per-set tallies by eccentricity and by
/// eccentricity x height (Figure 7 percentages, Figure 8 ratios) and the vertical-component effect;
/// with `items` (two-plane items were run) also "two_plane_items".
std::string summary_json(const StudySummary& summary, const StudyRunInfo& run,
                         const ItemSummary* items = nullptr);

}  // namespace rocking_monitor::core::study
