// Seeded mutation fuzzer (issue 19 part 4) for every record reader (read_record: AT2, BBP, SMC,
// CSV, miniSEED, COSMOS V2, K-NET), the catalogue parser (load_catalogue_file,
// load_catalogue_items_file) and the network parsers (issue 54, network_parsers.hpp: parse_datagram,
// the SeedLink packet header and replies, one miniSEED record through the bridge's decoder). Each input must either parse into finite SI values or throw the
// project's error type (RecordError / CatalogueError) whose message starts with "<file>:"; anything
// else (another exception, a non-finite value, a crash, a sanitizer report, an input taking longer
// than --timeout seconds) is a failure. Run by scripts/run_sanitizers.sh; docs/sanitizers.md.
//
//   fuzz_parsers --records DIR --config DIR [--inputs 10000] [--seconds 60] [--timeout 10]
//                [--seed 1] [--only NAME] [--work DIR] [--replay NAME:INDEX]
//
// Prints one line per parser: inputs, how many parsed, how many were rejected with a file-named
// error, how many failed (kept as <work>/failed_*). Exit status 0 only without any failure.

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "mutator.hpp"
#include "network_parsers.hpp"
#include "rocking_monitor/monitoring/catalogue_file.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "seed_records.hpp"

namespace fs = std::filesystem;
namespace rm = rocking_monitor::core;
namespace fz = rocking_monitor::fuzz;

namespace {

// What the alarm handler prints: the input being parsed (async-signal-safe: preformatted).
char g_current[512] = "";
bool g_rejected = false;  // the last check() ended in the project's error type

void on_timeout(int) {
  const char msg[] = "fuzz_parsers: TIMEOUT (hang) on ";
  (void)!write(2, msg, sizeof msg - 1);
  (void)!write(2, g_current, std::strlen(g_current));
  (void)!write(2, "\n", 1);
  _exit(3);
}

std::string arg(int argc, char** argv, const std::string& name, const std::string& fallback) {
  for (int i = 1; i + 1 < argc; ++i)
    if (name == argv[i]) return argv[i + 1];
  return fallback;
}

/// "" when the outcome is acceptable, else what is wrong.
std::string check(const fz::Target& target, const std::string& path) {
  if (fz::is_network_target(target.name)) {
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return fz::check_network(target.name, bytes, g_rejected);
  }
  const bool catalogue = target.name.rfind("catalogue", 0) == 0;
  g_rejected = true;
  try {
    if (target.name == "catalogue") {
      rm::load_catalogue_file(path);
    } else if (target.name == "catalogue_items") {
      rm::load_catalogue_items_file(path);
    } else {
      rm::ReadOptions o;
      if (target.name == "miniseed") o.gain_counts_per_mps2 = fz::miniseed_gain();
      for (const rm::Component& c : rm::read_record(path, o)) {
        if (!(std::isfinite(c.dt) && c.dt > 0.0 && std::isfinite(c.t0)))
          return "parsed with dt " + std::to_string(c.dt) + " t0 " + std::to_string(c.t0);
        if (c.accel.empty()) return "parsed with no samples";
        for (std::size_t i = 0; i < c.accel.size(); ++i)
          if (!std::isfinite(c.accel[i])) return "parsed with a non-finite sample " + std::to_string(i);
      }
    }
    g_rejected = false;
    return "";
  } catch (const rm::RecordError& e) {
    if (catalogue) return std::string("RecordError from the catalogue parser: ") + e.what();
    if (std::string(e.what()).rfind(path + ":", 0) != 0) return std::string("error without file: ") + e.what();
    return "";
  } catch (const rm::CatalogueError& e) {
    if (!catalogue) return std::string("CatalogueError from a record reader: ") + e.what();
    if (std::string(e.what()).rfind(path + ":", 0) != 0) return std::string("error without file: ") + e.what();
    return "";
  } catch (const std::exception& e) {
    return std::string("unexpected exception: ") + e.what();
  } catch (...) {
    return "unexpected non-std exception";
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string records = arg(argc, argv, "--records", "");
  const std::string config = arg(argc, argv, "--config", "");
  const long inputs = std::stol(arg(argc, argv, "--inputs", "10000"));
  const double seconds = std::stod(arg(argc, argv, "--seconds", "60"));
  const unsigned timeout = static_cast<unsigned>(std::stoul(arg(argc, argv, "--timeout", "10")));
  const unsigned long long seed = std::stoull(arg(argc, argv, "--seed", "1"));
  const std::string only = arg(argc, argv, "--only", "");
  const std::string replay = arg(argc, argv, "--replay", "");
  const fs::path work = arg(argc, argv, "--work", (fs::temp_directory_path() / ("fuzz_parsers_" + std::to_string(getpid()))).string());
  if (records.empty() || config.empty()) {
    std::fprintf(stderr, "usage: fuzz_parsers --records DIR --config DIR [--inputs N] [--seconds S] [--timeout S] "
                         "[--seed N] [--only NAME] [--work DIR] [--replay NAME:INDEX]\n");
    return 2;
  }
  std::vector<fz::Target> targets;
  try {
    targets = fz::make_targets(records, config);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_parsers: %s\n", e.what());
    return 2;
  }
  fs::create_directories(work);
  signal(SIGALRM, on_timeout);

  int failures = 0;
  for (const fz::Target& t : targets) {
    if (!only.empty() && t.name != only) continue;
    long first = 0, last = inputs;
    if (!replay.empty()) {
      if (replay.substr(0, replay.find(':')) != t.name) continue;
      first = std::stol(replay.substr(replay.find(':') + 1));
      last = first + 1;
    }
    // Every unmutated seed must parse: a seed the parser rejects would fuzz only its error paths.
    for (const fz::Seed& s : t.seeds) {
      const std::string path = (work / ("seed_" + s.file_name)).string();
      std::ofstream(path, std::ios::binary | std::ios::trunc) << s.bytes;
      const std::string problem = check(t, path);
      if (!problem.empty() || g_rejected) {
        std::string why = problem;
        try {
          if (t.name.rfind("catalogue", 0) != 0 && !fz::is_network_target(t.name)) rm::read_record(path);
        } catch (const std::exception& e) {
          why += e.what();
        }
        std::fprintf(stderr, "FAIL %s: seed %s does not parse: %s\n", t.name.c_str(), s.file_name.c_str(), why.c_str());
        ++failures;
      }
    }
    const auto start = std::chrono::steady_clock::now();
    long done = 0, parsed = 0, rejected = 0, failed = 0;
    for (long i = first; i < last; ++i) {
      if (replay.empty() && std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > seconds) break;
      // The input is a function of (seed, target, index) only: --replay NAME:INDEX rebuilds it.
      std::seed_seq sq{static_cast<unsigned long long>(seed), static_cast<unsigned long long>(i),
                       static_cast<unsigned long long>(std::hash<std::string>{}(t.name))};
      std::mt19937_64 rng(sq);
      const fz::Seed& s = t.seeds[static_cast<std::size_t>(rng() % t.seeds.size())];
      const std::string bytes = fz::mutate(s.bytes, rng, t.binary);
      const fs::path dir = work / t.name;
      fs::create_directories(dir);
      const std::string path = (dir / s.file_name).string();
      std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
      std::snprintf(g_current, sizeof g_current, "%s input %ld (--seed %llu --replay %s:%ld), file %s", t.name.c_str(),
                    i, seed, t.name.c_str(), i, path.c_str());
      alarm(timeout);
      const std::string problem = check(t, path);
      alarm(0);
      ++done;
      if (problem.empty()) {
        ++(g_rejected ? rejected : parsed);
      } else {
        ++failed;
        if (failed <= 5) std::fprintf(stderr, "FAIL %s: %s\n", g_current, problem.c_str());
        const fs::path keep = work / ("failed_" + t.name + "_" + std::to_string(i) + "_" + s.file_name);
        std::ofstream(keep, std::ios::binary) << bytes;
      }
    }
    const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%-16s %6ld inputs in %6.1f s: %ld parsed, %ld rejected with a file-named error, %ld failed%s\n",
                t.name.c_str(), done, took, parsed, rejected, failed,
                done < last - first ? " (time budget reached)" : "");
    std::fflush(stdout);
    failures += failed > 0 ? 1 : 0;
  }
  if (failures == 0) fs::remove_all(work);  // failing inputs are kept (failed_*) for the report
  return failures == 0 ? 0 : 1;
}
