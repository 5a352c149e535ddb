// The 3-D model's measures of how close it is to overturning: the rotation ratio, the energy margin,
// and COMMITTED on a corner, found by stepping the free motion ahead on a copy.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "rocking_3d_internal.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/physics/criteria.hpp"
#include "rocking_monitor/physics/impact_3d.hpp"

namespace rocking_monitor::core {

using rocking_3d::gravity_and_inertia;
using rocking_3d::rot_z;

bool Rocking3DModel::falls_if_shaking_stops(double t_now) {
  Rocking3DModel& p = *probe_;
  // the state of the motion (save/restore: plain values, no allocation), the input gone from now on
  Saved state;
  save(state);
  p.restore(state);
  p.t_ = t_now;
  p.a_prev_.setZero();
  p.dopri5_.invalidate();  // the derivative cached for the shaken motion no longer holds
  p.vector_.invalidate();
  p.flight_stepper_.invalidate();
  for (double s = 0.0; s < kProbeHorizon; s += kProbeStep) {
    p.step(Eigen::Vector3d::Zero(), kProbeStep);
    if (p.mode_ == Mode3D::Overturned) return true;
    if (p.mode_ == Mode3D::Rest) return false;
  }
  return false;
}

double Rocking3DModel::rotation_ratio() const {
  if (mode_ == Mode3D::Edge) return theta_ / fb().edge(contact_).pivot.alpha;
  if (mode_ == Mode3D::Overturned) return outcome_.max_rotation_ratio;  // as it went over (> 1)
  if (mode_ == Mode3D::Flight) {  // (about the lowest hull point: the corner it would land on)
    int low;
    lowest_point(yf_, low);
    return ratio_about(rotation(), low);
  }
  if (mode_ != Mode3D::Vertex) return 0.0;
  return ratio_of(y_);
}

double Rocking3DModel::ratio_of(const Vec7& y) const { return ratio_about(vertex_rotation(y), contact_); }

// How far the centre of mass has turned towards the vertical through hull vertex `vertex` in pose r.
double Rocking3DModel::ratio_about(const Eigen::Matrix3d& r, int vertex) const {
  const BaseVertex& v = hv(vertex);
  const Eigen::Vector3d lever = r * v.to_centre;
  // Which side of the vertical through the vertex the centre of mass is on: the side of the base
  // (inside, ratio < 1) or beyond it (ratio > 1). The base's inward direction is lowered by 45
  // degrees so that its horizontal part keeps its sign up to a tilt of 135 degrees (the base itself
  // stands vertical at the overturn angle of 90 degrees).
  const Eigen::Vector3d in_base = body_.centroid() - v.position;
  const Eigen::Vector3d inside = r * (in_base - in_base.norm() * Eigen::Vector3d::UnitZ());
  const double phi = std::atan2(std::hypot(lever.x(), lever.y()), lever.z());
  const bool beyond = lever.x() * inside.x() + lever.y() * inside.y() < 0.0;
  return beyond ? 1.0 + phi / v.alpha : 1.0 - phi / v.alpha;
}

// VERTEX: the vertical velocity of the centre of mass, m/s. On the base's side of the pivot the
// rotation ratio peaks where it turns from rising to falling (the planar model's omega = 0).
double Rocking3DModel::rise_rate(const Vec7& y) const {
  const Eigen::Vector3d w = y.tail<3>();
  return w.cross(vertex_rotation(y) * hv(contact_).to_centre).z();
}

OverturnMargin Rocking3DModel::margin() const {
  switch (mode_) {
    case Mode3D::Rest:
    case Mode3D::Slide: return {1.0, false};  // flat on its face: the whole way to tipping
    case Mode3D::Overturned: return {-1.0, true};
    case Mode3D::Edge:
      return overturn_margin(fb().edge(contact_).pivot, 1, ModelKind::Nonlinear, theta_, omega_);
    case Mode3D::Vertex: break;
    case Mode3D::Flight: {
      // As on a corner, about the lowest hull point p, with the energy a sticking landing there would
      // leave (the turn about p that keeps the angular momentum about it) and the height above it: the
      // flight's own height and drift do not tip the body.
      int low;
      const double energy = flight_energy(low);
      const double tip = kGravity * hv(low).radius, rest = kGravity * body_.centre_of_mass().z();
      const double m = (tip - energy) / (tip - rest);
      return {m, m < 0.0};
    }
  }
  const BaseVertex& v = hv(contact_);
  const double height = (vertex_rotation(y_) * v.to_centre).z();
  const double energy = kinetic_energy() + kGravity * height;
  // rest: the centre of mass's height standing on the base (= to_centre.z of a base vertex)
  const double tip = kGravity * v.radius, rest = kGravity * body_.centre_of_mass().z();
  const double m = (tip - energy) / (tip - rest);
  return {m, m < 0.0};
}

double Rocking3DModel::kinetic_energy() const {
  if (mode_ == Mode3D::Edge) return 0.5 * fb().edge(contact_).pivot.inertia * omega_ * omega_;
  if (mode_ == Mode3D::Slide)
    return 0.5 * slide_.head<2>().squaredNorm() + 0.5 * fb().central_inertia_per_mass()(2, 2) * slide_(2) * slide_(2);
  if (mode_ == Mode3D::Flight) {
    const Eigen::Matrix3d r = rotation();
    const Eigen::Vector3d w = yf_.segment<3>(4);
    return 0.5 * yf_.tail<3>().squaredNorm() + 0.5 * w.dot(r * body_.central_inertia_per_mass() * r.transpose() * w);
  }
  if (mode_ != Mode3D::Vertex) return 0.0;
  const Eigen::Matrix3d r = vertex_rotation(y_);
  const Eigen::Vector3d w = y_.tail<3>();
  if (pivot_slipping_) {
    // (the centre's velocity with the pivot's slip, and the turning about the centre)
    const Eigen::Vector3d c = r * hv(contact_).to_centre;
    const Eigen::Vector3d v = Eigen::Vector3d(ys_(9), ys_(10), 0.0) + w.cross(c);
    return 0.5 * v.squaredNorm() + 0.5 * w.dot(r * body_.central_inertia_per_mass() * r.transpose() * w);
  }
  return rotation_energy(r * hv(contact_).inertia * r.transpose(), w);
}

void Rocking3DModel::note_ratio() {
  const double ratio = rotation_ratio();
  if (ratio > outcome_.max_rotation_ratio) {
    outcome_.max_rotation_ratio = ratio;
    outcome_.max_rotation_side = contact_ + 1;
  }
  outcome3_.max_tilt = std::max(outcome3_.max_tilt, tilt());
  if (ratio > 1.0 && !outcome_.beyond_tipping) {
    outcome_.beyond_tipping = true;
    outcome_.beyond_tipping_time = t_;
    report_.beyond_tipping_entered = true;
  }
}

}  // namespace rocking_monitor::core
