// The study summary (issue 5) against an independent count of cases.csv.

#include "study_fixtures.hpp"

namespace rocking_monitor::core::study {
namespace {

// ------------------------------------------------------------------ summary

// Recounts cases.csv with the test's own parser and compares with summarize() and summary.json.
TEST(StudySummary, CountsMatchAnIndependentRecountOfTheCaseFile) {
  const StudyRecords recs = load_study_records(synthetic_records("sum").string());
  StudyGrid g = small_grid();
  g.eccentricities = {0.5, 0.4, 0.3, 0.2};
  const std::vector<StudyBody> bodies = grid_bodies(g);
  StudyOptions opt;
  opt.threads = 2;
  const auto results = run_study(bodies, recs.records, opt);
  const fs::path csv = temp_dir("sumcsv") / "cases.csv";
  {
    std::ofstream out(csv);
    write_case_csv_header(out);
    write_case_csv_rows(out, results, bodies, recs.records);
  }
  std::vector<CaseRow> rows;
  for (const auto& c : results) rows.push_back(to_case_row(c, bodies, recs.records));
  const StudySummary s = summarize(rows);
  const auto j = nlohmann::json::parse(summary_json(s, StudyRunInfo{}));

  // Independent recount.
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  const auto header = split(line);
  std::map<std::string, std::size_t> col;
  for (std::size_t i = 0; i < header.size(); ++i) col[header[i]] = i;
  const char* crit[] = {"housner", "ishiyama", "ishiyama_equivalent", "proposed"};
  struct Count {
    long cases = 0, over = 0;
    long missed[4] = {0, 0, 0, 0}, false_alarm[4] = {0, 0, 0, 0};
  };
  std::map<std::string, Count> by_nu_h, by_nu_v, by_nu_pgv;  // "nu|h", "nu" (vertical on), "nu|band"
  std::map<std::string, std::map<std::string, bool>> pair_off, pair_on;
  std::size_t n = 0;
  while (std::getline(in, line)) {
    const auto f = split(line);
    ASSERT_EQ(f.size(), header.size());
    ++n;
    const double nu1 = std::stod(f[col["nu1"]]);
    char key[64];
    std::snprintf(key, sizeof key, "%.2f", std::min(nu1, 1 - nu1));
    const bool over = f[col["overturned"]] == "1";
    const bool vert = f[col["vertical"]] == "1";
    Count& c = vert ? by_nu_v[key] : by_nu_h[std::string(key) + "|" + f[col["cg_height_m"]]];
    ++c.cases;
    c.over += over;
    for (int k = 0; k < 4; ++k) {
      const bool pred = f[col[std::string("predicts_") + crit[k]]] == "1";
      c.missed[k] += over && !pred;
      c.false_alarm[k] += pred && !over;
    }
    if (!vert) {
      const double pgv = std::stod(f[col["pgv_mps"]]);
      const int band = pgv < 0.1 ? 0 : pgv < 0.3 ? 1 : pgv < 1.0 ? 2 : 3;
      Count& b = by_nu_pgv[std::string(key) + "|" + std::to_string(band)];
      ++b.cases;
      b.over += over;
    }
    const std::string pk = f[col["body"]] + "/" + f[col["record"]] + "/" + f[col["polarity"]];
    (vert ? pair_on : pair_off)[key][pk] = over;
  }
  ASSERT_EQ(n, results.size());
  // Compare with the JSON, per eccentricity x height and per eccentricity.
  const auto& sets = j["sets"];
  std::size_t matched = 0;
  for (const auto& t : sets["horizontal_only"]["by_eccentricity_height"]) {
    char key[64];
    std::snprintf(key, sizeof key, "%.2f|%.9g", t["eccentricity"].get<double>(), t["cg_height_m"].get<double>());
    ASSERT_TRUE(by_nu_h.count(key)) << key;
    const Count& c = by_nu_h[key];
    EXPECT_EQ(t["cases"].get<long>(), c.cases) << key;
    EXPECT_EQ(t["overturned"].get<long>(), c.over) << key;
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(t["criteria"][crit[k]]["missed"].get<long>(), c.missed[k]) << key << crit[k];
      EXPECT_EQ(t["criteria"][crit[k]]["false_alarms"].get<long>(), c.false_alarm[k]) << key << crit[k];
    }
    ++matched;
  }
  EXPECT_EQ(matched, by_nu_h.size());
  long sym_cases = 0, sym_missed = 0, sym_over = 0;
  std::map<std::string, long> over_by_nu;
  for (const auto& [key, c] : by_nu_h) {
    over_by_nu[key.substr(0, 4)] += c.over;
    if (key.rfind("0.50|", 0) == 0) {
      sym_cases += c.cases;
      sym_missed += c.missed[1];
      sym_over += c.over;
    }
  }
  EXPECT_EQ(j["headline"]["cases"].get<long>(), sym_cases);
  EXPECT_EQ(j["headline"]["missed_by_ishiyama"].get<long>(), sym_missed);
  EXPECT_NEAR(j["headline"]["ishiyama_consistent_percent"].get<double>(), 100.0 * (sym_cases - sym_missed) / sym_cases, 1e-9);
  ASSERT_GT(sym_over, 0);
  for (const auto& t : sets["horizontal_only"]["by_eccentricity"]) {
    char key[16];
    std::snprintf(key, sizeof key, "%.2f", t["eccentricity"].get<double>());
    // Same number of cases per eccentricity, so the Figure 8 ratio is a ratio of counts.
    EXPECT_NEAR(t["ratio_to_symmetric"].get<double>(), double(over_by_nu[key]) / over_by_nu["0.50"], 1e-12) << key;
  }
  long band_cases = 0;
  for (const auto& t : sets["horizontal_only"]["by_eccentricity_pgv"]) {
    const double lo = t["pgv_min_mps"].get<double>();
    const int band = lo < 0.05 ? 0 : lo < 0.2 ? 1 : lo < 0.5 ? 2 : 3;
    char key[32];
    std::snprintf(key, sizeof key, "%.2f|%d", t["eccentricity"].get<double>(), band);
    const Count c = by_nu_pgv.count(key) ? by_nu_pgv[key] : Count{};
    EXPECT_EQ(t["cases"].get<long>(), c.cases) << key;
    EXPECT_EQ(t["overturned"].get<long>(), c.over) << key;
    band_cases += c.cases;
  }
  EXPECT_EQ(band_cases, sets["horizontal_only"]["all"]["cases"].get<long>());
  for (const auto& t : sets["vertical_subset_with_vertical"]["by_eccentricity"]) {
    char key[16];
    std::snprintf(key, sizeof key, "%.2f", t["eccentricity"].get<double>());
    EXPECT_EQ(t["cases"].get<long>(), by_nu_v[key].cases) << key;
    EXPECT_EQ(t["overturned"].get<long>(), by_nu_v[key].over) << key;
  }
  for (const auto& v : j["vertical_effect"]) {
    char key[16];
    std::snprintf(key, sizeof key, "%.2f", v["eccentricity"].get<double>());
    long pairs = 0, only_with = 0, only_without = 0;
    for (const auto& [pk, on] : pair_on[key]) {
      ++pairs;
      const bool off = pair_off[key].at(pk);
      only_with += on && !off;
      only_without += off && !on;
    }
    EXPECT_EQ(v["pairs"].get<long>(), pairs) << key;
    EXPECT_EQ(v["overturn_only_with_vertical"].get<long>(), only_with) << key;
    EXPECT_EQ(v["overturn_only_without_vertical"].get<long>(), only_without) << key;
  }
  // read_case_csv gives back the same rows (what --merge summarizes).
  const CaseFile back = read_case_csv(csv.string());
  ASSERT_EQ(back.rows.size(), rows.size());
  const StudySummary s2 = summarize(back.rows);
  EXPECT_EQ(summary_json(s2, StudyRunInfo{}), summary_json(s, StudyRunInfo{}));
  EXPECT_FALSE(format_summary(s).empty());
}

}  // namespace
}  // namespace rocking_monitor::core::study
