#include "rocking_monitor/physics/body.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/physics/impact.hpp"

namespace rocking_monitor::core {
namespace {

std::string bad(const char* field, double value, const char* requirement) {
  char number[32];
  std::snprintf(number, sizeof number, "%.12g", value);
  return std::string("invalid body: ") + field + " = " + number + " (" + requirement + ")";
}

}  // namespace

std::string validate(const BodyParameters& p) {
  if (!std::isfinite(p.width) || p.width <= 0.0) return bad("width", p.width, "must be a finite length > 0 m");
  if (!std::isfinite(p.cg_height) || p.cg_height <= 0.0)
    return bad("cg_height", p.cg_height, "must be a finite length > 0 m");
  if (!std::isfinite(p.nu1) || p.nu1 <= 0.0 || p.nu1 >= 1.0)
    return bad("eccentricity nu1", p.nu1, "must lie strictly between 0 and 1");
  if (!std::isnan(p.radius_of_gyration) && (!std::isfinite(p.radius_of_gyration) || p.radius_of_gyration <= 0.0))
    return bad("radius_of_gyration", p.radius_of_gyration, "must be a finite length > 0 m");
  if (std::isnan(p.mu_s) || p.mu_s < 0.0) return bad("mu_s", p.mu_s, "must be >= 0 (inf = not given)");
  if (!std::isnan(p.mu_k) && (p.mu_k < 0.0 || !std::isfinite(p.mu_k)))
    return bad("mu_k", p.mu_k, "must be a finite value >= 0");
  if (!std::isnan(p.restitution) && (p.restitution < 0.0 || p.restitution > 1.0))
    return bad("restitution", p.restitution, "angular-velocity ratio must lie in [0, 1]");
  if (!std::isfinite(p.restitution_shift) || p.restitution_shift < -1.0 || p.restitution_shift > 1.0)
    return bad("restitution_shift", p.restitution_shift, "must lie in [-1, 1]");
  if (!std::isfinite(p.overturn_angle) || p.overturn_angle <= 0.0 || p.overturn_angle > kPi)
    return bad("overturn_angle", p.overturn_angle, "must lie in (0, pi] rad");
  return {};
}

double Body::homogeneous_radius_of_gyration(double width, double cg_height) {
  return std::sqrt((width * width + 4.0 * cg_height * cg_height) / 12.0);
}

Body::Body(const BodyParameters& parameters) : params_(parameters) {
  if (const std::string error = validate(params_); !error.empty()) throw BodyError(error);
  ig_ = std::isnan(params_.radius_of_gyration)
            ? homogeneous_radius_of_gyration(params_.width, params_.cg_height)
            : params_.radius_of_gyration;
  pivot1_ = make_pivot(params_.nu1, 1.0 - params_.nu1);
  pivot2_ = make_pivot(1.0 - params_.nu1, params_.nu1);
  for (const Pivot* pv : {&pivot1_, &pivot2_}) {
    if (pv->alpha >= params_.overturn_angle)
      throw BodyError(bad("overturn_angle", params_.overturn_angle, "must exceed the tipping angle alpha"));
  }
}

bool Body::uses_theoretical_restitution() const { return std::isnan(params_.restitution); }

Pivot Body::make_pivot(double nu, double /*nu_other*/) const {
  const double b = params_.width;
  const double h = params_.cg_height;
  Pivot pv;
  pv.nu = nu;
  pv.alpha = std::atan2(nu * b, h);
  pv.radius = std::hypot(nu * b, h);
  pv.inertia = ig_ * ig_ + pv.radius * pv.radius;
  pv.p2 = kGravity * pv.radius / pv.inertia;
  pv.p = std::sqrt(pv.p2);
  pv.sin_alpha = std::sin(pv.alpha);
  pv.cos_alpha = std::cos(pv.alpha);
  pv.tan_alpha = nu * b / h;
  pv.gamma = h / (nu * b);
  // A negative ratio means the body cannot keep rocking after the impact (it stops).
  pv.restitution = std::isnan(params_.restitution)
                       ? impact_velocity_ratio(ig_ * ig_, h, b, nu)
                       : params_.restitution;
  if (params_.restitution_shift != 0.0)
    pv.restitution = std::clamp(pv.restitution + params_.restitution_shift, 0.0, 1.0);
  return pv;
}

}  // namespace rocking_monitor::core
