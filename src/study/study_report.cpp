#include "rocking_monitor/study/study_report.hpp"

#include <cstdio>
#include <sstream>
#include <string>

#include "study_internal.hpp"

namespace rocking_monitor::core::study {

using detail::format_number;

namespace {

// One cell of the overturn tables (by height, by PGV band): the overturned share and, in brackets,
// its ratio to the symmetric body's; "-" for a group without cases.
std::string overturn_cell(const Tally& t, double ratio_to_symmetric) {
  char buf[128];
  if (t.cases == 0)
    std::snprintf(buf, sizeof buf, " %17s", "-");
  else
    std::snprintf(buf, sizeof buf, " %6.2f%% [%6.2f]", t.overturned_percent(), ratio_to_symmetric);
  return buf;
}

// The symmetric bodies' line: how often Ishiyama's criterion held (the paper's 99.4 %).
void symmetric_line(const StudySummary& s, std::ostringstream& o) {
  const SetSummary& h = s.horizontal;
  const int sym = h.symmetric_index();
  if (sym < 0) return;
  char buf[512];
  const Tally& t = h.by_eccentricity[static_cast<std::size_t>(sym)];
  std::snprintf(buf, sizeof buf,
                "\nSymmetric bodies (nu = 0.5), horizontal only: Ishiyama's criterion satisfied in "
                "%.2f %% of %ld cases (paper: 99.4 %%); %ld overturns it did not predict.\n",
                t.consistent_percent(Screening::Ishiyama), t.cases,
                t.missed[static_cast<int>(Screening::Ishiyama)]);
  o << buf;
}

// A set's overturns and screening criteria's misses and false alarms, a row per eccentricity.
void eccentricity_table(const SetSummary& set, std::ostringstream& o) {
  char buf[512];
  o << "\n[" << set.name << "] overturns and screening criteria by eccentricity "
    << "(missed = overturned where the criterion predicts safety; false = predicted, stayed)\n";
  std::snprintf(buf, sizeof buf, "  %-5s %8s %8s %7s %8s | %-17s | %-17s | %-17s | %-17s\n", "nu",
                "cases", "overturn", "%", "x sym", "Housner miss/false", "Ishiyama miss/fals",
                "B'=2nuB miss/fals", "0.2 rule miss/fal");
  o << buf;
  for (std::size_t e = 0; e < set.eccentricities.size(); ++e) {
    const Tally& t = set.by_eccentricity[e];
    if (t.cases == 0) continue;
    std::snprintf(buf, sizeof buf, "  %-5.2f %8ld %8ld %6.2f%% %8.2f |", set.eccentricities[e],
                  t.cases, t.overturned, t.overturned_percent(), set.overturn_ratio(e));
    o << buf;
    for (int k = 0; k < kScreeningCount; ++k) {
      std::snprintf(buf, sizeof buf, " %7ld / %-7ld |", t.missed[k], t.false_alarms[k]);
      o << buf;
    }
    o << '\n';
  }
}

// A set's overturned share by height and eccentricity [Figures 7 and 8].
void height_table(const SetSummary& set, std::ostringstream& o) {
  char buf[512];
  o << "  overturned % by height (rows) and eccentricity (columns) [Figure 7]; "
    << "ratio to nu = 0.5 in brackets [Figure 8]\n";
  o << "  h [m]       ";
  for (double e : set.eccentricities) {
    std::snprintf(buf, sizeof buf, " %17s", ("nu=" + format_number("%.2f", e)).c_str());
    o << buf;
  }
  o << '\n';
  for (std::size_t hi = 0; hi < set.heights.size(); ++hi) {
    std::snprintf(buf, sizeof buf, "  %-12.3f", set.heights[hi]);
    o << buf;
    for (std::size_t e = 0; e < set.eccentricities.size(); ++e)
      o << overturn_cell(set.by_eccentricity_height[e][hi], set.overturn_ratio(e, static_cast<int>(hi)));
    o << '\n';
  }
}

// A set's overturned share by PGV band and eccentricity.
void pgv_table(const SetSummary& set, std::ostringstream& o) {
  char buf[512];
  o << "  overturned % by PGV band (rows) and eccentricity; ratio to nu = 0.5 in brackets\n";
  const auto& edges = pgv_band_edges();
  for (std::size_t b = 0; b <= edges.size(); ++b) {
    const std::string band = b == 0 ? "< " + format_number("%g", edges[0])
                                    : b == edges.size() ? ">= " + format_number("%g", edges.back())
                                                        : format_number("%g", edges[b - 1]) + "-" +
                                                              format_number("%g", edges[b]);
    std::snprintf(buf, sizeof buf, "  %-12s", (band + " m/s").c_str());
    o << buf;
    for (std::size_t e = 0; e < set.eccentricities.size(); ++e)
      o << overturn_cell(set.by_eccentricity_pgv[e][b], set.overturn_ratio_pgv(e, b));
    o << '\n';
  }
}

// The vertical component's effect: the same cases without and with it, by eccentricity.
void vertical_table(const VerticalEffect& v, std::ostringstream& o) {
  long total_pairs = 0;
  for (long p : v.pairs) total_pairs += p;
  if (total_pairs == 0) return;
  char buf[512];
  auto pct = [](long a, long b) { return b ? 100.0 * a / b : 0.0; };
  o << "\nVertical component (same body, record and polarity, without vs with the vertical)\n";
  std::snprintf(buf, sizeof buf, "  %-5s %8s %12s %12s %10s %12s\n", "nu", "pairs", "overturned",
                "with vert.", "only with", "only without");
  o << buf;
  for (std::size_t e = 0; e < v.eccentricities.size(); ++e) {
    if (v.pairs[e] == 0) continue;
    std::snprintf(buf, sizeof buf, "  %-5.2f %8ld %12ld %12ld %10ld %12ld   (%.2f %% -> %.2f %%)\n",
                  v.eccentricities[e], v.pairs[e], v.overturned_without[e], v.overturned_with[e],
                  v.only_with[e], v.only_without[e], pct(v.overturned_without[e], v.pairs[e]),
                  pct(v.overturned_with[e], v.pairs[e]));
    o << buf;
  }
}

}  // namespace

std::string format_summary(const StudySummary& s) {
  std::ostringstream o;
  o << "rocking_study: " << s.cases << " cases, " << s.bodies << " bodies x " << s.records
    << " horizontal record components (" << s.records_with_vertical
    << " with the station's vertical), both polarities\n";
  symmetric_line(s, o);
  for (const SetSummary* set : {&s.horizontal, &s.subset_without_vertical, &s.with_vertical}) {
    if (set->all.cases == 0) continue;
    eccentricity_table(*set, o);
    height_table(*set, o);
    pgv_table(*set, o);
  }
  vertical_table(s.vertical_effect, o);
  return o.str();
}

}  // namespace rocking_monitor::core::study
