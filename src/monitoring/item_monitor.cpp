#include "rocking_monitor/monitoring/item_monitor.hpp"

#include <stdexcept>
#include <string>

namespace rocking_monitor::core {
namespace {

const ItemSpec& checked(const ItemSpec& spec) {
  if (const std::string e = validate(spec); !e.empty()) throw std::invalid_argument(e);
  return spec;
}

int level_index(ItemMode m) { return static_cast<int>(m) - static_cast<int>(ItemMode::BeyondTipping); }

// A rectangle with its sides along the item's x and y (within 1e-6 of its size): the planar pair is
// exact for it under one component along a side.
bool axis_aligned_rectangle(const BaseBodyParameters& b) {
  if (b.base.size() != 4) return false;
  double size = 0.0;
  for (const auto& v : b.base) size = std::max(size, (v - b.base[0]).norm());
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector2d d = b.base[(i + 1) % 4] - b.base[i];
    if (std::min(std::abs(d.x()), std::abs(d.y())) > 1e-6 * size) return false;
  }
  return true;
}

}  // namespace

const char* to_string(SolidChoice choice) {
  switch (choice) {
    case SolidChoice::Planar: return "planar";
    case SolidChoice::Solid: return "3d";
    case SolidChoice::Auto: return "auto";
  }
  return "unknown";
}

bool parse_solid_choice(const std::string& text, SolidChoice& choice) {
  if (text == "planar") choice = SolidChoice::Planar;
  else if (text == "3d") choice = SolidChoice::Solid;
  else if (text == "auto") choice = SolidChoice::Auto;
  else return false;
  return true;
}

ItemMonitor::ItemMonitor(const ItemSpec& spec, const Options& options) : spec_(checked(spec)) {
  planes_[0] = std::make_unique<PlaneMonitor>(spec_.body, options);
  if (spec_.two_planes()) planes_[1] = std::make_unique<PlaneMonitor>(y_plane_body(spec_.body, spec_.depth), options);
  shares_friction_ = planes_[1] && planes_[0]->models_friction() && planes_[1]->models_friction();
  if (spec_.solid && options.solid != SolidChoice::Planar) {
    SolverSettings s = options.solver;
    s.method = Method::Dopri5;  // the 3-D model's only integrator
    s.model = ModelKind::Nonlinear;
    solid_ = std::make_unique<Rocking3DModel>(BaseBody(*spec_.solid), s);
    // A support (plinth, shelf, pedestal) is known to the 3-D model only: the planar pair would never
    // see the item reach its edge, so an item on one is the 3-D model's under every shaking.
    solid_always_ = options.solid == SolidChoice::Solid || !axis_aligned_rectangle(*spec_.solid) ||
                    !spec_.solid->support.empty();
    bidirectional_ratio_ = options.bidirectional_ratio;
  }
}

void ItemMonitor::start(double t, double ax, double ay, double az, double dt_nominal) {
  planes_[0]->start(t, ax, az, dt_nominal);
  if (planes_[1]) planes_[1]->start(t, ay, az, dt_nominal);
  last_input_[0] = {ax, az};
  last_input_[1] = {ay, az};
  alarmed_ = marked_;
  events_ = ItemEvents{};
  started_ = true;
  t_ = t;
  last_a_ = Eigen::Vector3d(ax, ay, az);
  peak_x_ = std::abs(ax);
  peak_y_ = std::abs(ay);
  if (solid_) {
    solid_->reset(t, last_a_);
    solid_active_ = solid_always_;
  }
}

void ItemMonitor::save(Saved& out) const {
  out.started = started_;
  if (!started_) return;
  out.two_planes = two_planes();
  for (int p = 0; p < plane_count(); ++p) planes_[p]->save(out.planes[p]);
  out.alarmed = alarmed_;
  out.last_input = last_input_;
  out.has_solid = solid_ != nullptr;
  if (solid_) solid_->save(out.solid);
  out.solid_active = solid_active_;
  out.peak_x = peak_x_;
  out.peak_y = peak_y_;
  out.t = t_;
  out.last_a = last_a_;
}

void ItemMonitor::restore(const Saved& in) {
  if (in.started && (in.two_planes != two_planes() || in.has_solid != (solid_ != nullptr)))
    throw std::invalid_argument("item '" + spec_.id + "': saved with " + (in.two_planes ? "two planes" : "one plane") +
                                (in.has_solid ? " and" : " without") + " the 3-D model, this monitor has " +
                                (two_planes() ? "two planes" : "one plane") + (solid_ ? " and" : " without") + " it");
  for (int p = 0; p < plane_count(); ++p) {
    try {
      planes_[p]->restore(in.started ? in.planes[p] : PlaneMonitor::Saved{});
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("item '" + spec_.id + "' plane " + to_string(static_cast<Plane>(p)) + ": " + e.what());
    }
  }
  events_ = ItemEvents{};
  started_ = in.started;
  if (!in.started) return;
  for (std::size_t l = 0; l < alarmed_.size(); ++l) alarmed_[l] = in.alarmed[l] || marked_[l];
  last_input_ = in.last_input;
  if (solid_) solid_->restore(in.solid);
  solid_active_ = in.solid_active;
  peak_x_ = in.peak_x;
  peak_y_ = in.peak_y;
  t_ = in.t;
  last_a_ = in.last_a;
}

const ItemEvents& ItemMonitor::step(double ax, double ay, double az, double dt) {
  return step_planes(ax, ay, az, dt, (1u << kPlaneCount) - 1);
}

const ItemEvents& ItemMonitor::step_planes(double ax, double ay, double az, double dt, unsigned planes,
                                           unsigned model_done) {
  events_.change_count = 0;
  events_.alarm_count = 0;
  if (solid_ && !solid_active_) {
    // Auto: the 3-D model takes over at rest once the shaking is bidirectional (reset when it does).
    peak_x_ = std::max(peak_x_, std::abs(ax));
    peak_y_ = std::max(peak_y_, std::abs(ay));
    if (solid_takes_over()) {
      solid_->reset(t_, last_a_);
      solid_active_ = true;
    }
  }
  share_friction(ax, ay, az, dt, planes, model_done);
  const PlaneEvents* ev[kPlaneCount] = {nullptr, nullptr};
  if (planes & 1u) {
    ev[0] = (model_done & 1u) ? &planes_[0]->step_after_model(ax, az) : &planes_[0]->step(ax, az, dt);
    last_input_[0] = {ax, az};
  }
  if (planes_[1] && (planes & 2u)) {
    ev[1] = (model_done & 2u) ? &planes_[1]->step_after_model(ay, az) : &planes_[1]->step(ay, az, dt);
    last_input_[1] = {ay, az};
  }
  for (int p = 0; p < kPlaneCount; ++p) {
    if (ev[p] == nullptr) continue;
    for (int i = 0; i < ev[p]->change_count; ++i) {
      CriterionChange& c = events_.changes[events_.change_count++];
      c = ev[p]->changes[i];
      c.plane = static_cast<Plane>(p);
    }
  }
  t_ += dt;
  last_a_ = Eigen::Vector3d(ax, ay, az);
  if (solid_active_) {
    step_solid(dt);
    return events_;
  }
  // Item-level alarms: each level once, from the plane that reached it first in this sample (tie: x).
  for (ItemMode level : {ItemMode::BeyondTipping, ItemMode::Committed, ItemMode::Overturned}) {
    const int l = level_index(level);
    if (alarmed_[l]) continue;
    const AlarmEvent* first = nullptr;
    Plane first_plane = Plane::X;
    for (int p = 0; p < kPlaneCount; ++p) {
      if (ev[p] == nullptr) continue;
      for (int i = 0; i < ev[p]->alarm_count; ++i) {
        const AlarmEvent& a = ev[p]->alarms[i];
        if (a.level == level && (first == nullptr || a.time < first->time)) {
          first = &a;
          first_plane = static_cast<Plane>(p);
        }
      }
    }
    if (first == nullptr) continue;
    alarmed_[l] = true;
    AlarmEvent& out = events_.alarms[events_.alarm_count++];
    out = *first;
    out.plane = first_plane;
  }
  return events_;
}

// The 3-D model's sample: it decides the item's levels (reported in the x plane's slot).
void ItemMonitor::step_solid(double dt) {
  const RockingOutcome& o = solid_->outcome();
  const bool tipped = o.beyond_tipping, committed = o.committed, overturned = o.overturned;
  solid_->step(last_a_, dt);
  auto alarm = [&](ItemMode level, bool before, bool now, double time) {
    const int l = level_index(level);
    if (before || !now || alarmed_[l]) return;
    alarmed_[l] = true;
    AlarmEvent& a = events_.alarms[events_.alarm_count++];
    a.level = level;
    // Sliding past the support's edge is the model's other way to overturn (rocking_3d.md "Supports
    // that end"): OVERTURNED, and COMMITTED at the same instant; the cause tells it from rocking over.
    const Rocking3DOutcome& o3 = solid_->outcome_3d();
    a.cause = o3.fell_off_support && time >= o3.fell_off_time ? AlarmCause::FellOffSupport : AlarmCause::Rocking;
    a.plane = Plane::X;
    a.time = time;
    a.rotation_ratio = solid_->rotation_ratio();
  };
  alarm(ItemMode::BeyondTipping, tipped, o.beyond_tipping, o.beyond_tipping_time);
  alarm(ItemMode::Committed, committed, o.committed, o.committed_time);
  alarm(ItemMode::Overturned, overturned, o.overturned, o.overturn_time);
}

FrictionShare ItemMonitor::friction_share_now(double ax, double ay, double az, double dt) const {
  const double x0[2] = {last_input_[0][0], last_input_[0][1]}, y0[2] = {last_input_[1][0], last_input_[1][1]};
  const double x1[2] = {ax, az}, y1[2] = {ay, az};
  return friction_share(*planes_[0]->adaptive(), *planes_[1]->adaptive(), x0, y0, x1, y1, dt);
}

// Before a sample: every plane's share of the budget from the state at its start. A plane the batch
// deferred (not in `planes`), or one whose model it stepped (`model_done`), was below the engaging
// demand with nothing slipping (MonitorBatch keeps an engaged item's planes stepping together): the
// whole budget, as without the batch.
void ItemMonitor::share_friction(double ax, double ay, double az, double dt, unsigned planes, unsigned model_done) {
  if (!shares_friction_) return;
  const unsigned all = (1u << kPlaneCount) - 1;
  const FrictionShare f = planes == all && model_done == 0 ? friction_share_now(ax, ay, az, dt) : FrictionShare{};
  for (int p = 0; p < kPlaneCount; ++p) planes_[p]->set_friction_share(f.share[p]);
}

bool ItemMonitor::solid_takes_over() const {
  return solid_ && !solid_active_ && mode() == ItemMode::Rest &&
         std::min(peak_x_, peak_y_) >= bidirectional_ratio_ * std::max(peak_x_, peak_y_) &&
         std::max(peak_x_, peak_y_) > 0.0;
}

void ItemMonitor::mark_alarmed(ItemMode level) {
  const int l = level_index(level);
  if (l < 0 || l >= static_cast<int>(marked_.size())) throw std::invalid_argument("mark_alarmed: not an alarm level");
  marked_[l] = alarmed_[l] = true;
}

void ItemMonitor::new_event(double t) {
  marked_.fill(false);
  alarmed_.fill(false);
  // The planes' last inputs (a batch that deferred samples keeps them there, not in t_ / last_a_).
  if (started_ && mode() == ItemMode::Rest)
    start(t, last_input_[0][0], last_input_[1][0], last_input_[0][1], planes_[0]->dt_nominal());
}

bool ItemMonitor::alarmed(ItemMode level) const {
  const int l = level_index(level);
  return l >= 0 && l < static_cast<int>(alarmed_.size()) && alarmed_[l];
}

ItemMode ItemMonitor::mode() const {
  if (solid_active_) {
    switch (solid_->mode()) {
      case Mode3D::Rest:
      case Mode3D::Slide: return ItemMode::Rest;  // flat on its base: sliding is not a tipping level
      case Mode3D::Overturned: return ItemMode::Overturned;
      default: break;
    }
    if (solid_->committed_now()) return ItemMode::Committed;
    return solid_->rotation_ratio() > 1.0 ? ItemMode::BeyondTipping : ItemMode::Rocking;
  }
  const ItemMode x = planes_[0]->mode();
  if (!planes_[1]) return x;
  const ItemMode y = planes_[1]->mode();
  return y > x ? y : x;
}

Plane ItemMonitor::worst_plane() const {
  if (!planes_[1]) return Plane::X;
  const ItemMode x = planes_[0]->mode(), y = planes_[1]->mode();
  if (y != x) return y > x ? Plane::Y : Plane::X;
  return planes_[1]->rotation_ratio() > planes_[0]->rotation_ratio() ? Plane::Y : Plane::X;
}

}  // namespace rocking_monitor::core
