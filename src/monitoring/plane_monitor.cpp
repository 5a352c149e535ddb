#include "rocking_monitor/monitoring/plane_monitor.hpp"

#include <array>
#include <cmath>
#include <utility>
#include <stdexcept>
#include <string>

namespace rocking_monitor::core {
namespace {

constexpr std::uint8_t bit(Criterion c) { return static_cast<std::uint8_t>(1u << static_cast<int>(c)); }

}  // namespace

PlaneMonitor::PlaneMonitor(const BodyParameters& body, const Options& options)
    : options_(options),
      model_(Body(body), options.solver),
      thresholds_(screening_thresholds(model_.body())) {
  // Adaptive without a friction coefficient is pure rocking (AdaptiveModel never switches then):
  // run it as such, so that its validity criteria are flagged as under Fidelity::Rocking.
  const bool rocking_only = options.fidelity == Fidelity::Adaptive && std::isinf(model_.body().mu_s());
  if (options.fidelity != Fidelity::Rocking && !rocking_only) {
    AdaptiveSettings a;
    a.fidelity = options.fidelity;
    a.rocking = options.solver;
    a.scene = options.scene;
    a.linearized_max_alpha = options.linearized_max_alpha;
    adaptive_ = std::make_unique<AdaptiveModel>(model_.body(), a);
  }
}

void PlaneMonitor::make_intensity(double dt_nominal) {
  StreamingIntensityConfig cfg;
  cfg.dt = dt_nominal;
  cfg.periods = {housner_period(model_.body())};
  cfg.velocity_highpass_hz = std::min(options_.velocity_highpass_hz, 0.4 / dt_nominal);
  intensity_ = std::make_unique<StreamingIntensity>(cfg);
}

void PlaneMonitor::start(double t, double ax, double ay, double dt_nominal) {
  model_.reset(t, ax, ay);
  if (adaptive_) adaptive_->reset(t, ax, ay);
  make_intensity(dt_nominal);
  intensity_->push(ax);
  exceeded_.fill(false);
  slid_at_uplift_ = false;
  events_ = PlaneEvents{};
  started_ = true;
}

void PlaneMonitor::save(Saved& out) const {
  out.started = started_;
  if (!started_) return;
  out.dt_nominal = intensity_->config().dt;
  out.has_adaptive = adaptive_ != nullptr;
  if (adaptive_) adaptive_->save(out.adaptive);
  else model_.save(out.model);  // with the adaptive model it is never stepped
  intensity_->save(out.intensity);
  out.slid_at_uplift = slid_at_uplift_;
  out.last_switch_criterion = last_switch_criterion_;
  out.exceeded = exceeded_;
}

void PlaneMonitor::restore(const Saved& in) {
  if (in.started && in.has_adaptive != (adaptive_ != nullptr))
    throw std::invalid_argument(std::string("PlaneMonitor::restore: saved ") +
                                (in.has_adaptive ? "with" : "without") + " the adaptive model, this plane runs " +
                                (adaptive_ ? "it" : "pure rocking"));
  events_ = PlaneEvents{};
  started_ = in.started;
  if (!in.started) return;
  make_intensity(in.dt_nominal);
  intensity_->restore(in.intensity);
  if (adaptive_) adaptive_->restore(in.adaptive);
  else model_.restore(in.model);
  slid_at_uplift_ = in.slid_at_uplift;
  last_switch_criterion_ = in.last_switch_criterion;
  exceeded_ = in.exceeded;
}

std::uint8_t PlaneMonitor::violations() const {
  if (adaptive_) return 0;  // sliding and flight are modelled, not flagged
  std::uint8_t v = model_.violations();
  if (slid_at_uplift_) v |= bit(Criterion::SlideAtUplift);
  return v;
}

ItemMode PlaneMonitor::mode() const {
  if (adaptive_) {
    if (adaptive_->outcome().overturned) return ItemMode::Overturned;
    if (side() == 0) return ItemMode::Rest;  // at rest or sliding on both corners
  } else {
    switch (model_.mode()) {
      case Mode::Rest: return ItemMode::Rest;
      case Mode::Overturned: return ItemMode::Overturned;
      case Mode::Rocking: break;
    }
  }
  if (margin().committed) return ItemMode::Committed;
  if (rotation_ratio() > 1.0) return ItemMode::BeyondTipping;
  return ItemMode::Rocking;
}

int PlaneMonitor::side() const { return adaptive_ ? adaptive_->side() : model_.side(); }
double PlaneMonitor::theta() const { return adaptive_ ? adaptive_->theta() : model_.theta(); }
double PlaneMonitor::omega() const { return adaptive_ ? adaptive_->omega() : model_.omega(); }
double PlaneMonitor::slip() const { return adaptive_ ? adaptive_->slip() : 0.0; }
long PlaneMonitor::impacts() const { return adaptive_ ? adaptive_->outcome().impacts : model_.outcome().impacts; }
const char* PlaneMonitor::active_model() const {
  if (!adaptive_) return "rocking";
  if (adaptive_->active() == ActiveModel::Contact) return "contact";
  return adaptive_->linearized() ? "rocking_linearized" : "rocking";
}

double PlaneMonitor::rotation_ratio() const {
  const int s = side();
  return s == 0 ? 0.0 : std::abs(theta()) / model_.body().pivot(s).alpha;
}

OverturnMargin PlaneMonitor::margin() const {
  if (!adaptive_) return model_.margin();
  if (adaptive_->outcome().overturned) return {-1.0, true};
  const int s = side();
  if (s == 0) return {1.0, false};
  return overturn_margin(model_.body().pivot(s), s, ModelKind::Nonlinear, theta(), omega());
}

ContactMode PlaneMonitor::contact_mode() const {
  if (adaptive_) return adaptive_->mode();
  switch (model_.mode()) {
    case Mode::Rest: return ContactMode::Rest;
    case Mode::Rocking: return ContactMode::Rock;
    case Mode::Overturned: return ContactMode::Overturned;
  }
  return ContactMode::Rest;
}

void PlaneMonitor::record_change(CriterionId id, bool exceeded, double value, double threshold,
                                double second_value, double second_threshold) {
  exceeded_[static_cast<int>(id)] = exceeded;
  CriterionChange& c = events_.changes[events_.change_count++];
  c.id = id;
  c.exceeded = exceeded;
  c.value = value;
  c.threshold = threshold;
  c.second_value = second_value;
  c.second_threshold = second_threshold;
}

void PlaneMonitor::evaluate_criteria(double ax, double ay) {
  // Screening criteria on the running intensity (monotone: once exceeded they stay so).
  const double pga = intensity_->pga(), pgv = intensity_->pgv(), sv = intensity_->psv()[0];
  const ScreeningPrediction p = screening_prediction(thresholds_, pga, pgv, sv);
  auto screen = [&](CriterionId id, bool now, const IshiyamaThreshold* t) {
    if (now == exceeded_[static_cast<int>(id)]) return;
    if (t == nullptr) record_change(id, now, sv, thresholds_.housner_pseudo_velocity);
    else record_change(id, now, pgv, t->velocity, pga, t->acceleration);
  };
  screen(CriterionId::Housner, p.housner, nullptr);
  screen(CriterionId::Ishiyama, p.ishiyama, &thresholds_.ishiyama);
  screen(CriterionId::IshiyamaEquivalent, p.ishiyama_equivalent, &thresholds_.ishiyama_equivalent);
  screen(CriterionId::Proposed, p.proposed, &thresholds_.proposed);

  if (adaptive_) return;  // validity criteria are reported as model switches (report_switch)
  // Model validity: the model's bitmask at the end of the sample. The values reported with a change
  // need the contact reaction; compute it only when some validity criterion changed state.
  const std::uint8_t v = violations();
  constexpr std::array<std::pair<CriterionId, Criterion>, 4> kValidity = {{
      {CriterionId::FreeFlight, Criterion::FreeFlight},
      {CriterionId::SlideFromRest, Criterion::SlideFromRest},
      {CriterionId::SlideAtUplift, Criterion::SlideAtUplift},
      {CriterionId::SlideWhileRocking, Criterion::SlideWhileRocking},
  }};
  bool changed = false;
  for (const auto& [id, c] : kValidity) changed |= ((v & bit(c)) != 0) != exceeded_[static_cast<int>(id)];
  if (!changed) return;
  const Body& body = model_.body();
  const double mu = body.mu_s();
  double normal = ay + kGravity, ratio = std::abs(ax) / std::max(normal, 1e-12);
  double required_mu = 0.0;
  if (model_.mode() == Mode::Rocking) {
    const Pivot& pv = body.pivot(model_.side());
    const ContactReaction r = model_.reaction();  // at this sample: (ax, ay) are its inputs
    normal = r.ry;
    ratio = std::abs(r.rx) / std::max(r.ry, 1e-12);
    required_mu = rock_without_slip_friction(body, pv, std::abs(ax) / std::max(ay + kGravity, 1e-12));
  }
  for (const auto& [id, c] : kValidity) {
    const bool now = (v & bit(c)) != 0;
    if (now == exceeded_[static_cast<int>(id)]) continue;
    switch (id) {
      case CriterionId::FreeFlight: record_change(id, now, -normal, 0.0); break;
      case CriterionId::SlideAtUplift: record_change(id, now, required_mu, mu); break;
      default: record_change(id, now, ratio, mu); break;
    }
  }
}

// With adaptive fidelity the validity criteria are why the contact model runs: a switch up is reported
// as the criterion that caused it becoming exceeded, the switch down as it clearing.
void PlaneMonitor::report_switch(SwitchReason reason, bool to_contact) {
  CriterionId id;
  switch (reason) {
    case SwitchReason::SlideFromRest: id = CriterionId::SlideFromRest; break;
    case SwitchReason::SlideAtUplift: id = CriterionId::SlideAtUplift; break;
    case SwitchReason::FreeFlight:
    case SwitchReason::NearLiftOff: id = CriterionId::FreeFlight; break;
    case SwitchReason::SlideWhileRocking:
    case SwitchReason::SlipAtImpact:
    case SwitchReason::FrictionNearLimit: id = CriterionId::SlideWhileRocking; break;
    case SwitchReason::SharedFrictionCone:  // from rest the base slides, else the pivot
      id = adaptive_->mode() == ContactMode::Slide ? CriterionId::SlideFromRest : CriterionId::SlideWhileRocking;
      break;
    default: id = last_switch_criterion_; break;  // switch down: clear what switched up
  }
  if (to_contact) last_switch_criterion_ = id;
  if (exceeded_[static_cast<int>(id)] == to_contact) return;
  record_change(id, to_contact, 0.0, model_.body().mu_s());
}

const PlaneEvents& PlaneMonitor::step_after_model(double ax, double ay) {
  events_.change_count = 0;
  events_.alarm_count = 0;
  intensity_->push(ax);
  evaluate_criteria(ax, ay);
  return events_;
}

const PlaneEvents& PlaneMonitor::step(double ax, double ay, double dt) {
  events_.change_count = 0;
  events_.alarm_count = 0;
  auto alarm = [&](ItemMode level, double time) {
    AlarmEvent& a = events_.alarms[events_.alarm_count++];
    a.level = level;
    a.time = time;
    a.rotation_ratio = rotation_ratio();
  };
  if (adaptive_) {
    const AdaptiveOutcome& o = adaptive_->outcome();
    const bool tipped = o.beyond_tipping, committed = o.committed, overturned = o.overturned;
    const AdaptiveReport& rep = adaptive_->step(ax, ay, dt);
    intensity_->push(ax);
    evaluate_criteria(ax, ay);
    if (rep.switched) report_switch(rep.reason, adaptive_->active() == ActiveModel::Contact);
    if (!tipped && o.beyond_tipping) alarm(ItemMode::BeyondTipping, o.beyond_tipping_time);
    if (!committed && o.committed) alarm(ItemMode::Committed, o.committed_time);
    if (!overturned && o.overturned) alarm(ItemMode::Overturned, o.overturn_time);
    return events_;
  }
  const StepReport& r = model_.step(ax, ay, dt);
  intensity_->push(ax);
  if (r.violation_onsets & bit(Criterion::SlideAtUplift)) slid_at_uplift_ = true;
  if (model_.mode() == Mode::Rest) slid_at_uplift_ = false;
  evaluate_criteria(ax, ay);

  const RockingOutcome& o = model_.outcome();
  if (r.beyond_tipping_entered) alarm(ItemMode::BeyondTipping, o.beyond_tipping_time);
  if (r.committed_entered) alarm(ItemMode::Committed, o.committed_time);
  if (r.overturned) alarm(ItemMode::Overturned, o.overturn_time);
  return events_;
}

}  // namespace rocking_monitor::core
