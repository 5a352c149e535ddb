// The rocking_study command line: options, identical files for 1 and 2 threads, shards + --merge
// equal to the whole run, error messages and exit status, a reduced run over real records, and the
// figure script on its output.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <map>
#include <regex>
#include <set>

#include "test_helpers.hpp"
#include <sstream>
#include <string>
#include <vector>

#include "temp_root.hpp"

namespace {

namespace fs = std::filesystem;

using CliRun = rocking_monitor::core::testing::CommandResult;

CliRun run(const std::string& cmd) { return rocking_monitor::core::testing::run_command(cmd + " 2>&1"); }

CliRun study(const std::string& args) { return run(std::string(ROCKING_STUDY_EXE) + " " + args); }

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

// Scratch files of this binary, removed when it ends.
const rocking_monitor::core::testing::TempRoot& kTemp = rocking_monitor::core::testing::TempRoot::registered("rocking_study_cli_");
const fs::path& root() { return kTemp.path(); }

// Three one-sine pulses (one with a vertical column) and a YAML body list.
fs::path fixture() {
  const fs::path dir = root() / "fixture";
  if (fs::exists(dir / "bodies.yaml")) return dir;
  fs::create_directories(dir / "records" / "pulses");
  struct P {
    const char* name;
    double a, f, av;
  };
  for (const P& p : {P{"strong", 4.0, 0.8, -1}, P{"mid", 2.5, 1.5, -1}, P{"vert", 3.5, 1.0, 3.0}}) {
    std::ofstream out(dir / "records" / "pulses" / (std::string(p.name) + ".csv"));
    const double w = 2 * 3.14159265358979323846 * p.f;
    for (int i = 0; i <= 800; ++i) {
      const double t = 0.01 * i;
      const double on = t <= 1.0 / p.f ? 1.0 : 0.0;
      char line[128];
      if (p.av >= 0)
        std::snprintf(line, sizeof line, "%.2f,%.17g,%.17g\n", t, on * p.a * std::sin(w * t),
                      on * p.av * std::sin(2 * w * t));
      else
        std::snprintf(line, sizeof line, "%.2f,%.17g\n", t, on * p.a * std::sin(w * t));
      out << line;
    }
  }
  std::ofstream(dir / "bodies.yaml") << "bodies:\n"
                                        "  - {name: vase, width: 0.12, cg_height: 0.35, nu1: [0.5, 0.3]}\n"
                                        "  - {name: cabinet, width: 0.45, cg_height: 0.9, nu1: [0.5, 0.4, 0.2]}\n"
                                        "  - {name: rack, width: 0.6, cg_height: 1.0}\n"
                                        "  - {name: cart, width: 0.3, cg_height: 0.5, nu1: 0.35,"
                                        " radius_of_gyration: 0.25}\n";
  return dir;
}

TEST(StudyCli, HelpListsTheOptions) {
  const CliRun r = study("--help");
  ASSERT_EQ(r.status, 0) << r.out;
  for (const char* opt : {"--records", "--bodies", "--method", "--tol", "--substeps", "--model", "--threads",
                          "--shard", "--out", "--merge", "--heights", "--widths", "--eccentricities", "--only",
                          "--no-vertical", "--quiet", "--azimuth"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
}

TEST(StudyCli, ThreadCountShardsAndMergeGiveIdenticalFiles) {
  const fs::path dir = fixture();
  const std::string common = "--records " + (dir / "records").string() + " --bodies " +
                             (dir / "bodies.yaml").string() + " --quiet";
  const fs::path one = root() / "one", two = root() / "two";
  CliRun r = study(common + " --threads 1 --out " + one.string());
  ASSERT_EQ(r.status, 0) << r.out;
  r = study(common + " --threads 2 --out " + two.string());
  ASSERT_EQ(r.status, 0) << r.out;
  const std::string whole = slurp(one / "cases.csv");
  EXPECT_EQ(whole, slurp(two / "cases.csv"));
  // 7 bodies x (2 + 2 + 4) inputs, plus the header.
  EXPECT_EQ(std::count(whole.begin(), whole.end(), '\n'), 1 + 7 * 8);
  EXPECT_EQ(slurp(one / "bodies.csv"), slurp(two / "bodies.csv"));
  EXPECT_EQ(slurp(one / "records.csv"), slurp(two / "records.csv"));

  std::string merge_args;
  std::string concatenated;
  for (int k = 1; k <= 3; ++k) {
    const fs::path out = root() / ("shard" + std::to_string(k));
    r = study(common + " --threads 2 --shard " + std::to_string(k) + "/3 --out " + out.string());
    ASSERT_EQ(r.status, 0) << r.out;
    const std::string part = slurp(out / "cases.csv");
    concatenated += part.substr(part.find('\n') + 1);  // without the header
    merge_args += " " + (out / "cases.csv").string();
  }
  EXPECT_EQ(whole.substr(whole.find('\n') + 1), concatenated);
  const fs::path merged = root() / "merged";
  r = study("--merge" + merge_args + " --out " + merged.string());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(slurp(merged / "cases.csv"), whole);
  const auto a = nlohmann::json::parse(slurp(one / "summary.json"));
  const auto b = nlohmann::json::parse(slurp(merged / "summary.json"));
  EXPECT_EQ(a["sets"], b["sets"]);
  EXPECT_EQ(a["vertical_effect"], b["vertical_effect"]);
  EXPECT_EQ(a["headline"], b["headline"]);
  EXPECT_EQ(a["cases"].get<long>(), 56);

  // A missing shard is an error naming the first missing case.
  r = study("--merge " + (root() / "shard1" / "cases.csv").string() + " " +
            (root() / "shard3" / "cases.csv").string() + " --out " + (root() / "bad_merge").string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("is missing"), std::string::npos) << r.out;
}

TEST(StudyCli, FragilityWritesRunsAndFitsAndRefusesBadOptions) {
  const fs::path dir = fixture(), out = root() / "fragility";
  const std::string common = "--records " + (dir / "records").string() + " --bodies " +
                             (dir / "bodies.yaml").string() + " --quiet --fragility --levels 5 --bootstrap 20";
  const CliRun r = study(common + " --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.out;
  // 7 bodies (the nu1 lists expand) x 3 pulses x 5 levels x 2 polarities, plus the header.
  const std::string runs = slurp(out / "fragility_runs.csv");
  EXPECT_EQ(std::count(runs.begin(), runs.end(), '\n'), 1 + 7 * 3 * 5 * 2);
  const nlohmann::json j = nlohmann::json::parse(slurp(out / "fragility.json"));
  EXPECT_EQ(j.at("intensity_measure"), "pgv");
  ASSERT_EQ(j.at("bodies").size(), 7u);
  for (const auto& b : j.at("bodies")) {
    EXPECT_EQ(b.at("runs"), 30);
    if (b.at("fitted").get<bool>()) EXPECT_GT(b.at("median").get<double>(), 0.0);
    else EXPECT_FALSE(b.at("note").get<std::string>().empty());
  }
  for (const char* bad : {"--im sa", "--pgv-range 2,0.02", "--pgv-range 0.1", "--levels 1"}) {
    const CliRun e = study(common + " --out " + (root() / "bad").string() + " " + bad);
    EXPECT_EQ(e.status, 2) << bad << ": " << e.out;
    EXPECT_NE(e.out.find("rocking_study: error"), std::string::npos) << e.out;
  }
}

TEST(StudyCli, FragilityRunsTheMembersOfUncertainCatalogueItems) {
  // A catalogue item with distributions runs its members (as the live node draws them); one with a
  // zero-spread law gives exactly the exact item's outcomes in every member.
  const fs::path dir = fixture(), out = root() / "fragility_members";
  const fs::path cat = root() / "uncertain.yaml";
  std::ofstream(cat) << "sensors: [{name: floor, topic: /imu}]\n"
                        "items:\n"
                        "  - {id: exact, sensor: floor, width: 0.25, cg_height: 0.5}\n"
                        "  - {id: zero_spread, sensor: floor, width: {uniform: [0.25, 0.25]}, cg_height: 0.5, ensemble_size: 3}\n"
                        "  - {id: uncertain, sensor: floor, width: {uniform: [0.2, 0.3]}, cg_height: {normal: [0.5, 0.05]}}\n";
  const CliRun r = study("--records " + (dir / "records").string() + " --bodies " + cat.string() +
                         " --quiet --fragility --levels 5 --bootstrap 20 --members 4 --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(slurp(out / "fragility.json"));
  ASSERT_EQ(j.at("bodies").size(), 3u);
  EXPECT_EQ(j["bodies"][0]["members"], 0);
  EXPECT_EQ(j["bodies"][1]["members"], 3);  // the item's own ensemble_size
  EXPECT_EQ(j["bodies"][2]["members"], 4);  // --members
  EXPECT_EQ(j["bodies"][2]["runs"], 4 * 3 * 5 * 2);
  // body,member,record_file,...,polarity,scale,im,overturned,beyond_tipping
  std::map<std::string, std::vector<std::string>> outcomes;  // body/member -> overturned per run
  std::istringstream runs(slurp(out / "fragility_runs.csv"));
  std::string line;
  std::getline(runs, line);
  EXPECT_EQ(line.rfind("body,member,", 0), 0u) << line;
  while (std::getline(runs, line)) {
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string c; std::getline(ls, c, ',');) f.push_back(c);
    ASSERT_EQ(f.size(), 11u) << line;
    outcomes[f[0] + "/" + f[1]].push_back(f[9]);
  }
  ASSERT_EQ(outcomes.size(), 1u + 3u + 4u);
  const auto& exact = outcomes.at("exact/");
  for (const char* m : {"zero_spread/0", "zero_spread/1", "zero_spread/2"}) EXPECT_EQ(outcomes.at(m), exact) << m;
}

TEST(StudyCli, BadInputExitsWithStatus2AndOneLineNamingTheProblem) {
  const fs::path dir = fixture();
  const fs::path bad = root() / "bad.yaml";
  std::ofstream(bad) << "bodies:\n  - {name: shelf, width: 0.4, cg_height: -2}\n";
  const std::string rec = " --records " + (dir / "records").string() + " --quiet --out " + (root() / "bad").string();
  struct Case {
    std::string args;
    std::vector<std::string> expect;
  };
  const std::vector<Case> cases{
      {"--bodies " + bad.string() + rec, {bad.string(), "bodies[0] (shelf)", "cg_height", "-2"}},
      {"--records " + (root() / "nowhere").string(), {"nowhere", "not a directory"}},
      {"--shard 3/2" + rec, {"invalid shard"}},
      {"--method analytic" + rec, {"analytic", "linearized"}},
      {"--eccentricities 0.5,x" + rec, {"--eccentricities", "'x'"}},
  };
  for (const auto& c : cases) {
    const CliRun r = study(c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.out;
    EXPECT_NE(r.out.find("rocking_study: error: "), std::string::npos) << r.out;
    for (const auto& s : c.expect) EXPECT_NE(r.out.find(s), std::string::npos) << r.out << " lacks " << s;
  }
}

// A reduced version of the documented full study: two stations of ../shared/records (one with a
// vertical) on a 2 x 3 grid, then the figure script on the result.
TEST(StudyCli, ReducedRunOverRealRecordsAndFigures) {
  const fs::path records(ROCKING_RECORDS_DIR);
  if (!fs::exists(records / "MANIFEST.csv")) GTEST_SKIP() << "no records at " << records;
  const fs::path out = root() / "real";
  const CliRun r = study("--records " + records.string() +
                      " --only Rinaldi --only CHY028 --heights 2 --widths 3 --eccentricities 0.5,0.3 "
                      "--method rk4 --quiet --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("Ishiyama's criterion satisfied in"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(slurp(out / "summary.json"));
  // 12 bodies x (Rinaldi 228/318 with UP: 2 x 2 x 2, CHY028 N/E: 2 x 2) = 12 x 12.
  EXPECT_EQ(j["cases"].get<long>(), 144);
  EXPECT_EQ(j["records"].get<long>(), 4);
  EXPECT_EQ(j["records_with_vertical"].get<long>(), 2);
  EXPECT_EQ(j["run"]["method"], "rk4");
  EXPECT_TRUE(j["run"]["from_manifest"].get<bool>());

  const CliRun probe = run(std::string(ROCKING_PYTHON) + " -c 'import matplotlib'");
  if (probe.status != 0) GTEST_SKIP() << "python3-matplotlib not installed: figures not checked";
  const fs::path figs = root() / "figures";
  const CliRun p = run(std::string(ROCKING_PYTHON) + " " + ROCKING_SOURCE_DIR + "/scripts/plot_study.py " +
                    out.string() + " --out " + figs.string());
  ASSERT_EQ(p.status, 0) << p.out;
  for (const char* f : {"figure4_nu0.50", "figure5_nu0.30", "figure7_overturned_percent", "figure8_ratio"}) {
    for (const char* ext : {".png", ".svg"}) {
      const fs::path file = figs / (std::string(f) + ext);
      ASSERT_TRUE(fs::exists(file)) << file;
      EXPECT_GT(fs::file_size(file), 10000u) << file;
    }
  }
  const CliRun pv = run(std::string(ROCKING_PYTHON) + " " + ROCKING_SOURCE_DIR + "/scripts/plot_study.py " +
                     out.string() + " --vertical --formats png --out " + (root() / "figures_v").string());
  EXPECT_EQ(pv.status, 0) << pv.out;
}

// Lines of a text file, without the trailing newline.
long line_count(const std::string& text) { return static_cast<long>(std::count(text.begin(), text.end(), '\n')); }

// Stations of `event` in ../shared/records/MANIFEST.csv with exactly two horizontals (an independent
// count of the station pairs: a plain split is enough for the rows of this event).
long manifest_pairs(const fs::path& records, const std::string& event) {
  std::ifstream in(records / "MANIFEST.csv");
  std::string line;
  std::map<std::string, int> horizontals;
  while (std::getline(in, line)) {
    if (line.rfind(event + ",", 0) != 0) continue;
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string field;
    while (std::getline(ss, field, ',')) f.push_back(field);
    if (f.size() > 3 && f[3].rfind("H:", 0) == 0) ++horizontals[f[2]];
  }
  long pairs = 0;
  for (const auto& h : horizontals) pairs += h.second == 2;
  return pairs;
}

// Entries with a depth in a catalogue file (comments stripped): the two-plane items it holds.
long depth_entries(const fs::path& yaml) {
  std::ifstream in(yaml);
  std::string line;
  long n = 0;
  const std::regex key(R"((^|[\s{,])depth\s*:)");
  while (std::getline(in, line)) {
    const std::string code = line.substr(0, line.find('#'));
    n += static_cast<long>(std::distance(std::sregex_iterator(code.begin(), code.end(), key), std::sregex_iterator()));
  }
  return n;
}

// Two-plane items on the station pairs of a small real event: the repository's own catalogue as is
// (its items with a depth, if any, give the rows), then our own items with repeated --azimuth.
TEST(StudyCli, TwoPlaneItemsRunOnStationPairsRotatedToAzimuths) {
  const fs::path records(ROCKING_RECORDS_DIR);
  if (!fs::exists(records / "MANIFEST.csv")) GTEST_SKIP() << "no records at " << records;
  const std::string event = "north_palm_springs_1986";
  const long pairs = manifest_pairs(records, event);
  ASSERT_EQ(pairs, 2);  // Anza - Red Mountain and Indio (see the records README)
  const fs::path catalogue = fs::path(ROCKING_SOURCE_DIR) / "config" / "catalogue_example.yaml";
  const fs::path out = root() / "catalogue";
  CliRun r = study("--records " + records.string() + " --bodies " + catalogue.string() + " --only " + event +
                   " --azimuth 0,90 --quiet --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(line_count(slurp(out / "item_cases.csv")), 1 + depth_entries(catalogue) * pairs * 2 * 2) << r.out;

  const fs::path yaml = root() / "two_plane.yaml";
  std::ofstream(yaml) << "sensors:\n  - {name: g, topic: /g/imu}\n"
                         "items:\n"
                         "  - {id: cabinet, sensor: g, width: 0.3, depth: 0.5, cg_height: 0.9, eccentricity: 0.4,\n"
                         "     pose: {parent_frame: a, x: 1}, description: \"a cabinet\"}\n"
                         "  - {id: vase, shape: cylinder, width: 0.1, depth: 0.1, cg_height: 0.35}\n"
                         "  - {id: cart, width: 0.5, cg_height: 0.7}\n";
  const fs::path mine = root() / "two_plane";
  r = study("--records " + records.string() + " --bodies " + yaml.string() + " --only " + event +
            " --azimuth 0 --azimuth 45,90 --quiet --out " + mine.string());
  ASSERT_EQ(r.status, 0) << r.out;
  const std::string table = slurp(mine / "item_cases.csv");
  EXPECT_EQ(line_count(table), 1 + 2 * pairs * 3 * 2);
  EXPECT_EQ(line_count(slurp(mine / "cases.csv")), 1 + 1 * 2 * pairs * 2);  // the cart: 4 components x 2
  EXPECT_NE(table.find(",vase,"), std::string::npos);
  EXPECT_EQ(table.find(",cart,"), std::string::npos);
  const auto j = nlohmann::json::parse(slurp(mine / "summary.json"));
  EXPECT_EQ(j["two_plane_items"]["all"]["cases"].get<long>(), 2 * pairs * 3 * 2);
  EXPECT_EQ(j["two_plane_items"]["station_pairs"].get<long>(), pairs);
  EXPECT_EQ(j["two_plane_items"]["azimuths_deg"], nlohmann::json({0.0, 45.0, 90.0}));
  EXPECT_EQ(j["two_plane_items"]["pairs_zero_padded"].get<long>(), 2);  // both pairs differ in length
  EXPECT_NE(j["run"]["rocking_model"].get<std::string>().find("pure rocking"), std::string::npos);
  EXPECT_NE(r.out.find("zero-padded"), std::string::npos) << r.out;  // noted, not silent

  // Errors: a bad azimuth, sharding items, a bad item field.
  const fs::path bad = root() / "bad_items.yaml";
  std::ofstream(bad) << "items:\n  - {id: shelf, width: 0.4, depth: -1, cg_height: 1}\n";
  const std::string rec = " --records " + records.string() + " --only " + event + " --quiet --out " +
                          (root() / "bad_items").string();
  const std::vector<std::pair<std::string, std::vector<std::string>>> errors{
      {"--bodies " + yaml.string() + " --azimuth 0,north" + rec, {"--azimuth", "'north'"}},
      {"--bodies " + yaml.string() + " --shard 1/2" + rec, {yaml.string(), "--shard"}},
      {"--bodies " + bad.string() + rec, {bad.string(), "items[0] 'shelf'", "depth", "-1"}},
  };
  for (const auto& e : errors) {
    const CliRun b = study(e.first);
    EXPECT_EQ(b.status, 2) << e.first << "\n" << b.out;
    EXPECT_NE(b.out.find("rocking_study: error: "), std::string::npos) << b.out;
    for (const auto& s : e.second) EXPECT_NE(b.out.find(s), std::string::npos) << b.out << " lacks " << s;
  }
}

}  // namespace
