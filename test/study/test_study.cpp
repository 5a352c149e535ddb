// The study (issue 5): grid, record pairing, agreement with rocking_sim case by case, determinism
// across thread counts and shards, the summary against an independent count of cases.csv, the YAML
// body file and its error messages, and the real records of ../shared/records.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/motion/response_spectrum.hpp"
#include "rocking_monitor/study/study.hpp"
#include "rocking_monitor/study/study_io.hpp"

#include "temp_root.hpp"

namespace rocking_monitor::core::study {
namespace {

namespace fs = std::filesystem;

// Scratch files of this binary, removed when it ends.
const rocking_monitor::core::testing::TempRoot& kTemp = rocking_monitor::core::testing::TempRoot::registered("rocking_study_test_");
const fs::path& temp_root() { return kTemp.path(); }

fs::path temp_dir(const std::string& tag) {
  const fs::path d = temp_root() / tag;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string run_command(const std::string& cmd, int* status) {
  std::string out;
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return out;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), pipe) != nullptr) out += buf.data();
  const int st = pclose(pipe);
  *status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return out;
}

// Quote-aware CSV split, written independently of the library's.
std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> f(1);
  bool q = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (q) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        f.back() += '"';
        ++i;
      } else if (c == '"') {
        q = false;
      } else {
        f.back() += c;
      }
    } else if (c == '"') {
      q = true;
    } else if (c == ',') {
      f.emplace_back();
    } else {
      f.back() += c;
    }
  }
  return f;
}

// Synthetic records: one-sine pulses (the Zhang & Makris family) in m/s^2, written as CSV.
struct Pulse {
  std::string name;
  double amplitude, omega, vertical_amplitude;  // vertical_amplitude < 0: no vertical column
};

void write_pulse_csv(const fs::path& path, const Pulse& p, double polarity, double dt = 0.01,
                     double t_end = 8.0) {
  std::ofstream out(path);
  out << (p.vertical_amplitude >= 0 ? "time_s,accel_h,accel_v\n" : "time_s,accel\n");
  const auto n = static_cast<std::size_t>(std::llround(t_end / dt)) + 1;
  const double tp = 2.0 * kPi / p.omega;
  char line[160];
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    const double a = t <= tp ? p.amplitude * std::sin(p.omega * t) : 0.0;
    // The vertical: a pulse at twice the frequency (starts upward), present during the horizontal one.
    const double v = t <= tp ? p.vertical_amplitude * std::sin(2.0 * p.omega * t) : 0.0;
    if (p.vertical_amplitude >= 0)
      std::snprintf(line, sizeof line, "%.6f,%.17g,%.17g\n", t, polarity * a, v);
    else
      std::snprintf(line, sizeof line, "%.6f,%.17g\n", t, polarity * a);
    out << line;
  }
}

const std::vector<Pulse> kPulses{
    {"p1_strong", 4.0, 2.0 * kPi * 0.8, -1.0},   // 4 m/s^2 at 0.8 Hz
    {"p2_mid", 2.5, 2.0 * kPi * 1.5, -1.0},      // 2.5 m/s^2 at 1.5 Hz
    {"p3_vert", 3.5, 2.0 * kPi * 1.0, 3.0},      // with a vertical component
};

fs::path synthetic_records(const std::string& tag) {
  const fs::path dir = temp_dir(tag) / "records";
  fs::create_directories(dir / "synthetic");
  for (const auto& p : kPulses) write_pulse_csv(dir / "synthetic" / (p.name + ".csv"), p, 1.0);
  std::ofstream(dir / "README.md") << "not a record\n";
  return dir;
}

StudyGrid small_grid() {
  StudyGrid g;
  g.heights = 2;
  g.widths = 3;
  g.eccentricities = {0.5, 0.3};
  return g;
}

bool same_double(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

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

std::string csv_of(const std::vector<CaseResult>& r, const std::vector<StudyBody>& b,
                   const std::vector<StudyRecord>& rec) {
  std::ostringstream os;
  write_case_csv_rows(os, r, b, rec);
  return os.str();
}

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

// ------------------------------------------------------------------ YAML bodies

fs::path write_yaml(const std::string& tag, const std::string& text) {
  const fs::path p = temp_dir("yaml_" + tag) / "bodies.yaml";
  std::ofstream(p) << text;
  return p;
}

TEST(StudyBodiesYaml, ReadsBodiesAndExpandsEccentricityLists) {
  const fs::path p = write_yaml("ok",
                                "bodies:\n"
                                "  - name: cabinet\n"
                                "    width: 0.6\n"
                                "    cg_height: 0.9\n"
                                "    nu1: [0.5, 0.3]\n"
                                "  - width: 0.2\n"
                                "    cg_height: 0.5\n"
                                "    radius_of_gyration: 0.3\n"
                                "    restitution: 0.9\n"
                                "    mu_s: 0.6\n");
  const auto b = load_bodies_yaml(p.string());
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[0].name, "cabinet_nu0.5");
  EXPECT_EQ(b[1].name, "cabinet_nu0.3");
  EXPECT_DOUBLE_EQ(b[1].parameters.nu1, 0.3);
  EXPECT_DOUBLE_EQ(b[0].parameters.radius_of_gyration, b[1].parameters.radius_of_gyration);
  EXPECT_DOUBLE_EQ(b[0].parameters.radius_of_gyration, Body::homogeneous_radius_of_gyration(0.6, 0.9));
  EXPECT_EQ(b[2].name, "body1");
  EXPECT_DOUBLE_EQ(b[2].parameters.radius_of_gyration, 0.3);
  EXPECT_DOUBLE_EQ(b[2].parameters.restitution, 0.9);
  EXPECT_DOUBLE_EQ(b[2].parameters.mu_s, 0.6);
  EXPECT_DOUBLE_EQ(b[2].parameters.nu1, 0.5);
}

TEST(StudyBodiesYaml, ErrorsNameTheFileItemAndField) {
  struct Bad {
    const char* text;
    std::vector<std::string> expect;  // substrings of the message
  };
  const std::vector<Bad> cases{
      {"bodies:\n  - {name: a, width: 0.5, cg_height: 1}\n  - {name: vase, width: -1, cg_height: 1}\n",
       {"bodies[1] (vase)", "width", "-1"}},
      {"bodies:\n  - {name: a, width: 0.5}\n", {"bodies[0] (a)", "cg_height", "missing"}},
      {"bodies:\n  - {name: a, width: 0.5, cg_height: 1, hieght: 2}\n", {"bodies[0] (a)", "hieght", "unknown field"}},
      {"bodies:\n  - {name: a, width: wide, cg_height: 1}\n", {"bodies[0] (a)", "width", "'wide'"}},
      {"bodies:\n  - {name: a, width: 0.5, cg_height: 1, nu1: [0.5, 1.5]}\n", {"bodies[0] (a)", "nu1", "1.5"}},
      {"bodies:\n  - {name: a, width: 0.5, cg_height: 1}\n  - {name: a, width: 0.4, cg_height: 1}\n",
       {"bodies[1] (a)", "used twice"}},
      {"bodies:\n  - name: a\n   width: [\n", {"bodies.yaml:"}},
      {"things: []\n", {"unknown top-level key 'things'"}},
      {"items: []\n", {"non-empty list"}},
      {"bodies: []\n", {"non-empty list"}},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const fs::path p = write_yaml("bad" + std::to_string(i), cases[i].text);
    try {
      load_bodies_yaml(p.string());
      ADD_FAILURE() << "no error for: " << cases[i].text;
    } catch (const StudyError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
      for (const auto& s : cases[i].expect) EXPECT_NE(msg.find(s), std::string::npos) << msg << " lacks " << s;
    }
  }
  EXPECT_THROW(load_bodies_yaml("/nonexistent/bodies.yaml"), StudyError);
}

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
