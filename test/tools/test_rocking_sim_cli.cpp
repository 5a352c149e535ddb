// The rocking_sim command line: JSON contract, agreement with the library, bad-input messages,
// every PEER .AT2 record in ../shared/records, and the second rocking plane (--depth, --record-y).
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/physics/item_verdict.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "rocking_monitor/monitoring/simulation.hpp"
#include "rocking_monitor/physics/principal_planes.hpp"
#include "test_helpers.hpp"

namespace rocking_monitor::core {
namespace {

namespace fs = std::filesystem;

using CliRun = testing::CommandResult;

CliRun run_sim(const std::string& args) {
  return testing::run_command(std::string(ROCKING_SIM_EXE) + " " + args + " 2>&1");
}

const std::string kPulse = std::string(ROCKING_SOURCE_DIR) + "/bags/one_sine_pulse.csv";

fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() / ("rocking_sim_cli_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

TEST(RockingSimCli, JsonHasTheDocumentedKeysAndMatchesTheLibrary) {
  for (const char* body : {"--width 0.15 --cg-height 0.35", "--width 0.5 --cg-height 0.9 --eccentricity 0.4"}) {
    const CliRun r = run_sim("--record " + kPulse + " " + body + " --fidelity rocking --json");
    ASSERT_EQ(r.status, 0) << r.out;
    const auto j = nlohmann::json::parse(r.out);
    for (const char* key : {"overturned", "committed", "beyond_tipping", "max_rotation_ratio", "impacts",
                            "uplift_time_s", "overturn_time_s", "violations", "method", "model", "steps",
                            "cpu_time_s"})
      EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["method"], "dopri5");
    EXPECT_EQ(j["model"], "nonlinear");
    // Same answer as the library on the same samples.
    const auto comps = read_record(kPulse);
    BodyParameters p;
    p.width = j["body"]["width_m"];
    p.cg_height = j["body"]["cg_height_m"];
    p.nu1 = j["body"]["nu1"];
    const SimulationResult lib = simulate(Body(p), SolverSettings{}, make_ground_motion(comps[0], nullptr, 1.0));
    EXPECT_EQ(j["overturned"].get<bool>(), lib.outcome.overturned);
    EXPECT_EQ(j["impacts"].get<long>(), lib.outcome.impacts);
    EXPECT_DOUBLE_EQ(j["max_rotation_ratio"].get<double>(), lib.outcome.max_rotation_ratio);
    if (lib.outcome.overturned) {
      EXPECT_DOUBLE_EQ(j["overturn_time_s"].get<double>(), lib.outcome.overturn_time);
    } else {
      EXPECT_TRUE(j["overturn_time_s"].is_null());
    }
  }
  // The slender vase falls, the stocky eccentric cabinet survives this pulse.
  EXPECT_TRUE(nlohmann::json::parse(run_sim("--record " + kPulse + " --width 0.15 --cg-height 0.35 --fidelity rocking --json").out)["overturned"].get<bool>());
  EXPECT_FALSE(nlohmann::json::parse(run_sim("--record " + kPulse + " --width 0.5 --cg-height 0.9 --eccentricity 0.4 --fidelity rocking --json").out)["overturned"].get<bool>());
}

TEST(RockingSimCli, HistoryAndOptions) {
  const fs::path d = temp_dir();
  const std::string hist = (d / "h.csv").string();
  const CliRun r = run_sim("--record " + kPulse + " --width 0.2 --cg-height 0.5 --method rk4 --substeps 8 --model linearized --scale 0.5 --fidelity rocking --history " + hist + " --json");
  ASSERT_EQ(r.status, 0) << r.out;
  std::ifstream in(hist);
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("time_s,", 0), 0u);
  int rows = 0;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 1601);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["method"], "rk4");
  EXPECT_EQ(j["model"], "linearized");
  EXPECT_NEAR(j["record"]["pga_mps2"].get<double>(), 2.0, 1e-3);  // scaled by 0.5
}

void expect_error(const std::string& args, const std::string& needle) {
  const CliRun r = run_sim(args);
  EXPECT_NE(r.status, 0) << args;
  EXPECT_NE(r.out.find(needle), std::string::npos) << "expected '" << needle << "' in: " << r.out;
  // One clear line, not a stack of messages.
  EXPECT_LE(std::count(r.out.begin(), r.out.end(), '\n'), 2) << r.out;
}

TEST(RockingSimCli, BadInputGivesOneClearLine) {
  const fs::path d = temp_dir();
  const std::string body = " --width 0.3 --cg-height 0.6";
  expect_error("--record /no/such/file.csv" + body, "/no/such/file.csv");
  {
    std::ofstream(d / "bad_token.csv") << "time_s,accel\n0.00,0.1\n0.01,abc\n0.02,0.3\n";
    expect_error("--record " + (d / "bad_token.csv").string() + body, "bad_token.csv:3");
  }
  {
    std::ofstream(d / "nan.csv") << "0.00 0.1\n0.01 nan\n0.02 0.3\n";
    expect_error("--record " + (d / "nan.csv").string() + body, "nan.csv:2");
  }
  expect_error("--record " + kPulse + body + " --units furlongs", "--units");
  expect_error("--record " + kPulse + " --width -1 --cg-height 0.6", "width = -1");
  expect_error("--record " + kPulse + " --width 0.3 --cg-height nan", "cg_height = nan");
  expect_error("--record " + kPulse + body + " --eccentricity 1.2", "nu1 = 1.2");
  expect_error("--record " + kPulse + body + " --method analytic", "linearized");
  expect_error("--record " + kPulse + body + " --tol 0", "tol = 0");
  expect_error("--record " + kPulse + body + " --restitution 1.4", "restitution = 1.4");
}

TEST(RockingSimCli, RunsOnEveryAt2RecordAndRejectsACorruptedCopy) {
  const fs::path dir = ROCKING_RECORDS_DIR;
  if (!fs::is_directory(dir)) GTEST_SKIP() << "records directory not found: " << dir << " (skipped)";
  int files = 0;
  fs::path first;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file() || e.path().extension() != ".AT2") continue;
    if (first.empty()) first = e.path();
    const CliRun r = run_sim("--record '" + e.path().string() + "' --width 0.3 --cg-height 0.6 --eccentricity 0.4 --json");
    ASSERT_EQ(r.status, 0) << e.path() << ": " << r.out;
    const auto j = nlohmann::json::parse(r.out.substr(r.out.find('{')));  // after any note line
    EXPECT_GT(j["samples"].get<long>(), 100) << e.path();
    ++files;
  }
  EXPECT_GE(files, 190);
  // A copy cut in the middle of its data has fewer values than NPTS.
  const fs::path d = temp_dir();
  std::ifstream in(first);
  std::ofstream out(d / "truncated.AT2");
  std::string line;
  for (int i = 0; i < 40 && std::getline(in, line); ++i) out << line << "\n";
  out.close();
  const CliRun r = run_sim("--record " + (d / "truncated.AT2").string() + " --width 0.3 --cg-height 0.6 --json");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("truncated.AT2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("NPTS"), std::string::npos) << r.out;
}

// ---- Two rocking planes (issue 11) ----

const fs::path kRecords = ROCKING_RECORDS_DIR;
const std::string kRinaldi = (kRecords / "northridge_1994/Rinaldi228.AT2").string();
const std::string kRinaldiUp = (kRecords / "northridge_1994/RinaldiUP.AT2").string();
bool have_rinaldi() { return fs::is_regular_file(kRinaldi) && fs::is_regular_file(kRinaldiUp); }

// The JSON object of a successful run (after any note lines).
nlohmann::json sim_json(const std::string& args) {
  const CliRun r = run_sim(args + " --json");
  EXPECT_EQ(r.status, 0) << args << ": " << r.out;
  const auto brace = r.out.find('{');
  if (r.status != 0 || brace == std::string::npos) return nlohmann::json::object();
  return nlohmann::json::parse(r.out.substr(brace));
}

// A plane's block without what legitimately differs between two runs of the same physics.
nlohmann::json physics_of(nlohmann::json block) {
  for (const char* k : {"cpu_time_s", "record", "planes", "item"}) block.erase(k);
  return block;
}

// A CSV of zeros on the given time grid ('time_s accel' rows, m/s^2).
std::string zeros_csv(const std::string& name, double dt, int samples) {
  const fs::path file = temp_dir() / name;
  std::ofstream out(file);
  out << "time_s,accel_mps2\n";
  for (int i = 0; i < samples; ++i) out << i * dt << ",0\n";
  return file.string();
}

std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

LevelTimes times_of(const nlohmann::json& plane) {
  LevelTimes l;
  const std::pair<Level, const char*> keys[] = {{Level::BeyondTipping, "beyond_tipping_time_s"},
                                                {Level::Committed, "committed_time_s"},
                                                {Level::Overturned, "overturn_time_s"}};
  for (const auto& [level, key] : keys)
    if (!plane[key].is_null()) l.time[static_cast<int>(level)] = plane[key].get<double>();
  return l;
}

// (a) The same record in both planes and the same geometry across them: the y plane is the x plane.
TEST(RockingSimTwoPlanes, SameRecordAndGeometryGiveIdenticalPlanes) {
  std::vector<std::string> cases = {"--record " + kPulse + " --record-y " + kPulse +
                                    " --width 0.15 --depth 0.15 --cg-height 0.35 --eccentricity 0.4"
                                    " --eccentricity-y 0.4 --mu-s 0.6"};
  if (have_rinaldi())
    cases.push_back("--record " + kRinaldi + " --record-y " + kRinaldi + " --vertical " + kRinaldiUp +
                    " --width 0.4 --depth 0.4 --cg-height 0.9 --eccentricity 0.3 --eccentricity-y 0.3"
                    " --radius-of-gyration 0.5 --mu-s 0.5");
  for (const std::string& args : cases) {
    for (const char* fidelity : {"rocking", "contact", "adaptive"}) {
      const auto j = sim_json(args + " --fidelity " + fidelity);
      ASSERT_TRUE(j.contains("planes")) << args;
      ASSERT_TRUE(j["planes"].contains("y")) << args;
      EXPECT_EQ(physics_of(j["planes"]["y"]), physics_of(j["planes"]["x"])) << args << " " << fidelity;
      EXPECT_EQ(j["planes"]["y"]["body"], j["planes"]["x"]["body"]);  // incl. the derived i_y = i_x
      EXPECT_EQ(physics_of(j), physics_of(j["planes"]["x"])) << "top level = x plane";
      EXPECT_EQ(j["item"]["plane_count"], 2);
      // A tie names the x plane.
      for (const char* level : {"beyond_tipping_plane", "committed_plane", "overturn_plane"})
        if (!j["item"][level].is_null()) EXPECT_EQ(j["item"][level], "x") << level;
    }
  }
}

// (b) A y record of zeros: the y plane never uplifts and the x plane is the single-plane run, also
// its history file; a longer --record is cut to the common length with a note.
TEST(RockingSimTwoPlanes, ZeroYRecordLeavesTheXPlaneAsTheSinglePlaneRun) {
  struct Case { std::string x_args; double dt; int samples; };
  std::vector<Case> cases = {{"--record " + kPulse + " --width 0.15 --cg-height 0.35 --mu-s 0.6", 0.005, 1601},
                             {"--record " + kPulse + " --width 0.5 --cg-height 0.9 --eccentricity 0.4", 0.005, 1601}};
  if (have_rinaldi())
    cases.push_back({"--record " + kRinaldi + " --vertical " + kRinaldiUp +
                         " --width 0.4 --cg-height 0.9 --eccentricity 0.3 --mu-s 0.5", 0.01, 1991});
  const fs::path d = temp_dir();
  int n = 0;
  for (const Case& c : cases) {
    const std::string zeros = zeros_csv("zeros_" + std::to_string(n++) + ".csv", c.dt, c.samples);
    for (const char* fidelity : {"rocking", "adaptive"}) {
      const std::string single_hist = (d / "single.csv").string(), two_hist = (d / "two.csv").string();
      const std::string f = std::string(" --fidelity ") + fidelity;
      const auto single = sim_json(c.x_args + f + " --history " + single_hist);
      const auto two = sim_json(c.x_args + f + " --record-y " + zeros + " --depth 0.3 --history " + two_hist);
      EXPECT_EQ(physics_of(two["planes"]["x"]), physics_of(single)) << c.x_args << f;
      EXPECT_EQ(physics_of(two), physics_of(single)) << c.x_args << f;
      EXPECT_EQ(two["record"], single["record"]);
      EXPECT_FALSE(single["planes"].contains("y"));
      EXPECT_EQ(single["item"]["plane_count"], 1);
      const auto& y = two["planes"]["y"];
      EXPECT_TRUE(y["uplift_time_s"].is_null()) << y.dump();
      EXPECT_EQ(y["impacts"], 0);
      EXPECT_EQ(y["max_rotation_ratio"].get<double>(), 0.0);
      EXPECT_FALSE(y["beyond_tipping"].get<bool>());
      EXPECT_EQ(y["record"]["pga_mps2"].get<double>(), 0.0);
      EXPECT_EQ(y["record"]["has_vertical"], single["record"]["has_vertical"]);
      // The x history is the single-plane file (bar nothing); the y plane's goes next to it.
      EXPECT_EQ(read_lines(two_hist), read_lines(single_hist)) << fidelity;
      const auto y_hist = read_lines((d / "two_y.csv").string());
      ASSERT_EQ(y_hist.size(), read_lines(single_hist).size());
      EXPECT_EQ(y_hist.front(), read_lines(single_hist).front());
    }
  }
  // A shorter --record-y: both planes run on its length, the note says what of --record was left.
  const std::string short_zeros = zeros_csv("short_zeros.csv", 0.005, 1000);
  const CliRun r = run_sim("--record " + kPulse + " --record-y " + short_zeros +
                           " --width 0.3 --depth 0.3 --cg-height 0.6 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("rocking_sim: note:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("601 samples of " + kPulse), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(r.out.substr(r.out.find('{')));
  EXPECT_EQ(j["record"]["samples"], 1000);
  EXPECT_EQ(j["planes"]["y"]["record"]["samples"], 1000);
  // --depth alone: the y plane sees only the vertical, said in one note line.
  const CliRun alone = run_sim("--record " + kPulse + " --width 0.3 --depth 0.3 --cg-height 0.6 --json");
  ASSERT_EQ(alone.status, 0) << alone.out;
  EXPECT_NE(alone.out.find("rocking_sim: note: --depth without --record-y"), std::string::npos) << alone.out;
  EXPECT_EQ(nlohmann::json::parse(alone.out.substr(alone.out.find('{')))["planes"]["y"]["impacts"], 0);
}

// (c) The item's verdict is core combine() of the planes' times and names the plane.
TEST(RockingSimTwoPlanes, ItemVerdictIsCombineOfThePlanes) {
  struct Case { std::string args; const char* overturn_plane; };
  // Deep-and-narrow: the narrow y plane falls, the wide x plane does not (and the mirror image).
  std::vector<Case> cases = {
      {"--record " + kPulse + " --record-y " + kPulse + " --width 0.5 --depth 0.15 --cg-height 0.35 --mu-s 0.6", "y"},
      {"--record " + kPulse + " --record-y " + kPulse + " --width 0.15 --depth 0.5 --cg-height 0.35 --mu-s 0.6", "x"}};
  if (have_rinaldi())
    cases.push_back({"--record " + kRinaldi + " --record-y " + kRinaldi + " --width 0.6 --depth 0.2 --cg-height 0.5", "y"});
  for (const Case& c : cases) {
    for (const char* fidelity : {"rocking", "adaptive"}) {
      const auto j = sim_json(c.args + " --fidelity " + fidelity);
      const LevelTimes x = times_of(j["planes"]["x"]), y = times_of(j["planes"]["y"]);
      const ItemVerdict v = combine(x, &y);
      const auto& item = j["item"];
      const std::pair<Level, std::string> levels[] = {{Level::BeyondTipping, "beyond_tipping"},
                                                      {Level::Committed, "committed"},
                                                      {Level::Overturned, "overturn"}};
      for (const auto& [level, name] : levels) {
        const std::string flag = level == Level::Overturned ? "overturned" : name;
        EXPECT_EQ(item[flag].get<bool>(), v.levels.reached(level)) << c.args << " " << name;
        if (v.levels.reached(level)) {
          EXPECT_EQ(item[name + "_time_s"].get<double>(), v.levels.at(level)) << name;
          EXPECT_EQ(item[name + "_plane"], to_string(v.plane[static_cast<int>(level)])) << name;
        } else {
          EXPECT_TRUE(item[name + "_time_s"].is_null()) << name;
          EXPECT_TRUE(item[name + "_plane"].is_null()) << name;
        }
      }
      EXPECT_EQ(item["overturn_plane"], c.overturn_plane) << c.args << " " << fidelity;
      const char* other = std::string(c.overturn_plane) == "x" ? "y" : "x";
      EXPECT_FALSE(j["planes"][other]["overturned"].get<bool>()) << c.args;
      EXPECT_TRUE(j["planes"][c.overturn_plane]["overturned"].get<bool>()) << c.args;
    }
  }
  // Text: every plane line labelled, one item line naming the plane.
  const CliRun t = run_sim(cases[0].args + " --fidelity rocking");
  ASSERT_EQ(t.status, 0) << t.out;
  EXPECT_NE(t.out.find("[x] result      survived"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("[y] result      OVERTURNED"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("item        OVERTURNED"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("(y plane)\n"), std::string::npos) << t.out;
}

// (d) The default fidelity is adaptive; --fidelity rocking is the previous default, the library's
// simulate(); a body without mu_s gets the same alarms from both (adaptive without friction is the
// pure-rocking body, also when it flags a free-flight onset).
TEST(RockingSimCli, DefaultFidelityIsAdaptiveAndRockingIsSimulate) {
  struct Case { std::string record; std::string body; GroundMotion motion; };
  const auto pulse = read_record(kPulse);
  std::vector<Case> cases;
  for (const char* body : {"--width 0.15 --cg-height 0.35", "--width 0.5 --cg-height 0.9 --eccentricity 0.4"})
    cases.push_back({"--record " + kPulse, body, make_ground_motion(pulse[0], nullptr, 1.0)});
  if (have_rinaldi()) {  // a cabinet whose fall the rocking model flags as a free-flight onset
    const auto h = read_record(kRinaldi), v = read_record(kRinaldiUp);
    cases.push_back({"--record " + kRinaldi + " --vertical " + kRinaldiUp,
                     "--width 0.5 --cg-height 0.9 --eccentricity 0.4", make_ground_motion(h[0], &v[0], 1.0)});
  }
  for (const Case& c : cases) {
    const std::string& body = c.body;
    const GroundMotion& motion = c.motion;
    const std::string args = c.record + " " + body;
    const auto plain = sim_json(args);
    const auto adaptive = sim_json(args + " --fidelity adaptive");
    const auto rocking = sim_json(args + " --fidelity rocking");
    EXPECT_EQ(plain["fidelity"], "adaptive") << body;
    EXPECT_EQ(physics_of(plain), physics_of(adaptive)) << body;
    EXPECT_EQ(plain["item"], adaptive["item"]) << body;
    // --fidelity rocking: what the default used to be, the library's simulate() on the same samples.
    BodyParameters p;
    p.width = rocking["body"]["width_m"];
    p.cg_height = rocking["body"]["cg_height_m"];
    p.nu1 = rocking["body"]["nu1"];
    const SimulationResult lib = simulate(Body(p), SolverSettings{}, motion);
    EXPECT_EQ(rocking["fidelity"], "rocking");
    EXPECT_EQ(rocking["overturned"].get<bool>(), lib.outcome.overturned) << body;
    EXPECT_EQ(rocking["impacts"].get<long>(), lib.outcome.impacts) << body;
    EXPECT_EQ(rocking["steps"].get<long>(), lib.outcome.integrator_steps) << body;
    EXPECT_EQ(rocking["max_rotation_ratio"].get<double>(), lib.outcome.max_rotation_ratio) << body;
    EXPECT_EQ(rocking["violations"].size(), lib.violations.size()) << body;
    EXPECT_EQ(plain["model_switches"], 0) << body;
    for (const char* k : {"overturned", "committed", "beyond_tipping", "impacts", "max_rotation_ratio",
                          "uplift_time_s", "beyond_tipping_time_s", "committed_time_s", "overturn_time_s"})
      EXPECT_EQ(plain[k], rocking[k]) << body << " " << k;
  }
}

// (e) Bad second-plane input: status 2 and one line naming the field or the files.
TEST(RockingSimTwoPlanes, BadInputGivesOneClearLine) {
  const std::string base = "--record " + kPulse + " --width 0.3 --cg-height 0.6";
  auto expect_status_2 = [](const std::string& args, const std::vector<std::string>& needles) {
    const CliRun r = run_sim(args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    EXPECT_EQ(r.out.rfind("rocking_sim: error: ", 0), 0u) << r.out;
    for (const std::string& n : needles) EXPECT_NE(r.out.find(n), std::string::npos) << "'" << n << "' in " << r.out;
  };
  expect_status_2(base + " --depth -1", {"depth = -1"});
  expect_status_2(base + " --depth nan", {"depth = nan"});
  expect_status_2(base + " --depth 0.3 --eccentricity-y 1.2", {"eccentricity_y = 1.2"});
  expect_status_2(base + " --depth 0.3 --radius-of-gyration-y -0.1", {"radius_of_gyration_y = -0.1"});
  expect_status_2(base + " --record-y " + kPulse, {"--record-y needs --depth"});
  expect_status_2(base + " --eccentricity-y 0.4", {"--eccentricity-y needs --depth"});
  const std::string coarse = zeros_csv("coarse.csv", 0.01, 800);
  expect_status_2(base + " --depth 0.3 --record-y " + coarse, {kPulse, coarse, "0.005", "0.01"});
}

}  // namespace
}  // namespace rocking_monitor::core

namespace rocking_monitor::core {
namespace {

// The 3-D model in rocking_sim (issue 27): a box under one horizontal along x (the y horizontal zero)
// rocks about its x edges exactly as the x plane (the model's reduction, through the CLI: the same
// decisions, uplift time and peak to 1e-9), the item's verdict is the 3-D run's, and its history
// file is one row per sample with a unit quaternion and, sampled, the JSON's peak tilt.
TEST(RockingSim3D, ABoxUnderOneHorizontalIsItsXPlane) {
  const std::string zeros = zeros_csv("zeros_3d.csv", 0.005, 1601);
  const fs::path d = temp_dir();
  long overturned = 0, rocked = 0;
  for (const std::string body : {"--width 0.15 --cg-height 0.35 --eccentricity 0.45",
                                 "--width 0.3 --cg-height 0.6 --eccentricity 0.4",
                                 "--width 0.5 --cg-height 0.9 --eccentricity 0.4"}) {
    const std::string hist = (d / "box3d.csv").string();
    const std::string args = "--record " + kPulse + " --record-y " + zeros + " " + body +
                             " --depth 0.3 --eccentricity-y 0.35 --fidelity rocking --solid-model 3d";
    const auto j = sim_json(args + " --history-3d " + hist);
    ASSERT_TRUE(j.contains("solid")) << args;
    const auto &s = j["solid"], &x = j["planes"]["x"];
    EXPECT_TRUE(s["in_charge"].get<bool>());
    EXPECT_EQ(s["in_charge_from_s"].get<double>(), 0.0);
    EXPECT_EQ(s["overturned"], x["overturned"]) << body;
    EXPECT_EQ(s["committed"], x["committed"]) << body;
    EXPECT_EQ(s["beyond_tipping"], x["beyond_tipping"]) << body;
    EXPECT_EQ(s["impacts"], x["impacts"]) << body;
    EXPECT_EQ(s["edge_to_vertex"], 0) << body;
    EXPECT_NEAR(s["max_rotation_ratio"].get<double>(), x["max_rotation_ratio"].get<double>(), 1e-9) << body;
    ASSERT_EQ(s["uplift_time_s"].is_null(), x["uplift_time_s"].is_null()) << body;
    if (!x["uplift_time_s"].is_null())
      EXPECT_NEAR(s["uplift_time_s"].get<double>(), x["uplift_time_s"].get<double>(), 1e-9) << body;
    // the item's verdict: the 3-D run's alarms, at the x plane's times
    EXPECT_EQ(j["item"]["model"], "rocking_3d");
    EXPECT_EQ(j["item"]["overturned"], x["overturned"]) << body;
    if (x["overturned"].get<bool>()) {
      EXPECT_NEAR(j["item"]["overturn_time_s"].get<double>(), x["overturn_time_s"].get<double>(), 1e-9);
      EXPECT_EQ(j["item"]["overturn_plane"], "3d");
    }
    overturned += x["overturned"].get<bool>();
    rocked += x["impacts"].get<long>() > 0 && !x["overturned"].get<bool>();
    // the history: header, one row per sample, at rest first, |q| = 1, its peak tilt the JSON's
    const auto rows = read_lines(hist);
    ASSERT_EQ(rows.size(), 1u + s["samples"].get<std::size_t>());
    EXPECT_EQ(rows[0], "time_s,ax_mps2,ay_mps2,az_mps2,model,mode,contact,tilt_rad,rotation_ratio,"
                       "qw,qx,qy,qz,wx_radps,wy_radps,wz_radps,slip_x_m,slip_y_m");
    double peak = 0.0;
    for (std::size_t k = 1; k < rows.size(); ++k) {
      std::vector<std::string> f;
      std::stringstream ss(rows[k]);
      for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
      ASSERT_EQ(f.size(), 18u) << rows[k];
      if (k == 1) EXPECT_EQ(f[5], "REST");
      const double qw = std::stod(f[9]), qx = std::stod(f[10]), qy = std::stod(f[11]), qz = std::stod(f[12]);
      EXPECT_NEAR(qw * qw + qx * qx + qy * qy + qz * qz, 1.0, 1e-9) << rows[k];
      if (f[5] != "OVERTURNED") peak = std::max(peak, std::stod(f[7]));
    }
    // the JSON's peak is found inside samples too (at every integrator step), the history's at their ends
    if (!s["overturned"].get<bool>()) {
      EXPECT_LE(peak, s["max_tilt_rad"].get<double>() + 1e-12);
      EXPECT_GT(peak, 0.99 * s["max_tilt_rad"].get<double>());
    }
  }
  EXPECT_GT(overturned, 0) << "one of the boxes must overturn for the test to cover the alarm";
  EXPECT_GT(rocked, 0) << "one must rock and survive";
}

// A catalogue item with a turned base (a square at 30 deg: oblique) runs the 3-D model under
// --solid-model auto, from the first sample, and the planes only with planar; the errors name the flag.
TEST(RockingSim3D, AnObliqueCatalogueItemRunsIn3DAndErrorsAreClear) {
  const fs::path d = temp_dir();
  const fs::path cat = d / "oblique.yaml";
  {
    std::ofstream out(cat);
    const double c = std::cos(kPi / 6.0) * 0.15, s = std::sin(kPi / 6.0) * 0.15;
    out << "items:\n  - id: turned\n    sensor: floor\n    width: 0.3\n    depth: 0.3\n    cg_height: 0.5\n"
        << "    mass: 40\n    centre_of_mass: [0, 0, 0.5]\n"
        << "    central_inertia: [[4.0, 0, 0], [0, 4.0, 0], [0, 0, 0.6]]\n"
        << "    base_polygon: [[" << c << ", " << s << "], [" << -s << ", " << c << "], [" << -c << ", " << -s
        << "], [" << s << ", " << -c << "]]\n";
  }
  const std::string base = "--record " + kPulse + " --catalogue " + cat.string() + " --item turned";
  const auto j = sim_json(base);
  ASSERT_TRUE(j.contains("solid")) << j.dump();
  EXPECT_TRUE(j["solid"]["in_charge"].get<bool>());
  EXPECT_EQ(j["solid"]["solid_model"], "auto");
  EXPECT_EQ(j["item"]["model"], "rocking_3d");
  EXPECT_EQ(j["solid"]["body"]["vertices"], 4);
  const auto planar = sim_json(base + " --solid-model planar");
  EXPECT_FALSE(planar.contains("solid"));
  EXPECT_EQ(planar["item"]["model"], "planar");
  const CliRun no_depth = run_sim("--record " + kPulse + " --width 0.3 --cg-height 0.5 --solid-model 3d");
  EXPECT_EQ(no_depth.status, 2);
  EXPECT_NE(no_depth.out.find("rocking_sim: error: --solid-model 3d needs --depth"), std::string::npos) << no_depth.out;
  const CliRun no_model = run_sim("--record " + kPulse + " --width 0.3 --cg-height 0.5 --history-3d x.csv");
  EXPECT_EQ(no_model.status, 2);
  EXPECT_NE(no_model.out.find("rocking_sim: error: --history-3d needs the 3-D model"), std::string::npos) << no_model.out;
}

// The docs' urn on its 9 cm pedestal (docs/supports/urn_on_pedestal.yaml, the tool's output) under two
// of the station pairs where the events bound put it down flat at 50e71fa (rocking_sim's forced_rests,
// 1 each): El Centro #6 (a vertex below the floor that rose, taken for a touchdown at each landing) and
// UCLA Grounds, one component along the diagonal (a hop whose top lay before the search's first probe).
TEST(RockingSim3D, TheUrnOnItsPedestalNeverReachesTheEventsBound) {
  const std::string e06 = kRecords.string() + "/imperial_valley_1979/RSN181_IMPVALL.H_H-E06";
  const std::string ucla = kRecords.string() + "/northridge_1994/s05.bbp";
  if (!fs::exists(e06 + "140.AT2") || !fs::exists(ucla)) GTEST_SKIP() << "records absent";
  const std::string urn = "--catalogue " + std::string(ROCKING_SOURCE_DIR) +
                          "/docs/supports/urn_on_pedestal.yaml --item lobby_urn --solid-model 3d";
  for (const std::string& pair : {"--record " + e06 + "140.AT2 --record-y " + e06 + "230.AT2",
                                  "--record " + ucla + " --record-y " + ucla}) {
    const auto j = sim_json(urn + " " + pair);
    ASSERT_TRUE(j.contains("solid")) << j.dump();
    EXPECT_EQ(j["solid"]["forced_rests"], 0) << pair;
    EXPECT_EQ(j["solid"]["forced_overturns"], 0) << pair;
    EXPECT_TRUE(j["solid"]["fell_off_support"].get<bool>()) << pair;  // each falls off its pedestal
  }
}

// Lips (support_lips): the box on its plinth slides off at Rinaldi; with a lip all round the plinth it
// trips over the lip instead and stays on, and rocking_sim says so (JSON counts and the lips line).
TEST(RockingSim3D, ALippedPlinthKeepsTheBoxThatSlidesOffTheOpenOne) {
  const std::string rinaldi318 = (kRecords / "northridge_1994/Rinaldi318.AT2").string();
  if (!fs::exists(kRinaldi) || !fs::exists(rinaldi318)) GTEST_SKIP() << "records absent";
  const std::string plinths = std::string(ROCKING_SOURCE_DIR) + "/docs/supports/plinths.yaml";
  const std::string pair = " --item box_gap10 --solid-model 3d --record " + kRinaldi + " --record-y " + rinaldi318;
  const auto open = sim_json("--catalogue " + plinths + pair);
  ASSERT_TRUE(open.contains("solid")) << open.dump();
  EXPECT_TRUE(open["solid"]["fell_off_support"].get<bool>());
  EXPECT_EQ(open["solid"]["lip_trips"], 0);
  std::ifstream in(plinths);
  std::string yaml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (std::size_t at = yaml.find("  support:"); at != std::string::npos; at = yaml.find("  support:", at + 40))
    yaml.insert(at, "  support_lips: [1, 2, 3, 4]\n");
  const std::string lipped = ::testing::TempDir() + "/plinths_lipped.yaml";
  std::ofstream(lipped) << yaml;
  const auto held = sim_json("--catalogue " + lipped + pair);
  ASSERT_TRUE(held.contains("solid")) << held.dump();
  EXPECT_FALSE(held["solid"]["fell_off_support"].get<bool>());
  EXPECT_FALSE(held["solid"]["overturned"].get<bool>());
  EXPECT_GT(held["solid"]["lip_trips"].get<long>(), 0);
  const CliRun text = run_sim("--catalogue " + lipped + pair);
  EXPECT_NE(text.out.find("lips        "), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("tripped over a lip"), std::string::npos) << text.out;
}

}  // namespace
}  // namespace rocking_monitor::core
