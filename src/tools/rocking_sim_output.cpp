#include "rocking_sim_output.hpp"
#include "rocking_sim_solid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <utility>

#include "rocking_monitor/csv/csv_writer.hpp"
#include "rocking_monitor/json_text.hpp"
#include "rocking_monitor/monitoring/friction_share.hpp"
#include "rocking_monitor/monitoring/simulation.hpp"
#include "rocking_monitor/physics/criteria.hpp"
#include "rocking_sim_ensemble.hpp"

namespace rocking_monitor::tools::sim {

json nullable(double v) { return std::isnan(v) ? json(nullptr) : json(v); }

std::string format(const char* fmt, ...) {
  char buf[1024];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, args);
  va_end(args);
  return buf;
}

namespace {

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

// One plane's AdaptiveModel over its record, and its history file (--history, --history-y).
class FidelityPlane {
 public:
  FidelityPlane(const rm::Body& body, const rm::AdaptiveSettings& settings, const rm::GroundMotion& motion,
                const std::string& history_path)
      : model_(body, settings), motion_(motion), path_(history_path), writer_(hist_) {
    if (path_.empty()) return;
    hist_.open(path_);
    if (!hist_) throw std::runtime_error(path_ + ": cannot open for writing");
    hist_ << "time_s,ax_mps2,ay_mps2,model,mode,pivot,theta_rad,omega_radps,slip_m\n";
  }
  rm::AdaptiveModel& model() { return model_; }
  double horizontal(std::size_t i) const { return motion_.horizontal[i]; }
  double vertical(std::size_t i) const { return motion_.vertical.empty() ? 0.0 : motion_.vertical[i]; }
  double dt() const { return motion_.dt; }
  void start() {
    model_.reset(0.0, horizontal(0), vertical(0));
    row(0);
  }
  void step(std::size_t i) {
    const std::clock_t t0 = std::clock();  // CPU time, as simulate()
    model_.step(horizontal(i), vertical(i), motion_.dt);
    cpu_ += std::clock() - t0;
    row(i);
  }
  FidelityRun finish() {
    FidelityRun r;
    r.cpu_time_s = static_cast<double>(cpu_) / CLOCKS_PER_SEC;
    r.outcome = model_.outcome();
    r.final_mode = model_.mode_name();
    r.switches = model_.switches();
    r.initial = model_.initial_reason();
    r.bound = model_.sliding_bound();
    if (hist_.is_open() && !hist_) throw std::runtime_error(path_ + ": write failed");
    return r;
  }

 private:
  void row(std::size_t i) {
    if (!hist_.is_open()) return;
    writer_.number("%.6f", model_.time()).number("%.9g", horizontal(i));
    writer_.number("%.9g", vertical(i)).text(rm::to_string(model_.active())).text(model_.mode_name());
    writer_.value(std::to_string(model_.side())).number("%.12g", model_.theta());
    writer_.number("%.12g", model_.omega()).number("%.12g", model_.slip());
    writer_.end_row();
  }
  rm::AdaptiveModel model_;
  const rm::GroundMotion& motion_;
  std::string path_;
  std::ofstream hist_;
  rm::csv::Writer writer_;
  std::clock_t cpu_ = 0;
};

FidelityRun run_fidelity(const rm::Body& body, const rm::AdaptiveSettings& settings,
                         const rm::GroundMotion& motion, const std::string& history_path) {
  FidelityPlane plane(body, settings, motion, history_path);
  plane.start();
  for (std::size_t i = 1; i < motion.size(); ++i) plane.step(i);
  return plane.finish();
}

// The two planes in step, sharing one friction budget (monitoring/friction_share.hpp), as the node's
// ItemMonitor steps them: before each sample the shares from both planes' states at its start.
std::pair<FidelityRun, FidelityRun> run_fidelity_pair(FidelityPlane& x, FidelityPlane& y, std::size_t samples) {
  x.start();
  y.start();
  for (std::size_t i = 1; i < samples; ++i) {
    const double x0[2] = {x.horizontal(i - 1), x.vertical(i - 1)}, y0[2] = {y.horizontal(i - 1), y.vertical(i - 1)};
    const double x1[2] = {x.horizontal(i), x.vertical(i)}, y1[2] = {y.horizontal(i), y.vertical(i)};
    const rm::FrictionShare f = rm::friction_share(x.model(), y.model(), x0, y0, x1, y1, x.dt());
    x.model().set_friction_share(f.share[0]);
    y.model().set_friction_share(f.share[1]);
    x.step(i);
    y.step(i);
  }
  return {x.finish(), y.finish()};
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

// --fidelity contact | adaptive: the options' adaptive settings, the scene from this plane's record.
rm::AdaptiveSettings adaptive_settings(const RunOptions& opt, const rm::GroundMotion& motion) {
  rm::AdaptiveSettings as;
  as.fidelity = opt.fidelity;
  as.rocking = opt.settings;
  as.scene = parse_scene(opt.scene_text, motion);  // "auto": this plane's own record
  as.contact = opt.contact;
  as.hold_time_s = opt.hold_time_s;
  as.linearized_max_alpha = opt.linearized_max_alpha;
  return as;
}

// The adaptive model's single-plane JSON: the levels, its episodes, switches, scene and cost.
json adaptive_json(const RunOptions& opt, const rm::AdaptiveSettings& as, const FidelityRun& f, const rm::Body& rigid,
                   const rm::GroundMotion& motion, double pga) {
  const rm::AdaptiveOutcome& o = f.outcome;
  const rm::SolverSettings& settings = opt.settings;
  json reasons = json::array();
  for (const auto& sw : f.switches)
    reasons.push_back({{"time_s", sw.time}, {"onset_time_s", sw.onset_time},
                       {"to", rm::to_string(sw.to)}, {"reason", rm::to_string(sw.reason)}});
  json out = outcome_json(o);
  out.update({{"final_mode", f.final_mode},
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
              {"record", record_json(motion, opt.scale, pga)}});
  return out;
}

// The adaptive model's text summary, after the record line.
void adaptive_lines(const RunOptions& opt, const rm::AdaptiveSettings& as, const FidelityRun& f, const rm::Body& rigid,
                    std::vector<std::string>& L) {
  const rm::AdaptiveOutcome& o = f.outcome;
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
}

// The pure-rocking model's single-plane JSON: simulate()'s outcome, violations and cost.
json rocking_json(const RunOptions& opt, const rm::SimulationResult& r, const rm::Body& rigid,
                  const rm::GroundMotion& motion, double pga) {
  const rm::RockingOutcome& o = r.outcome;
  const rm::SolverSettings& settings = opt.settings;
  json violations = json::array();
  for (const auto& v : r.violations)
    violations.push_back({{"criterion", rm::to_string(v.criterion)}, {"time_s", v.time}});
  json out = outcome_json(o);
  out.update({{"max_rotation_pivot", o.max_rotation_side},
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
              {"record", record_json(motion, opt.scale, pga)}});
  return out;
}

// The pure-rocking model's text summary, after the record line.
void rocking_lines(const rm::SolverSettings& settings, const rm::SimulationResult& r, const rm::Body& rigid,
                   std::vector<std::string>& L) {
  const rm::RockingOutcome& o = r.outcome;
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
}

}  // namespace

// One plane through its record, exactly as the single-plane tool: simulate() for --fidelity rocking,
// the AdaptiveModel loop for contact / adaptive.
namespace {

double record_pga(const rm::GroundMotion& motion) {
  double pga = 0.0;
  for (double a : motion.horizontal) pga = std::max(pga, std::abs(a));
  return pga;
}

std::string record_line(const rm::GroundMotion& motion, double pga) {
  return format("record      %s (%zu samples, dt %.4g s, PGA %.3f m/s^2)", motion.description.c_str(), motion.size(),
                motion.dt, pga);
}

// A plane's lines and JSON from its adaptive run.
PlaneRun adaptive_plane(const RunOptions& opt, const rm::AdaptiveSettings& as, const FidelityRun& f,
                        const rm::Body& rigid, const rm::GroundMotion& motion) {
  PlaneRun run;
  const double pga = record_pga(motion);
  run.lines.push_back(record_line(motion, pga));
  run.levels = level_times(f.outcome);
  run.out = adaptive_json(opt, as, f, rigid, motion, pga);
  adaptive_lines(opt, as, f, rigid, run.lines);
  return run;
}

}  // namespace

PlaneRun run_plane(const RunOptions& opt, const rm::BodyParameters& params,
                   const rm::GroundMotion& motion, const std::string& history_path) {
  const rm::Body rigid(params);
  if (opt.fidelity != rm::Fidelity::Rocking) {
    const rm::AdaptiveSettings as = adaptive_settings(opt, motion);
    return adaptive_plane(opt, as, run_fidelity(rigid, as, motion, history_path), rigid, motion);
  }
  const double pga = record_pga(motion);
  PlaneRun run;
  run.lines.push_back(record_line(motion, pga));
  const rm::SimulationResult r = rm::simulate(rigid, opt.settings, motion, !history_path.empty());
  if (!history_path.empty()) write_history(history_path, r);
  run.levels = level_times(r.outcome);
  run.out = rocking_json(opt, r, rigid, motion, pga);
  rocking_lines(opt.settings, r, rigid, run.lines);
  return run;
}

bool planes_share_friction(const RunOptions& opt, const rm::BodyParameters& x) {
  return opt.fidelity != rm::Fidelity::Rocking && !std::isinf(rm::Body(x).mu_s());
}

std::pair<PlaneRun, PlaneRun> run_plane_pair(const RunOptions& opt, const rm::BodyParameters& x,
                                             const rm::BodyParameters& y, const rm::GroundMotion& mx,
                                             const rm::GroundMotion& my, const std::string& history_x,
                                             const std::string& history_y) {
  if (mx.size() != my.size())  // (read_motions puts both on one grid: the common length, dt within 1e-6)
    throw std::invalid_argument("the two planes' records differ in length: " +
                                std::to_string(mx.size()) + " and " + std::to_string(my.size()) + " samples");
  const rm::Body bx(x), by(y);
  const rm::AdaptiveSettings ax = adaptive_settings(opt, mx), ay = adaptive_settings(opt, my);
  FidelityPlane px(bx, ax, mx, history_x), py(by, ay, my, history_y);
  const auto [fx, fy] = run_fidelity_pair(px, py, mx.size());
  return {adaptive_plane(opt, ax, fx, bx, mx), adaptive_plane(opt, ay, fy, by, my)};
}

void print_result(bool as_json, const PlaneRun& x, const PlaneRun* y, const rm::ItemVerdict& item,
                  const rm::CatalogueItem* item_entry, const EnsembleRun* ensemble, const SolidRun* solid) {
  // Who reached each level: a plane, or the 3-D model (then the item's verdict is the 3-D run's).
  auto reached_at = [&](rm::Level level) {
    return solid != nullptr ? solid->levels.at(level) : item.levels.at(level);
  };
  auto reached_by = [&](rm::Level level) -> std::string {
    return solid != nullptr ? solid->by[static_cast<int>(level)] : rm::to_string(item.plane[static_cast<int>(level)]);
  };
  const bool overturned = !std::isnan(reached_at(rm::Level::Overturned));
if (as_json) {
  json out = x.out;  // the top level stays the x plane's single-plane output
  json planes = {{"x", x.out}};
  planes["x"].erase("record");  // it is the top-level "record"
  if (y != nullptr) planes["y"] = y->out;  // its "record" is the y horizontal + the shared vertical
  out["planes"] = planes;
  json verdict = {{"plane_count", y != nullptr ? 2 : 1},
                  {"model", solid != nullptr && solid->decided ? "rocking_3d" : "planar"}};
  const std::pair<rm::Level, const char*> levels[] = {{rm::Level::BeyondTipping, "beyond_tipping"},
                                                      {rm::Level::Committed, "committed"},
                                                      {rm::Level::Overturned, "overturn"}};
  for (const auto& [level, name] : levels) {
    const bool reached = !std::isnan(reached_at(level));
    // "overturned" as the top-level flag, "overturn_time_s" as the top-level time
    verdict[level == rm::Level::Overturned ? std::string("overturned") : std::string(name)] = reached;
    verdict[std::string(name) + "_time_s"] = nullable(reached_at(level));
    verdict[std::string(name) + "_plane"] = reached ? json(reached_by(level)) : json(nullptr);
  }
  out["item"] = verdict;
  if (item_entry != nullptr) out["item"]["id"] = item_entry->spec.id;
  if (solid != nullptr) out["solid"] = solid->out;
  if (ensemble != nullptr) out["ensemble"] = ensemble->out;
  std::cout << json_text(out, 2) << "\n";
} else {
  const bool prefixed = y != nullptr || solid != nullptr;
  const std::string px = prefixed ? "[x] " : "", py = "[y] ", p3 = "[3d] ", indent = prefixed ? "    " : "";
  for (const std::string& line : x.lines) std::printf("%s%s\n", px.c_str(), line.c_str());
  if (y != nullptr)
    for (const std::string& line : y->lines) std::printf("%s%s\n", py.c_str(), line.c_str());
  if (solid != nullptr)
    for (const std::string& line : solid->lines) std::printf("%s%s\n", p3.c_str(), line.c_str());
  auto level_text = [&](rm::Level level) {
    const double t = reached_at(level);
    if (std::isnan(t)) return std::string("never");
    const std::string by = reached_by(level);
    return std::to_string(t) + " s (" + (by == "3d" ? std::string("3-D model") : by + " plane") + ")";
  };
  std::printf("%sitem        %s: beyond tipping %s, committed %s, overturned %s\n", indent.c_str(),
              overturned ? "OVERTURNED" : "survived",
              level_text(rm::Level::BeyondTipping).c_str(), level_text(rm::Level::Committed).c_str(),
              level_text(rm::Level::Overturned).c_str());
  if (ensemble != nullptr)
    for (const std::string& line : ensemble->lines) std::printf("%s%s\n", indent.c_str(), line.c_str());
}
}

}  // namespace rocking_monitor::tools::sim
