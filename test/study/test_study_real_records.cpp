// The study (issue 5) on the real records of ../shared/records: record pairing from the manifest and
// the batch engine against one model per case.

#include "study_fixtures.hpp"

namespace rocking_monitor::core::study {
namespace {

// ------------------------------------------------------------------ real records

TEST(StudyRealRecords, ManifestGivesEveryHorizontalComponentWithItsVertical) {
  const fs::path dir(ROCKING_RECORDS_DIR);
  if (!fs::exists(dir / "MANIFEST.csv")) GTEST_SKIP() << "no records at " << dir << " (see README)";
  const StudyRecords recs = load_study_records(dir.string());
  EXPECT_TRUE(recs.from_manifest);
  // Independent count from the manifest: horizontal rows, and those whose (event, station) has a V row.
  std::ifstream in(dir / "MANIFEST.csv");
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<std::string>> rows;
  std::set<std::pair<std::string, std::string>> with_v;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    rows.push_back(split(line));
    if (rows.back()[3].rfind("V:", 0) == 0) with_v.insert({rows.back()[0], rows.back()[2]});
  }
  std::size_t horizontals = 0, paired = 0;
  std::set<std::string> events;
  for (const auto& r : rows) {
    if (r[3].rfind("H:", 0) != 0) continue;
    const StudyRecord& s = recs.records.at(horizontals);
    EXPECT_EQ(s.file, r[4]);
    // PGA against the manifest's pga_g (4 decimals).
    EXPECT_NEAR(s.pga / kGravity, std::stod(r[9]), 6e-5) << r[4];
    EXPECT_GT(s.pgv, 0.0);
    EXPECT_EQ(s.has_vertical(), with_v.count({r[0], r[2]}) > 0) << r[4];
    paired += s.has_vertical();
    events.insert(r[0]);
    ++horizontals;
  }
  EXPECT_EQ(recs.records.size(), horizontals);
  EXPECT_EQ(horizontals, 263u);
  EXPECT_EQ(events.size(), 13u);
  EXPECT_EQ(paired, 74u);
  // Rinaldi: both horizontals with RinaldiUP.
  const StudyRecords rinaldi = load_study_records(dir.string(), {{"Rinaldi"}, {}});
  ASSERT_EQ(rinaldi.records.size(), 2u);
  for (const auto& r : rinaldi.records) EXPECT_EQ(r.vertical_file, "northridge_1994/RinaldiUP.AT2");
  // A short study on them: 2 bodies x 2 components x 2 polarities x (without, with vertical).
  std::vector<StudyBody> bodies = grid_bodies(small_grid());
  bodies.resize(2);
  StudyOptions opt;
  opt.threads = 2;
  const auto res = run_study(bodies, rinaldi.records, opt);
  EXPECT_EQ(res.size(), 16u);
  long v_on = 0;
  for (const auto& c : res) v_on += c.vertical;
  EXPECT_EQ(v_on, 8);
}

TEST(StudyBatch, BatchEngineEqualsOneModelPerCaseBitForBit) {
  // The batch path (bodies of a record input stepped together, SIMD) against one RockingModel per
  // case, on real Rinaldi components with and without the vertical, bodies with friction (sliding
  // onsets are violations) and without, whole and in shards that cut through the bodies.
  const std::string dir = ROCKING_RECORDS_DIR;
  const StudyRecords rinaldi = load_study_records(dir, {{"Rinaldi"}, {}});
  ASSERT_EQ(rinaldi.records.size(), 2u);
  StudyGrid g = small_grid();
  g.widths = 6;
  g.eccentricities = {0.5, 0.3};
  std::vector<StudyBody> bodies = grid_bodies(g);
  for (std::size_t b = 0; b < bodies.size(); b += 3) bodies[b].parameters.mu_s = 0.3;
  StudyOptions batch, scalar;
  batch.threads = scalar.threads = 2;
  batch.trig = BatchTrig::Exact;  // the exact path, kept bit for bit (the default Fast meets the policy)
  scalar.batch = false;
  const auto a = run_study(bodies, rinaldi.records, batch);
  const auto c = run_study(bodies, rinaldi.records, scalar);
  ASSERT_EQ(a.size(), c.size());
  int overturned = 0, violated = 0, rocked = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].index, c[i].index);
    EXPECT_EQ(a[i].outcome.overturned, c[i].outcome.overturned) << i;
    EXPECT_EQ(a[i].outcome.impacts, c[i].outcome.impacts) << i;
    EXPECT_EQ(a[i].outcome.integrator_steps, c[i].outcome.integrator_steps) << i;
    EXPECT_EQ(a[i].outcome.samples, c[i].outcome.samples) << i;
    EXPECT_EQ(a[i].final_mode, c[i].final_mode) << i;
    EXPECT_EQ(a[i].violations, c[i].violations) << i;
    EXPECT_TRUE(same_double(a[i].first_violation_time, c[i].first_violation_time)) << i;
    EXPECT_TRUE(same_double(a[i].outcome.max_rotation_ratio, c[i].outcome.max_rotation_ratio)) << i;
    EXPECT_TRUE(same_double(a[i].outcome.overturn_time, c[i].outcome.overturn_time)) << i;
    EXPECT_TRUE(same_double(a[i].outcome.committed_time, c[i].outcome.committed_time)) << i;
    EXPECT_TRUE(same_double(a[i].max_theta, c[i].max_theta)) << i;
    overturned += a[i].outcome.overturned;
    violated += a[i].violations != 0;
    rocked += a[i].outcome.impacts > 0;
  }
  // A real comparison: some cases fall, some rock, some break the pure-rocking assumptions.
  EXPECT_GT(overturned, 0);
  EXPECT_GT(rocked, overturned);
  EXPECT_GT(violated, 0);
  const std::string whole = csv_of(c, bodies, rinaldi.records);
  EXPECT_EQ(csv_of(a, bodies, rinaldi.records), whole);
  for (int n : {3, 7}) {
    std::string joined;
    for (int k = 1; k <= n; ++k) {
      StudyOptions s = batch;
      s.range = shard_range(a.size(), k, n);
      joined += csv_of(run_study(bodies, rinaldi.records, s), bodies, rinaldi.records);
    }
    EXPECT_EQ(joined, whole) << n << " shards";
  }
}

}  // namespace
}  // namespace rocking_monitor::core::study
