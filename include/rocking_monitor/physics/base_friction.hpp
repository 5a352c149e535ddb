#pragma once

// Coulomb friction over a flat base that slides and turns on the floor (issue 51): the limit-surface
// view of planar sliding with dry friction (Goyal, Ruina & Papadopoulos 1991). Every point of the
// contact polygon carries friction mu p(x) against its own slip velocity, isotropically; integrated
// over the polygon this gives one force and one torque about the vertical for the body's slip
// velocity and spin.
//
// The normal pressure is the linear distribution over the polygon with its resultant at the centre
// of pressure that rigid-body equilibrium puts it at (the moment of gravity, the ground's inertia
// and the friction about the centre of mass): p(x) = N [1/A + k . (x - g)], g the polygon's
// centroid, k from the polygon's second moment of area. A uniform pressure is k = 0.
//
// The integral is exact, in closed form: the polygon is the signed sum of the triangles from the
// instantaneous centre of rotation to its edges; on each, the slip direction depends on the angle
// only and the pressure is linear, so the radial integral is a polynomial and the angular one
// reduces to integrals of x^m / sqrt(x^2 + d^2) (asinh and square roots). No quadrature, no
// allocation.

#include <vector>

#include <Eigen/Core>

namespace rocking_monitor::core {

/// Friction per unit (mu N): force (2-D, against the slip, |force| <= 1) and torque about the
/// reference point (m, per unit mu N).
struct FrictionLoad {
  Eigen::Vector2d force = Eigen::Vector2d::Zero();
  double torque = 0.0;
};

class BaseFriction {
 public:
  /// The contact polygon (m, counter-clockwise, convex, >= 3 vertices; validated by BaseBody).
  BaseFriction() = default;
  explicit BaseFriction(const std::vector<Eigen::Vector2d>& polygon);

  /// The load of a base whose point `ref` slips with velocity `v` (m/s, relative to the floor) while
  /// the base turns at `spin` (rad/s, about the vertical), under the linear pressure whose resultant
  /// acts at `pressure_centre` (m). v = 0 and spin = 0: no slip, the zero load (the static law
  /// decides then, not this function).
  FrictionLoad load(const Eigen::Vector2d& v, double spin, const Eigen::Vector2d& ref,
                    const Eigen::Vector2d& pressure_centre) const;

  /// The pressure per unit N at x (1/m^2) for a resultant at `pressure_centre`; negative where the
  /// centre of pressure lies outside the polygon's kern (the linear law then pulls: see the docs).
  double pressure(const Eigen::Vector2d& x, const Eigen::Vector2d& pressure_centre) const;

  double area() const { return area_; }                     ///< m^2
  const Eigen::Vector2d& centroid() const { return centroid_; }  ///< m
  int size() const { return n_; }

 private:
  Eigen::Vector2d gradient(const Eigen::Vector2d& pressure_centre) const;
  FrictionLoad from_centre(const Eigen::Vector2d& centre, double spin, const Eigen::Vector2d& ref,
                           const Eigen::Vector2d& k, double p_centre) const;
  FrictionLoad by_quadrature(const Eigen::Vector2d& centre, double spin, const Eigen::Vector2d& ref,
                             const Eigen::Vector2d& k) const;
  std::vector<Eigen::Vector2d> v_;
  int n_ = 0;
  double size_ = 0.0;  // m, the largest distance of a vertex from the centroid
  double area_ = 0.0;
  Eigen::Vector2d centroid_ = Eigen::Vector2d::Zero();
  Eigen::Matrix2d second_moment_inverse_ = Eigen::Matrix2d::Zero();  // of area about the centroid, 1/m^4
};

}  // namespace rocking_monitor::core
