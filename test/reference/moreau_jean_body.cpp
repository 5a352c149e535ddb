#include "moreau_jean_body.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>
#include <Eigen/LU>

extern "C" {
#include <siconos/numerics/FrictionContactProblem.h>
#include <siconos/numerics/Friction_cst.h>
#include <siconos/numerics/NonSmoothDrivers.h>
#include <siconos/numerics/NumericsMatrix.h>
#include <siconos/numerics/SolverOptions.h>
}

#include "rocking_monitor/constants.hpp"

namespace rocking_monitor::reference {

namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

constexpr int kPerm[3] = {2, 0, 1};  // Siconos' local frame at a floor contact: (n, t1, t2) = (z, x, y)

// A point counts as a contact when its gap, predicted half a step ahead (as Siconos' Moreau-Jean
// integrator activates its interactions), is below this: contact points at rest sit within rounding
// of the floor, and a slightly open point that is held at zero approach speed costs nothing.
constexpr double kActiveGap = 1e-9;  // m

}  // namespace

MoreauJeanRigidBody::MoreauJeanRigidBody(const MoreauJeanBody& body, const MoreauJeanSettings& settings)
    : body_(body), settings_(settings), x_(body.centre_of_mass), x0_(body.centre_of_mass) {
  if (body.points.size() < 4 || !(body.mass > 0.0) || !(settings.step > 0.0))
    throw std::invalid_argument("MoreauJeanRigidBody: >= 4 points, mass > 0 and step > 0");
  for (Eigen::Vector3d& p : body_.points) p -= body.centre_of_mass;  // rest frame about the centre
}

double MoreauJeanRigidBody::tilt() const { return std::acos(std::clamp(r_(2, 2), -1.0, 1.0)); }

void MoreauJeanRigidBody::contact_impulses(const std::vector<int>& active, const Eigen::Vector3d& v_free,
                                           const Eigen::Vector3d& w_free, const Eigen::Matrix3d& j_inv,
                                           std::vector<Eigen::Vector3d>& impulse) {
  const int n = static_cast<int>(active.size()), m = 3 * n;
  std::vector<Eigen::Vector3d> arm(n);
  for (int k = 0; k < n; ++k) arm[k] = r_ * body_.points[active[k]];
  NumericsMatrix* w = NM_create(NM_DENSE, m, m);
  std::vector<double> q(m), mus(n, settings_.mu), velocity(m, 0.0);
  std::vector<double> reaction = active == warm_set_ ? warm_ : std::vector<double>(m, 0.0);
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d u = v_free + w_free.cross(arm[k]);
    for (int l = 0; l < n; ++l) {
      // Delassus block: the velocity at k per unit impulse at l.
      const Eigen::Matrix3d block =
          Eigen::Matrix3d::Identity() / body_.mass - skew(arm[k]) * j_inv * skew(arm[l]);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) w->matrix0[(3 * k + i) + (3 * l + j) * m] = block(kPerm[i], kPerm[j]);
    }
    for (int i = 0; i < 3; ++i) q[3 * k + i] = u(kPerm[i]);
  }
  FrictionContactProblem* problem = frictionContactProblem_new_with_data(3, n, w, q.data(), mus.data());
  SolverOptions* options = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  options->iparam[SICONOS_IPARAM_MAX_ITER] = 10000;
  options->dparam[SICONOS_DPARAM_TOL] = settings_.solver_tol;
  if (fc3d_driver(problem, reaction.data(), velocity.data(), options) != 0) ++outcome_.unconverged;
  outcome_.worst_residual = std::max(outcome_.worst_residual, options->dparam[SICONOS_DPARAM_RESIDU]);
  solver_options_delete(options);
  problem->q = nullptr;  // borrowed (std::vector); the problem owns the matrix
  problem->mu = nullptr;
  frictionContactProblem_free(problem);
  impulse.assign(n, Eigen::Vector3d::Zero());
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < 3; ++i) impulse[k](kPerm[i]) = reaction[3 * k + i];
  warm_ = reaction;
  warm_set_ = active;
}

void MoreauJeanRigidBody::substep(const Eigen::Vector3d& a, double h) {
  const Eigen::Vector3d g_eff(-a.x(), -a.y(), -(core::kGravity + a.z()));
  const Eigen::Matrix3d j = r_ * body_.central_inertia * r_.transpose();
  const Eigen::Matrix3d j_inv = j.inverse();
  // Free motion over the step (gravity, the ground's inertial force, the gyroscopic torque).
  const Eigen::Vector3d v_free = v_ + h * g_eff;
  const Eigen::Vector3d w_free = w_ - h * j_inv * w_.cross(j * w_);
  std::vector<int> active;
  for (int i = 0; i < static_cast<int>(body_.points.size()); ++i) {
    const Eigen::Vector3d arm = r_ * body_.points[i];
    const double z = x_.z() + arm.z(), uz = v_.z() + w_.cross(arm).z();
    if (z + 0.5 * h * uz <= kActiveGap) active.push_back(i);
  }
  Eigen::Vector3d v_new = v_free, w_new = w_free;
  if (!active.empty()) {
    std::vector<Eigen::Vector3d> impulse;
    contact_impulses(active, v_free, w_free, j_inv, impulse);
    for (std::size_t k = 0; k < active.size(); ++k) {
      v_new += impulse[k] / body_.mass;
      w_new += j_inv * (r_ * body_.points[active[k]]).cross(impulse[k]);
    }
  }
  // theta = 1/2: positions move with the mean of the step's velocities.
  x_ += 0.5 * h * (v_ + v_new);
  const Eigen::Vector3d turn = 0.5 * h * (w_ + w_new);
  if (turn.norm() > 0.0) r_ = Eigen::AngleAxisd(turn.norm(), turn.normalized()).toRotationMatrix() * r_;
  v_ = v_new;
  w_ = w_new;
}

void MoreauJeanRigidBody::step(const Eigen::Vector3d& a, double dt) {
  if (!(dt > 0.0)) throw std::invalid_argument("MoreauJeanRigidBody::step: dt > 0");
  const int n = std::max(1, static_cast<int>(std::ceil(dt / settings_.step - 1e-9)));
  const double h = dt / n;
  for (int i = 0; i < n; ++i) {
    substep(a_prev_ + (i + 0.5) / n * (a - a_prev_), h);  // the hold's midpoint over the sub-step
    t_ += h;
    if (outcome_.overturned) continue;
    const double th = tilt();
    outcome_.max_tilt = std::max(outcome_.max_tilt, th);
    if (th >= settings_.overturn_tilt) {
      outcome_.overturned = true;
      outcome_.overturn_time = t_;
    }
  }
  a_prev_ = a;
}

}  // namespace rocking_monitor::reference
