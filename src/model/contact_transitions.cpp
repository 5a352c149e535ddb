// ContactModel's transitions between phases: set_mode (with the episode counters), the entries
// into ROCK / SLIDE-ROCK (enter_pivot, project_rock, consistent_sigma) and into REST / SLIDE
// (enter_flat), impacts and landings, and leaving REST.
#include "rocking_monitor/model/contact_model.hpp"

#include <algorithm>
#include <cmath>

#include "contact_model_internal.hpp"
#include "rocking_monitor/physics/impact.hpp"

namespace rocking_monitor::core {

namespace {
inline int sgn(double v) { return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0); }
inline bool slipping(ContactMode m) { return m == ContactMode::Slide || m == ContactMode::SlideRock; }
}  // namespace

void ContactModel::set_mode(ContactMode m, int side, int sigma, double tau) {
  const ContactMode old = mode_;
  if (slipping(m) && !slipping(old)) {
    ++report_.slip_episodes;
    ++outcome_.slip_episodes;
    if (std::isnan(outcome_.first_slip_time)) outcome_.first_slip_time = t_ + tau;
  }
  if (m == ContactMode::Flight && old != ContactMode::Flight) {
    ++report_.flight_episodes;
    ++outcome_.flight_episodes;
    if (std::isnan(outcome_.first_flight_time)) outcome_.first_flight_time = t_ + tau;
  }
  if (pivoting(m) && (old == ContactMode::Rest || old == ContactMode::Slide) &&
      std::isnan(outcome_.first_uplift_time))
    outcome_.first_uplift_time = t_ + tau;
  mode_ = m;
  side_ = pivoting(m) ? side : 0;
  sigma_ = sigma;
  if (m == ContactMode::Rock) {
    double rx, ry;
    corner(side_, x_, rx, ry);
    pivot_x_ = x_[0] + rx;
  }
}

// Puts the state exactly on the pure-rocking manifold (pivot fixed at pivot_x_, y_pivot = 0).
void ContactModel::project_rock() {
  double rx, ry;
  corner(side_, x_, rx, ry);
  x_[0] = pivot_x_ - rx;
  x_[4] = -ry;
  x_[1] = x_[3] * ry;   // v_c = v_pivot(=0) - w x r
  x_[5] = -x_[3] * rx;
}

// Slip direction for slide-rock starting from a sticking pivot: the one whose pivot acceleration
// agrees with it (Coulomb consistency); -sgn(R_x) first.
int ContactModel::consistent_sigma(int side, const GroundInput& in, double tau) const {
  double rx_req;
  rock_friction_ok(in, tau, side, rx_req);
  const int first = rx_req > 0.0 ? -1 : 1;
  const double G = in.ay(tau) + kGravity;
  double rx, ry;
  corner(side, x_, rx, ry);
  for (int sigma : {first, -first}) {
    double normal;
    const double acc = slide_rock_theta_ddot(side, sigma, G, x_, normal);
    const double xdd = -in.ax(tau) - sigma * mu_k_ * normal;
    const double a_pivot = xdd - acc * ry - x_[3] * x_[3] * rx;
    if (sigma * a_pivot > 0.0) return sigma;
  }
  return first;
}

void ContactModel::enter_pivot(int side, const GroundInput& in, double tau) {
  double rx, ry;
  corner(side, x_, rx, ry);
  const double vp = x_[1] - x_[3] * ry;
  const double v_scale = 1e-9 * (std::abs(x_[1]) + std::abs(x_[3]) * body_.pivot(side).radius);
  if (std::abs(vp) > v_scale && !std::isinf(mu_k_)) {
    set_mode(ContactMode::SlideRock, side, sgn(vp), tau);
    return;
  }
  x_[1] = x_[3] * ry;  // pivot slip velocity exactly zero
  double rx_req;
  if (rock_friction_ok(in, tau, side, rx_req)) {
    set_mode(ContactMode::Rock, side, 0, tau);
    project_rock();
  } else {
    set_mode(ContactMode::SlideRock, side, consistent_sigma(side, in, tau), tau);
  }
}

// Both corners on the floor: theta = omega = y' = 0. Keeps the horizontal CoM velocity (so the
// kinetic energy cannot increase); a velocity below the rest-capture scale is zeroed.
void ContactModel::enter_flat(const GroundInput& in, double tau) {
  const double x_base = slip();
  x_[2] = 0.0;
  x_[3] = 0.0;
  x_[4] = body_.cg_height();
  x_[5] = 0.0;
  x_[0] = x_base + body_.nu1() * body_.width();
  const Pivot& pv = body_.pivot(1);
  const double v_tiny = settings_.rest_capture_ratio * pv.p * pv.alpha * pv.radius;
  // Without a kinetic friction limit the base cannot slide: friction stops it at once (an impulse).
  // (Before: a landing with a leftover horizontal velocity entered Slide, which ran to infinity.)
  if (std::abs(x_[1]) <= v_tiny || std::isinf(mu_k_)) x_[1] = 0.0;
  const double ax = in.ax(tau), G = in.ay(tau) + kGravity;
  if (x_[1] != 0.0) {
    set_mode(ContactMode::Slide, 0, sgn(x_[1]), tau);
  } else if (std::isinf(mu_s_) || std::abs(ax) <= mu_s_ * std::max(G, 0.0)) {
    set_mode(ContactMode::Rest, 0, 0, tau);
  } else {
    set_mode(ContactMode::Slide, 0, -sgn(ax), tau);
  }
}

// Impact at corner c: perfectly plastic in the normal direction, Coulomb friction on the
// tangential impulse (stick if |P_x| <= mu_s P_y, else P_x = -sigma mu_k P_y). The angular
// momentum about the contact corner is conserved in both cases (the impulse acts there); for a
// sticking impact from pure rocking this is exactly eq. 34.
void ContactModel::impact(int c, const GroundInput& in, double tau, bool from_flight) {
  ++report_.impacts;
  ++outcome_.impacts;
  double& vx = x_[1];
  double& vy = x_[5];
  double& w = x_[3];
  if (from_flight && x_[2] == 0.0 && w == 0.0) {  // flat landing on both corners
    const double py = std::max(-vy, 0.0);
    vy = 0.0;
    if (std::isinf(mu_s_) || std::abs(vx) <= mu_s_ * py) vx = 0.0;
    else vx -= sgn(vx) * std::min(mu_k_ * py, std::abs(vx));
    enter_flat(in, tau);
    return;
  }
  double rx, ry;
  corner(c, x_, rx, ry);
  const double w_before = w;
  const double vcx = vx - w * ry, vcy = vy + w * rx;
  const double a11 = 1.0 + ry * ry / ig2_, a12 = -rx * ry / ig2_, a22 = 1.0 + rx * rx / ig2_;
  const double det = a11 * a22 - a12 * a12;
  double px = (-vcx * a22 + vcy * a12) / det;
  double py = (-vcy * a11 + vcx * a12) / det;
  bool stick = py >= 0.0 && (std::isinf(mu_s_) || std::abs(px) <= mu_s_ * py);
  if (py < 0.0) {  // separating: no impulse
    px = py = 0.0;
  } else if (!stick) {
    const int sigma = sgn(vcx);
    const double denom = a22 - sigma * mu_k_ * a12;
    const double py_slip = denom > 0.0 ? -vcy / denom : -1.0;
    const double px_slip = -sigma * mu_k_ * py_slip;
    const double vcx_after = vcx + a11 * px_slip + a12 * py_slip;
    if (py_slip >= 0.0 && sigma != 0 && sigma * vcx_after >= 0.0) {
      px = px_slip;
      py = py_slip;
    } else {
      stick = true;  // friction would reverse the slip inside the impact: it sticks
    }
  }
  vx += px;
  vy += py;
  w += (rx * py - ry * px) / ig2_;
  const Pivot& pv = body_.pivot(c);
  if (stick && py > 0.0 && !from_flight && !body_.uses_theoretical_restitution()) {
    // User restitution replaces eq. 34's ratio; the part due to a pre-impact slip is kept.
    const double e_theory = impact_velocity_ratio(ig2_, body_.cg_height(), body_.width(), pv.nu);
    w = pv.restitution * w_before + (w - e_theory * w_before);
    vx = w * ry;
    vy = -w * rx;
  }
  if (!from_flight) {
    x_[2] = 0.0;
    if (c * w <= 0.0 || std::abs(w) < settings_.rest_capture_ratio * pv.p * pv.alpha) {
      // Rest capture collapses the rest of a Zeno sequence of impacts. After a sticking impact
      // those would stick too, so their tangential impulse stops the CoM with the rotation (a
      // leftover w * r_y would otherwise start a nanometre slide the pure-rocking model never has).
      if (stick) vx = vy = 0.0;
      enter_flat(in, tau);
      return;
    }
  }
  enter_pivot(c, in, tau);
}

void ContactModel::leave_rest(const GroundInput& in, double tau, unsigned fired, int up_side) {
  x_[1] = x_[3] = x_[5] = 0.0;
  if (fired & kFiredFlight) {
    set_mode(ContactMode::Flight, 0, 0, tau);
    return;
  }
  const double ax = in.ax(tau), G = in.ay(tau) + kGravity;
  double rx_req;
  if ((fired & kFiredUplift) && rock_friction_ok(in, tau, up_side, rx_req)) {
    set_mode(ContactMode::Rock, up_side, 0, tau);  // eq. 19 with eq. 25 satisfied
    return;
  }
  // Sliding (eq. 22 violated, or rocking would need more friction than eq. 25 allows).
  int sigma = -sgn(ax);
  if (sigma == 0) sigma = up_side != 0 ? -up_side : 1;
  // Is pure sliding consistent? Corner normal forces with F = -sigma mu_k G (moments about CoM):
  // N1 = nu2 G + h F / B, N2 = nu1 G - h F / B.
  const double F = -sigma * mu_k_ * std::max(G, 0.0);
  const double hb = body_.cg_height() / body_.width();
  const double n1 = body_.nu2() * G + hb * F, n2 = body_.nu1() * G - hb * F;
  if (n1 >= 0.0 && n2 >= 0.0) {
    set_mode(ContactMode::Slide, 0, sigma, tau);
  } else {
    set_mode(ContactMode::SlideRock, n2 < 0.0 ? 1 : -1, sigma, tau);  // Shenton's slide-rock
  }
}

}  // namespace rocking_monitor::core
