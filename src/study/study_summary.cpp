#include "rocking_monitor/study/study_summary.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <tuple>

namespace rocking_monitor::core::study {
namespace {

// Index of a value in a sorted list of distinct keys (relative tolerance 1e-9).
std::size_t key_index(const std::vector<double>& keys, double v) {
  for (std::size_t i = 0; i < keys.size(); ++i)
    if (std::abs(keys[i] - v) <= 1e-9 * std::max(1.0, std::abs(v))) return i;
  return keys.size();
}

void add_key(std::vector<double>& keys, double v) {
  if (key_index(keys, v) == keys.size()) keys.push_back(v);
}

}  // namespace

const char* to_string(Screening criterion) {
  switch (criterion) {
    case Screening::Housner: return "housner";
    case Screening::Ishiyama: return "ishiyama";
    case Screening::IshiyamaEquivalent: return "ishiyama_equivalent";
    case Screening::Proposed: return "proposed";
  }
  return "unknown";
}

CaseRow to_case_row(const CaseResult& c, const std::vector<StudyBody>& bodies,
                    const std::vector<StudyRecord>& records) {
  const double pgv = records.at(c.record).pgv;
  CaseRow row;
  row.index = c.index;
  row.body = c.body;
  row.record = c.record;
  const BodyParameters& b = bodies.at(c.body).parameters;
  row.width = b.width;
  row.cg_height = b.cg_height;
  row.nu1 = b.nu1;
  row.pgv = pgv;
  row.polarity = c.polarity;
  row.vertical = c.vertical;
  row.overturned = c.outcome.overturned;
  row.committed = c.outcome.committed;
  row.beyond_tipping = c.outcome.beyond_tipping;
  row.predicted = {c.prediction.housner, c.prediction.ishiyama, c.prediction.ishiyama_equivalent,
                   c.prediction.proposed};
  return row;
}

void Tally::add(const CaseRow& row) {
  ++cases;
  overturned += row.overturned;
  committed += row.committed;
  beyond_tipping += row.beyond_tipping;
  for (int k = 0; k < kScreeningCount; ++k) {
    predicted[k] += row.predicted[k];
    missed[k] += row.overturned && !row.predicted[k];
    false_alarms[k] += !row.overturned && row.predicted[k];
  }
}

int SetSummary::symmetric_index() const {
  for (std::size_t i = 0; i < eccentricities.size(); ++i)
    if (std::abs(eccentricities[i] - 0.5) < 1e-9) return static_cast<int>(i);
  return -1;
}

namespace {

// Ratio of overturn shares (equal to the ratio of counts when both groups have the same cases).
double share_ratio(const Tally& num_t, const Tally& den_t) {
  if (den_t.overturned == 0 || num_t.cases == 0 || den_t.cases == 0) return std::nan("");
  return (static_cast<double>(num_t.overturned) / num_t.cases) /
         (static_cast<double>(den_t.overturned) / den_t.cases);
}

}  // namespace

std::size_t pgv_band(double pgv) {
  const auto& edges = pgv_band_edges();
  return static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), pgv) - edges.begin());
}

double SetSummary::overturn_ratio(std::size_t e, int h) const {
  const int s = symmetric_index();
  if (s < 0 || e >= eccentricities.size()) return std::nan("");
  const auto si = static_cast<std::size_t>(s);
  if (h < 0) return share_ratio(by_eccentricity[e], by_eccentricity[si]);
  const auto hi = static_cast<std::size_t>(h);
  return share_ratio(by_eccentricity_height[e][hi], by_eccentricity_height[si][hi]);
}

double SetSummary::overturn_ratio_pgv(std::size_t e, std::size_t band) const {
  const int s = symmetric_index();
  if (s < 0 || e >= eccentricities.size() || band > pgv_band_edges().size()) return std::nan("");
  return share_ratio(by_eccentricity_pgv[e][band], by_eccentricity_pgv[static_cast<std::size_t>(s)][band]);
}

StudySummary summarize(const std::vector<CaseRow>& rows) {
  StudySummary s;
  std::vector<double> eccs, heights;
  std::set<std::size_t> bodies, records, vertical_records;
  for (const CaseRow& r : rows) {
    add_key(eccs, std::min(r.nu1, 1.0 - r.nu1));
    add_key(heights, r.cg_height);
    bodies.insert(r.body);
    records.insert(r.record);
    if (r.vertical) vertical_records.insert(r.record);
  }
  std::sort(eccs.begin(), eccs.end(), std::greater<double>());
  std::sort(heights.begin(), heights.end());
  s.cases = rows.size();
  s.bodies = bodies.size();
  s.records = records.size();
  s.records_with_vertical = vertical_records.size();

  auto init = [&](SetSummary& set, const char* name) {
    set.name = name;
    set.eccentricities = eccs;
    set.heights = heights;
    set.by_eccentricity.assign(eccs.size(), Tally{});
    set.by_eccentricity_height.assign(eccs.size(), std::vector<Tally>(heights.size()));
    set.by_eccentricity_pgv.assign(eccs.size(), std::vector<Tally>(pgv_band_edges().size() + 1));
  };
  init(s.horizontal, "horizontal_only");
  init(s.subset_without_vertical, "vertical_subset_without_vertical");
  init(s.with_vertical, "vertical_subset_with_vertical");
  auto add = [](SetSummary& set, std::size_t e, std::size_t h, const CaseRow& r) {
    set.all.add(r);
    set.by_eccentricity[e].add(r);
    set.by_eccentricity_height[e][h].add(r);
    set.by_eccentricity_pgv[e][pgv_band(r.pgv)].add(r);
  };

  VerticalEffect& ve = s.vertical_effect;
  ve.eccentricities = eccs;
  for (auto* v : {&ve.pairs, &ve.overturned_without, &ve.overturned_with, &ve.only_with, &ve.only_without})
    v->assign(eccs.size(), 0);
  // (body, record, polarity) -> overturned without (bit 0/1 set) and with (bit 2/3 set) the vertical.
  std::map<std::tuple<std::size_t, std::size_t, int>, int> pairs;

  for (const CaseRow& r : rows) {
    const std::size_t e = key_index(eccs, std::min(r.nu1, 1.0 - r.nu1));
    const std::size_t h = key_index(heights, r.cg_height);
    const bool in_subset = vertical_records.count(r.record) > 0;
    if (r.vertical) {
      add(s.with_vertical, e, h, r);
    } else {
      add(s.horizontal, e, h, r);
      if (in_subset) add(s.subset_without_vertical, e, h, r);
    }
    if (in_subset) {
      int& bits = pairs[{r.body, r.record, r.polarity}];
      bits |= (r.vertical ? 4 : 1) << (r.overturned ? 1 : 0);
      bits |= static_cast<int>(e) << 8;
    }
  }
  for (const auto& [key, bits] : pairs) {
    const bool have_off = bits & 3, have_on = bits & 12;
    if (!have_off || !have_on) continue;
    const std::size_t e = static_cast<std::size_t>(bits >> 8);
    const bool off = bits & 2, on = bits & 8;
    ++ve.pairs[e];
    ve.overturned_without[e] += off;
    ve.overturned_with[e] += on;
    ve.only_with[e] += on && !off;
    ve.only_without[e] += off && !on;
  }
  return s;
}

}  // namespace rocking_monitor::core::study
