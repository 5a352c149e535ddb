// The frictional plastic impact over a contact set (physics/frictional_impact.hpp) against closed
// forms (a contact under the centre of mass: Routh's slip impact; a box landing on an edge: the
// planar corner impact with Coulomb friction, as in Brach, "Mechanical impact dynamics", ch. 5),
// against the sticking law of issue 40 (its limit of large friction), and against the laws it must
// keep on random landings: kinetic energy never grows, the contact law holds at every contact.
// Siconos numerics solves the same problems in test/reference/test_siconos_friction.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <Eigen/Dense>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/physics/frictional_impact.hpp"
#include "rocking_monitor/physics/impact_3d.hpp"
#include "random_landings.hpp"

namespace rocking_monitor::core {
namespace {

LandingContacts points_at(const std::vector<Eigen::Vector2d>& xy) {
  LandingContacts c;
  c.base_vertex_count = static_cast<int>(xy.size());
  for (const Eigen::Vector2d& p : xy) {
    c.point[c.count] = Eigen::Vector3d(p.x(), p.y(), 0.0);
    c.vertex[c.count] = c.count;
    ++c.count;
  }
  return c;
}

// A point under the centre of mass at depth h, an axisymmetric body (J_x = J_y = J): the tangential
// impulse does not change the normal velocity, the contact's tangential mobility is 1 + h^2 / J.
// The impact stops the fall (P_n = -v_z) and sticks when |v_t| / (1 + h^2/J) <= mu P_n; otherwise
// it slips along v_t with P_t = mu_k P_n against it (Routh's graphical method, the collinear case).
TEST(FrictionalImpact, APointUnderTheCentreOfMassIsRouthsSlipImpact) {
  const double h = 0.4, jxy = 0.05, jz = 0.03;
  const Eigen::Matrix3d jc = Eigen::Vector3d(jxy, jxy, jz).asDiagonal();
  const double mobility = 1.0 + h * h / jxy;
  for (double mu : {0.05, 0.2, 0.5, 2.0}) {
    for (double angle : {0.0, 0.7, 2.5}) {
      const Eigen::Vector3d v(0.6 * std::cos(angle), 0.6 * std::sin(angle), -0.8);
      const LandingBody b{jc, Eigen::Vector3d(0, 0, h), Eigen::Vector3d::Zero(), v};
      const FrictionalLanding f = frictional_landing(b, points_at({{0, 0}}), {mu, mu});
      ASSERT_TRUE(f.converged);
      const double pn = 0.8, vt = 0.6;
      const bool sticks = vt / mobility <= mu * pn;
      const double pt = sticks ? vt / mobility : mu * pn;  // magnitude, against v_t
      const Eigen::Vector3d impulse(-pt * std::cos(angle), -pt * std::sin(angle), pn);
      EXPECT_LT((f.velocity - (v + impulse)).norm(), 1e-12) << mu << " " << angle;
      // The tangential impulse at depth h turns the body: J w = a x P with a = (0, 0, -h).
      const Eigen::Vector3d w = jc.inverse() * Eigen::Vector3d(0, 0, -h).cross(impulse);
      EXPECT_LT((f.omega - w).norm(), 1e-12);
      EXPECT_EQ(f.stay, 1);
      EXPECT_EQ(f.slipping, sticks ? 0 : 1);
      const Eigen::Vector3d u = point_velocity(f.omega, f.velocity, b.centre, Eigen::Vector3d::Zero());
      EXPECT_NEAR(u.z(), 0.0, 1e-12);
      if (!sticks) EXPECT_NEAR(std::hypot(u.x(), u.y()), vt - mobility * mu * pn, 1e-12);
    }
  }
}

// The planar corner impact with Coulomb friction (in the x-z plane, rotation about y, lever a from
// the centre of mass to the corner, J the inertia per mass about y): with W = [[1 + a_z^2/J,
// -a_x a_z/J], [-a_x a_z/J, 1 + a_x^2/J]] over (P_x, P_z) the corner's velocity changes by W P. Stick:
// W P = -u; slip (|P_x| > mu P_z): P_x = -s mu P_z with P_z from u_z = 0, s the sign of the slip.
struct Planar {
  double px, pz;
  bool stick;
};
Planar planar_corner_impact(double ax, double az, double j, double ux, double uz, double mu) {
  const double w11 = 1 + az * az / j, w12 = -ax * az / j, w22 = 1 + ax * ax / j;
  const double det = w11 * w22 - w12 * w12;
  const double px = (-ux * w22 + uz * w12) / det, pz = (-uz * w11 + ux * w12) / det;
  if (pz >= 0 && std::abs(px) <= mu * pz) return {px, pz, true};
  const double s = px > 0 ? -1.0 : 1.0;  // the slip opposes the sticking impulse's direction
  const double pz_slip = -uz / (w22 - s * mu * w12);
  return {-s * mu * pz_slip, pz_slip, false};
}

// A box B x D x H (centre of mass at height cz, x = cx) rocking about its edge x = B lands flat: the
// whole base touches; the new pivot edge x = 0 takes the impulse, the old one leaves the floor.
TEST(FrictionalImpact, ABoxLandingFlatIsThePlanarCornerImpactWithCoulombFriction) {
  const double b = 0.4, d = 0.3, hgt = 1.2;
  int slips = 0, sticks = 0;
  for (double cx : {0.2, 0.15, 0.26}) {
    const double cz = 0.5 * hgt;
    const Eigen::Matrix3d jc =
        Eigen::Vector3d((d * d + hgt * hgt) / 12, (b * b + hgt * hgt) / 12, (b * b + d * d) / 12).asDiagonal();
    for (double mu : {0.05, 0.1, 0.15, 0.3, 0.6}) {
      const Eigen::Vector3d c(cx, 0.0, cz), pivot(b, 0.0, 0.0);
      const Eigen::Vector3d omega(0.0, -1.3, 0.0);  // back to flat: the edge x = 0 comes down
      const LandingBody body{jc, c, omega, omega.cross(c - pivot)};
      const LandingContacts set = points_at({{0, -d / 2}, {b, -d / 2}, {b, d / 2}, {0, d / 2}});
      const FrictionalLanding f = frictional_landing(body, set, {mu, mu});
      ASSERT_TRUE(f.converged) << mu;
      const Eigen::Vector3d u0 = point_velocity(omega, body.velocity, c, Eigen::Vector3d::Zero());
      const Planar p = planar_corner_impact(-cx, -cz, jc(1, 1), u0.x(), u0.z(), mu);
      (p.stick ? sticks : slips) += 1;
      const Eigen::Vector3d v = body.velocity + Eigen::Vector3d(p.px, 0.0, p.pz);
      const double wy = omega.y() + (-cz * p.px + cx * p.pz) / jc(1, 1);
      EXPECT_LT((f.velocity - v).norm(), 1e-10) << cx << " " << mu;
      EXPECT_LT((f.omega - Eigen::Vector3d(0, wy, 0)).norm(), 1e-10) << cx << " " << mu;
      // the old edge leaves the floor; the new one stays, slipping exactly when the closed form slips
      EXPECT_GT(point_velocity(f.omega, f.velocity, c, pivot).z(), 0.0);
      EXPECT_EQ(f.stay, 2);
      EXPECT_EQ(f.slipping, p.stick ? 0 : 2);
      if (p.stick) {
        // and then it is exactly issue 40's sticking landing (eq. 34)
        const Landing l = plastic_landing(body, set);
        EXPECT_LT((f.omega - l.omega).norm(), 1e-12);
        EXPECT_LT((f.velocity - l.velocity).norm(), 1e-12);
      }
    }
  }
  EXPECT_GT(slips, 3);
  EXPECT_GT(sticks, 3);
}

// Random landings as in test_impact_law.cpp: irregular convex bases, off-centre centres of mass,
// any spin. Energy never grows; the contact law holds at every contact after; with friction far
// above any demand the law is the sticking law wherever that has an admissible solution; and the
// landings without one (about 5 %) get an answer too.
TEST(FrictionalImpact, RandomLandingsKeepTheContactLawAndNeverGainEnergy) {
  std::mt19937 rng(51);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  constexpr int kTrials = 800;
  int same_as_sticking = 0, several = 0, other = 0, without_sticking = 0, solved_without = 0, slipping = 0, unconverged = 0;
  long sweeps = 0;
  double worst_unconverged = 0.0;
  for (int trial = 0; trial < kTrials; ++trial) {
    const testing::RandomLanding rl = testing::random_landing(rng, trial);
    const LandingBody& body = rl.body;
    const LandingContacts& set = rl.set;
    const Eigen::Vector3d& omega = body.omega;
    const double scale = body.velocity.norm() + omega.norm();
    const double mu = 0.1 + 0.9 * (1 + u(rng)) / 2;
    const FrictionalLanding f = frictional_landing(body, set, {mu, mu});
    sweeps += f.sweeps;
    EXPECT_LE(f.energy_after, f.energy_before * (1 + 1e-12)) << trial;
    if (!f.converged) {
      ++unconverged;  // Gauss-Seidel cycles: reported (the model keeps the sticking law there)
      worst_unconverged = std::max(worst_unconverged, f.residual / scale);
      continue;
    }
    EXPECT_LT(f.residual, 1e-10 * scale) << trial;
    if (f.slipping > 0) ++slipping;
    const Landing l = plastic_landing(body, set);
    const FrictionalLanding big = frictional_landing(body, set, {1e6, 1e6});
    if (l.violation == 0.0 && big.converged) {
      if (l.admissible > 1) {
        ++several;  // the sticking law has several solutions; it takes the least dissipative
        continue;
      }
      if ((big.omega - l.omega).norm() > 1e-8 * scale || (big.velocity - l.velocity).norm() > 1e-8 * scale) {
        // Another solution of the (non-unique) law: a contact with no impulse slides along the floor,
        // which the sticking law's enumeration (vertices, edges, the face) does not try. It still
        // keeps the law and dissipates more.
        ++other;
        EXPECT_LE(big.energy_after, l.energy_after) << trial;
        continue;
      }
      ++same_as_sticking;
    } else if (l.violation > 0.0) {
      ++without_sticking;
      ++solved_without;  // f converged: the contact law holds with finite friction
    }
  }
  // Measured: 735 equal the sticking law; 21 where that law has several solutions; 32 landings without
  // a sticking solution solved; 11 of 800 (1.4 %) not converged within the 2,000 sweeps (3 with
  // 20,000, at 100 times the worst cost); ~60 sweeps on average.
  std::printf("[ measure ] %d landings: %d = the sticking law at mu 1e6 (%d where it has several solutions), "
              "%d without a sticking solution solved, %d slip at mu in [0.1, 1], %d unconverged (residual up to %.2g of the "
              "velocity scale), %d another solution; %.1f sweeps on average\n",
              kTrials, same_as_sticking, several, solved_without, slipping, unconverged, worst_unconverged, other, double(sweeps) / kTrials);
  EXPECT_GT(same_as_sticking, 650);
  EXPECT_GT(solved_without, 20);
  EXPECT_GT(slipping, 200);
  EXPECT_LE(unconverged, kTrials / 50);
  EXPECT_LE(other, 3);
}

}  // namespace
}  // namespace rocking_monitor::core
