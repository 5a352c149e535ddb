#include "bullet_rocking.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <btBulletDynamicsCommon.h>

#include "rocking_monitor/constants.hpp"

namespace rocking_monitor::reference {

struct BulletRocking::World {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  btStaticPlaneShape floor_shape{btVector3(0, 0, 1), 0};
  std::unique_ptr<btConvexHullShape> hull;
  std::unique_ptr<btRigidBody> floor;
  std::unique_ptr<btRigidBody> body;
  Eigen::Matrix3d principal = Eigen::Matrix3d::Identity();  // body frame axes in the floor frame

  ~World() {
    if (body) world.removeRigidBody(body.get());
    if (floor) world.removeRigidBody(floor.get());
  }
};

namespace {

Eigen::Matrix3d to_eigen(const btMatrix3x3& m) {
  Eigen::Matrix3d r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = m[i][j];
  return r;
}

}  // namespace

BulletRocking::BulletRocking(const BulletBody& body, const BulletSettings& settings)
    : w_(std::make_unique<World>()), settings_(settings) {
  if (body.points.size() < 4 || !(body.mass > 0.0) || !(settings.substep > 0.0))
    throw std::invalid_argument("BulletRocking: >= 4 points, mass > 0 and substep > 0");
  // Bullet wants the body frame at the centre of mass along the principal axes of inertia: the
  // points are moved into that frame (the same as a compound shape's child transform, without the
  // compound's extra collision layer).
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(body.central_inertia);
  if (eig.info() != Eigen::Success || !(eig.eigenvalues().minCoeff() > 0.0))
    throw std::invalid_argument("BulletRocking: the central inertia must be positive definite");
  Eigen::Matrix3d v = eig.eigenvectors();
  if (v.determinant() < 0.0) v.col(2) = -v.col(2);
  w_->principal = v;
  w_->hull = std::make_unique<btConvexHullShape>();
  for (const Eigen::Vector3d& p : body.points) {
    const Eigen::Vector3d q = v.transpose() * (p - body.centre_of_mass);
    w_->hull->addPoint(btVector3(q.x(), q.y(), q.z()), false);
  }
  w_->hull->recalcLocalAabb();
  w_->hull->optimizeConvexHull();  // keep the hull's vertices only (a mesh has thousands)
  w_->hull->setMargin(settings.margin);

  // Contact: up to 4 manifold points from the plane-convex algorithm; with perturbation it finds
  // all the corners a flat base rests on (the default finds one per step).
  w_->config.setPlaneConvexMultipointIterations(3, 3);
  gContactBreakingThreshold = settings.contact_threshold;  // Bullet's global (default 2 cm)
  btContactSolverInfo& info = w_->world.getSolverInfo();
  info.m_numIterations = settings.solver_iterations;
  info.m_splitImpulse = settings.split_impulse ? 1 : 0;
  // Every penetration goes to split-impulse recovery (the default only splits deep ones, > 4 cm).
  info.m_splitImpulsePenetrationThreshold = 1.0;
  info.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;  // friction in both tangent directions
  info.m_restitution = 0.0;
  w_->world.setGravity(btVector3(0, 0, -core::kGravity));

  btRigidBody::btRigidBodyConstructionInfo floor_info(0.0, nullptr, &w_->floor_shape);
  floor_info.m_friction = 1.0;
  floor_info.m_restitution = 0.0;
  w_->floor = std::make_unique<btRigidBody>(floor_info);
  w_->world.addRigidBody(w_->floor.get());

  const Eigen::Vector3d ev = eig.eigenvalues();
  btRigidBody::btRigidBodyConstructionInfo info_b(body.mass, nullptr, w_->hull.get(),
                                                  btVector3(ev.x(), ev.y(), ev.z()));
  info_b.m_friction = settings.friction;
  info_b.m_restitution = 0.0;
  info_b.m_linearDamping = info_b.m_angularDamping = 0.0;
  btTransform start;
  start.setBasis(btMatrix3x3(v(0, 0), v(0, 1), v(0, 2), v(1, 0), v(1, 1), v(1, 2), v(2, 0), v(2, 1),
                             v(2, 2)));
  // The hull is inflated by the margin: lift the body by it so that it just touches the floor.
  const Eigen::Vector3d& c = body.centre_of_mass;
  start.setOrigin(btVector3(c.x(), c.y(), c.z() + settings.margin));
  info_b.m_startWorldTransform = start;
  w_->body = std::make_unique<btRigidBody>(info_b);
  w_->body->setActivationState(DISABLE_DEACTIVATION);
  w_->body->setContactProcessingThreshold(settings.contact_threshold);
  w_->world.addRigidBody(w_->body.get());

  // Settle under gravity alone (the contact's compliance takes up the weight), then start at rest.
  const int n_settle = static_cast<int>(std::ceil(settings.settle_time / settings.substep));
  for (int i = 0; i < n_settle; ++i) substep(Eigen::Vector3d::Zero(), settings.substep);
  w_->body->setLinearVelocity(btVector3(0, 0, 0));
  w_->body->setAngularVelocity(btVector3(0, 0, 0));
  rest_ = body_rotation();
  settle_tilt_ = std::acos(std::clamp(rest_(2, 2), -1.0, 1.0));
  t_ = 0.0;
}

BulletRocking::~BulletRocking() = default;

Eigen::Matrix3d BulletRocking::body_rotation() const {
  // From the floor frame at rest (the given points) to now: body basis x principal axes^T.
  return to_eigen(w_->body->getWorldTransform().getBasis()) * w_->principal.transpose();
}

Eigen::Matrix3d BulletRocking::rotation() const { return body_rotation() * rest_.transpose(); }

double BulletRocking::tilt() const { return std::acos(std::clamp(rotation()(2, 2), -1.0, 1.0)); }

void BulletRocking::substep(const Eigen::Vector3d& a, double h) {
  // The ground's inertial force per unit mass plus gravity, held over the step.
  w_->body->setGravity(btVector3(-a.x(), -a.y(), -(core::kGravity + a.z())));
  w_->world.stepSimulation(h, 0);  // maxSubSteps = 0: exactly one step of h
}

void BulletRocking::step(const Eigen::Vector3d& a, double dt) {
  if (!(dt > 0.0)) throw std::invalid_argument("BulletRocking::step: dt > 0");
  const int n = std::max(1, static_cast<int>(std::ceil(dt / settings_.substep - 1e-9)));
  const double h = dt / n;
  double tilt_before = tilt();
  for (int i = 0; i < n; ++i) {
    // Midpoint of the sub-step on the first-order hold.
    const double s = (i + 0.5) / n;
    const Eigen::Vector3d am = a_prev_ + s * (a - a_prev_);
    substep(am, h);
    t_ += h;
    const double th = tilt();
    if (record_) history_.emplace_back(t_, th);
    if (outcome_.overturned) {
      tilt_before = th;
      continue;
    }
    outcome_.max_tilt = std::max(outcome_.max_tilt, th);
    if (th >= settings_.overturn_tilt) {
      outcome_.overturned = true;
      // Linear between the sub-steps (the step is small against the fall).
      const double f = (settings_.overturn_tilt - tilt_before) / (th - tilt_before);
      outcome_.overturn_time = t_ - h + std::clamp(f, 0.0, 1.0) * h;
    }
    tilt_before = th;
  }
  a_prev_ = a;
}

}  // namespace rocking_monitor::reference
