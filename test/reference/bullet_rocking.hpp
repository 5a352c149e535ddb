#pragma once

// Test-only independent 3-D reference for Rocking3DModel (issue 27): the same free-standing rigid
// body simulated by Bullet Physics (Debian libbullet-dev, double-precision build) as a convex hull
// on a static floor plane, with high friction (no sliding) and restitution 0.
//
// Bullet knows nothing of rocking modes or impact laws: contact is penetration-based (a few
// contact points in a persistent manifold, solved by sequential impulses at a fixed step), and an
// impact is whatever the impulse solver makes of a corner arriving at the floor with restitution
// 0. That independence is the point; it is also why the two codes differ (see the test's header).
//
// The ground frame is non-inertial, as in the core: the floor stays put and the ground's
// acceleration a acts on the body as the body force -m a, added to gravity (the body's own gravity
// vector is set to (-a_x, -a_y, -(g + a_z)) at every sub-step, a linear in time between samples).

#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Core>

namespace rocking_monitor::reference {

/// The body in its floor frame at rest (z up, floor z = 0), SI units.
struct BulletBody {
  /// Points whose convex hull is the body (a box's 8 corners, a mesh's vertices), m. The lowest
  /// must be at z = 0 (the body rests on them).
  std::vector<Eigen::Vector3d> points;
  double mass = 1.0;                                          ///< kg
  Eigen::Vector3d centre_of_mass = Eigen::Vector3d::Zero();   ///< m
  Eigen::Matrix3d central_inertia = Eigen::Matrix3d::Zero();  ///< kg m^2 about the centre of mass
};

struct BulletSettings {
  double substep = 1.0 / 4000.0;   ///< s, Bullet's fixed step (the tests halve it to check convergence)
  double friction = 1.5;           ///< body friction (the floor's is 1: Bullet multiplies them)
  double margin = 2e-4;            ///< m, collision margin of the hull (Bullet inflates the hull by it)
  /// m, Bullet's contact breaking threshold (a manifold point is dropped beyond it) and the body's
  /// contact processing threshold (points farther than this are not given to the solver).
  double contact_threshold = 1e-3;
  /// Sequential-impulse iterations per step (one body, <= 4 contacts: the box's peaks change by
  /// < 0.1 % from 30 to 100 at 1/8000 s; the records cost 2.3x more at 100).
  int solver_iterations = 30;
  bool split_impulse = true;       ///< penetration recovery without adding momentum
  double settle_time = 0.5;        ///< s under gravity alone before t = 0 (the contact settles)
  double overturn_tilt = 1.5707963267948966;  ///< rad: tilt at which the body counts overturned
};

struct BulletOutcome {
  bool overturned = false;
  double overturn_time = std::numeric_limits<double>::quiet_NaN();  ///< s, tilt first >= overturn_tilt
  double max_tilt = 0.0;  ///< rad, largest tilt at any sub-step (until the overturn)
};

class BulletRocking {
 public:
  BulletRocking(const BulletBody& body, const BulletSettings& settings);
  ~BulletRocking();
  BulletRocking(const BulletRocking&) = delete;
  BulletRocking& operator=(const BulletRocking&) = delete;

  /// One input sample: the ground acceleration (m/s^2) linear from the previous sample's to `a`
  /// over dt (first-order hold, as Rocking3DModel::step); whole sub-steps of at most `substep`.
  void step(const Eigen::Vector3d& a, double dt);

  /// The ground acceleration at t = 0 (the first sample), m/s^2 (default 0).
  void set_input(const Eigen::Vector3d& a) { a_prev_ = a; }
  double time() const { return t_; }
  /// Angle of the body's base normal from the vertical, rad (0 in the settled rest pose).
  double tilt() const;
  /// The body's rotation from its settled rest pose.
  Eigen::Matrix3d rotation() const;
  const BulletOutcome& outcome() const { return outcome_; }
  /// How far settling turned the body from the given pose, rad (a check on the contact's
  /// compliance: it should be tiny).
  double settle_tilt() const { return settle_tilt_; }
  /// Sub-step history (t, tilt), when record_history(true).
  void record_history(bool on) { record_ = on; }
  const std::vector<Eigen::Vector2d>& history() const { return history_; }

 private:
  struct World;
  void substep(const Eigen::Vector3d& a, double h);
  Eigen::Matrix3d body_rotation() const;

  std::unique_ptr<World> w_;
  BulletSettings settings_;
  Eigen::Matrix3d rest_ = Eigen::Matrix3d::Identity();  // body rotation in the settled rest pose
  Eigen::Vector3d a_prev_ = Eigen::Vector3d::Zero();
  double t_ = 0.0;
  double settle_tilt_ = 0.0;
  bool record_ = false;
  std::vector<Eigen::Vector2d> history_;
  BulletOutcome outcome_;
};

}  // namespace rocking_monitor::reference
