#pragma once

// Random landings for the impact laws' tests (test_impact_law.cpp, test_frictional_impact.cpp,
// test_siconos_friction.cpp): an irregular convex base (points on an ellipse at perturbed angles:
// convex, as BaseBody requires), an off-centre centre of mass, a turned inertia, the body turning
// about one base vertex with any spin; the contact set is the whole base on the floor.
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/physics/impact_3d.hpp"

namespace rocking_monitor::core::testing {

struct RandomLanding {
  std::vector<Eigen::Vector2d> base;
  int pivot = 0;  ///< the base vertex the body turns about
  LandingBody body;
  LandingContacts set;  ///< every base vertex on the floor, vertex k = base vertex k
};

/// Trial `trial` draws its base size (3 + trial % 6 vertices) and pivot (trial % n) from it; the rest
/// from `rng` (and Eigen's Random, std::rand).
inline RandomLanding random_landing(std::mt19937& rng, int trial) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RandomLanding out;
  const int n = 3 + trial % 6;
  const double ry = 0.3 * (1.0 + 0.5 * u(rng));
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * (i + 0.4 * u(rng)) / n;
    out.base.emplace_back(0.3 * std::cos(a), ry * std::sin(a));
  }
  const Eigen::Vector3d c(0.05 * u(rng), 0.05 * u(rng), 0.08 + 0.6 * (1 + u(rng)));
  const Eigen::Matrix3d a = Eigen::Matrix3d::Random() * 0.1;
  const Eigen::Matrix3d jc = a * a.transpose() + 0.02 * Eigen::Matrix3d::Identity();
  out.pivot = trial % n;
  const Eigen::Vector3d p(out.base[out.pivot].x(), out.base[out.pivot].y(), 0.0);
  const Eigen::Vector3d omega(u(rng), u(rng), 0.3 * u(rng));
  out.body = LandingBody{jc, c, omega, omega.cross(c - p)};
  out.set.base_vertex_count = n;
  for (int i = 0; i < n; ++i) {
    out.set.point[out.set.count] = Eigen::Vector3d(out.base[i].x(), out.base[i].y(), 0.0);
    out.set.vertex[out.set.count++] = i;
  }
  return out;
}

}  // namespace rocking_monitor::core::testing
