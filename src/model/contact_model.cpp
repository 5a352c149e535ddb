#include "rocking_monitor/model/contact_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rocking_monitor/physics/criteria.hpp"
#include "rocking_monitor/integrate/event_location.hpp"
#include "rocking_monitor/physics/impact.hpp"

namespace rocking_monitor::core {

const char* to_string(ContactMode mode) {
  switch (mode) {
    case ContactMode::Rest: return "REST";
    case ContactMode::Slide: return "SLIDE";
    case ContactMode::Rock: return "ROCK";
    case ContactMode::SlideRock: return "SLIDE_ROCK";
    case ContactMode::Flight: return "FLIGHT";
    case ContactMode::Overturned: return "OVERTURNED";
  }
  return "UNKNOWN";
}

namespace {
constexpr unsigned kFiredFlight = 1u, kFiredSlide = 2u, kFiredUplift = 4u;
inline int sgn(double v) { return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0); }
inline bool slipping(ContactMode m) { return m == ContactMode::Slide || m == ContactMode::SlideRock; }
inline bool pivoting(ContactMode m) { return m == ContactMode::Rock || m == ContactMode::SlideRock; }
}  // namespace

ContactModel::ContactModel(const BodyParameters& body, const ContactSettings& settings)
    : ContactModel(Body(body), settings) {}

ContactModel::ContactModel(const Body& body, const ContactSettings& settings)
    : body_(body), settings_(settings) {
  if (settings_.substeps < 1 || settings_.substeps > 100000)
    throw std::invalid_argument("ContactSettings::substeps must be in [1, 100000]");
  if (settings_.max_events_per_sample < 1)
    throw std::invalid_argument("ContactSettings::max_events_per_sample must be >= 1");
  if (!(settings_.rest_capture_ratio >= 0.0))
    throw std::invalid_argument("ContactSettings::rest_capture_ratio must be >= 0");
  mu_s_ = body_.mu_s();
  mu_k_ = std::isnan(body_.parameters().mu_k) ? mu_s_ : body_.parameters().mu_k;
  if (mu_k_ > mu_s_) throw std::invalid_argument("ContactModel: mu_k must not exceed mu_s");
  ig2_ = body_.radius_of_gyration() * body_.radius_of_gyration();
  reset(0.0);
}

void ContactModel::reset(double t, double ax, double ay) {
  mode_ = ContactMode::Rest;
  side_ = 0;
  sigma_ = 0;
  x_ = {body_.nu1() * body_.width(), 0.0, 0.0, 0.0, body_.cg_height(), 0.0};
  pivot_x_ = 0.0;
  t_ = t;
  ax_prev_ = ax;
  ay_prev_ = ay;
  report_ = ContactReport{};
  outcome_ = ContactOutcome{};
}

void ContactModel::set_state(double t, double ax, double ay, int side, double theta, double omega,
                             double slip, const ContactOutcome& outcome) {
  set_state(t, ax, ay, side, theta, omega, slip);
  outcome_ = outcome;
}

void ContactModel::set_state(double t, double ax, double ay, int side, double theta, double omega,
                             double slip) {
  if (!std::isfinite(t) || !std::isfinite(ax) || !std::isfinite(ay) || !std::isfinite(theta) ||
      !std::isfinite(omega) || !std::isfinite(slip))
    throw std::invalid_argument("ContactModel::set_state: arguments must be finite");
  if (side != 0 && side != 1 && side != -1)
    throw std::invalid_argument("ContactModel::set_state: side must be 0 (REST), +1 or -1 (ROCK)");
  if (side == 0 && (theta != 0.0 || omega != 0.0))
    throw std::invalid_argument("ContactModel::set_state: REST needs theta = omega = 0");
  if (side != 0 && (side * theta < 0.0 || std::abs(theta) >= body_.overturn_angle()))
    throw std::invalid_argument(
        "ContactModel::set_state: ROCK needs side * theta >= 0 and |theta| < overturn angle");
  t_ = t;
  ax_prev_ = ax;
  ay_prev_ = ay;
  sigma_ = 0;
  if (side == 0) {
    mode_ = ContactMode::Rest;
    side_ = 0;
    pivot_x_ = 0.0;
    x_ = {slip + body_.nu1() * body_.width(), 0.0, 0.0, 0.0, body_.cg_height(), 0.0};
  } else {
    mode_ = ContactMode::Rock;
    side_ = side;
    pivot_x_ = slip + (side > 0 ? 0.0 : body_.width());  // corner 1 at u, corner 2 at u + B
    x_[2] = theta;
    x_[3] = omega;
    project_rock();
  }
  report_ = ContactReport{};
  report_.mode = mode_;
  report_.side = side_;
  report_.slip = this->slip();
  report_.slip_velocity = slip_velocity();
  report_.theta = x_[2];
}

// Vector from the centre of mass to corner c (+1: corner 1, -1: corner 2), rotated by theta.
void ContactModel::corner(int c, const State& s, double& rx, double& ry) const {
  const double dx = c > 0 ? -body_.nu1() * body_.width() : body_.nu2() * body_.width();
  const double dy = -body_.cg_height();
  const double ct = std::cos(s[2]), st = std::sin(s[2]);
  rx = ct * dx - st * dy;
  ry = st * dx + ct * dy;
}

double ContactModel::slip() const {
  const int c = x_[2] < 0.0 ? -1 : 1;
  double rx, ry;
  corner(c, x_, rx, ry);
  return x_[0] + rx - (c > 0 ? 0.0 : body_.width());
}

double ContactModel::slip_velocity() const {
  const int c = x_[2] < 0.0 ? -1 : 1;
  double rx, ry;
  corner(c, x_, rx, ry);
  return x_[1] - x_[3] * ry;
}

double ContactModel::energy() const {
  return 0.5 * (x_[1] * x_[1] + x_[5] * x_[5] + ig2_ * x_[3] * x_[3]) + kGravity * x_[4];
}

// Slide-rock about corner `side` with the pivot slipping in direction sigma (friction
// -sigma mu_k N). Newton-Euler with the constraint y_pivot = 0 (see docs/contact_model.md):
//   theta'' = -K (G - R cos(phi) w^2) / (i_g^2 + K s R sin(phi)),  K = R (s sin(phi) + mu_k sigma cos(phi))
//   N = G + s R sin(phi) theta'' - R cos(phi) w^2,   x'' = -a_xg - sigma mu_k N,   y'' = N - G.
double ContactModel::slide_rock_theta_ddot(int side, int sigma, double G, const State& s,
                                           double& normal) const {
  const Pivot& pv = body_.pivot(side);
  const double phi = pv.alpha - side * s[2];
  const double sp = std::sin(phi), cp = std::cos(phi), w2 = s[3] * s[3], R = pv.radius;
  const double K = R * (side * sp + mu_k_ * sigma * cp);
  const double acc = -K * (G - R * cp * w2) / (ig2_ + K * side * R * sp);
  normal = G + side * R * sp * acc - R * cp * w2;
  return acc;
}

void ContactModel::derivative(const GroundInput& in, double tau, const State& s, State& d) const {
  const double ax = in.ax(tau), G = in.ay(tau) + kGravity;
  d = {s[1], 0.0, s[3], 0.0, s[5], 0.0};
  switch (mode_) {
    case ContactMode::Slide:
      d[1] = -ax - sigma_ * mu_k_ * std::max(G, 0.0);
      break;
    case ContactMode::Rock: {
      const Pivot& pv = body_.pivot(side_);
      const RockingOde ode{&pv, side_, ModelKind::Nonlinear, in};
      const double acc = ode.angular_acceleration(tau, s[2]);
      const double phi = pv.alpha - side_ * s[2];
      const double c = std::cos(phi), sn = std::sin(phi), w2 = s[3] * s[3];
      d[3] = acc;
      d[1] = -pv.radius * (c * acc + side_ * sn * w2);
      d[5] = -pv.radius * c * w2 + side_ * pv.radius * sn * acc;
      break;
    }
    case ContactMode::SlideRock: {
      double normal;
      d[3] = slide_rock_theta_ddot(side_, sigma_, G, s, normal);
      d[1] = -ax - sigma_ * mu_k_ * normal;
      d[5] = normal - G;
      break;
    }
    case ContactMode::Flight:
      d[1] = -ax;
      d[5] = -G;
      break;
    default:
      d = {0, 0, 0, 0, 0, 0};
  }
}

void ContactModel::rk4(const GroundInput& in, double tau, const State& s0, double h,
                       State& out) const {
  State k1, k2, k3, k4, y;
  derivative(in, tau, s0, k1);
  for (int i = 0; i < 6; ++i) y[i] = s0[i] + 0.5 * h * k1[i];
  derivative(in, tau + 0.5 * h, y, k2);
  for (int i = 0; i < 6; ++i) y[i] = s0[i] + 0.5 * h * k2[i];
  derivative(in, tau + 0.5 * h, y, k3);
  for (int i = 0; i < 6; ++i) y[i] = s0[i] + h * k3[i];
  derivative(in, tau + h, y, k4);
  for (int i = 0; i < 6; ++i) out[i] = s0[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
}

bool ContactModel::rock_friction_ok(const GroundInput& in, double tau, int side, double& rx) const {
  const Pivot& pv = body_.pivot(side);
  const RockingOde ode{&pv, side, ModelKind::Nonlinear, in};
  const double acc = ode.angular_acceleration(tau, x_[2]);
  const ContactReaction r = rocking_reaction(pv, side, x_[2], x_[3], acc, in.ax(tau), in.ay(tau));
  rx = r.rx;
  return std::isinf(mu_s_) || std::abs(r.rx) <= mu_s_ * std::max(r.ry, 0.0);
}

// Event functions: the event happens when the function becomes > 0.
double ContactModel::event_fn(int ev, const GroundInput& in, double tau, const State& s) const {
  const double G = in.ay(tau) + kGravity;
  switch (mode_) {
    case ContactMode::Slide:
      if (ev == kFlight) return -G;
      if (ev == kSlipOrStick) return -sigma_ * s[1];  // relative velocity reached zero
      return -1.0;
    case ContactMode::Rock: {
      if (ev == kImpact) return -side_ * s[2];
      if (ev == kOverturn) return side_ * s[2] - body_.overturn_angle();
      if (ev != kFlight && ev != kSlipOrStick) return -1.0;
      const Pivot& pv = body_.pivot(side_);
      const RockingOde ode{&pv, side_, ModelKind::Nonlinear, in};
      const double acc = ode.angular_acceleration(tau, s[2]);
      const ContactReaction r = rocking_reaction(pv, side_, s[2], s[3], acc, in.ax(tau), in.ay(tau));
      if (ev == kFlight) return -r.ry;
      if (std::isinf(mu_s_)) return -1.0;
      return std::abs(r.rx) - mu_s_ * r.ry;
    }
    case ContactMode::SlideRock: {
      if (ev == kImpact) return -side_ * s[2];
      if (ev == kOverturn) return side_ * s[2] - body_.overturn_angle();
      if (ev == kFlight) {
        double normal;
        slide_rock_theta_ddot(side_, sigma_, G, s, normal);
        return -normal;
      }
      if (ev == kSlipOrStick) {  // pivot slip velocity reached zero
        double rx, ry;
        corner(side_, s, rx, ry);
        return -sigma_ * (s[1] - s[3] * ry);
      }
      return -1.0;
    }
    case ContactMode::Flight: {
      if (ev == kOverturn) return std::abs(s[2]) - body_.overturn_angle();
      if (ev != kLanding) return -1.0;
      double rx1, ry1, rx2, ry2;
      corner(1, s, rx1, ry1);
      corner(-1, s, rx2, ry2);
      return -(s[4] + std::min(ry1, ry2));
    }
    default: return -1.0;
  }
}

// REST: every exit condition is linear in the ground acceleration, hence linear in time within a
// sample; crossings are solved exactly. fired: which conditions cross at the returned time.
double ContactModel::find_rest_exit(const GroundInput& in, double tau, double tau_end,
                                    unsigned& fired, int& up_side) const {
  const double inf = std::numeric_limits<double>::infinity();
  auto crossing = [&](auto f) {
    const double f0 = f(tau), f1 = f(tau_end);
    if (f0 > 0.0) return tau;
    if (f1 > 0.0) return std::clamp(tau + (tau_end - tau) * (-f0) / (f1 - f0), tau, tau_end);
    return inf;
  };
  const double t_flight = crossing([&](double t) { return -(in.ay(t) + kGravity); });
  double t_slide = inf;
  if (!std::isinf(mu_s_)) {
    t_slide = std::min(
        crossing([&](double t) { return in.ax(t) - mu_s_ * (in.ay(t) + kGravity); }),
        crossing([&](double t) { return -in.ax(t) - mu_s_ * (in.ay(t) + kGravity); }));
  }
  double t_up = inf;
  up_side = 0;
  for (int s : {1, -1}) {
    const Pivot& pv = body_.pivot(s);
    const double when = crossing([&](double t) {
      return uplift_function(pv, s, ModelKind::Nonlinear, in.ax(t), in.ay(t));
    });
    if (std::isinf(when)) continue;
    const RockingOde ode{&pv, s, ModelKind::Nonlinear, in};  // same guard as RockingModel
    if (!(s * ode.angular_acceleration(when, 0.0) > 0.0) &&
        !(s * ode.angular_acceleration(tau_end, 0.0) > 0.0))
      continue;
    if (when < t_up || (when == t_up && s == tipping_side(in.ax(when)))) {
      t_up = when;
      up_side = s;
    }
  }
  const double when = std::min({t_flight, t_slide, t_up});
  fired = 0;
  if (std::isinf(when)) return when;
  const double eps = 1e-12 * (tau_end - tau);
  if (t_flight <= when + eps) fired |= kFiredFlight;
  if (t_slide <= when + eps) fired |= kFiredSlide;
  if (t_up <= when + eps) fired |= kFiredUplift;
  return when;
}

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
  if (std::abs(x_[1]) <= v_tiny) x_[1] = 0.0;
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

int ContactModel::advance(const GroundInput& in, double& tau, double tau_end) {
  const double h_nom = dt_ / settings_.substeps;
  const double t_tol = 1e-12 * dt_;
  while (tau < tau_end) {
    double h = std::min(h_nom, tau_end - tau);
    if (tau_end - tau - h < 1e-9 * h_nom) h = tau_end - tau;
    State x1;
    rk4(in, tau, x_, h, x1);
    ++report_.integrator_steps;
    int best = kNone;
    double t_best = tau + h;
    for (int ev = 0; ev < kCount; ++ev) {
      const double f1 = event_fn(ev, in, tau + h, x1);
      if (!(f1 > 0.0)) continue;
      const double f0 = event_fn(ev, in, tau, x_);
      double te = tau;
      if (!(f0 > 0.0)) {
        const State x0 = x_;
        const double t0 = tau;
        te = bracketed_root(
            [&](double t) {
              State y;
              rk4(in, t0, x0, t - t0, y);
              return event_fn(ev, in, t, y);
            },
            t0, t0 + h, f0, f1, t_tol);
      }
      if (best == kNone || te < t_best) {
        best = ev;
        t_best = te;
      }
    }
    if (best == kNone) {
      x_ = x1;
      tau = (h == tau_end - tau) ? tau_end : tau + h;
      const int s = x_[2] < 0.0 ? -1 : 1;
      outcome_.max_rotation_ratio =
          std::max(outcome_.max_rotation_ratio, std::abs(x_[2]) / body_.pivot(s).alpha);
      continue;
    }
    if (t_best > tau) {
      State xe;
      rk4(in, tau, x_, t_best - tau, xe);
      x_ = xe;
    }
    tau = t_best;
    return best;
  }
  return kNone;
}

void ContactModel::handle_event(int ev, const GroundInput& in, double tau) {
  if (ev == kOverturn) {
    const int s = x_[2] < 0.0 ? -1 : 1;
    mode_ = ContactMode::Overturned;
    side_ = s;
    x_[2] = s * body_.overturn_angle();
    x_[1] = x_[3] = x_[5] = 0.0;
    report_.overturned = true;
    outcome_.overturned = true;
    outcome_.overturn_time = t_ + tau;
    return;
  }
  switch (mode_) {
    case ContactMode::Slide:
      if (ev == kFlight) {
        set_mode(ContactMode::Flight, 0, 0, tau);
      } else {  // stick: relative velocity reached zero
        x_[1] = 0.0;
        enter_flat(in, tau);
      }
      return;
    case ContactMode::Rock:
      if (ev == kImpact) {
        x_[2] = 0.0;
        project_rock();
        impact(-side_, in, tau, false);
      } else if (ev == kFlight) {
        set_mode(ContactMode::Flight, 0, 0, tau);
      } else {  // |R_x| reached mu_s R_y: the pivot starts to slip
        set_mode(ContactMode::SlideRock, side_, consistent_sigma(side_, in, tau), tau);
      }
      return;
    case ContactMode::SlideRock:
      if (ev == kImpact) {
        x_[2] = 0.0;
        double rx, ry;
        corner(side_, x_, rx, ry);
        x_[4] = -ry;
        impact(-side_, in, tau, false);
      } else if (ev == kFlight) {
        set_mode(ContactMode::Flight, 0, 0, tau);
      } else {  // pivot slip velocity reached zero
        double rx, ry;
        corner(side_, x_, rx, ry);
        x_[1] = x_[3] * ry;
        enter_pivot(side_, in, tau);
      }
      return;
    case ContactMode::Flight: {
      int c = x_[2] > 0.0 ? 1 : (x_[2] < 0.0 ? -1 : (x_[3] > 0.0 ? 1 : -1));
      double rx, ry;
      corner(c, x_, rx, ry);
      x_[4] = -ry;  // exactly on the floor
      impact(c, in, tau, true);
      return;
    }
    default: return;
  }
}

const ContactReport& ContactModel::step(double ax, double ay, double dt) {
  require_valid_sample(ax, ay, dt, "ContactModel::step");
  report_ = ContactReport{};
  dt_ = dt;
  const GroundInput in = GroundInput::first_order_hold(ax_prev_, ay_prev_, ax, ay, dt);

  double tau = 0.0;
  int events = 0;
  while (tau < dt && mode_ != ContactMode::Overturned) {
    if (mode_ == ContactMode::Rest) {
      unsigned fired = 0;
      int up_side = 0;
      const double when = find_rest_exit(in, tau, dt, fired, up_side);
      if (std::isinf(when)) break;
      tau = when;
      leave_rest(in, tau, fired, up_side);
    } else {
      const int ev = advance(in, tau, dt);
      if (ev == kNone) break;
      handle_event(ev, in, tau);
    }
    ++report_.transitions;
    if (++events >= settings_.max_events_per_sample && tau < dt) {
      const double u = slip();
      x_ = {u + body_.nu1() * body_.width(), 0.0, 0.0, 0.0, body_.cg_height(), 0.0};
      mode_ = ContactMode::Rest;
      side_ = sigma_ = 0;
      report_.forced_rest = true;
      ++outcome_.forced_rests;
      break;
    }
  }
  t_ += dt;
  ax_prev_ = ax;
  ay_prev_ = ay;
  ++outcome_.samples;
  report_.mode = mode_;
  report_.side = side_;
  report_.slip = slip();
  report_.slip_velocity = slip_velocity();
  report_.theta = x_[2];
  outcome_.max_abs_slip = std::max(outcome_.max_abs_slip, std::abs(report_.slip));
  return report_;
}

}  // namespace rocking_monitor::core
