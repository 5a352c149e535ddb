#pragma once

// The summary numbers of the study: overturns and screening-criterion tallies by eccentricity,
// height and PGV band, and the effect of the vertical component.

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "rocking_monitor/study/study_bodies.hpp"
#include "rocking_monitor/study/study_records.hpp"
#include "rocking_monitor/study/study_runner.hpp"

namespace rocking_monitor::core::study {

/// The screening criteria compared (ScreeningPrediction fields), in this order.
enum class Screening : int { Housner = 0, Ishiyama = 1, IshiyamaEquivalent = 2, Proposed = 3 };
inline constexpr int kScreeningCount = 4;
const char* to_string(Screening criterion);

/// What the summary needs of a case (from a CaseResult or from a cases.csv row).
struct CaseRow {
  std::size_t index = 0, body = 0, record = 0;
  double width = 0.0, cg_height = 0.0, nu1 = 0.5;
  double pgv = 0.0;  ///< m/s, of the record component
  int polarity = 1;
  bool vertical = false;
  bool overturned = false, committed = false, beyond_tipping = false;
  std::array<bool, kScreeningCount> predicted{};
};
CaseRow to_case_row(const CaseResult& result, const std::vector<StudyBody>& bodies,
                    const std::vector<StudyRecord>& records);

/// Counts over a group of cases. For each criterion: predicted = it predicts overturning;
/// missed = overturned although it predicted safety (the criterion is "not satisfied");
/// false_alarm = predicted overturning, the body stayed.
struct Tally {
  long cases = 0, overturned = 0, committed = 0, beyond_tipping = 0;
  std::array<long, kScreeningCount> predicted{}, missed{}, false_alarms{};
  void add(const CaseRow& row);
  double overturned_percent() const { return cases ? 100.0 * overturned / cases : 0.0; }
  /// Share (%) of cases where the criterion is satisfied: no overturn where it predicts safety.
  double consistent_percent(Screening c) const {
    return cases ? 100.0 * (cases - missed[static_cast<int>(c)]) / cases : 0.0;
  }
};

/// Upper edges of the PGV bands of SetSummary::by_eccentricity_pgv, m/s (the last band is open).
inline const std::vector<double>& pgv_band_edges() {
  static const std::vector<double> edges{0.1, 0.3, 1.0};
  return edges;
}
/// Band of a PGV (0 .. pgv_band_edges().size()).
std::size_t pgv_band(double pgv);

/// Tallies of one set of cases, by eccentricity (descending: 0.5 first), centre-of-mass height
/// (ascending) and PGV band.
struct SetSummary {
  std::string name;
  std::vector<double> eccentricities;
  std::vector<double> heights;
  std::vector<Tally> by_eccentricity;
  std::vector<std::vector<Tally>> by_eccentricity_height;  ///< [eccentricity][height]
  std::vector<std::vector<Tally>> by_eccentricity_pgv;     ///< [eccentricity][pgv band]
  Tally all;
  /// Index of eccentricity 0.5 (symmetric) or -1.
  int symmetric_index() const;
  /// Overturned share at eccentricity e / overturned share at 0.5 (Figure 8), over all cases of that
  /// eccentricity (height < 0) or of one height; equal to the ratio of counts when every
  /// eccentricity has the same cases (the grid). NaN without symmetric overturns.
  double overturn_ratio(std::size_t eccentricity, int height = -1) const;
  /// The same restricted to one PGV band.
  double overturn_ratio_pgv(std::size_t eccentricity, std::size_t band) const;
};

/// The effect of the vertical component: cases that have a vertical, paired on (body, record,
/// polarity), by eccentricity.
struct VerticalEffect {
  std::vector<double> eccentricities;
  std::vector<long> pairs, overturned_without, overturned_with, only_with, only_without;
};

struct StudySummary {
  std::size_t cases = 0, bodies = 0, records = 0, records_with_vertical = 0;
  SetSummary horizontal;               ///< every record, vertical off (the paper's setting)
  SetSummary subset_without_vertical;  ///< records that have a vertical, vertical off
  SetSummary with_vertical;            ///< the same records, vertical on
  VerticalEffect vertical_effect;
};

/// Summary of any set of cases (rows in any order).
StudySummary summarize(const std::vector<CaseRow>& rows);

}  // namespace rocking_monitor::core::study
