// The 3-D rocking model (model/rocking_3d_model.hpp) against the planar model where it must reduce
// to it exactly, against the planar equation where symmetry confines the 3-D motion to a plane, and
// against conservation laws and symmetry elsewhere.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/model/rocking_model.hpp"
#include "rocking_monitor/physics/impact_3d.hpp"

namespace rocking_monitor::core {
namespace {

SolverSettings tight() {
  SolverSettings s;
  s.tol = 1e-10;
  return s;
}

BodyParameters box_x(double b, double h, double nu1) {
  BodyParameters p;
  p.width = b;
  p.cg_height = h;
  p.nu1 = nu1;
  return p;
}

// A ground motion rich enough to rock, impact many times and sometimes overturn: two sine pulses
// and a decaying tail, along x only, plus a vertical component.
struct Motion {
  std::vector<double> ax, az;
  double dt;
};
Motion pulses(double amp_g, double f_hz, double vert_g, double dt, double t_end) {
  Motion m;
  m.dt = dt;
  for (double t = 0.0; t < t_end; t += dt) {
    const double w = 2.0 * kPi * f_hz;
    double a = t < 2.0 / f_hz ? std::sin(w * t) : 0.4 * std::exp(-(t - 2.0 / f_hz)) * std::sin(1.7 * w * t);
    m.ax.push_back(amp_g * kGravity * a);
    m.az.push_back(vert_g * kGravity * std::sin(2.3 * w * t));
  }
  return m;
}

// Rectangular base, one horizontal component parallel to a side: every sample's state, impact
// time and the outcome equal RockingModel's (the edge at x = 0 is corner 1, x = B corner 2).
TEST(Rocking3D, RectangularBaseUnderOneComponentIsThePlanarModel) {
  struct Case { double b, h, nu1, amp, f, vert; };
  const Case cases[] = {{0.4, 0.6, 0.5, 0.45, 1.5, 0.0},  {0.4, 0.6, 0.35, 0.5, 1.2, 0.2},
                        {0.3, 0.9, 0.7, 0.35, 0.8, 0.1},  {0.5, 0.5, 0.5, 0.9, 3.0, 0.3},
                        {0.25, 1.0, 0.4, 0.6, 0.7, 0.0}};
  int overturned = 0, impacts = 0;
  for (const Case& c : cases) {
    const BodyParameters x = box_x(c.b, c.h, c.nu1);
    RockingModel planar(x, tight());
    Rocking3DModel solid(BaseBody(box_base_body(x, 0.3, 0.5, std::nan(""))), tight());
    const Motion m = pulses(c.amp, c.f, c.vert, 0.01, 12.0);
    for (std::size_t k = 0; k < m.ax.size(); ++k) {
      const StepReport& rp = planar.step(m.ax[k], m.az[k], m.dt);
      const StepReport& rs = solid.step(Eigen::Vector3d(m.ax[k], 0.0, m.az[k]), m.dt);
      ASSERT_EQ(rp.impacts, rs.impacts) << "sample " << k;
      if (rp.impacts > 0) ASSERT_NEAR(rp.first_impact_time, rs.first_impact_time, 1e-9) << "sample " << k;
      ASSERT_EQ(planar.mode() == Mode::Overturned, solid.mode() == Mode3D::Overturned);
      if (planar.mode() == Mode::Rocking) {
        ASSERT_EQ(solid.mode(), Mode3D::Edge) << "sample " << k;
        // corner 1 (theta > 0) is the edge at x = 0 (edge 3 of the box), corner 2 the edge x = B (1)
        ASSERT_EQ(solid.contact(), planar.theta() > 0.0 || (planar.theta() == 0.0 && planar.omega() > 0.0) ? 3 : 1);
        ASSERT_NEAR(solid.theta(), std::abs(planar.theta()), 1e-9) << "sample " << k;
        ASSERT_NEAR(solid.omega(), planar.side() * planar.omega(), 1e-9) << "sample " << k;
      }
    }
    const RockingOutcome& op = planar.outcome();
    const RockingOutcome& os = solid.outcome();
    EXPECT_EQ(op.overturned, os.overturned);
    EXPECT_EQ(op.impacts, os.impacts);
    EXPECT_EQ(op.beyond_tipping, os.beyond_tipping);
    EXPECT_NEAR(op.max_rotation_ratio, os.max_rotation_ratio, 1e-9);
    if (op.overturned) EXPECT_NEAR(op.overturn_time, os.overturn_time, 1e-9);
    EXPECT_NEAR(op.uplift_time, os.uplift_time, 1e-9);
    EXPECT_EQ(solid.outcome_3d().edge_to_vertex, 0);  // the symmetric depth keeps both ends down
    overturned += op.overturned;
    impacts += static_cast<int>(op.impacts);
  }
  // The cases exercise what they claim to: impacts, and at least one overturn and one survivor.
  EXPECT_GT(impacts, 20);
  EXPECT_GE(overturned, 1);
  EXPECT_LE(overturned, 4);
}

// A square box released tilted about the horizontal axis through a corner perpendicular to the
// diagonal: by symmetry it turns about that axis only, so pivoting on the vertex is planar rocking
// with the diagonal's geometry. The vertex mode (quaternion and Euler's equations) must give the
// planar equation's motion (RockingModel with width B sqrt 2) up to the first impact.
TEST(Rocking3D, PivotingOnACornerInTheDiagonalPlaneIsPlanarRocking) {
  const double b = 0.4, h = 0.8;
  BodyParameters x = box_x(b, h, 0.5);
  BaseBodyParameters p = box_base_body(x, b, 0.5, std::nan(""));
  const BaseBody body(p);
  BodyParameters diag = box_x(b * std::sqrt(2.0), h, 0.5);
  diag.radius_of_gyration = std::sqrt((b * b + 4.0 * h * h) / 12.0);  // about any horizontal axis
  RockingModel planar(diag, tight());
  Rocking3DModel solid(body, tight());
  const double alpha = planar.body().pivot(1).alpha;
  ASSERT_NEAR(alpha, body.vertex(0).alpha, 1e-12);
  const double theta0 = 0.6 * alpha;
  planar.set_state(theta0, 0.0);
  // Vertex 0 at (0, 0): tilting lifts the base about the axis (1, -1, 0)/sqrt 2 through it.
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, -1.0, 0.0).normalized();
  solid.set_vertex_state(0, Eigen::Quaterniond(Eigen::AngleAxisd(theta0, axis)), Eigen::Vector3d::Zero());
  const double dt = 0.005;
  double t_impact_planar = -1.0, t_impact_solid = -1.0;
  for (int k = 0; k < 2000 && (t_impact_planar < 0.0 || t_impact_solid < 0.0); ++k) {
    const StepReport& rp = planar.step(0.0, 0.0, dt);
    const StepReport& rs = solid.step(Eigen::Vector3d::Zero(), dt);
    if (rp.impacts > 0 && t_impact_planar < 0.0) t_impact_planar = rp.first_impact_time;
    if (rs.impacts > 0 && t_impact_solid < 0.0) t_impact_solid = rs.first_impact_time;
    if (t_impact_planar < 0.0 && t_impact_solid < 0.0) {
      ASSERT_EQ(solid.mode(), Mode3D::Vertex);
      ASSERT_NEAR(solid.tilt(), std::abs(planar.theta()), 1e-7) << "t = " << planar.time();
      // The motion stays a rotation about the fixed horizontal axis.
      ASSERT_NEAR(solid.angular_velocity().normalized().cwiseAbs().dot(axis.cwiseAbs()), 1.0, 1e-9);
    }
  }
  ASSERT_GT(t_impact_planar, 0.0);
  EXPECT_NEAR(t_impact_solid, t_impact_planar, 1e-7);
}

// Without ground motion and before any impact, pivoting on a vertex conserves energy (kinetic +
// potential) and the angular momentum about the vertical through the pivot (gravity has no moment
// about it): an irregular body spinning and wobbling on one corner.
TEST(Rocking3D, FreeWobbleOnAVertexConservesEnergyAndVerticalAngularMomentum) {
  BaseBodyParameters p;
  p.mass = 350.0;
  p.base = {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.3, -0.05), Eigen::Vector2d(0.45, 0.2),
            Eigen::Vector2d(0.2, 0.35), Eigen::Vector2d(-0.05, 0.2)};
  p.centre_of_mass = Eigen::Vector3d(0.18, 0.13, 0.5);
  Eigen::Matrix3d i;
  i << 20.0, 1.5, -2.0, 1.5, 24.0, 0.8, -2.0, 0.8, 9.0;
  p.central_inertia = i;
  const BaseBody body(p);
  Rocking3DModel m(body, tight());
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.25, Eigen::Vector3d(1.0, -1.2, 0.0).normalized()));
  m.set_vertex_state(0, q, Eigen::Vector3d(0.1, -0.2, 1.5));
  auto energy = [&] { return m.kinetic_energy() + kGravity * (m.rotation() * body.centre_of_mass() + m.translation()).z(); };
  auto lz = [&] {
    const Eigen::Matrix3d r = m.rotation();
    const Eigen::Vector3d pivot = m.rotation() * body.vertex(0).position + m.translation();
    const Eigen::Vector3d c = r * body.centre_of_mass() + m.translation();
    return angular_momentum_about(r * body.central_inertia_per_mass() * r.transpose(), m.angular_velocity(),
                                  c, pivot, pivot).z();
  };
  const double e0 = energy(), l0 = lz();
  int samples = 0;
  for (int k = 0; k < 400 && m.mode() == Mode3D::Vertex && m.outcome().impacts == 0; ++k, ++samples) {
    m.step(Eigen::Vector3d::Zero(), 0.002);
    if (m.outcome().impacts == 0 && m.mode() == Mode3D::Vertex) {
      ASSERT_NEAR(energy(), e0, 1e-7 * std::abs(e0));
      ASSERT_NEAR(lz(), l0, 1e-7 * std::max(1.0, std::abs(l0)));
    }
  }
  EXPECT_GT(samples, 20);  // it wobbled for a while before touching down
}

BaseBodyParameters random_body(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  BaseBodyParameters p;
  do {
  p = BaseBodyParameters{};
  const int n = 3 + static_cast<int>(u(rng) * 6.0);
  std::vector<double> angles;
  for (int k = 0; k < n; ++k) angles.push_back(2.0 * kPi * (k + 0.2 + 0.6 * u(rng)) / n);
  const double rx = 0.15 + 0.3 * u(rng), ry = 0.15 + 0.3 * u(rng);
  for (double a : angles) p.base.emplace_back(rx * std::cos(a), ry * std::sin(a));
  p.centre_of_mass = Eigen::Vector3d(0.3 * rx * (u(rng) - 0.5), 0.3 * ry * (u(rng) - 0.5), 0.3 + 0.8 * u(rng));
  const double h = p.centre_of_mass.z();
  // A homogeneous ellipsoid-like body of the base's size, turned about the vertical.
  Eigen::Matrix3d i = Eigen::Vector3d((ry * ry + h * h) / 5.0, (rx * rx + h * h) / 5.0, (rx * rx + ry * ry) / 5.0).asDiagonal();
  const Eigen::Matrix3d r = Eigen::AngleAxisd(2.0 * kPi * u(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  p.central_inertia = r * i * r.transpose();
  } while (!validate(p).empty());  // a few draws put the centre of mass outside a thin triangle
  return p;
}

// The impact law never makes energy: random irregular bodies under random bidirectional shaking,
// every impact's kinetic energy after <= before; the runs visit every mode.
TEST(Rocking3D, ImpactsNeverIncreaseKineticEnergy) {
  std::mt19937 rng(27);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  long impacts = 0, vertex_impacts = 0, flat = 0, lifts = 0, overturns = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const BaseBody body(random_body(rng));
    Rocking3DModel m(body, SolverSettings{});
    const double ax = 0.3 + 0.6 * u(rng), ay = 0.3 + 0.6 * u(rng), f = 0.8 + 2.0 * u(rng), ph = 2.0 * kPi * u(rng);
    for (double t = 0.0; t < 8.0; t += 0.01) {
      const double env = t < 4.0 ? 1.0 : std::exp(-(t - 4.0) * 2.0);
      m.step(kGravity * env * Eigen::Vector3d(ax * std::sin(2.0 * kPi * f * t), ay * std::sin(2.0 * kPi * 0.83 * f * t + ph),
                                             0.1 * std::sin(2.0 * kPi * 2.1 * f * t)), 0.01);
      if (m.mode() == Mode3D::Overturned) break;
    }
    const Rocking3DOutcome& o = m.outcome_3d();
    EXPECT_LE(o.max_impact_energy_ratio, 1.0 + 1e-9) << "trial " << trial;
    impacts += m.outcome().impacts;
    vertex_impacts += o.vertex_impacts;
    flat += o.flat_impacts;
    lifts += o.edge_to_vertex;
    overturns += m.outcome().overturned;
  }
  EXPECT_GT(vertex_impacts, 10);
  EXPECT_GT(flat, 10);
  EXPECT_GT(lifts, 10);
  EXPECT_GT(overturns, 0);
  EXPECT_LT(overturns, 60);
  EXPECT_EQ(impacts, vertex_impacts + flat);
}

// Turning the box and the input together by 90 degrees about the vertical changes nothing: a box
// on a corner under a pulse along its diagonal.
TEST(Rocking3D, TurningBoxAndInputTogetherBy90DegreesGivesTheSameResponse) {
  BodyParameters x = box_x(0.35, 0.7, 0.45);
  const BaseBodyParameters p = box_base_body(x, 0.25, 0.6, std::nan(""));
  BaseBodyParameters turned = p;
  auto turn2 = [](const Eigen::Vector2d& v) { return Eigen::Vector2d(-v.y(), v.x()); };  // exact
  for (auto& v : turned.base) v = turn2(v);
  turned.centre_of_mass = Eigen::Vector3d(-p.centre_of_mass.y(), p.centre_of_mass.x(), p.centre_of_mass.z());
  Eigen::Matrix3d r;
  r << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  turned.central_inertia = r * p.central_inertia * r.transpose();
  Rocking3DModel a{BaseBody(p), tight()}, b{BaseBody(turned), tight()};
  const Eigen::Vector3d dir = Eigen::Vector3d(-0.35, -0.25, 0.0).normalized();  // towards corner 0
  long modes_vertex = 0;
  for (double t = 0.0; t < 6.0; t += 0.005) {
    const double s = t < 0.8 ? std::sin(2.0 * kPi * t / 0.8) : 0.0;
    const Eigen::Vector3d acc = 0.55 * kGravity * s * dir;
    a.step(acc, 0.005);
    b.step(r * acc, 0.005);
    ASSERT_EQ(a.mode(), b.mode()) << "t = " << t;
    ASSERT_EQ(a.contact(), b.contact()) << "t = " << t;
    ASSERT_NEAR(a.tilt(), b.tilt(), 1e-8) << "t = " << t;
    const Eigen::Vector3d wa = r * a.angular_velocity(), wb = b.angular_velocity();
    ASSERT_LT((wa - wb).norm(), 1e-7) << "t = " << t;
    modes_vertex += a.mode() == Mode3D::Vertex;
  }
  EXPECT_GT(modes_vertex, 10);  // it did pivot on the corner
  EXPECT_GT(a.outcome().impacts, 0);
  EXPECT_EQ(a.outcome().impacts, b.outcome().impacts);
}

// Oblique pulses on a box (every direction between the sides, amplitudes around overturning): the
// model never needs the per-sample event bound (no EDGE/VERTEX chatter that puts a swinging body
// down: found by the Bullet reference at 0.6 g along (1, 2)), and impacts stay few per sample.
TEST(Rocking3D, ObliquePulsesNeverHitTheEventBound) {
  BodyParameters x = box_x(0.3, 0.45, 0.5);
  const BaseBody body(box_base_body(x, 0.3, 0.5, std::nan("")));
  long rocked = 0, overturned = 0, vertex = 0;
  for (double deg : {0.0, 10.0, 20.0, 30.0, 40.0, 45.0, 50.0, 60.0, 63.43494882, 70.0, 80.0, 90.0}) {
    for (double amp : {0.5, 0.6, 0.7, 0.9}) {
      Rocking3DModel m(body, SolverSettings{});
      const Eigen::Vector3d dir(std::cos(deg * kPi / 180.0), std::sin(deg * kPi / 180.0), 0.0);
      int most = 0;
      for (double t = 0.0; t < 3.0; t += 0.001) {
        const double s = t < 0.5 ? std::sin(2.0 * kPi * 2.0 * t) : 0.0;
        most = std::max(most, m.step(amp * kGravity * s * dir, 0.001).impacts);
      }
      EXPECT_EQ(m.outcome().forced_rest_captures, 0) << deg << " deg, " << amp << " g";
      EXPECT_LT(most, 50) << deg << " deg, " << amp << " g";
      rocked += m.outcome().impacts > 0;
      overturned += m.outcome().overturned;
      vertex += m.outcome_3d().edge_to_vertex > 0;
    }
  }
  EXPECT_GT(rocked, 20);
  EXPECT_GT(overturned, 5);
  EXPECT_GT(vertex, 5);
}

// COMMITTED on a corner means what it means about an edge: it would overturn if the shaking stopped
// now. Checked against an independent free run: a fresh model put in the state of the moment the
// flag was raised (set_vertex_state) and left under gravity alone for 10 s with 1 ms steps
// overturns. The flag comes before the overturn (the alarm's lead time) and never for a body that
// stands at the end of the same shaking.
TEST(Rocking3D, CommittedOnACornerMeansItFallsWhenTheShakingStops) {
  BodyParameters x = box_x(0.3, 0.45, 0.5);
  const BaseBody body(box_base_body(x, 0.3, 0.5, std::nan("")));
  long committed_on_corner = 0, with_lead = 0;
  for (double deg : {20.0, 30.0, 40.0, 45.0, 50.0, 60.0, 70.0}) {
    for (double amp : {0.5, 0.6, 0.7, 0.9}) {
      Rocking3DModel m(body, SolverSettings{});
      const Eigen::Vector3d dir(std::cos(deg * kPi / 180.0), std::sin(deg * kPi / 180.0), 0.0);
      bool checked = false;
      for (double t = 0.0; t < 3.0; t += 0.001) {
        const double s = t < 0.5 ? std::sin(2.0 * kPi * 2.0 * t) : 0.0;
        const bool before = m.outcome().committed;
        m.step(amp * kGravity * s * dir, 0.001);
        if (before || !m.outcome().committed || m.mode() != Mode3D::Vertex) continue;
        ++committed_on_corner;
        checked = true;
        EXPECT_TRUE(m.committed_now()) << "the energy must suffice to pass over the corner";
        Rocking3DModel free(body, SolverSettings{});
        free.reset(m.time());
        free.set_vertex_state(m.contact(), Eigen::Quaterniond(m.rotation()), m.angular_velocity());
        for (int k = 0; k < 10000 && free.mode() != Mode3D::Overturned && free.mode() != Mode3D::Rest; ++k)
          free.step(Eigen::Vector3d::Zero(), 0.001);
        EXPECT_EQ(free.mode(), Mode3D::Overturned) << deg << " deg, " << amp << " g, committed at " << m.time();
      }
      if (checked) {
        EXPECT_TRUE(m.outcome().overturned) << deg << " deg, " << amp << " g: committed but standing";
        with_lead += m.outcome().overturn_time > m.outcome().committed_time + 0.05;
      }
    }
  }
  EXPECT_GT(committed_on_corner, 3) << "the cases must commit while on a corner for this to test it";
  EXPECT_EQ(with_lead, committed_on_corner) << "committed at least 50 ms before the overturn";
}

TEST(Rocking3D, InvalidBasesAreRefusedWithTheField) {
  BaseBodyParameters p = box_base_body(box_x(0.4, 0.6, 0.5), 0.3, 0.5, std::nan(""));
  auto message = [](const BaseBodyParameters& q) {
    try { BaseBody b(q); } catch (const BodyError& e) { return std::string(e.what()); }
    return std::string();
  };
  EXPECT_EQ(message(p), "");
  BaseBodyParameters cw = p;
  std::swap(cw.base[1], cw.base[3]);
  EXPECT_NE(message(cw).find("base_polygon: not strictly convex and counter-clockwise"), std::string::npos);
  BaseBodyParameters outside = p;
  outside.centre_of_mass.x() = 0.5;
  EXPECT_NE(message(outside).find("centre_of_mass: its plan position lies outside"), std::string::npos);
  BaseBodyParameters bad_inertia = p;
  bad_inertia.central_inertia(0, 1) = 1.0;
  EXPECT_NE(message(bad_inertia).find("central_inertia"), std::string::npos);
  BaseBodyParameters two = p;
  two.base.resize(2);
  EXPECT_NE(message(two).find("base_polygon: needs at least 3 vertices"), std::string::npos);
}

}  // namespace
}  // namespace rocking_monitor::core
