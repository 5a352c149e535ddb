// The study (issue 5): grid, shards, record pairing, agreement with rocking_sim case by case and
// determinism across thread counts and shards. The summary, the YAML body file and the real records:
// test_study_summary.cpp, test_study_bodies_yaml.cpp, test_study_real_records.cpp.

#include "study_fixtures.hpp"

namespace rocking_monitor::core::study {
namespace {

// ------------------------------------------------------------------ grid

TEST(StudyGrid, IsThePapersFortyEightBodiesPerEccentricity) {
  const std::vector<StudyBody> bodies = grid_bodies();
  ASSERT_EQ(bodies.size(), 4u * 48u);
  std::set<std::string> names;
  std::set<double> heights;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const BodyParameters& p = bodies[i].parameters;
    names.insert(bodies[i].name);
    heights.insert(p.cg_height);
    EXPECT_GE(p.width, std::max(0.08, 0.16 * p.cg_height) * (1 - 1e-12));
    EXPECT_LE(p.width, std::min(3.5, 1.2 * p.cg_height) * (1 + 1e-12));
    // Eccentric bodies keep the radius of gyration of the symmetric twin 48 bodies earlier.
    const BodyParameters& twin = bodies[i % 48].parameters;
    EXPECT_EQ(p.width, twin.width);
    EXPECT_EQ(p.cg_height, twin.cg_height);
    EXPECT_DOUBLE_EQ(p.radius_of_gyration, std::sqrt((twin.width * twin.width + 4 * twin.cg_height * twin.cg_height) / 12));
    EXPECT_DOUBLE_EQ(p.nu1, std::vector<double>({0.5, 0.4, 0.3, 0.2})[i / 48]);
  }
  EXPECT_EQ(names.size(), bodies.size());
  ASSERT_EQ(heights.size(), 4u);
  const std::vector<double> h(heights.begin(), heights.end());
  EXPECT_DOUBLE_EQ(h.front(), 0.25);
  EXPECT_DOUBLE_EQ(h.back(), 4.0);
  for (std::size_t k = 1; k < h.size(); ++k) EXPECT_NEAR(h[k] / h[k - 1], std::pow(16.0, 1.0 / 3.0), 1e-12);
  // Widths of one height: geometric, from max(0.08, 0.16 h) to min(3.5, 1.2 h).
  EXPECT_DOUBLE_EQ(bodies[0].parameters.width, 0.08);
  EXPECT_DOUBLE_EQ(bodies[11].parameters.width, 0.30);
  EXPECT_DOUBLE_EQ(bodies[36].parameters.width, 0.64);
  EXPECT_DOUBLE_EQ(bodies[47].parameters.width, 3.5);
  for (int k = 1; k < 12; ++k)
    EXPECT_NEAR(bodies[k].parameters.width / bodies[k - 1].parameters.width, std::pow(0.30 / 0.08, 1.0 / 11), 1e-12);
}

TEST(StudyGrid, RejectsAnEmptyWidthRange) {
  StudyGrid g;
  g.min_width = 5.0;
  EXPECT_THROW(grid_bodies(g), StudyError);
  g = StudyGrid{};
  g.eccentricities = {0.0};
  EXPECT_THROW(grid_bodies(g), StudyError);
}

// ------------------------------------------------------------------ shards

TEST(StudyShards, PartitionTheCasesContiguously) {
  for (std::size_t total : {0u, 1u, 7u, 1000u, 129023u}) {
    for (int n : {1, 2, 3, 8, 13}) {
      std::size_t expect = 0;
      for (int k = 1; k <= n; ++k) {
        const CaseRange r = shard_range(total, k, n);
        EXPECT_EQ(r.begin, expect);
        EXPECT_LE(r.size(), total / n + 1);
        expect = r.end;
      }
      EXPECT_EQ(expect, total);
    }
  }
  EXPECT_EQ(parse_shard("3/8"), std::make_pair(3, 8));
  for (const char* bad : {"0/2", "3/2", "2", "a/b", "1/0", "1/2x", ""}) EXPECT_THROW(parse_shard(bad), StudyError) << bad;
}

// ------------------------------------------------------------------ synthetic records

TEST(StudyRecords, ScanPairsTheVerticalAndComputesPeaks) {
  const fs::path dir = synthetic_records("scan");
  const StudyRecords recs = load_study_records(dir.string());
  EXPECT_FALSE(recs.from_manifest);
  ASSERT_EQ(recs.records.size(), kPulses.size());  // README.md is not a record
  for (std::size_t i = 0; i < kPulses.size(); ++i) {
    const StudyRecord& r = recs.records[i];
    EXPECT_EQ(r.file, "synthetic/" + kPulses[i].name + ".csv");
    EXPECT_EQ(r.has_vertical(), kPulses[i].vertical_amplitude >= 0) << r.file;
    EXPECT_NEAR(r.pga, kPulses[i].amplitude, 0.01 * kPulses[i].amplitude);
    // PGV of a one-sine pulse: 2 a / omega (the velocity goes 0 -> 2a/w -> 0); the linear baseline
    // fit over the 8 s record changes it by a few per cent.
    EXPECT_NEAR(r.pgv, 2 * kPulses[i].amplitude / kPulses[i].omega, 0.1 * 2 * kPulses[i].amplitude / kPulses[i].omega);
  }
  // Only/exclude select by path.
  EXPECT_EQ(load_study_records(dir.string(), {{"p2_"}, {}}).records.size(), 1u);
  EXPECT_EQ(load_study_records(dir.string(), {{}, {"p2_"}}).records.size(), 2u);
  EXPECT_THROW(load_study_records(dir.string(), {{"nothing"}, {}}), StudyError);
  EXPECT_THROW(load_study_records((dir / "missing").string()), StudyError);
}

TEST(StudyCases, InputsAreBothPolaritiesAndVerticalOnOff) {
  const StudyRecords recs = load_study_records(synthetic_records("inputs").string());
  const std::vector<StudyInput> in = study_inputs(recs.records);
  ASSERT_EQ(in.size(), 2u + 2u + 4u);
  EXPECT_EQ(in[4].record, 2u);
  EXPECT_EQ(in[4].polarity, 1);
  EXPECT_FALSE(in[4].vertical);
  EXPECT_TRUE(in[5].vertical);
  EXPECT_EQ(in[6].polarity, -1);
  EXPECT_EQ(study_inputs(recs.records, {false, false}).size(), 3u);
  EXPECT_EQ(study_case_count(10, recs.records), 80u);
}

// Every case of a small grid gives the same answer as the rocking_sim binary on a CSV file holding
// exactly that excitation (polarity applied to the horizontal, vertical column when on).
TEST(StudyCases, AgreeWithRockingSimCaseByCase) {
  const fs::path dir = synthetic_records("vs_sim");
  const StudyRecords recs = load_study_records(dir.string());
  const std::vector<StudyBody> bodies = grid_bodies(small_grid());
  ASSERT_EQ(bodies.size(), 12u);
  for (const char* method : {"dopri5", "rk4"}) {
    StudyOptions opt;
    opt.trig = BatchTrig::Exact;  // case by case to the bit: the exact path
    opt.threads = 2;
    parse_method(method, opt.settings.method);
    const std::vector<CaseResult> results = run_study(bodies, recs.records, opt);
    ASSERT_EQ(results.size(), 12u * 8u);
    int overturned = 0, rocked_and_stayed = 0, violations = 0;
    const fs::path tmp = dir.parent_path();
    for (const CaseResult& c : results) {
      const Pulse& p = kPulses[c.record];
      Pulse written = p;
      if (!c.vertical) written.vertical_amplitude = -1.0;
      const fs::path file = tmp / ("case_" + std::to_string(c.index) + ".csv");
      write_pulse_csv(file, written, c.polarity);
      const BodyParameters& b = bodies[c.body].parameters;
      char args[512];
      std::snprintf(args, sizeof args,
                    " --record %s --width %.17g --cg-height %.17g --eccentricity %.17g "
                    "--radius-of-gyration %.17g --method %s --fidelity rocking --json",
                    file.c_str(), b.width, b.cg_height, b.nu1, b.radius_of_gyration, method);
      int status = -1;
      const std::string out = run_command(std::string(ROCKING_SIM_EXE) + args, &status);
      ASSERT_EQ(status, 0) << out;
      const auto j = nlohmann::json::parse(out);
      const std::string what = bodies[c.body].name + " " + p.name + " polarity " +
                               std::to_string(c.polarity) + (c.vertical ? " +V" : "") + " " + method;
      EXPECT_EQ(j["overturned"].get<bool>(), c.outcome.overturned) << what;
      EXPECT_EQ(j["committed"].get<bool>(), c.outcome.committed) << what;
      EXPECT_EQ(j["impacts"].get<long>(), c.outcome.impacts) << what;
      EXPECT_DOUBLE_EQ(j["max_rotation_ratio"].get<double>(), c.outcome.max_rotation_ratio) << what;
      EXPECT_EQ(j["record"]["has_vertical"].get<bool>(), c.vertical) << what;
      if (c.outcome.overturned) EXPECT_DOUBLE_EQ(j["overturn_time_s"].get<double>(), c.outcome.overturn_time) << what;
      // Pure-rocking violations (free flight of a falling body): same first onset.
      if (j["violations"].empty()) {
        EXPECT_TRUE(std::isnan(c.first_violation_time)) << what;
        EXPECT_EQ(c.violations, 0) << what;
      } else {
        EXPECT_DOUBLE_EQ(j["violations"][0]["time_s"].get<double>(), c.first_violation_time) << what;
        violations += 1;
      }
      overturned += c.outcome.overturned;
      rocked_and_stayed += !c.outcome.overturned && c.outcome.impacts > 0;
      fs::remove(file);
    }
    // The grid and pulses are chosen so both outcomes occur.
    EXPECT_GT(overturned, 5) << method;
    EXPECT_GT(rocked_and_stayed, 5) << method;
    EXPECT_GT(violations, 0) << method;  // a fast fall lifts the pivot (R_y < 0): compared above
  }
}

TEST(StudyCases, ThresholdsPredictionsAndPsvAreTheCoreFunctions) {
  const StudyRecords recs = load_study_records(synthetic_records("pred").string());
  const StudyBody sb = grid_bodies(small_grid())[7];
  const Body body(sb.parameters);
  const StudyRecord& r = recs.records[0];
  const CaseResult c = run_case(body, r, -1, false, SolverSettings{}, std::nan(""));
  EXPECT_DOUBLE_EQ(c.housner_period, housner_period(body));
  // PSV from the response spectrum module at that period, on the corrected record.
  const ResponseSpectrum sp = response_spectrum(r.corrected, r.dt, {c.housner_period});
  EXPECT_NEAR(c.housner_psv, sp.psv[0], 1e-12 * sp.psv[0]);
  const ScreeningPrediction p =
      screening_prediction(screening_thresholds(body), r.pga, r.pgv, c.housner_psv);
  EXPECT_EQ(c.prediction.housner, p.housner);
  EXPECT_EQ(c.prediction.ishiyama, p.ishiyama);
  EXPECT_EQ(c.prediction.ishiyama_equivalent, p.ishiyama_equivalent);
  EXPECT_EQ(c.prediction.proposed, p.proposed);
}

// A symmetric body is its own mirror image: reversing the record's polarity must give exactly the
// same outcome (with or without the vertical). An eccentric body is not, and must differ somewhere.
TEST(StudyCases, ReversedPolarityMirrorsASymmetricBodyExactly) {
  const StudyRecords recs = load_study_records(synthetic_records("mirror").string());
  const std::vector<StudyBody> bodies = grid_bodies(small_grid());
  StudyOptions opt;
  opt.threads = 2;
  const auto res = run_study(bodies, recs.records, opt);
  std::map<std::tuple<std::size_t, std::size_t, bool>, const CaseResult*> first;
  int eccentric_differs = 0, compared = 0;
  for (const CaseResult& c : res) {
    const auto k = std::make_tuple(c.body, c.record, c.vertical);
    if (c.polarity > 0) {
      first[k] = &c;
      continue;
    }
    const CaseResult& p = *first.at(k);
    if (bodies[c.body].parameters.nu1 == 0.5) {
      ++compared;
      EXPECT_EQ(c.outcome.overturned, p.outcome.overturned);
      EXPECT_EQ(c.outcome.impacts, p.outcome.impacts);
      EXPECT_EQ(c.outcome.max_rotation_ratio, p.outcome.max_rotation_ratio);
      EXPECT_EQ(c.outcome.max_rotation_side, -p.outcome.max_rotation_side);
      EXPECT_TRUE(same_double(c.outcome.overturn_time, p.outcome.overturn_time));
    } else {
      eccentric_differs += c.outcome.overturned != p.outcome.overturned ||
                           c.outcome.max_rotation_ratio != p.outcome.max_rotation_ratio;
    }
  }
  EXPECT_EQ(compared, 6 * 4);
  EXPECT_GT(eccentric_differs, 0);
}

// ------------------------------------------------------------------ determinism

TEST(StudyDeterminism, OneAndTwoThreadsAndShardsGiveIdenticalResults) {
  const StudyRecords recs = load_study_records(synthetic_records("det").string());
  StudyGrid g = small_grid();
  g.widths = 5;
  g.eccentricities = {0.5, 0.4, 0.2};
  const std::vector<StudyBody> bodies = grid_bodies(g);
  StudyOptions one, two;
  one.threads = 1;
  two.threads = 2;
  std::size_t progress_calls = 0, last_done = 0;
  two.progress = [&](std::size_t done, std::size_t total) {
    ++progress_calls;
    EXPECT_LE(done, total);
    EXPECT_GE(done, last_done);
    last_done = done;
  };
  const auto a = run_study(bodies, recs.records, one);
  const auto b = run_study(bodies, recs.records, two);
  ASSERT_EQ(a.size(), 240u);  // 30 bodies x 8 inputs
  ASSERT_EQ(a.size(), b.size());
  EXPECT_GE(progress_calls, 1u);
  EXPECT_EQ(last_done, a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].index, i);
    EXPECT_EQ(b[i].index, i);
    EXPECT_EQ(a[i].outcome.overturned, b[i].outcome.overturned);
    EXPECT_EQ(a[i].outcome.impacts, b[i].outcome.impacts);
    EXPECT_EQ(a[i].outcome.integrator_steps, b[i].outcome.integrator_steps);
    EXPECT_TRUE(same_double(a[i].outcome.max_rotation_ratio, b[i].outcome.max_rotation_ratio));
    EXPECT_TRUE(same_double(a[i].outcome.overturn_time, b[i].outcome.overturn_time));
    EXPECT_TRUE(same_double(a[i].outcome.uplift_time, b[i].outcome.uplift_time));
    EXPECT_TRUE(same_double(a[i].housner_psv, b[i].housner_psv));
  }
  const std::string whole = csv_of(a, bodies, recs.records);
  EXPECT_EQ(whole, csv_of(b, bodies, recs.records));
  // The union of the shards, in shard order, is the whole.
  for (int n : {2, 3, 7, 250}) {  // 250 > 240 cases: some shards are empty
    std::string joined;
    for (int k = 1; k <= n; ++k) {
      StudyOptions s;
      s.threads = 2;
      s.range = shard_range(a.size(), k, n);
      const auto part = run_study(bodies, recs.records, s);
      ASSERT_EQ(part.size(), s.range.size());
      if (!part.empty()) EXPECT_EQ(part.front().index, s.range.begin);
      joined += csv_of(part, bodies, recs.records);
    }
    EXPECT_EQ(joined, whole) << n << " shards";
  }
}

}  // namespace
}  // namespace rocking_monitor::core::study
