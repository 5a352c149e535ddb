#pragma once

// Test-only independent reference for the 3-D model's friction (issue 51): a rigid convex body on a
// floor, stepped by Moreau-Jean time-stepping (the scheme of Siconos' kernel, MoreauJeanOSI with
// theta = 1/2 and restitution 0), each step's frictional contact problem solved by Siconos
// numerics' fc3d (Debian ships Siconos numerics; its kernel and mechanics are further packages the
// project does not need for this). Coulomb's cone is exact at every contact point; there are no
// modes, events or impact laws: sticking, slipping, rocking on a slipping corner and landing all come
// out of one velocity-impulse problem per step, first order in the step.
//
// The ground frame is non-inertial, as in the core: the floor stays put and the ground's acceleration
// a acts on the body as -m a, added to gravity, linear in time between samples (first-order hold).

#include <limits>
#include <vector>

#include <Eigen/Core>

namespace rocking_monitor::reference {

struct MoreauJeanBody {
  std::vector<Eigen::Vector3d> points;  ///< hull vertices at rest (floor z = 0), m; the contact points
  double mass = 1.0;                    ///< kg
  Eigen::Vector3d centre_of_mass = Eigen::Vector3d::Zero();   ///< m
  Eigen::Matrix3d central_inertia = Eigen::Matrix3d::Zero();  ///< kg m^2 about the centre of mass
};

struct MoreauJeanSettings {
  double step = 1e-4;       ///< s
  double mu = 0.3;          ///< Coulomb friction at every point (static = kinetic)
  double solver_tol = 1e-10;  ///< fc3d residual (Siconos NSGS)
  double overturn_tilt = 1.2;  ///< rad
};

struct MoreauJeanOutcome {
  bool overturned = false;
  double overturn_time = std::numeric_limits<double>::quiet_NaN();  ///< s
  double max_tilt = 0.0;           ///< rad, at sub-step ends (until the overturn)
  long unconverged = 0;            ///< steps whose fc3d did not reach solver_tol (in 10,000 sweeps)
  double worst_residual = 0.0;     ///< fc3d's largest residual at the end of a step (relative)
};

class MoreauJeanRigidBody {
 public:
  MoreauJeanRigidBody(const MoreauJeanBody& body, const MoreauJeanSettings& settings);

  /// One input sample: ground acceleration (m/s^2) linear from the previous one over dt; whole steps.
  void step(const Eigen::Vector3d& a, double dt);
  void set_input(const Eigen::Vector3d& a) { a_prev_ = a; }

  /// Centre of mass's displacement from rest, m.
  Eigen::Vector3d displacement() const { return x_ - x0_; }
  /// Angle of the body's z axis from the vertical, rad.
  double tilt() const;
  const MoreauJeanOutcome& outcome() const { return outcome_; }
  double time() const { return t_; }

 private:
  void substep(const Eigen::Vector3d& a, double h);
  /// Contact impulses (world) on the points that are active, from fc3d on the free velocities.
  void contact_impulses(const std::vector<int>& active, const Eigen::Vector3d& v_free,
                        const Eigen::Vector3d& w_free, const Eigen::Matrix3d& j_inv,
                        std::vector<Eigen::Vector3d>& impulse);

  MoreauJeanBody body_;
  MoreauJeanSettings settings_;
  Eigen::Vector3d x_, x0_, v_ = Eigen::Vector3d::Zero(), w_ = Eigen::Vector3d::Zero();  // world
  Eigen::Matrix3d r_ = Eigen::Matrix3d::Identity();  // body (rest frame about the centre) to world
  Eigen::Vector3d a_prev_ = Eigen::Vector3d::Zero();
  std::vector<double> warm_;  // last step's reactions (warm start when the active set repeats)
  std::vector<int> warm_set_;
  double t_ = 0.0;
  MoreauJeanOutcome outcome_;
};

}  // namespace rocking_monitor::reference
