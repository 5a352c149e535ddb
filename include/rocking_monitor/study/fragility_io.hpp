#pragma once

// The fragility study's outputs: fragility_runs.csv (one row per run), fragility.json (per body: the
// lognormal fit, its bootstrap band and the screening thresholds in the same intensity measure) and a
// text summary. Read by scripts/plot_fragility.py.

#include <ostream>
#include <string>
#include <vector>

#include "rocking_monitor/study/fragility_study.hpp"

namespace rocking_monitor::core::study {

void write_fragility_runs_csv(std::ostream& out, const FragilityResult& result, const std::vector<StudyBody>& bodies,
                              const std::vector<StudyRecord>& records, const FragilityOptions& options);
void write_fragility_json(std::ostream& out, const FragilityResult& result, const std::vector<StudyBody>& bodies,
                          const FragilityOptions& options);
std::string format_fragility(const FragilityResult& result, const std::vector<StudyBody>& bodies,
                             const FragilityOptions& options);

/// The screening criteria's thresholds expressed in an intensity measure (the vertical lines of a
/// fragility plot): PGV -> the Ishiyama-type velocity thresholds; PGA -> their acceleration thresholds;
/// PSV -> Housner's S_v. Pairs (name, value); empty names are left out.
std::vector<std::pair<std::string, double>> thresholds_in(const ScreeningThresholds& t, IntensityMeasure im);

}  // namespace rocking_monitor::core::study
