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
/// Unknown keys are errors (a typo must not silently fall back to a default). Throws StudyError
/// "<file>: bodies[<i>] (<name>): <field>: <problem>" or "<file>:<line>:<col>: <YAML problem>".
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

/// summary.json: run info, the symmetric-body headline, per-set tallies by eccentricity and by
/// eccentricity x height (Figure 7 percentages, Figure 8 ratios) and the vertical-component effect.
std::string summary_json(const StudySummary& summary, const StudyRunInfo& run);

}  // namespace rocking_monitor::core::study
