// Free flight in 3-D (issue 51 part 2): where the floor's normal force on the body vanishes (the floor
// dropping faster than gravity: REST and SLIDE at g + a_z <= 0; EDGE and VERTEX where the pivot's normal
// reaction reaches zero) the body leaves the floor. In the ground's frame gravity and the ground's
// inertial force act at the centre of mass, so in flight the centre moves under them alone and the
// body turns free of torque about it (Euler's equations). The flight ends where a hull point comes
// back to the floor: a landing under the same impact law as every other (rocking_3d_landing.cpp), with
// the centre's velocity of the flight. Followed where the item gives a friction coefficient and stands
// on no support (follows_flight()); elsewhere the onset is counted as before (pivot_lifts).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "rocking_3d_internal.hpp"
#include "rocking_monitor/integrate/event_location.hpp"
#include "rocking_monitor/physics/impact_3d.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"

namespace rocking_monitor::core {

using rocking_3d::gravity_and_inertia;

// REST, SLIDE: the first instant in [tau, tau_end] where g + a_z <= 0 (linear in the sample: closed
// form); +inf if none, or where flight is not followed.
double Rocking3DModel::flight_onset(const GroundInput3& in, double tau, double tau_end) const {
  const double inf = std::numeric_limits<double>::infinity();
  if (!follows_flight()) return inf;
  const double n0 = kGravity + in.at(tau).z(), n1 = kGravity + in.at(tau_end).z();
  if (!(n0 > 0.0)) return tau;
  if (n1 > 0.0) return inf;
  return std::clamp(tau + (tau_end - tau) * n0 / (n0 - n1), tau, tau_end);
}

// EDGE, VERTEX (sticking), where watch_pivot found the reaction leaving the cone through its apex at
// lift_at in the step [t0, t1] just taken (or, outside it, the floor dropping faster than gravity): the
// instant the normal reaction reaches zero, on the dense output, not before lift_at (lift_at where it
// only touches zero); NaN without a lift.
double Rocking3DModel::lift_in_step(const GroundInput3& in, double t0, double t1, double t_tol, double lift_at) const {
  if (std::isnan(lift_at)) return lift_at;
  const double f1 = pivot_reaction(in, t1).z();
  if (f1 > 0.0) return lift_at;
  auto normal = [&](double t) { return pivot_reaction(in, t).z(); };
  const double f0 = normal(t0);
  // (no earlier than lift_at: outside the cone, the floor dropping faster than gravity lets it go there)
  return std::max(f0 > 0.0 ? bracketed_root(normal, t0, t1, f0, f1, t_tol) : t0, lift_at);
}

// The body leaves the floor at tau with the pose and velocities of the mode it leaves.
void Rocking3DModel::enter_flight(double tau) {
  const Eigen::Matrix3d r = rotation();
  const Eigen::Vector3d c = r * body_.centre_of_mass() + translation();
  // (sliding, the turn about the vertical is the slide's spin)
  const Eigen::Vector3d w = mode_ == Mode3D::Slide ? Eigen::Vector3d(0.0, 0.0, slide_(2)) : angular_velocity();
  const Eigen::Quaterniond q(r);
  Vec13 y;
  y << q.w(), q.x(), q.y(), q.z(), w, c, centre_velocity();
  int lowest;
  const double z = lowest_point(y, lowest);
  if (z < 0.0) y(9) -= z;  // (an event's pose a few nm below the floor: it leaves from the floor)
  dopri5_.invalidate();
  vector_.invalidate();
  slide_stepper_.invalidate();
  fly(y);
  flight_stepper_.reset(sample_dt_);
  ++outcome3_.flights;
  if (std::isnan(outcome3_.first_flight_time)) outcome3_.first_flight_time = t_ + tau;
}

// Per unit mass: the centre under gravity and the ground's inertial force; Euler's equations about the
// centre with no torque, in the body's frame (J constant there): J wb' = -wb x J wb.
void Rocking3DModel::flight_rhs(const GroundInput3& in, double t, const Vec13& y, Vec13& dy) const {
  const Eigen::Matrix3d r = rocking_3d::quaternion_rotation(y);
  const Eigen::Vector3d w = y.segment<3>(4);
  dy.segment<3>(4) = free_spin_rate(r, w);
  dy.head<4>() = rocking_3d::quaternion_rate(w, y);
  dy.segment<3>(7) = y.segment<3>(10);
  dy.segment<3>(10) = gravity_and_inertia(in.at(t));
}

// The height of the body's lowest hull point above the floor, m, and which it is.
double Rocking3DModel::lowest_point(const Vec13& y, int& lowest) const {
  const Eigen::Matrix3d r = rocking_3d::quaternion_rotation(y);
  const Eigen::Vector3d up = r.row(2).transpose();
  const double base = y(9) - up.dot(body_.centre_of_mass());
  double low = std::numeric_limits<double>::infinity();
  lowest = -1;
  const int n = static_cast<int>(hull().vertices.size());
  for (int i = 0; i < n; ++i) {
    const double z = base + up.dot(hv(i).position);
    if (z < low) {
      low = z;
      lowest = i;
    }
  }
  return low;
}

// The first instant in [t0, t1] (dense output valid) at which a hull point comes back to the floor
// (a contact tolerance below it: the body leaves from the floor), probed so that a grazing dip inside
// the step is not missed; +inf and touching -1 if none.
double Rocking3DModel::flight_touchdown(const Vec13& y0, double t0, double t1, double t_tol, int& touching) const {
  touching = -1;
  auto height = [&](const Vec13& y, int i) {
    const Eigen::Matrix3d r = rocking_3d::quaternion_rotation(y);
    return y(9) + (r * (hv(i).position - body_.centre_of_mass())).z() + floor_tol_;
  };
  double ta = t0;
  Vec13 ya = y0;
  for (int k = 1; k <= kVertexProbes; ++k) {
    const double tb = k == kVertexProbes ? t1 : t0 + (t1 - t0) * k / kVertexProbes;
    const Vec13 yb = k == kVertexProbes ? Vec13(flight_stepper_.y1()) : Vec13(flight_stepper_.eval(tb));
    int low;
    if (lowest_point(yb, low) + floor_tol_ <= 0.0) {
      double t_event = std::numeric_limits<double>::infinity();
      const int n = static_cast<int>(hull().vertices.size());
      for (int i = 0; i < n; ++i) {
        const double za = height(ya, i), zb = height(yb, i);
        if (!(zb <= 0.0) || !(za > 0.0)) continue;
        const double te = bracketed_root([&](double t) { return height(Vec13(flight_stepper_.eval(t)), i); }, ta, tb,
                                         za, zb, t_tol);
        if (te < t_event) {
          t_event = te;
          touching = i;
        }
      }
      if (touching >= 0) return t_event;
    }
    ta = tb;
    ya = yb;
  }
  return std::numeric_limits<double>::infinity();
}

// Steps the flight to the first touchdown (Impact, `touching`) or the body lying on its side (Overturn).
Rocking3DModel::Event Rocking3DModel::advance_flight(const GroundInput3& in, double& tau, double tau_end,
                                                     int& touching) {
  const double alpha = body_.min_alpha(), p = body_.max_p(), length = hv(0).radius;
  Vec13 atol;
  atol << Eigen::Vector4d::Constant(settings_.tol * alpha), Eigen::Vector3d::Constant(settings_.tol * p * alpha),
      Eigen::Vector3d::Constant(settings_.tol * length), Eigen::Vector3d::Constant(settings_.tol * p * length);
  auto f = [&](double t, const Vec13& y, Vec13& dy) { flight_rhs(in, t, y, dy); };
  const double t_tol = 1e-12 * std::max(sample_dt_, 1e-6);
  const double cos_over = std::cos(body_.overturn_angle());
  auto upright = [&](const Vec13& y) {
    return rocking_3d::quaternion_rotation(y)(2, 2) - cos_over;
  };
  while (tau < tau_end) {
    const Vec13 y0 = yf_;
    report_.integrator_steps += flight_stepper_.step(f, tau, yf_, tau_end, settings_.tol, atol);
    const double t0 = flight_stepper_.t0(), t1 = flight_stepper_.t1();
    double t_event = flight_touchdown(y0, t0, t1, t_tol, touching);
    Event event = touching >= 0 ? Event::Impact : Event::None;
    const double c1 = upright(flight_stepper_.y1());
    if (c1 <= 0.0) {
      const double c0 = upright(y0);
      const double te = c0 > 0.0 ? bracketed_root([&](double t) { return upright(Vec13(flight_stepper_.eval(t))); },
                                                   t0, std::min(t1, t_event), c0, c1, t_tol)
                                 : t0;
      if (te < t_event) {
        t_event = te;
        event = Event::Overturn;
      }
    }
    const double t_stop = event == Event::None ? t1 : t_event;
    yf_ = event == Event::None ? Vec13(flight_stepper_.y1()) : Vec13(flight_stepper_.eval(t_stop));
    yf_.head<4>().normalize();
    outcome3_.flight_time += t_stop - t0;
    tau = t_stop;
    int low;
    outcome3_.max_flight_height = std::max(outcome3_.max_flight_height, lowest_point(yf_, low));
    note_ratio();  // (the tilt, and the turn towards the corner it would land on)
    if (event != Event::None) {
      flight_stepper_.invalidate();
      return event;
    }
  }
  return Event::None;
}

void Rocking3DModel::set_flight_state(const Eigen::Quaterniond& rotation, const Eigen::Vector3d& centre,
                                      const Eigen::Vector3d& velocity, const Eigen::Vector3d& omega) {
  Vec13 y;
  const Eigen::Quaterniond q = rotation.normalized();
  y << q.w(), q.x(), q.y(), q.z(), omega, centre, velocity;
  int low;
  if (!y.allFinite() || !(lowest_point(y, low) >= 0.0))
    throw std::invalid_argument("set_flight_state: a finite state with the body clear of the floor");
  fly(y);
  flight_stepper_.invalidate();
}

// FLIGHT from the state y (q, omega, centre, velocity): no contact, no slip, no lip.
void Rocking3DModel::fly(const Vec13& y) {
  yf_ = y;
  mode_ = Mode3D::Flight;
  contact_ = -1;
  pivot_slipping_ = false;
  lip_held_ = -1;
}

// FLIGHT: the energy per unit mass about the lowest hull point p (returned in `lowest`) that a sticking
// landing there would leave, J/kg: the turn about p keeping the angular momentum about p,
// L_p = J_c w + (c - p) x v, and the centre's height above p.
double Rocking3DModel::flight_energy(int& lowest) const {
  lowest_point(yf_, lowest);
  const Eigen::Matrix3d r = rotation();
  const Eigen::Vector3d c = yf_.segment<3>(7), p = r * (hv(lowest).position - body_.centre_of_mass()) + c;
  const Eigen::Matrix3d jc = r * body_.central_inertia_per_mass() * r.transpose();
  const Eigen::Vector3d lp = jc * yf_.segment<3>(4) + (c - p).cross(yf_.tail<3>());
  const Eigen::Matrix3d jp = inertia_about(jc, c, p);
  return 0.5 * lp.dot(jp.ldlt().solve(lp)) + kGravity * (c.z() - p.z());
}

// Vertical acceleration of the body point at to_pivot from the centre (world) were the body free (no
// contact force): the floor lets go of a pivot only where that point would rise, m/s^2.
double Rocking3DModel::free_rise(const GroundInput3& in, double t, const Eigen::Matrix3d& r, const Eigen::Vector3d& w,
                                 const Eigen::Vector3d& to_pivot) const {
  return (gravity_and_inertia(in.at(t)) + free_spin_rate(r, w).cross(to_pivot) + w.cross(w.cross(to_pivot))).z();
}

// The angular acceleration of the body turning free of torque (Euler's equations about the centre, in
// the body's frame, where J is constant: J wb' = -wb x J wb), world, rad/s^2.
Eigen::Vector3d Rocking3DModel::free_spin_rate(const Eigen::Matrix3d& r, const Eigen::Vector3d& w) const {
  const Eigen::Vector3d wb = r.transpose() * w;
  return r * (central_inverse_ * -wb.cross(body_.central_inertia_per_mass() * wb));
}

// At the events bound in flight: put down flat on the face it would land on under its lowest point.
void Rocking3DModel::put_down_from_flight() {
  int low;
  lowest_point(yf_, low);
  const Eigen::Matrix3d r = rotation();
  Eigen::Vector3d point = r * (hv(low).position - body_.centre_of_mass()) + yf_.segment<3>(7);
  point.z() = 0.0;
  place_flat(r, low, point, hull().from_hull ? hull().face_down(r) : 0);
}

// The pose at a landing from flight: a body point x (item frame) at r x + t, lifted so that its lowest
// point lies on the floor (the touchdown is located a contact tolerance below it).
void Rocking3DModel::flight_pose(Eigen::Matrix3d& r, Eigen::Vector3d& t) const {
  r = rocking_3d::quaternion_rotation(yf_);
  t = yf_.segment<3>(7) - r * body_.centre_of_mass();
  int lowest;
  t.z() -= lowest_point(yf_, lowest);
}

}  // namespace rocking_monitor::core
