#include "rocking_sim_ensemble.hpp"
#include "rocking_sim_solid.hpp"

#include <algorithm>
#include <ctime>

namespace rocking_monitor::tools::sim {

namespace {

const char* level_name(rm::Level level) {
  switch (level) {
    case rm::Level::BeyondTipping: return "beyond_tipping";
    case rm::Level::Committed: return "committed";
    case rm::Level::Overturned: return "overturned";
  }
  return "?";
}

}  // namespace

EnsembleRun run_ensemble(const RunOptions& opt, const rm::UncertainItemSpec& spec, int samples, std::uint64_t seed,
                         double threshold, const rm::GroundMotion& mx, const rm::GroundMotion* my) {
  std::vector<int> pulled;
  const std::vector<rm::ItemSpec> members = rm::draw_members(spec, samples, seed, &pulled);
  const rm::ItemMonitor::Options o = monitor_options(opt, mx, my);
  rm::ItemEnsemble ensemble(members, o, threshold);
  auto ay = [&](std::size_t i) { return my != nullptr ? my->horizontal[i] : 0.0; };
  auto az = [&](std::size_t i) { return mx.vertical.empty() ? 0.0 : mx.vertical[i]; };
  const std::clock_t start = std::clock();
  ensemble.start(0.0, mx.horizontal.front(), ay(0), az(0), mx.dt);
  std::vector<rm::ProbabilityCrossing> crossings;
  for (std::size_t i = 1; i < mx.size(); ++i) {
    const rm::EnsembleEvents& ev = ensemble.step(mx.horizontal[i], ay(i), az(i), mx.dt);
    for (int k = 0; k < ev.count; ++k) crossings.push_back(ev.crossings[static_cast<std::size_t>(k)]);
  }
  const double cpu = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  EnsembleRun run;
  json levels = json::object();
  std::string summary;
  for (int l = 0; l < rm::kLevelCount; ++l) {
    const auto level = static_cast<rm::Level>(l);
    const rm::WilsonInterval w = ensemble.interval(level);
    json crossing = nullptr;
    for (const auto& c : crossings)
      if (c.level == level) crossing = {{"time_s", c.time}, {"probability", c.probability}};
    levels[level_name(level)] = {{"probability", ensemble.probability(level)},
                                    {"wilson_95", {w.lower, w.upper}},
                                    {"members_reached", ensemble.reached(level)},
                                    {"crossing", crossing}};
    summary += format("%sP(%s) %.3f [%.3f, %.3f]", l ? ", " : "", level_name(level), ensemble.probability(level),
                      w.lower, w.upper);
  }
  run.out = {{"members", ensemble.size()},
             {"seed", seed},
             {"alarm_probability", threshold},
             {"pulled_toward_nominal", pulled.size()},
             {"levels", levels},
             {"cpu_time_s", cpu}};
  run.lines.push_back(format("ensemble    %d members (Latin hypercube, seed %llu), given this record: %s",
                             ensemble.size(), static_cast<unsigned long long>(seed), summary.c_str()));
  for (const auto& c : crossings)
    run.lines.push_back(format("crossing    P(%s) reached %.3f >= %.2f at %.4f s", level_name(c.level),
                               c.probability, threshold, c.time));
  if (!pulled.empty())
    run.lines.push_back(format("note        %zu members drawn outside the valid geometry were pulled toward the "
                               "nominal item", pulled.size()));
  return run;
}

}  // namespace rocking_monitor::tools::sim
