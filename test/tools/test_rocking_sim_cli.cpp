// The rocking_sim command line: JSON contract, agreement with the library, bad-input messages,
// and every PEER .AT2 record in ../shared/records.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "rocking_monitor/motion/record_reader.hpp"
#include "rocking_monitor/monitoring/simulation.hpp"
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
    const CliRun r = run_sim("--record " + kPulse + " " + body + " --json");
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
  EXPECT_TRUE(nlohmann::json::parse(run_sim("--record " + kPulse + " --width 0.15 --cg-height 0.35 --json").out)["overturned"].get<bool>());
  EXPECT_FALSE(nlohmann::json::parse(run_sim("--record " + kPulse + " --width 0.5 --cg-height 0.9 --eccentricity 0.4 --json").out)["overturned"].get<bool>());
}

TEST(RockingSimCli, HistoryAndOptions) {
  const fs::path d = temp_dir();
  const std::string hist = (d / "h.csv").string();
  const CliRun r = run_sim("--record " + kPulse + " --width 0.2 --cg-height 0.5 --method rk4 --substeps 8 --model linearized --scale 0.5 --history " + hist + " --json");
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

}  // namespace
}  // namespace rocking_monitor::core
