#include "rocking_sim_solid.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <fstream>
#include <optional>
#include <stdexcept>

#include "rocking_monitor/csv/csv_writer.hpp"
#include "rocking_sim_output.hpp"

namespace rocking_monitor::tools::sim {

namespace {

int level_of(rm::ItemMode m) { return static_cast<int>(m) - static_cast<int>(rm::ItemMode::BeyondTipping); }

json body_json(const rm::BaseBody& b) {
  json base = json::array();
  for (int i = 0; i < b.vertex_count(); ++i) base.push_back({b.vertex(i).position.x(), b.vertex(i).position.y()});
  const Eigen::Vector3d& c = b.centre_of_mass();
  return {{"vertices", b.vertex_count()},
          {"base_polygon_m", base},
          {"centre_of_mass_m", {c.x(), c.y(), c.z()}},
          {"min_alpha_rad", b.min_alpha()},
          {"restitution_factor", b.restitution_factor()}};
}

}  // namespace

// Every mode change of the 3-D model, located and named (the first Rocking3DModel::kMaxTransitionRecords).
json transitions_json(const rm::Rocking3DModel& m) {
  json out = json::array();
  for (int i = 0; i < m.transition_records(); ++i) {
    const rm::Transition3DRecord& r = m.transition(i);
    out.push_back({{"t_s", r.time}, {"from", rm::to_string(r.from)}, {"to", rm::to_string(r.to)},
                   {"reason", rm::to_string(r.reason)}, {"contact", r.contact}});
  }
  return out;
}

void transition_lines(const rm::Rocking3DModel& m, std::vector<std::string>& lines) {
  constexpr int kListed = 10;
  lines.push_back(format("transitions %ld (%d in the JSON's \"transitions\")%s", m.outcome_3d().transitions,
                         m.transition_records(), m.transition_records() > kListed ? "; the first 10:" : ":"));
  for (int i = 0; i < std::min(m.transition_records(), kListed); ++i) {
    const rm::Transition3DRecord& r = m.transition(i);
    lines.push_back(format("  %10.4f s  %s -> %s  %s", r.time, rm::to_string(r.from), rm::to_string(r.to),
                           rm::to_string(r.reason)));
  }
}

rm::ItemMonitor::Options monitor_options(const RunOptions& opt, const rm::GroundMotion& mx,
                                         const rm::GroundMotion* my) {
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
  return o;
}

namespace {

double y_accel(const rm::GroundMotion* my, std::size_t i) { return my != nullptr ? my->horizontal[i] : 0.0; }
double z_accel(const rm::GroundMotion& mx, std::size_t i) { return mx.vertical.empty() ? 0.0 : mx.vertical[i]; }

// --history-3d: one row per sample of the 3-D model's state (nothing when the path is empty).
class SolidHistory {
 public:
  SolidHistory(const std::string& path) : path_(path) {
    if (path.empty()) return;
    file_.open(path);
    if (!file_) throw std::runtime_error(path + ": cannot open for writing");
    file_ << "time_s,ax_mps2,ay_mps2,az_mps2,model,mode,contact,tilt_rad,rotation_ratio,"
             "qw,qx,qy,qz,wx_radps,wy_radps,wz_radps,slip_x_m,slip_y_m\n";
    row_.emplace(file_);
  }
  void write(double t, std::size_t i, const rm::ItemMonitor& item, const rm::GroundMotion& mx,
             const rm::GroundMotion* my) {
    if (!row_) return;
    const rm::Rocking3DModel& model = *item.solid();
    const Eigen::Quaterniond q(model.rotation());
    const Eigen::Vector3d w = model.angular_velocity();
    row_->number("%.6f", t).number("%.9g", mx.horizontal[i]).number("%.9g", y_accel(my, i)).number("%.9g", z_accel(mx, i));
    row_->text(item.solid_active() ? "3d" : "planar").text(rm::to_string(model.mode()));
    row_->value(std::to_string(model.contact())).number("%.12g", model.tilt()).number("%.9g", model.rotation_ratio());
    row_->number("%.12g", q.w()).number("%.12g", q.x()).number("%.12g", q.y()).number("%.12g", q.z());
    row_->number("%.12g", w.x()).number("%.12g", w.y()).number("%.12g", w.z());
    const Eigen::Vector2d slip = model.slip();  // the centre of mass's horizontal displacement (issue 51)
    row_->number("%.12g", slip.x()).number("%.12g", slip.y());
    row_->end_row();
  }
  void finish() {
    if (file_ && !file_.flush()) throw std::runtime_error(path_ + ": write failed");
  }

 private:
  std::string path_;
  std::ofstream file_;
  std::optional<rm::csv::Writer> row_;
};

// The item through the records, as the node steps it: the levels its alarms reach and by which
// model into `run`. Returns when the 3-D model took over (NaN: never); `cpu` its CPU time, s.
double step_solid(rm::ItemMonitor& item, const rm::GroundMotion& mx, const rm::GroundMotion* my,
                  SolidHistory& history, SolidRun& run, double& cpu) {
  double taken_over = item.solid_active() ? 0.0 : std::nan("");
  const std::clock_t start = std::clock();
  item.start(0.0, mx.horizontal.front(), y_accel(my, 0), z_accel(mx, 0), mx.dt);
  if (item.solid_active()) taken_over = 0.0;
  history.write(0.0, 0, item, mx, my);
  for (std::size_t i = 1; i < mx.size(); ++i) {
    const rm::ItemEvents& ev = item.step(mx.horizontal[i], y_accel(my, i), z_accel(mx, i), mx.dt);
    const double t = static_cast<double>(i) * mx.dt;
    if (item.solid_active() && std::isnan(taken_over)) taken_over = t - mx.dt;  // at rest, before the sample
    for (int k = 0; k < ev.alarm_count; ++k) {
      const rm::AlarmEvent& a = ev.alarms[static_cast<std::size_t>(k)];
      const int l = level_of(a.level);
      if (l < 0 || l >= rm::kLevelCount || run.levels.reached(static_cast<rm::Level>(l))) continue;
      run.levels.time[static_cast<std::size_t>(l)] = a.time;
      run.by[static_cast<std::size_t>(l)] = item.solid_active() ? "3d" : rm::to_string(a.plane);
    }
    history.write(t, i, item, mx, my);
  }
  cpu = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  return taken_over;
}

// The 3-D model's JSON block: levels, impacts, landings, sliding, support, hull, transitions, cost.
json solid_json(const rm::Rocking3DModel& model, rm::SolidChoice choice, bool decided, double taken_over,
                std::size_t samples, double cpu) {
  const rm::RockingOutcome& r = model.outcome();
  const rm::Rocking3DOutcome& r3 = model.outcome_3d();
  json out = outcome_json(r);
  out.update({{"model", "rocking_3d"},
              {"solid_model", rm::to_string(choice)},
              {"in_charge", decided},
              {"in_charge_from_s", nullable(taken_over)},
              {"max_tilt_rad", r3.max_tilt},
              {"edge_to_vertex", r3.edge_to_vertex},
              {"vertex_impacts", r3.vertex_impacts},
              {"flat_impacts", r3.flat_impacts},
              {"edge_captures", r3.edge_captures},
              {"max_landing_violation_m_s", r3.max_landing_violation},
              {"max_friction_demand", r3.max_friction_demand},
              {"slipping_landings", r3.slipping_landings},
              {"frictional_landings", r3.frictional_landings},
              {"landing_slides", r3.landing_slides},
              {"pivot_slip_landings", r3.pivot_slip_landings},
              {"unresolved_landings", r3.unresolved_landings},
              {"max_pivot_friction_demand", r3.max_pivot_friction_demand},
              {"pivot_slips", r3.pivot_slips},
              {"pivot_lifts", r3.pivot_lifts},
              {"first_pivot_slip_time_s", nullable(r3.first_pivot_slip_time)},
              {"pivot_sticks", r3.pivot_sticks},
              {"pivot_slip_time_s", r3.pivot_slip_time},
              {"pivot_slip_distance_m", r3.pivot_slip_distance},
              {"pivot_slips_not_followed", r3.pivot_slips_not_followed},
              {"pulled_pivots", r3.pulled_pivots},
              {"flights", r3.flights},
              {"first_flight_time_s", nullable(r3.first_flight_time)},
              {"flight_time_s", r3.flight_time},
              {"max_flight_height_m", r3.max_flight_height},
              {"flight_landings", r3.flight_landings},
              {"corner_slip_landings", r3.corner_slip_landings},
              {"final_mode", rm::to_string(model.mode())},
              {"final_contact", model.contact()},
              {"final_face", model.face()},
              {"hull_faces", model.body().contact_hull().from_hull ? static_cast<long>(model.body().contact_hull().faces.size()) : 0L},
              {"hull_landings", r3.hull_landings},
              {"rests_off_base", r3.rests_off_base},
              {"slides", r3.slides},
              {"sticks", r3.sticks},
              {"slide_to_rock", r3.slide_to_rock},
              {"first_slip_time_s", nullable(r3.first_slip_time)},
              {"max_slip_m", r3.max_slip},
              {"final_slip_m", model.slip().norm()},
              {"max_slip_speed_m_s", r3.max_slip_speed},
              {"max_twist_rad", r3.max_twist},
              {"slip_time_s", r3.slip_time},
              {"fell_off_support", r3.fell_off_support},
              {"fell_off_time_s", nullable(r3.fell_off_time)},
              {"slides_over_support_edge", r3.slides_over_support_edge},
              {"lip_trips", r3.lip_trips},
              {"lip_holds", r3.lip_holds},
              {"lip_slipping_trips", r3.lip_slipping_trips},
              {"lip_ends_passed", r3.lip_ends_passed},
              {"max_lip_overhang_m", r3.max_lip_overhang},
              {"lip_face_impacts", r3.lip_face_impacts},
              {"lip_faces_not_followed", r3.lip_faces_not_followed},
              {"pedestal_beyond_base", r3.pedestal_beyond_base},
              {"vertex_refits", r3.vertex_refits},
              {"forced_overturns", r3.forced_overturns},
              {"forced_rests", r.forced_rest_captures},
              {"support_margin_m", nullable(model.support_margin())},
              {"transitions_total", r3.transitions},
              {"transitions", transitions_json(model)},
              {"samples", samples},
              {"cpu_time_s", cpu},
              {"body", body_json(model.body())}});
  return out;
}

// The text lines of what happened: result, impacts, landings, sliding.
void solid_motion_lines(const rm::Rocking3DModel& model, std::vector<std::string>& L) {
  const rm::RockingOutcome& r = model.outcome();
  const rm::Rocking3DOutcome& r3 = model.outcome_3d();
  L.push_back(format("result      %s, final mode %s, max tilt %.5f rad, max |theta|/alpha %.4f",
                     r.overturned ? "OVERTURNED" : "survived", rm::to_string(model.mode()), r3.max_tilt,
                     r.max_rotation_ratio));
  L.push_back(format("impacts     %ld (flat %ld, on a vertex %ld, from flight %ld), edge-to-vertex lifts %ld", r.impacts,
                     r3.flat_impacts, r3.vertex_impacts, r3.flight_landings, r3.edge_to_vertex));
  L.push_back(format("landings    friction demand up to %.3f (%ld above mu_s), largest violation of the sticking "
                     "law %.2g m/s; friction decided %ld: %ld slid on flat, %ld with a slipping pivot (slide-rock, "
                     "followed as sticking), %ld unresolved", r3.max_friction_demand, r3.slipping_landings,
                     r3.max_landing_violation, r3.frictional_landings, r3.landing_slides, r3.pivot_slip_landings,
                     r3.unresolved_landings));
  L.push_back(format("pivot       friction demand while rocking up to %.3f; %ld slip onsets, %ld lift-offs (first at "
                     "%s); on a vertex slide-rock for %.3f s over %.4f m, %ld sticks (on an edge followed as sticking; "
                     "lift-offs not flown without mu_s or on a support); %ld times held down by a pull outside the cone",
                     r3.max_pivot_friction_demand, r3.pivot_slips, r3.pivot_lifts,
                     std::isnan(r3.first_pivot_slip_time) ? "-" : format("%.4f s", r3.first_pivot_slip_time).c_str(),
                     r3.pivot_slip_time, r3.pivot_slip_distance, r3.pivot_sticks, r3.pulled_pivots));
  L.push_back(format("sliding     %ld slip onsets from rest and %ld from landings (the first at %s), %ld sticks; max "
                     "slip %.4f m, final %.4f m, max slip speed %.3f m/s, max twist %.4f rad, %.3f s sliding; %ld slides "
                     "ended by an edge lifting", r3.slides, r3.landing_slides,
                     std::isnan(r3.first_slip_time) ? "-" : format("%.4f s", r3.first_slip_time).c_str(),
                     r3.sticks, r3.max_slip, model.slip().norm(), r3.max_slip_speed, r3.max_twist, r3.slip_time,
                     r3.slide_to_rock));
  L.push_back(format("flight      %ld lift-offs (the first at %s), %.4f s in the air, lowest point up to %.4f m above the "
                     "floor, %ld landings from it (%ld on a corner that slipped on)", r3.flights,
                     std::isnan(r3.first_flight_time) ? "-" : format("%.4f s", r3.first_flight_time).c_str(),
                     r3.flight_time, r3.max_flight_height, r3.flight_landings, r3.corner_slip_landings));
}

// The support's and the hull's lines, for a body that has them.
void solid_support_and_hull_lines(const rm::Rocking3DModel& model, std::vector<std::string>& L) {
  const rm::Rocking3DOutcome& r3 = model.outcome_3d();
  if (!model.body().parameters().support.empty())
    L.push_back(r3.fell_off_support
                    ? format("support     FELL OFF its support at %.4f s (over its edge); %ld slides braking within mu_k h "
                             "of its edge (slide-rock over it, followed as sliding)", r3.fell_off_time, r3.slides_over_support_edge)
                    : format("support     stayed on its support: the centre of mass %.4f m inside its edge at the end; %ld "
                             "slides braking within mu_k h of its edge (slide-rock over it, followed as sliding)",
                             model.support_margin(), r3.slides_over_support_edge));
  if (!model.body().parameters().support_lips.empty())
    L.push_back(format("lips        %ld slides tripped over a lip (%ld of them needing more than mu_s at its foot), %ld held "
                       "by one (sliding along it); corners over a lip by up to %.4f m (swung over it in the air, "
                       "turning on a corner); %ld met a lip's line beyond its end; %ld lifted corners met a lip's face "
                       "(%ld samples at the bound on them)", r3.lip_trips, r3.lip_slipping_trips, r3.lip_holds,
                       r3.max_lip_overhang, r3.lip_ends_passed, r3.lip_face_impacts, r3.lip_faces_not_followed));
  if (!model.body().parameters().support.empty() && r3.vertex_refits > 0)
    L.push_back(format("support     the contact cut again %ld times pivoting on a corner, where the body had turned on it",
                       r3.vertex_refits));
  if (r3.forced_overturns > 0)
    L.push_back(format("events      the bound on events per sample reached beyond the tipping point: overturned there (%ld)",
                       r3.forced_overturns));
  if (model.outcome().forced_rest_captures > 0)
    L.push_back(format("events      the bound on events per sample reached below the tipping point: put down flat there (%ld)",
                       model.outcome().forced_rest_captures));
  if (model.body().contact_hull().from_hull)
    L.push_back(format("hull        %zu faces, %zu vertices; %ld landings onto another face, %ld rests off the base; "
                       "ends on %s", model.body().contact_hull().faces.size(), model.body().contact_hull().vertices.size(),
                       r3.hull_landings, r3.rests_off_base,
                       model.mode() == rm::Mode3D::Overturned ? "its side (overturned)"
                       : model.face() == 0                     ? "its base"
                                                               : ("hull face " + std::to_string(model.face())).c_str()));
  if (!model.body().parameters().support.empty() && !model.body().parameters().hull.empty())
    L.push_back(format("hull        on its pedestal the contact is the pedestal's top: its hull cannot land there%s",
                       r3.pedestal_beyond_base == 0
                           ? ""
                           : format("; %ld contacts cut where it had slid or turned so that the pedestal reached beyond "
                                    "its base, where the hull could land (not modelled: it rocks on its base there)",
                                    r3.pedestal_beyond_base).c_str()));
}

}  // namespace

SolidRun run_solid(const RunOptions& opt, const rm::ItemSpec& spec, rm::SolidChoice choice,
                   double bidirectional_ratio, const rm::GroundMotion& mx, const rm::GroundMotion* my,
                   const std::string& history_path) {
  if (!spec.solid) throw std::invalid_argument("item '" + spec.id + "' has no 3-D description");
  rm::ItemMonitor::Options o = monitor_options(opt, mx, my);
  o.solid = choice;
  o.bidirectional_ratio = bidirectional_ratio;
  rm::ItemMonitor item(spec, o);
  const rm::Rocking3DModel& model = *item.solid();
  SolidHistory history(history_path);
  SolidRun run;
  double cpu = 0.0;
  const double taken_over = step_solid(item, mx, my, history, run, cpu);
  history.finish();
  run.decided = !std::isnan(taken_over);
  run.out = solid_json(model, choice, run.decided, taken_over, mx.size(), cpu);
  auto& L = run.lines;
  L.push_back(format("body        %d-vertex base, centre of mass (%.4f, %.4f, %.4f) m, smallest edge alpha "
                     "%.4f rad", model.body().vertex_count(), model.body().centre_of_mass().x(),
                     model.body().centre_of_mass().y(), model.body().centre_of_mass().z(), model.body().min_alpha()));
  L.push_back(run.decided ? format("model       rocking_3d in charge from %.4f s (--solid-model %s)", taken_over,
                                   rm::to_string(choice))
                          : format("model       the planar pair decided (--solid-model auto: a rectangle, the "
                                   "shaking never bidirectional at ratio %.2f)", bidirectional_ratio));
  solid_motion_lines(model, L);
  solid_support_and_hull_lines(model, L);
  transition_lines(model, L);
  L.push_back(format("cost        %zu samples, %.4f s CPU", mx.size(), cpu));
  return run;
}

}  // namespace rocking_monitor::tools::sim
