// Free flight in 3-D (issue 51 part 2): the floor dropping faster than gravity throws the body up.
// Oracles: the closed form of a body thrown off a floor whose acceleration is piecewise linear (the
// samples' first-order hold: its motion is a piecewise cubic) and of the flat landing's Coulomb rule
// (plastic normal impulse, friction up to mu_s of it, else mu_k of it, then Coulomb sliding to rest);
// the free symmetric top (Euler's torque-free motion in closed form: Landau & Lifshitz, Mechanics,
// section 33); the planar contact model's slide-rock and FLIGHT (an independent code: x, y, theta with
// RK4 and its own events) for a rhombus on its corner; and a snapshot taken in flight resuming bit for
// bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "rocking_monitor/model/contact_model.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rhombus_on_corner.hpp"
#include "test_helpers.hpp"

namespace rocking_monitor::core {
namespace {

SolverSettings flight_settings() { return testing::tight_settings(1e-11); }  // (dopri5, nonlinear: the defaults)

// Exact motion under an acceleration linear in each sample [t_i, t_i + dt] (the first-order hold of
// the samples acc(t_i)): position and velocity at t from (t0, x0, v0).
struct HeldMotion {
  std::function<double(double)> acc;  // at the sample instants
  double dt;
  void advance(double t0, double t, double& x, double& v) const {
    double s = t0;
    while (s < t) {
      const double k = std::floor(s / dt + 1e-9);
      const double a_start = k * dt, a_end = (k + 1) * dt;
      const double e = std::min(t, a_end);
      const double slope = (acc(a_end) - acc(a_start)) / dt;
      const double c0 = acc(a_start) + slope * (s - a_start), h = e - s;
      x += v * h + c0 * h * h / 2 + slope * h * h * h / 6;
      v += c0 * h + slope * h * h / 2;
      s = e;
    }
  }
};

// The first return to z = 0 after t0 of the motion from z = 0 at rest (bisection on the closed form,
// sample by sample).
double landing_time(const HeldMotion& m, double t0) {
  double z = 0.0, v = 0.0, t = t0;
  const double h = m.dt / 64;
  for (;;) {
    double z1 = z, v1 = v;
    m.advance(t, t + h, z1, v1);
    if (z1 < 0.0 && t > t0 + h) {
      double a = t, b = t + h;
      for (int i = 0; i < 200 && b - a > 1e-15; ++i) {
        const double c = 0.5 * (a + b);
        double zc = z, vc = v;
        m.advance(t, c, zc, vc);
        (zc > 0.0 ? a : b) = c;
      }
      return 0.5 * (a + b);
    }
    z = z1;
    v = v1;
    t += h;
  }
}

// The first transition out of `from` (its instant, s), NaN if none.
double leaves(const Rocking3DModel& m, Mode3D from) {
  for (int i = 0; i < m.transition_records(); ++i)
    if (m.transition(i).from == from && m.transition(i).to != from) return m.transition(i).time;
  return NAN;
}

// A box at rest; the floor drops with a half-sine of Z g (faster than gravity) from 0.1 s for 0.2 s
// and, once the box is in the air, moves sideways (a pulse of X g): it lifts off where g + a_z = 0,
// drifts, lands flat where it comes back to the floor, and slides to rest under Coulomb's law where
// its landing's friction could not stop it. Every number from the closed form.
TEST(Rocking3DFlight, AFloorDroppingFasterThanGravityThrowsTheBoxUpAndItLandsFlat) {
  const double b = 0.4, d = 0.5, h = 0.6, dt = 0.005;
  int cases = 0, slid = 0;
  for (double Z : {1.2, 1.6, 2.5})
    for (double X : {0.0, 0.5, -1.5})
      for (double mu : {0.2, 0.3}) {  // (below tan alpha = 1/3: braking does not tip it)
        auto az = [&](double t) { return t > 0.1 + 1e-12 && t < 0.3 - 1e-12 ? -Z * kGravity * std::sin(kPi * (t - 0.1) / 0.2) : 0.0; };
        // lift-off: the first sample interval where g + a_z turns <= 0 (linear there)
        double t_lift = NAN;
        for (int i = 1; i < 100 && std::isnan(t_lift); ++i) {
          const double n0 = kGravity + az((i - 1) * dt), n1 = kGravity + az(i * dt);
          if (n0 > 0.0 && n1 <= 0.0) t_lift = (i - 1) * dt + dt * n0 / (n0 - n1);
        }
        ASSERT_FALSE(std::isnan(t_lift));
        const double x_from = (std::floor(t_lift / dt) + 2) * dt, x_to = x_from + 0.03;
        auto ax = [&](double t) { return t >= x_from - 1e-12 && t <= x_to + 1e-12 ? X * kGravity : 0.0; };
        const HeldMotion vertical{[&](double t) { return -(kGravity + az(t)); }, dt};
        const HeldMotion horizontal{[&](double t) { return -ax(t); }, dt};
        const double t_land = landing_time(vertical, t_lift);
        ASSERT_GT(t_land, x_to + dt);  // (the sideways pulse is over before it lands)
        double z = 0.0, vz = 0.0, x = 0.0, vx = 0.0;
        vertical.advance(t_lift, t_land, z, vz);
        horizontal.advance(t_lift, t_land, x, vx);
        // The flat landing: the normal impulse stops the fall; friction takes up to mu_s of it, else
        // mu_k of it off the slip; then Coulomb sliding (g, no more input) to rest.
        const double pn = -vz;
        double u = std::abs(vx) <= mu * pn ? 0.0 : vx - std::copysign(mu * pn, vx);
        const double slip = x + std::copysign(u * u / (2 * mu * kGravity), u);
        Rocking3DModel m(BaseBody(testing::uniform_box(b, d, h, mu, mu)), flight_settings());
        m.reset(0.0);
        double top = 0.0;
        for (int i = 1; i * dt <= 1.5 + 1e-12; ++i) {
          m.step(Eigen::Vector3d(ax(i * dt), 0.0, az(i * dt)), dt);
          if (m.mode() == Mode3D::Flight) {
            EXPECT_LT(m.tilt(), 1e-12);  // no torque about the centre: it never turns
            top = std::max(top, m.translation().z());
            // Flying flat is no step towards tipping: the flight's height and speed do not count.
            EXPECT_LT(m.rotation_ratio(), 1e-9);
            EXPECT_FALSE(m.committed_now());
          }
        }
        const Rocking3DOutcome& o = m.outcome_3d();
        std::printf("[ measure ] Z %.1f g X %+.1f g mu %.1f: lift-off %.9f (closed form %.9f), landing %.9f (%.9f), "
                    "final slip %.9f m (%.9f), %ld flights\n", Z, X, mu, o.first_flight_time, t_lift,
                    leaves(m, Mode3D::Flight), t_land, m.slip().x(), slip, o.flights);
        ++cases;
        EXPECT_EQ(o.landing_slides > 0, u != 0.0);  // (the landing's friction could not stop it: slides on)
        slid += o.landing_slides > 0;
        ASSERT_EQ(o.flights, 1);
        EXPECT_EQ(o.flight_landings, 1);
        EXPECT_NEAR(o.first_flight_time, t_lift, 1e-9);
        EXPECT_NEAR(leaves(m, Mode3D::Flight), t_land, 1e-8);
        EXPECT_NEAR(o.flight_time, t_land - t_lift, 1e-8);
        double z_top = 0.0, v_top = 0.0;  // the apex: where the vertical velocity turns down
        const double t_top = [&] {
          double a = t_lift, c = t_land;
          for (int i = 0; i < 200; ++i) {
            const double mid = 0.5 * (a + c);
            double zz = 0.0, vv = 0.0;
            vertical.advance(t_lift, mid, zz, vv);
            (vv > 0.0 ? a : c) = mid;
          }
          return a;
        }();
        vertical.advance(t_lift, t_top, z_top, v_top);
        EXPECT_LE(o.max_flight_height, z_top + 1e-9);
        EXPECT_LE(top, z_top + 1e-9);
        EXPECT_GT(o.max_flight_height, 0.5 * z_top);
        EXPECT_EQ(m.mode(), Mode3D::Rest);
        EXPECT_NEAR(m.slip().x(), slip, 1e-8);
        EXPECT_NEAR(m.slip().y(), 0.0, 1e-12);
        EXPECT_LE(o.max_impact_energy_ratio, 1.0 + 1e-12);
      }
  std::printf("[ measure ] %d flights, %d of them slid on after landing\n", cases, slid);
  EXPECT_GE(slid, 3);
}

// A spinning square-based box (a symmetric top: I1 = I2) thrown into the air over a shaking floor:
// in flight no torque acts about the centre of mass, so its angular momentum there is constant and its
// orientation is the free symmetric top's, R(t) = Rot(L, |L| t / I1) R0 Rot(e3, (1/I3 - 1/I1)(a.L) t)
// (a: the symmetry axis; the body's angular velocity J^-1 L is the sum of the two rates); its centre
// moves under gravity and the floor's inertial force alone (the closed form of the held samples).
TEST(Rocking3DFlight, ASpinningBoxInFlightTurnsAsTheFreeSymmetricTop) {
  const double b = 0.4, h = 0.6, dt = 0.005;
  const BaseBodyParameters p = testing::uniform_box(b, b, h, 0.5, 0.5);
  const double i1 = p.central_inertia(0, 0), i3 = p.central_inertia(2, 2);
  int samples = 0;
  double worst_rotation = 0.0, worst_centre = 0.0, worst_momentum = 0.0;
  for (double spin : {6.0, -9.0})
    for (double tilt0 : {0.05, 0.15}) {
      auto a_at = [&](double t) {
        return Eigen::Vector3d(0.3 * kGravity * std::sin(2 * kPi * t / 0.4), -0.2 * kGravity * std::cos(2 * kPi * t / 0.3),
                               0.2 * kGravity * std::sin(2 * kPi * t / 0.5));
      };
      Rocking3DModel m(BaseBody(p), flight_settings());
      m.reset(0.0, a_at(0.0));
      const Eigen::Quaterniond q0(Eigen::AngleAxisd(tilt0, Eigen::Vector3d(1.0, 0.4, 0.0).normalized()));
      const Eigen::Vector3d c0(0.1, -0.05, 1.4), v0(0.3, -0.2, 1.0), w0(0.5, -0.3, spin);
      m.set_flight_state(q0, c0, v0, w0);
      const Eigen::Matrix3d r0 = q0.toRotationMatrix();
      const Eigen::Matrix3d j0 = r0 * p.central_inertia * r0.transpose();
      const Eigen::Vector3d l = j0 * w0, a0 = r0.col(2);
      const double lambda = (1.0 / i3 - 1.0 / i1) * a0.dot(l), energy = 0.5 * w0.dot(l);
      for (int i = 1; i * dt <= 3.0 + 1e-12; ++i) {
        const double t = i * dt;
        m.step(a_at(t), dt);
        if (m.mode() != Mode3D::Flight) break;
        ++samples;
        const Eigen::Matrix3d r = m.rotation();
        const Eigen::Matrix3d expected = Eigen::AngleAxisd(l.norm() * t / i1, l.normalized()) * r0 *
                                         Eigen::AngleAxisd(lambda * t, Eigen::Vector3d::UnitZ());
        worst_rotation = std::max(worst_rotation, (r - expected).cwiseAbs().maxCoeff());
        const Eigen::Vector3d w = m.angular_velocity();
        const Eigen::Vector3d lt = r * p.central_inertia * r.transpose() * w;
        worst_momentum = std::max(worst_momentum, (lt - l).norm() / l.norm());
        EXPECT_NEAR(0.5 * w.dot(lt), energy, 1e-8 * energy);
        Eigen::Vector3d c = c0, v = v0;
        for (int k = 0; k < 3; ++k) {
          const HeldMotion axis{[&](double s) { return k == 2 ? -(kGravity + a_at(s).z()) : -a_at(s)(k); }, dt};
          axis.advance(0.0, t, c(k), v(k));
        }
        const Eigen::Vector3d centre = r * p.centre_of_mass + m.translation();
        worst_centre = std::max(worst_centre, (centre - c).norm());
        EXPECT_LT((m.centre_velocity() - v).norm(), 1e-8);
      }
      const Rocking3DOutcome& o = m.outcome_3d();
      EXPECT_NE(m.mode(), Mode3D::Flight);  // it came down
      EXPECT_EQ(o.flight_landings, 1);
      EXPECT_LE(o.max_impact_energy_ratio, 1.0 + 1e-12);
    }
  std::printf("[ measure ] %d samples in flight: rotation within %.2g of the free top, angular momentum within %.2g, "
              "centre within %.2g m of the closed form\n", samples, worst_rotation, worst_momentum, worst_centre);
  EXPECT_GT(samples, 350);
  EXPECT_LT(worst_rotation, 1e-8);
  EXPECT_LT(worst_momentum, 1e-9);
  EXPECT_LT(worst_centre, 1e-8);
}

// Slide-rock and flight on a vertex against the planar contact model (an independent code: x, y,
// theta with RK4 and its own events): a rhombus base (a vertex at +x, symmetric about the x-z plane)
// pivoting on its +x vertex moves in the x-z plane as the planar body of width 2a with the same height
// and radius of gyration on its corner. The floor drops faster than gravity: the corner slips, the
// normal force vanishes, the body flies and lands on a corner (friction stopping it, or not: then the
// corner slips on, the frictional impact at one corner being Routh's in both codes). Sample by sample
// until the landing after the flight's, or the overturn: the same lift-off, flight, landing and motion
// after it.
TEST(Rocking3DFlight, ARhombusFliesOffItsVertexAsThePlanarContactModel) {
  const double a = 0.25, c = 0.3, h = 0.9, ig = 0.35, dt = 0.005;
  int flights = 0, compared = 0, overturns = 0;
  long slipped = 0;
  double worst_lift = 0.0, worst = 0.0;
  for (double tol : {1e-11, 1e-8})  // (the tests' and the node's default)
  for (double mu : {0.2, 0.6})
    for (double drop : {1.3, 2.0})
      for (double amp : {0.0, 0.3})
        for (double omega0 : {0.8, -0.5}) {
          const BaseBodyParameters p = testing::rhombus(a, c, h, ig, mu);
          Rocking3DModel solid(BaseBody(p), testing::tight_settings(tol));
          ContactModel planar(testing::planar_rhombus(a, h, ig, mu), testing::fine_contact());
          testing::tilt_on_corner(solid, planar, 0.08, omega0);
          double worst_theta = 0.0, worst_x = 0.0, worst_z = 0.0;
          const double x0 = (solid.rotation() * p.centre_of_mass + solid.translation()).x(), px0 = planar.state()[0];
          double lift3 = NAN, lift2 = NAN, land3 = NAN, land2 = NAN;
          int run_samples = 0;
          bool over3 = false, over2 = false;
          for (int i = 1; i <= 300; ++i) {
            const double t = i * dt, ax = amp * kGravity * std::sin(2 * kPi * t / 0.8);
            const double az = t < 0.3 ? -drop * kGravity * std::sin(kPi * t / 0.3) : 0.0;
            solid.step(Eigen::Vector3d(ax, 0.0, az), dt);
            // (the planar convention mirrors x about corner 1, the 3-D +x vertex)
            const ContactReport& r = planar.step(-ax, az, dt);
            if (std::isnan(lift2) && !std::isnan(planar.outcome().first_flight_time)) lift2 = planar.outcome().first_flight_time;
            if (std::isnan(lift3) && !std::isnan(solid.outcome_3d().first_flight_time)) lift3 = solid.outcome_3d().first_flight_time;
            if (!std::isnan(lift2) && std::isnan(land2) && planar.mode() != ContactMode::Flight) land2 = t;  // (the sample it lands in)
            if (!std::isnan(lift3) && std::isnan(land3) && solid.mode() != Mode3D::Flight) land3 = t;
            const long landings = std::max<long>(solid.outcome().impacts, planar.outcome().impacts);
            if (landings > 1 || (landings == 1 && std::isnan(lift3))) break;
            over3 = solid.mode() == Mode3D::Overturned;
            over2 = planar.mode() == ContactMode::Overturned;
            if (over3 || over2) break;
            const Eigen::Vector3d centre = solid.rotation() * p.centre_of_mass + solid.translation();
            worst_theta = std::max(worst_theta, std::abs(solid.tilt() - std::abs(planar.theta())));
            worst_x = std::max(worst_x, std::abs((centre.x() - x0) + (planar.state()[0] - px0)));
            worst_z = std::max(worst_z, std::abs(centre.z() - planar.cg_height()));
            EXPECT_NEAR(centre.y(), 0.0, 1e-12);
            ++run_samples;
          }
          std::printf("[ measure ] mu %.1f drop %.1f g amp %.1f g omega0 %+.1f: lift-off %.9f / %.9f, landed in the sample "
                      "to %.3f / %.3f s (3-D / planar), %ld slip onsets, %ld landings friction decided; tilt within %.2g rad, "
                      "centre within %.2g m (x), %.2g m (z)\n", mu, drop, amp, omega0, lift3, lift2, land3, land2,
                      solid.outcome_3d().pivot_slips, solid.outcome_3d().frictional_landings, worst_theta, worst_x, worst_z);
          ASSERT_FALSE(std::isnan(lift2));
          EXPECT_LE(solid.outcome_3d().max_impact_energy_ratio, 1.0 + 1e-12);
          ++flights;
          EXPECT_NEAR(lift3, lift2, 1e-9);
          worst_lift = std::max(worst_lift, std::abs(lift3 - lift2));
          // (friction decided the landing where the corner needed more than mu_s: it slips on in both)
          slipped += solid.outcome_3d().corner_slip_landings;
          compared += run_samples;
          EXPECT_EQ(land3, land2);
          EXPECT_EQ(over3, over2);
          overturns += over2;
          EXPECT_LT(worst_theta, 1e-7);
          EXPECT_LT(std::max(worst_x, worst_z), 1e-7);
          worst = std::max({worst, worst_theta, worst_x, worst_z});
        }
  std::printf("[ measure ] %d flights, lift-off within %.2g s; %d samples: tilt and centre within %.2g (rad, m); %d "
              "overturns in the same sample; %ld landings on a corner that slipped on\n", flights, worst_lift, compared,
              worst, overturns, slipped);
  EXPECT_EQ(flights, 32);
  EXPECT_GE(slipped, 3);
}

// A tall box thrown turning hard about y: in the air it turns past its tipping point and lies on its
// side. BEYOND_TIPPING (the rotation ratio about the corner it would land on past 1) comes first, then
// the overturn where the tilt reaches the overturn angle.
TEST(Rocking3DFlight, ATumblingBoxPassesItsTippingPointBeforeItOverturns) {
  const BaseBodyParameters p = testing::uniform_box(0.3, 0.4, 0.6, 0.5, 0.5);
  Rocking3DModel m(BaseBody(p), flight_settings());
  m.reset(0.0);
  m.set_flight_state(Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY())), Eigen::Vector3d(0.0, 0.0, 1.2),
                     Eigen::Vector3d(0.0, 0.0, 2.0), Eigen::Vector3d(0.0, 6.0, 0.0));
  double ratio_before = 0.0;
  for (int i = 1; i <= 100 && m.mode() == Mode3D::Flight; ++i) {
    ratio_before = std::max(ratio_before, m.rotation_ratio());
    m.step(Eigen::Vector3d::Zero(), 0.005);
  }
  const RockingOutcome& o = m.outcome();
  std::printf("[ measure ] beyond tipping at %.4f s, overturned at %.4f s, largest ratio %.3f\n", o.beyond_tipping_time,
              o.overturn_time, o.max_rotation_ratio);
  ASSERT_EQ(m.mode(), Mode3D::Overturned);
  EXPECT_EQ(m.outcome_3d().flight_landings, 0);  // (on its side in the air)
  EXPECT_TRUE(o.beyond_tipping);
  EXPECT_LT(o.beyond_tipping_time, o.overturn_time);
  EXPECT_GT(o.max_rotation_ratio, 1.0);
  EXPECT_GT(ratio_before, 1.0);
  EXPECT_TRUE(o.committed);
}

// A box about a side whose edge's reaction leaves the cone (an edge's slide-rock: counted, followed as
// sticking), then the floor drops: its normal force turns negative with the pivot already outside the
// cone. Below g that is not a lift-off of the body's motion (the real box slide-rocks until its normal
// force vanishes): counted as held down by a pull (pulled_pivots), not flown. Faster than g the floor
// lets go of any pivot: it flies.
TEST(Rocking3DFlight, AnEdgeOutsideTheConeIsCountedPulledOrFliesWithTheFloor) {
  const double b = 0.4, d = 0.5, h = 0.8, dt = 0.005;
  for (double drop : {0.95, 1.6}) {
    Rocking3DModel m(BaseBody(testing::uniform_box(b, d, h, 0.6, 0.6)), flight_settings());
    m.reset(0.0);
    long pulled_on_edge = 0;
    for (int i = 1; i * dt <= 0.45 + 1e-12; ++i) {
      const double t = i * dt;
      const long before = m.outcome_3d().pulled_pivots;
      m.step(Eigen::Vector3d(t < 0.6 ? 0.6 * kGravity * std::sin(2 * kPi * t / 0.6) : 0.0, 0.0,
                             t > 0.3 && t < 0.5 ? -drop * kGravity * std::sin(kPi * (t - 0.3) / 0.2) : 0.0), dt);
      if (m.outcome_3d().pulled_pivots > before && m.mode() == Mode3D::Edge) ++pulled_on_edge;
    }
    const Rocking3DOutcome& o = m.outcome_3d();
    std::printf("[ measure ] drop %.2f g: %ld slip onsets on the edge, %ld pulls (%ld on the edge), %ld flights\n", drop,
                o.pivot_slips, o.pulled_pivots, pulled_on_edge, o.flights);
    EXPECT_GE(o.pivot_slips, 1);
    if (drop < 1.0) {
      EXPECT_GE(pulled_on_edge, 1);
      EXPECT_EQ(o.flights, 0);
    } else {
      EXPECT_EQ(o.pulled_pivots, 0);
      EXPECT_EQ(o.flights, 1);
    }
  }
}

// A snapshot taken in flight resumes exactly (save/restore carry the flight's state and stepper): the
// copy goes on as the original, through the landing and the slide after it, sample for sample.
TEST(Rocking3DFlight, ASnapshotTakenInFlightResumesExactly) {
  const double dt = 0.005;
  auto a_at = [](double t) {
    return Eigen::Vector3d(t > 0.2 && t < 0.25 ? -1.5 * kGravity : 0.0, 0.3 * kGravity * std::sin(2 * kPi * t),
                           t > 0.1 && t < 0.3 ? -1.6 * kGravity * std::sin(kPi * (t - 0.1) / 0.2) : 0.0);
  };
  const BaseBodyParameters p = testing::uniform_box(0.4, 0.5, 0.6, 0.3, 0.25);
  Rocking3DModel a(BaseBody(p), flight_settings()), b(BaseBody(p), flight_settings());
  a.reset(0.0);
  int i = 1;
  for (; (a.mode() != Mode3D::Flight || i * dt < 0.3) && i * dt < 1.0; ++i) a.step(a_at(i * dt), dt);
  Rocking3DModel::Saved saved;
  a.save(saved);
  b.restore(saved);
  ASSERT_EQ(b.mode(), Mode3D::Flight);
  for (; i * dt <= 1.5 + 1e-12; ++i) {
    a.step(a_at(i * dt), dt);
    b.step(a_at(i * dt), dt);
    ASSERT_EQ(a.mode(), b.mode()) << i;
    ASSERT_EQ(a.translation(), b.translation()) << i;
    ASSERT_EQ(a.rotation(), b.rotation()) << i;
  }
  EXPECT_EQ(b.outcome_3d().flight_landings, 1);
  EXPECT_EQ(a.outcome_3d().flight_time, b.outcome_3d().flight_time);
  EXPECT_GT(b.outcome_3d().landing_slides + b.outcome_3d().slides, 0);  // (it slid after landing)
}

// Where flight is not followed the onset is counted as before: on a support (its cut of the base would
// move with the body) and without a friction coefficient (the paper's pure-rocking body).
TEST(Rocking3DFlight, OnASupportOrWithoutFrictionTheBodyDoesNotFly) {
  const double dt = 0.005;
  BaseBodyParameters on_plinth = testing::uniform_box(0.4, 0.5, 0.6, 0.3, 0.3);
  on_plinth.support = {{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};
  const BaseBodyParameters pure = testing::uniform_box(0.4, 0.5, 0.6, INFINITY, NAN);
  for (const BaseBodyParameters& p : {on_plinth, pure}) {
    Rocking3DModel m(BaseBody(p), flight_settings());
    m.reset(0.0);
    for (int i = 1; i * dt <= 1.0 + 1e-12; ++i) {
      const double t = i * dt;
      m.step(Eigen::Vector3d(0.3 * kGravity * std::sin(2 * kPi * t / 0.5), 0.0,
                             t > 0.1 && t < 0.3 ? -1.6 * kGravity * std::sin(kPi * (t - 0.1) / 0.2) : 0.0), dt);
      ASSERT_NE(m.mode(), Mode3D::Flight) << t;
    }
    EXPECT_EQ(m.outcome_3d().flights, 0);
    EXPECT_TRUE(std::isnan(m.outcome_3d().first_flight_time));
    EXPECT_GT(m.outcome_3d().pivot_lifts, 0);  // (the onset counted, as before flight was modelled)
  }
}

}  // namespace
}  // namespace rocking_monitor::core
