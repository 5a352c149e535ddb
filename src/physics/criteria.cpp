#include "rocking_monitor/physics/criteria.hpp"

#include <algorithm>
#include <cmath>

namespace rocking_monitor::core {

const char* to_string(Criterion criterion) {
  switch (criterion) {
    case Criterion::FreeFlight: return "free_flight";
    case Criterion::SlideFromRest: return "slide_from_rest";
    case Criterion::SlideAtUplift: return "slide_at_uplift";
    case Criterion::SlideWhileRocking: return "slide_while_rocking";
  }
  return "unknown";
}

double acceleration_ratio(double ax, double ay) { return ax / (ay + kGravity); }

double uplift_function(const Pivot& pv, int side, ModelKind model, double ax, double ay) {
  if (model == ModelKind::Linearized) return side * ax - (ay + kGravity) * pv.alpha;
  return side * ax * pv.cos_alpha - (ay + kGravity) * pv.sin_alpha;
}

int uplift_side(const Body& body, double ax, double ay, ModelKind model) {
  const int preferred = tipping_side(ax);
  if (uplift_function(body.pivot(preferred), preferred, model, ax, ay) > 0.0) return preferred;
  // Only possible in free flight (a_yg + g < 0): both corners "lift"; eq. 12-13 picks the side.
  if (uplift_function(body.pivot(-preferred), -preferred, model, ax, ay) > 0.0) return -preferred;
  return 0;
}

bool slides_from_rest(const Body& body, double ax, double ay) {
  if (std::isinf(body.mu_s())) return false;
  const double normal = ay + kGravity;
  return std::abs(ax) > body.mu_s() * std::max(normal, 0.0);
}

double rock_without_slip_friction(const Body& body, const Pivot& pv, double abs_a) {
  const double nub = pv.nu * body.width();
  const double k = body.radius_of_gyration() * body.radius_of_gyration() / (nub * nub);
  const double gamma = pv.gamma;
  return (abs_a * k + abs_a + gamma) / (k + abs_a * gamma + gamma * gamma);  // eq. 25
}

bool slides_while_rocking(const ContactReaction& reaction, double mu_s) {
  if (std::isinf(mu_s)) return false;
  return std::abs(reaction.rx) > mu_s * std::max(reaction.ry, 0.0);
}

double housner_pseudo_velocity(double alpha, double r) {
  return std::sqrt(8.0 / 3.0 * kGravity * r * (1.0 - std::cos(alpha))) / std::cos(alpha);
}

IshiyamaThreshold ishiyama_threshold(double base, double cg_height, double coefficient) {
  const double height = 2.0 * cg_height;
  const double alpha = std::atan2(base, height);
  const double r = 0.5 * std::hypot(base, height);
  return {coefficient * housner_pseudo_velocity(alpha, r), base / height * kGravity};
}

double housner_period(const Body& body) {
  const Pivot& weak = body.pivot(1).alpha <= body.pivot(-1).alpha ? body.pivot(1) : body.pivot(-1);
  return 2.0 * kPi / weak.p;
}

ScreeningThresholds screening_thresholds(const Body& body) {
  const Pivot& weak = body.pivot(1).alpha <= body.pivot(-1).alpha ? body.pivot(1) : body.pivot(-1);
  ScreeningThresholds t;
  t.housner_pseudo_velocity = housner_pseudo_velocity(weak.alpha, weak.radius);
  t.ishiyama = ishiyama_threshold(body.width(), body.cg_height(), 0.4);
  t.ishiyama_equivalent = ishiyama_threshold(2.0 * weak.nu * body.width(), body.cg_height(), 0.4);
  t.proposed = ishiyama_threshold(body.width(), body.cg_height(), 0.2);
  return t;
}

ScreeningPrediction screening_prediction(const ScreeningThresholds& t, double pga, double pgv,
                                         double spectral_pseudo_velocity) {
  auto ishiyama = [&](const IshiyamaThreshold& th) {
    return pgv > th.velocity && pga >= th.acceleration;
  };
  ScreeningPrediction p;
  p.housner = spectral_pseudo_velocity >= t.housner_pseudo_velocity;
  p.ishiyama = ishiyama(t.ishiyama);
  p.ishiyama_equivalent = ishiyama(t.ishiyama_equivalent);
  p.proposed = ishiyama(t.proposed);
  return p;
}

}  // namespace rocking_monitor::core
