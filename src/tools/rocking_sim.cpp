// rocking_sim: runs one body through one ground-motion record (or two: its x and y rocking
// planes, uncoupled) with the ROS-free core.
// Thin command-line layer: parse, read, simulate, print. All physics lives in the core library.
#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <ctime>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "command_line.hpp"
#include "rocking_monitor/csv/csv_writer.hpp"
#include "rocking_monitor/model/adaptive_model.hpp"
#include "rocking_monitor/monitoring/catalogue_file.hpp"
#include "rocking_monitor/monitoring/item_ensemble.hpp"
#include "rocking_monitor/physics/item_verdict.hpp"
#include "rocking_monitor/monitoring/simulation.hpp"
#include "rocking_monitor/motion/ground_motion.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "rocking_monitor/physics/criteria.hpp"
#include "rocking_monitor/physics/principal_planes.hpp"

namespace rm = rocking_monitor::core;
using nlohmann::json;

namespace {

json nullable(double v) { return std::isnan(v) ? json(nullptr) : json(v); }

// The rocking-direction input: the file's first horizontal component. A file that holds only a
// vertical component is used as given (the user asked for it), with a note.
const rm::Component& first_horizontal(const std::vector<rm::Component>& comps) {
  for (const auto& c : comps)
    if (!c.vertical) return c;
  std::cerr << "rocking_sim: note: " << comps.front().file << " holds only a vertical component ("
            << comps.front().label << "); it is used as the horizontal input as asked\n";
  return comps.front();
}

void write_history(const std::string& path, const rm::SimulationResult& r) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  out << "time_s,ax_mps2,ay_mps2,mode,pivot,theta_rad,omega_radps,rotation_ratio,energy_margin\n";
  rm::csv::Writer row(out);
  for (const auto& h : r.history) {
    row.number("%.6f", h.t).number("%.9g", h.ax).number("%.9g", h.ay);
    row.text(rm::to_string(h.mode)).value(std::to_string(h.side)).number("%.12g", h.theta);
    row.number("%.12g", h.omega).number("%.9g", h.rotation_ratio).number("%.9g", h.margin);
    row.end_row();
  }
  if (!out) throw std::runtime_error(path + ": write failed");
}

// --fidelity contact | adaptive: the AdaptiveModel over the record, as a SimulationResult-like summary.
struct FidelityRun {
  rm::AdaptiveOutcome outcome;
  std::string final_mode;
  std::vector<rm::SwitchRecord> switches;
  rm::SwitchReason initial = rm::SwitchReason::None;
  rm::SlidingBound bound;
  double cpu_time_s = 0.0;
};

json nullable_inf(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// --scene: "auto" (the record's own peaks), "unknown", or "H,V" (m/s^2).
rm::SceneEnvelope parse_scene(const std::string& text, const rm::GroundMotion& motion) {
  rm::SceneEnvelope e;
  if (text == "unknown") return e;
  if (text == "auto") {
    e.horizontal = e.vertical = 0.0;
    for (double a : motion.horizontal) e.horizontal = std::max(e.horizontal, std::abs(a));
    for (double a : motion.vertical) e.vertical = std::max(e.vertical, std::abs(a));
    return e;
  }
  char* end = nullptr;
  e.horizontal = std::strtod(text.c_str(), &end);
  const bool comma = *end == ',';
  if (comma) e.vertical = std::strtod(end + 1, &end);
  if (!comma || *end != '\0' || !(e.horizontal >= 0.0) || !(e.vertical >= 0.0))
    throw std::invalid_argument("--scene '" + text +
                                "': expected auto, unknown or H,V (two numbers >= 0, m/s^2)");
  return e;
}

FidelityRun run_fidelity(const rm::Body& body, const rm::AdaptiveSettings& settings,
                         const rm::GroundMotion& motion, const std::string& history_path) {
  rm::AdaptiveModel model(body, settings);
  std::ofstream hist;
  if (!history_path.empty()) {
    hist.open(history_path);
    if (!hist) throw std::runtime_error(history_path + ": cannot open for writing");
    hist << "time_s,ax_mps2,ay_mps2,model,mode,pivot,theta_rad,omega_radps,slip_m\n";
  }
  auto ay = [&](std::size_t i) { return motion.vertical.empty() ? 0.0 : motion.vertical[i]; };
  rm::csv::Writer writer(hist);
  auto row = [&](std::size_t i) {
    if (!hist.is_open()) return;
    writer.number("%.6f", model.time()).number("%.9g", motion.horizontal[i]);
    writer.number("%.9g", ay(i)).text(rm::to_string(model.active())).text(model.mode_name());
    writer.value(std::to_string(model.side())).number("%.12g", model.theta());
    writer.number("%.12g", model.omega()).number("%.12g", model.slip());
    writer.end_row();
  };
  const std::clock_t start = std::clock();  // CPU time, as simulate()
  model.reset(0.0, motion.horizontal.front(), ay(0));
  row(0);
  for (std::size_t i = 1; i < motion.size(); ++i) {
    model.step(motion.horizontal[i], ay(i), motion.dt);
    row(i);
  }
  FidelityRun r;
  r.cpu_time_s = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  r.outcome = model.outcome();
  r.final_mode = model.mode_name();
  r.switches = model.switches();
  r.initial = model.initial_reason();
  r.bound = model.sliding_bound();
  if (hist.is_open() && !hist) throw std::runtime_error(history_path + ": write failed");
  return r;
}

// What both planes share: solver, fidelity and its settings, the scale.
struct RunOptions {
  rm::SolverSettings settings;
  rm::Fidelity fidelity = rm::Fidelity::Adaptive;
  std::string scene_text;
  rm::ContactSettings contact;
  double linearized_max_alpha = 0.0;
  double scale = 1.0;
};

// One plane's answer: the single-plane JSON of its fidelity, its text summary lines and its level
// times for combine().
struct PlaneRun {
  json out;
  std::vector<std::string> lines;
  rm::LevelTimes levels;
};

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* fmt, ...) {
  char buf[1024];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, args);
  va_end(args);
  return buf;
}

std::string when(double t) { return std::isnan(t) ? std::string("never") : std::to_string(t) + " s"; }

template <class Outcome>
rm::LevelTimes level_times(const Outcome& o) {
  rm::LevelTimes l;
  l.time[static_cast<int>(rm::Level::BeyondTipping)] = o.beyond_tipping_time;
  l.time[static_cast<int>(rm::Level::Committed)] = o.committed_time;
  l.time[static_cast<int>(rm::Level::Overturned)] = o.overturn_time;
  return l;
}

json record_json(const rm::GroundMotion& motion, double scale, double pga) {
  return {{"description", motion.description},
          {"dt_s", motion.dt},
          {"samples", motion.size()},
          {"duration_s", motion.dt * static_cast<double>(motion.size() - 1)},
          {"scale", scale},
          {"pga_mps2", pga},
          {"has_vertical", !motion.vertical.empty()}};
}

json body_json(const rm::Body& rigid) {
  const rm::Pivot& p1 = rigid.pivot(1);
  const rm::Pivot& p2 = rigid.pivot(-1);
  return {{"width_m", rigid.width()},
          {"cg_height_m", rigid.cg_height()},
          {"nu1", rigid.nu1()},
          {"radius_of_gyration_m", rigid.radius_of_gyration()},
          {"alpha1_rad", p1.alpha},
          {"alpha2_rad", p2.alpha},
          {"p1_radps", p1.p},
          {"p2_radps", p2.p},
          {"restitution_to_1", p1.restitution},
          {"restitution_to_2", p2.restitution}};
}

// One plane through its record, exactly as the single-plane tool: simulate() for --fidelity rocking,
// the AdaptiveModel loop for contact / adaptive.
PlaneRun run_plane(const RunOptions& opt, const rm::BodyParameters& params,
                   const rm::GroundMotion& motion, const std::string& history_path) {
  const rm::Body rigid(params);
  const rm::SolverSettings& settings = opt.settings;
  double pga = 0.0;
  for (double a : motion.horizontal) pga = std::max(pga, std::abs(a));
  PlaneRun run;
  const std::string record_line = format("record      %s (%zu samples, dt %.4g s, PGA %.3f m/s^2)",
                                         motion.description.c_str(), motion.size(), motion.dt, pga);
  if (opt.fidelity != rm::Fidelity::Rocking) {
    rm::AdaptiveSettings as;
    as.fidelity = opt.fidelity;
    as.rocking = settings;
    as.scene = parse_scene(opt.scene_text, motion);  // "auto": this plane's own record
    as.contact = opt.contact;
    as.linearized_max_alpha = opt.linearized_max_alpha;
    const FidelityRun f = run_fidelity(rigid, as, motion, history_path);
    const rm::AdaptiveOutcome& o = f.outcome;
    run.levels = level_times(o);
    json reasons = json::array();
    for (const auto& sw : f.switches)
      reasons.push_back({{"time_s", sw.time}, {"onset_time_s", sw.onset_time},
                         {"to", rm::to_string(sw.to)}, {"reason", rm::to_string(sw.reason)}});
    run.out = {{"overturned", o.overturned},
               {"committed", o.committed},
               {"beyond_tipping", o.beyond_tipping},
               {"max_rotation_ratio", o.max_rotation_ratio},
               {"impacts", o.impacts},
               {"uplift_time_s", nullable(o.uplift_time)},
               {"beyond_tipping_time_s", nullable(o.beyond_tipping_time)},
               {"committed_time_s", nullable(o.committed_time)},
               {"overturn_time_s", nullable(o.overturn_time)},
               {"final_mode", f.final_mode},
               {"slip_episodes", o.slip_episodes},
               {"flight_episodes", o.flight_episodes},
               {"first_slip_time_s", nullable(o.first_slip_time)},
               {"first_flight_time_s", nullable(o.first_flight_time)},
               {"max_abs_slip_m", o.max_abs_slip},
               {"method", rm::to_string(settings.method)},
               {"model", rm::to_string(settings.model)},
               {"fidelity", rm::to_string(opt.fidelity)},
               {"initial_model_reason", rm::to_string(f.initial)},
               {"sliding_ruled_out", o.sliding_ruled_out},
               {"scene",
                {{"source", opt.scene_text},
                 {"horizontal_mps2", nullable_inf(as.scene.horizontal)},
                 {"vertical_mps2", nullable_inf(as.scene.vertical)},
                 {"required_mu", nullable_inf(f.bound.required_mu())},
                 {"samples_outside", o.samples_outside_scene}}},
               {"samples_rocking_model", o.samples_rocking_model},
               {"samples_contact_model", o.samples_contact_model},
               {"samples_linearized_model", o.samples_linearized_model},
               {"linearized_fallbacks", o.linearized_fallbacks},
               {"replayed_samples", o.recomputed_samples},  // samples recomputed at up switches
               {"model_switches", o.model_switches},
               {"switch_reasons", reasons},
               {"steps", o.rocking_steps + o.contact_steps},
               {"steps_rocking_model", o.rocking_steps},
               {"steps_contact_model", o.contact_steps},
               {"samples", o.samples},
               {"cpu_time_s", f.cpu_time_s},
               {"body", body_json(rigid)},
               {"record", record_json(motion, opt.scale, pga)}};
    auto& L = run.lines;
    L.push_back(record_line);
    L.push_back(format("fidelity    %s (start: %s)", rm::to_string(opt.fidelity), rm::to_string(f.initial)));
    L.push_back(format("scene       %s: |a_h| <= %.4g, |a_v| <= %.4g m/s^2; friction needed to rule out "
                       "sliding, slip at impact and flight: %.4g (mu_s %.4g)",
                       opt.scene_text.c_str(), as.scene.horizontal, as.scene.vertical,
                       f.bound.required_mu(), rigid.mu_s()));
    L.push_back(format("result      %s, final mode %s", o.overturned ? "OVERTURNED" : "survived",
                       f.final_mode.c_str()));
    L.push_back(format("times       uplift %s, beyond tipping %s, committed %s, overturned %s, "
                       "first slip %s, first flight %s",
                       when(o.uplift_time).c_str(), when(o.beyond_tipping_time).c_str(),
                       when(o.committed_time).c_str(), when(o.overturn_time).c_str(),
                       when(o.first_slip_time).c_str(), when(o.first_flight_time).c_str()));
    for (const auto& sw : f.switches)
      L.push_back(format("switch      to %s at %.4f s (detected %.4f s): %s", rm::to_string(sw.to),
                         sw.time, sw.onset_time, rm::to_string(sw.reason)));
    L.push_back(format("cost        %ld rocking-model + %ld contact-model samples, %ld + %ld steps, "
                       "%.4f s CPU",
                       o.samples_rocking_model, o.samples_contact_model, o.rocking_steps,
                       o.contact_steps, f.cpu_time_s));
    return run;
  }

  const rm::SimulationResult r = rm::simulate(rigid, settings, motion, !history_path.empty());
  if (!history_path.empty()) write_history(history_path, r);
  const rm::RockingOutcome& o = r.outcome;
  run.levels = level_times(o);
  json violations = json::array();
  for (const auto& v : r.violations)
    violations.push_back({{"criterion", rm::to_string(v.criterion)}, {"time_s", v.time}});
  run.out = {{"overturned", o.overturned},
             {"committed", o.committed},
             {"beyond_tipping", o.beyond_tipping},
             {"max_rotation_ratio", o.max_rotation_ratio},
             {"max_rotation_pivot", o.max_rotation_side},
             {"impacts", o.impacts},
             {"uplift_time_s", nullable(o.uplift_time)},
             {"beyond_tipping_time_s", nullable(o.beyond_tipping_time)},
             {"committed_time_s", nullable(o.committed_time)},
             {"overturn_time_s", nullable(o.overturn_time)},
             {"final_mode", rm::to_string(r.final_mode)},
             {"violations", violations},
             {"rest_captures", o.rest_captures},
             {"forced_rest_captures", o.forced_rest_captures},
             {"method", rm::to_string(settings.method)},
             {"model", rm::to_string(settings.model)},
             {"fidelity", "rocking"},
             {"samples_rocking_model", o.samples},
             {"samples_contact_model", 0},
             {"model_switches", 0},
             {"switch_reasons", json::array()},
             {"tol", settings.tol},
             {"substeps", settings.substeps},
             {"steps", o.integrator_steps},
             {"samples", o.samples},
             {"cpu_time_s", r.cpu_time_s},
             {"body", body_json(rigid)},
             {"record", record_json(motion, opt.scale, pga)}};
  auto& L = run.lines;
  L.push_back(record_line);
  L.push_back(format("body        B %.3f m, h %.3f m, nu1 %.3f, alpha1 %.4f rad, alpha2 %.4f rad",
                     rigid.width(), rigid.cg_height(), rigid.nu1(), rigid.pivot(1).alpha,
                     rigid.pivot(-1).alpha));
  L.push_back(format("solver      %s, %s model", rm::to_string(settings.method),
                     rm::to_string(settings.model)));
  L.push_back(format("result      %s%s%s", o.overturned ? "OVERTURNED" : "survived",
                     (!o.overturned && o.beyond_tipping) ? " (passed its tipping angle and came back)" : "",
                     (!o.overturned && o.committed) ? " (was committed at some instant)" : ""));
  L.push_back(format("max |theta|/alpha %.4f, impacts %ld", o.max_rotation_ratio, o.impacts));
  L.push_back(format("times       uplift %s, beyond tipping %s, committed %s, overturned %s",
                     when(o.uplift_time).c_str(), when(o.beyond_tipping_time).c_str(),
                     when(o.committed_time).c_str(), when(o.overturn_time).c_str()));
  for (const auto& v : r.violations)
    L.push_back(format("violation   %s at %.4f s (pure rocking assumption broken)",
                       rm::to_string(v.criterion), v.time));
  L.push_back(format("cost        %ld steps, %.4f s CPU", o.integrator_steps, r.cpu_time_s));
  return run;
}

// --units applies to CSV only: a PEER/BBP/SMC file states its own.
rm::RecordFormat check_units(const std::string& file, const std::string& units_text) {
  const rm::RecordFormat format = rm::detect_format(file);
  if (!units_text.empty() && format != rm::RecordFormat::Csv) {
    throw rm::RecordError(file + ": --units applies to CSV records only; this " +
                          rm::to_string(format) + " file states its own units");
  }
  return format;
}

// --history-y default: the --history file with "_y" before its extension (h.csv -> h_y.csv).
std::string y_history_path(const std::string& x_path) {
  const std::string::size_type slash = x_path.find_last_of('/');
  const std::string::size_type dot = x_path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash) || dot == slash + 1)
    return x_path + "_y";
  return x_path.substr(0, dot) + "_y" + x_path.substr(dot);
}

// --samples: the item's ensemble (the live node's members: draw_members() with the same seed, each
// an ItemMonitor) through the record(s); P(level) with its Wilson interval and the threshold crossings.
const char* level_name(rm::Level level) {
  switch (level) {
    case rm::Level::BeyondTipping: return "beyond_tipping";
    case rm::Level::Committed: return "committed";
    case rm::Level::Overturned: return "overturned";
  }
  return "?";
}

struct EnsembleRun {
  json out;
  std::vector<std::string> lines;
};

EnsembleRun run_ensemble(const RunOptions& opt, const rm::UncertainItemSpec& spec, int samples, std::uint64_t seed,
                         double threshold, const rm::GroundMotion& mx, const rm::GroundMotion* my) {
  std::vector<int> pulled;
  const std::vector<rm::ItemSpec> members = rm::draw_members(spec, samples, seed, &pulled);
  rm::ItemMonitor::Options o;
  o.solver = opt.settings;
  o.fidelity = opt.fidelity;
  o.linearized_max_alpha = opt.linearized_max_alpha;
  o.scene = parse_scene(opt.scene_text, mx);
  if (my != nullptr) {  // one envelope for both planes: the larger of each
    const rm::SceneEnvelope sy = parse_scene(opt.scene_text, *my);
    o.scene.horizontal = std::max(o.scene.horizontal, sy.horizontal);
    o.scene.vertical = std::max(o.scene.vertical, sy.vertical);
  }
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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "rocking_sim: rocking and overturning of a free-standing (optionally eccentric) rigid body "
      "under horizontal and vertical ground acceleration (Boroschek & Romo). With --depth the item "
      "rocks in two uncoupled principal planes: x-z (width, --record) and y-z (depth, --record-y)."};
  std::string record, record_y, vertical_file, units_text, history_path, history_y_path,
      method_text = "dopri5", model_text = "nonlinear";
  RunOptions opt;
  rm::BodyParameters body;
  rm::DepthParameters depth;
  rm::SolverSettings& settings = opt.settings;
  bool as_json = false;
  app.add_option("--record", record,
                 "Ground acceleration along the item's x: PEER .AT2 (g), SCEC .bbp, USGS .smc, or "
                 "CSV/whitespace rows 'time_s accel' or 'time_s accel_h accel_v' (units from --units)")
      ->required();
  app.add_option("--record-y", record_y,
                 "Ground acceleration along the item's y (needs --depth): same formats and --units "
                 "rule as --record, its first horizontal component is used; same dt as --record");
  app.add_option("--vertical", vertical_file,
                 "Separate vertical component file (positive up), shared by both planes");
  app.add_option("--units", units_text, "Units of CSV records: g | m/s2 | cm/s2 (default m/s2)")
      ->check(CLI::IsMember({"g", "m/s2", "cm/s2"}));
  rm::ReadOptions options;
  rocking_monitor::tools::add_miniseed_options(app, options);
  app.add_option("--scale", opt.scale, "Multiply the ground acceleration by S")->default_val(1.0);
  std::string catalogue_file, item_id;
  int samples = 0;
  std::uint64_t ensemble_seed = 1;
  double alarm_probability = 0.5;
  app.add_option("--catalogue", catalogue_file,
                 "Take the body from a monitor catalogue (YAML, the node's grammar) instead of --width ...; "
                 "with --item");
  app.add_option("--item", item_id, "--catalogue: the item's id");
  app.add_option("--samples", samples,
                 "Run N ensemble members of a --catalogue item given with distributions (as the node: "
                 "~ensemble_size or the item's ensemble_size) and report P(beyond tipping), P(committed), "
                 "P(overturned) given this record, with 95 % Wilson intervals")
      ->check(CLI::Range(1, 100000));
  app.add_option("--seed", ensemble_seed, "--samples: seed of the members' Latin hypercube (the node's ~ensemble_seed)")
      ->default_val(ensemble_seed);
  app.add_option("--alarm-probability", alarm_probability,
                 "--samples: report when P(level) first reaches this (the node's ~alarm_probability)")
      ->default_val(alarm_probability)->check(CLI::Range(1e-9, 1.0));
  app.add_option("--width", body.width, "Base width B along x, m (required without --catalogue)");
  app.add_option("--cg-height", body.cg_height, "Height h of the centre of mass, m (required without --catalogue)");
  app.add_option("--eccentricity", body.nu1,
                 "nu1: CoM at nu1*B from corner 1, in (0,1); 0.5 = symmetric")
      ->default_val(0.5);
  app.add_option("--radius-of-gyration", body.radius_of_gyration,
                 "Central radius of gyration i_g, m (default: homogeneous rectangle B x 2h)");
  app.add_option("--depth", depth.depth,
                 "Base depth D along y, m: the item also rocks in its y-z plane (under --record-y and "
                 "the vertical; without --record-y under the vertical only)");
  app.add_option("--eccentricity-y", depth.eccentricity_y,
                 "CoM at NU*D from the -y corner, in (0,1); 0.5 = symmetric (needs --depth)")
      ->default_val(0.5);
  app.add_option("--radius-of-gyration-y", depth.radius_of_gyration_y,
                 "Central radius of gyration for rocking in the y-z plane, m (needs --depth; default: "
                 "derived from --radius-of-gyration for a plan-uniform mass, else homogeneous D x 2h)");
  app.add_option("--mu-s", body.mu_s, "Static friction coefficient (default: not checked)");
  app.add_option("--mu-k", body.mu_k,
                 "Kinetic friction coefficient for --fidelity contact|adaptive (default mu_s)");
  // adaptive by default: the cheapest valid model per sample; without --mu-s it is the pure-rocking
  // model (until free flight), so only items given a friction coefficient can see the contact model.
  std::string fidelity_text = "adaptive";
  app.add_option("--fidelity", fidelity_text,
                 "adaptive (default: rocking model while valid, contact model when needed; without "
                 "--mu-s pure rocking) | rocking (the paper's pure-rocking model only, violations "
                 "flagged; simulate()) | contact (full contact model: slide, slide-rock, flight); "
                 "docs/fidelity.md")
      ->check(CLI::IsMember({"rocking", "contact", "adaptive"}))
      ->default_val("adaptive");
  app.add_option("--contact-substeps", opt.contact.substeps,
                 "RK4 sub-steps per input sample of the contact model (--fidelity contact|adaptive)")
      ->default_val(opt.contact.substeps)
      ->check(CLI::Range(1, 100000));
  app.add_option("--linearized-max-alpha", opt.linearized_max_alpha,
                 "--fidelity adaptive: items with both tipping angles <= this (rad) rock on the linearized "
                 "closed form while |theta|/alpha < 0.5 (0 = off; docs/fidelity.md)")
      ->default_val(0.0)
      ->check(CLI::NonNegativeNumber);
  opt.scene_text = "auto";
  app.add_option("--scene", opt.scene_text,
                 "Scene envelope for the adaptive pre-check (docs/fidelity.md): auto = each plane's "
                 "record's own peak |a_h|, |a_v| (the whole scene is known offline); unknown; or H,V in m/s^2")
      ->default_val(opt.scene_text);
  app.add_option("--restitution", body.restitution,
                 "Measured angular-velocity ratio at impact, overrides eq. 34");
  app.add_option("--model", model_text, "nonlinear | linearized")
      ->check(CLI::IsMember({"nonlinear", "linearized"}))
      ->default_val("nonlinear");
  app.add_option("--method", method_text, "dopri5 | rk4 | analytic")
      ->check(CLI::IsMember({"dopri5", "rk4", "analytic"}))
      ->default_val("dopri5");
  app.add_option("--tol", settings.tol, "dopri5 relative tolerance")->default_val(settings.tol);
  app.add_option("--substeps", settings.substeps, "rk4 sub-steps per input sample")
      ->default_val(settings.substeps);
  app.add_option("--history", history_path,
                 "Write the time history (CSV) to this file; with --depth it holds the x plane (same "
                 "columns as without) and the y plane goes to --history-y");
  app.add_option("--history-y", history_y_path,
                 "With --depth and --history: the y plane's history (default: the --history name "
                 "with _y before its extension, h.csv -> h_y.csv)");
  app.add_flag("--json", as_json, "Print one JSON object instead of a text summary");
  if (const auto status = rocking_monitor::tools::parse_command_line(app, argc, argv, "rocking_sim")) return *status;

  try {
    rm::parse_method(method_text, settings.method);
    rm::parse_model(model_text, settings.model);
    if (const std::string e = rm::validate(settings); !e.empty()) throw std::invalid_argument(e);
    rm::parse_fidelity(fidelity_text.c_str(), opt.fidelity);
    // The body: from the flags, or a catalogue item (then no body flag: one source of truth).
    std::optional<rm::CatalogueItem> item_entry;
    static const char* const kBodyFlags[] = {"--width", "--cg-height", "--eccentricity", "--radius-of-gyration",
                                             "--depth", "--eccentricity-y", "--radius-of-gyration-y", "--mu-s",
                                             "--mu-k", "--restitution"};
    if (!catalogue_file.empty()) {
      if (item_id.empty()) throw std::invalid_argument("--catalogue needs --item ID");
      for (const char* flag : kBodyFlags)
        if (app.count(flag) > 0)
          throw std::invalid_argument(std::string(flag) + " cannot be combined with --catalogue (the item gives the body)");
      for (const rm::CatalogueItem& c : rm::load_catalogue_items_file(catalogue_file))
        if (c.spec.id == item_id) item_entry = c;
      if (!item_entry) throw std::invalid_argument(catalogue_file + ": no item with id '" + item_id + "'");
      body = item_entry->spec.body;
      depth = item_entry->spec.depth;
    } else {
      if (!item_id.empty()) throw std::invalid_argument("--item needs --catalogue FILE");
      for (const char* flag : {"--width", "--cg-height"})
        if (app.count(flag) == 0) throw std::invalid_argument(std::string(flag) + " is required (or --catalogue and --item)");
    }
    if (samples > 0 && !(item_entry && item_entry->uncertain.uncertain()))
      throw std::invalid_argument("--samples needs a --catalogue item given with distributions (" +
                                  (item_entry ? "'" + item_id + "' has none" : std::string("no --catalogue")) + ")");
    const rm::Body rigid(body);  // validates the x plane's body

    // The y plane: asked for by --depth (NaN in DepthParameters means "not given", so an explicit
    // --depth nan is refused here rather than silently dropping the plane).
    const bool two_planes = item_entry ? item_entry->spec.two_planes() : app.count("--depth") > 0;
    if (two_planes && std::isnan(depth.depth))
      throw rm::BodyError("invalid body: depth = nan (must be a finite length > 0 m)");
    if (!two_planes) {
      for (const char* flag : {"--record-y", "--eccentricity-y", "--radius-of-gyration-y", "--history-y"})
        if (app.count(flag) > 0)
          throw std::invalid_argument(std::string(flag) +
                                      " needs --depth (the item's base depth along y, m)");
    }
    std::optional<rm::BodyParameters> body_y;
    if (two_planes) {
      body_y = rm::y_plane_body(body, depth);  // throws naming depth / eccentricity_y / radius_of_gyration_y
      (void)rm::Body(*body_y);                 // and the y body as a whole, before any file is read
    }
    if (!history_y_path.empty() && history_path.empty())
      throw std::invalid_argument("--history-y needs --history");
    const bool derived_history_y = two_planes && !history_path.empty() && history_y_path.empty();
    if (derived_history_y) history_y_path = y_history_path(history_path);

    const bool miniseed_options = rocking_monitor::tools::miniseed_options_given(options);
    if (units_text == "g") options.csv_units = rm::AccelUnits::G;
    else if (units_text == "cm/s2") options.csv_units = rm::AccelUnits::CentimetersPerSecond2;
    const rm::RecordFormat format = check_units(record, units_text);
    // The miniSEED options would be silently meaningless for a file that states its own units.
    if (miniseed_options && format != rm::RecordFormat::MiniSeed)
      throw rm::RecordError(record + ": --gain, --sensor-azimuth and --channel-table apply to miniSEED records only; this " +
                            std::string(rm::to_string(format)) + " file states its own units and directions");
    const std::vector<rm::Component> comps = rm::read_record(record, options);
    rm::Component horizontal = first_horizontal(comps);
    std::optional<rm::Component> vertical;
    if (format == rm::RecordFormat::Csv && comps.size() > 1) vertical = comps[1];
    // A miniSEED or COSMOS file of a whole station gives its vertical channel too.
    if (format == rm::RecordFormat::MiniSeed || format == rm::RecordFormat::CosmosV2) {
      for (const auto& c : comps)
        if (c.vertical) vertical = c;
    }
    if (!vertical_file.empty() && vertical_file != record) {
      if (vertical)
        throw rm::RecordError(record + ": has a vertical column and --vertical was also given");
      rm::ReadOptions vopt = options;
      const std::vector<rm::Component> vcomps = rm::read_record(vertical_file, vopt);
      // A multi-component file given as --vertical contributes its vertical channel.
      const rm::Component* pick = &vcomps.front();
      for (const auto& c : vcomps)
        if (c.vertical) { pick = &c; break; }
      vertical = *pick;
    }

    std::optional<rm::Component> horizontal_y;
    if (two_planes && !record_y.empty()) {
      const rm::RecordFormat format_y = check_units(record_y, units_text);
      const std::vector<rm::Component> comps_y = rm::read_record(record_y, options);
      horizontal_y = first_horizontal(comps_y);
      if (format_y == rm::RecordFormat::Csv && comps_y.size() > 1)
        std::cerr << "rocking_sim: note: " << record_y << ": its vertical column is not used (the "
                  << "vertical comes from --record or --vertical and is shared by both planes)\n";
      // Both planes run on one time grid.
      if (std::abs(horizontal_y->dt - horizontal.dt) > 1e-6 * horizontal.dt) {
        std::ostringstream os;
        os << "--record-y " << record_y << " has dt = " << horizontal_y->dt << " s but --record "
           << record << " has dt = " << horizontal.dt << " s (the two horizontals must share one sample interval)";
        throw rm::RecordError(os.str());
      }
      // Different lengths: the common length, and say what was left out.
      const std::size_t nx = horizontal.accel.size(), ny = horizontal_y->accel.size();
      if (nx != ny) {
        rm::Component& longer = nx > ny ? horizontal : *horizontal_y;
        const std::size_t n = std::min(nx, ny);
        std::cerr << "rocking_sim: note: --record " << record << " has " << nx << " samples, --record-y "
                  << record_y << " " << ny << ": both planes use the common " << n << "; the last "
                  << longer.accel.size() - n << " samples of " << longer.file << " are not used\n";
        longer.accel.resize(n);
      }
    } else if (two_planes) {
      // --depth without --record-y: no horizontal input along y, only the shared vertical.
      horizontal_y = rm::Component{};
      horizontal_y->file = "no y horizontal";
      horizontal_y->dt = horizontal.dt;
      horizontal_y->t0 = horizontal.t0;
      horizontal_y->accel.assign(horizontal.accel.size(), 0.0);
      std::cerr << "rocking_sim: note: --depth without --record-y: the y plane sees only the vertical"
                << (vertical ? "" : " (none given: it stays at rest)") << "\n";
    }

    std::string notice;
    const rm::GroundMotion motion =
        rm::make_ground_motion(horizontal, vertical ? &*vertical : nullptr, opt.scale, &notice);
    if (!notice.empty()) std::cerr << "rocking_sim: note: " << notice << "\n";
    std::optional<rm::GroundMotion> motion_y;
    if (horizontal_y) {
      std::string notice_y;
      motion_y = rm::make_ground_motion(*horizontal_y, vertical ? &*vertical : nullptr, opt.scale, &notice_y);
      if (!notice_y.empty() && notice_y != notice) std::cerr << "rocking_sim: note: " << notice_y << "\n";
    }

    const PlaneRun x = run_plane(opt, body, motion, history_path);
    std::optional<PlaneRun> y;
    if (body_y) y = run_plane(opt, *body_y, *motion_y, history_y_path);
    if (derived_history_y)  // said once it is written, so a failed run still prints one error line
      std::cerr << "rocking_sim: note: the y plane's history is in " << history_y_path
                << " (--history-y to choose)\n";
    const rm::ItemVerdict item = rm::combine(x.levels, y ? &y->levels : nullptr);
    std::optional<EnsembleRun> ensemble;
    if (samples > 0)
      ensemble = run_ensemble(opt, item_entry->uncertain, samples, ensemble_seed, alarm_probability, motion,
                              motion_y ? &*motion_y : nullptr);

    if (as_json) {
      json out = x.out;  // the top level stays the x plane's single-plane output
      json planes = {{"x", x.out}};
      planes["x"].erase("record");  // it is the top-level "record"
      if (y) planes["y"] = y->out;  // its "record" is the y horizontal + the shared vertical
      out["planes"] = planes;
      json verdict = {{"plane_count", y ? 2 : 1}};
      const std::pair<rm::Level, const char*> levels[] = {{rm::Level::BeyondTipping, "beyond_tipping"},
                                                          {rm::Level::Committed, "committed"},
                                                          {rm::Level::Overturned, "overturn"}};
      for (const auto& [level, name] : levels) {
        const bool reached = item.levels.reached(level);
        // "overturned" as the top-level flag, "overturn_time_s" as the top-level time
        verdict[level == rm::Level::Overturned ? std::string("overturned") : std::string(name)] = reached;
        verdict[std::string(name) + "_time_s"] = nullable(item.levels.at(level));
        verdict[std::string(name) + "_plane"] =
            reached ? json(rm::to_string(item.plane[static_cast<int>(level)])) : json(nullptr);
      }
      out["item"] = verdict;
      if (item_entry) out["item"]["id"] = item_entry->spec.id;
      if (ensemble) out["ensemble"] = ensemble->out;
      std::cout << out.dump(2) << "\n";
    } else {
      const std::string px = y ? "[x] " : "", py = "[y] ";
      for (const std::string& line : x.lines) std::printf("%s%s\n", px.c_str(), line.c_str());
      if (y)
        for (const std::string& line : y->lines) std::printf("%s%s\n", py.c_str(), line.c_str());
      auto level_text = [&](rm::Level level) {
        const double t = item.levels.at(level);
        if (std::isnan(t)) return std::string("never");
        return std::to_string(t) + " s (" + rm::to_string(item.plane[static_cast<int>(level)]) + " plane)";
      };
      std::printf("%sitem        %s: beyond tipping %s, committed %s, overturned %s\n", y ? "    " : "",
                  item.overturned() ? "OVERTURNED" : "survived",
                  level_text(rm::Level::BeyondTipping).c_str(), level_text(rm::Level::Committed).c_str(),
                  level_text(rm::Level::Overturned).c_str());
      if (ensemble)
        for (const std::string& line : ensemble->lines) std::printf("%s%s\n", y ? "    " : "", line.c_str());
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "rocking_sim: error: " << e.what() << "\n";
    return 2;
  }
}
