// Lips along a support's edges (issue 51): a box sliding square into a lip trips over it with the
// kerb's closed form (angular momentum about the lip's foot kept: omega = v h / (I_O / m)), at the
// instant a 1-D Coulomb slider reaches the lip; pressed against the lip it rocks about the lip's edge
// exactly as the planar body (where without the lip it slides); pressed and pulled along it, it slides
// along the lip as the 1-D slider of the pull along it, until the push turns away; under
// bidirectional shaking no base corner crosses a lip; a snapshot resumes a held slide exactly; bad
// lip fields are refused naming the item and the field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/model/rocking_model.hpp"
#include "rocking_monitor/monitoring/catalogue.hpp"
#include "catalogue_error.hpp"

namespace rocking_monitor::core {
namespace {

SolverSettings lip_settings() {
  SolverSettings s;
  s.tol = 1e-10;
  return s;
}

// The plinth box of test_rocking_3d_support.cpp: base 0.6 x 0.5 m, 0.7 m tall, centre of mass 0.35 m up.
constexpr double kHalfX = 0.3, kHalfY = 0.25, kH = 0.35;

BaseBodyParameters lip_box(double mu) {
  BaseBodyParameters p;
  p.centre_of_mass = {0.0, 0.0, kH};
  p.base = {{-kHalfX, -kHalfY}, {kHalfX, -kHalfY}, {kHalfX, kHalfY}, {-kHalfX, kHalfY}};
  p.central_inertia = Eigen::Vector3d((0.25 + 4 * kH * kH) / 12, (0.36 + 4 * kH * kH) / 12, (0.36 + 0.25) / 12).asDiagonal();
  p.mu_s = mu;
  return p;
}

// How far the base's corners lie inside the support's lipped edges (m; < 0: one crossed a lip), flat.
double corners_inside_lips(const Rocking3DModel& m, const BaseBodyParameters& p) {
  double worst = INFINITY;
  const Eigen::Matrix3d r = m.rotation();
  const Eigen::Vector3d t = m.translation();
  for (int k : p.support_lips) {
    const Eigen::Vector2d a = p.support[static_cast<std::size_t>(k)], b = p.support[(static_cast<std::size_t>(k) + 1) % p.support.size()];
    const Eigen::Vector2d d = (b - a).normalized(), n(d.y(), -d.x());
    for (const Eigen::Vector2d& c : p.base) worst = std::min(worst, (a - (r * Eigen::Vector3d(c.x(), c.y(), 0.0) + t).head<2>()).dot(n));
  }
  return worst;
}

// Sliding square into a lip 0.1 m ahead (no shaking: friction mu g brakes it), the box trips over the
// lip's foot: the sticking impact keeps the angular momentum about the base's edge there, so it rocks
// with omega0 = v1 h / (I_O / m), I_O / m = (B^2 + H^2) / 3 for the box B wide and H tall, where v1 is
// the exact slider's speed at the lip (v1^2 = v0^2 - 2 mu g 0.1, at t = (v0 - v1) / (mu g)). Its
// largest tilt follows from energy: g (R cos(alpha - theta) - h) = omega0^2 (I_O / m) / 2; above
// R - h it goes over the lip: a fall off the support.
TEST(Rocking3DLip, ABoxSlidingSquareIntoALipTripsAsTheKerbsClosedForm) {
  const double mu = 0.3, gap = 0.1, dt = 0.01;
  const double io = (4 * kHalfX * kHalfX + 4 * kH * kH) / 3, radius = std::hypot(kHalfX, kH), alpha = std::atan(kHalfX / kH);
  int tripped = 0, over = 0;
  for (double v0 : {0.9, 1.2, 1.6, 2.0, 2.4, 2.8}) {
    BaseBodyParameters p = lip_box(mu);
    p.support = {{-0.5, -0.4}, {kHalfX + gap, -0.4}, {kHalfX + gap, 0.4}, {-0.5, 0.4}};
    p.support_lips = {1};
    Rocking3DModel m(BaseBody(p), lip_settings());
    m.reset(0.0);
    m.set_slide_state(Eigen::Vector2d(v0, 0.0), 0.0);
    const double v1 = std::sqrt(v0 * v0 - 2 * mu * kGravity * gap), t_hit = (v0 - v1) / (mu * kGravity);
    const double omega0 = v1 * kH / io, rise = 0.5 * io * omega0 * omega0 / kGravity;
    const bool goes_over = kH + rise > radius;
    const std::string label = "v0 " + std::to_string(v0);
    for (int i = 0; i < 400 && m.mode() != Mode3D::Overturned; ++i) {
      m.step(Eigen::Vector3d::Zero(), dt);
      if (m.mode() == Mode3D::Rest || m.mode() == Mode3D::Slide) ASSERT_GT(corners_inside_lips(m, p), -1e-9) << label << " " << i;
      if (m.mode() == Mode3D::Edge && m.outcome().impacts == 0) {
        // free rocking about the lip's edge: its energy is omega0's
        const double z = radius * std::cos(alpha - m.theta());
        ASSERT_NEAR(0.5 * io * m.omega() * m.omega() + kGravity * (z - kH), 0.5 * io * omega0 * omega0, 1e-7 * io * omega0 * omega0) << label;
      }
    }
    ASSERT_EQ(m.outcome_3d().lip_trips, 1) << label;
    EXPECT_NEAR(m.outcome().uplift_time, t_hit, 1e-8) << label;  // (located a contact tolerance, 5e-10 m, beyond the lip)
    EXPECT_EQ(m.transition(0).reason, Transition3D::TripsOverLip) << label;
    EXPECT_EQ(m.transition(0).to, Mode3D::Edge) << label;
    EXPECT_LT(0.5 * io * omega0 * omega0, 0.5 * v1 * v1) << label;  // the plastic impact takes energy
    ++tripped;
    EXPECT_EQ(m.outcome().overturned, goes_over) << label;
    if (goes_over) {
      ++over;
      EXPECT_TRUE(m.outcome_3d().fell_off_support) << label;  // over the lipped edge: off the plinth
      continue;
    }
    EXPECT_NEAR(m.outcome_3d().max_tilt, alpha - std::acos((kH + rise) / radius), 1e-7) << label;
    EXPECT_EQ(m.mode(), Mode3D::Rest) << label;
    EXPECT_FALSE(m.outcome_3d().fell_off_support) << label;
  }
  EXPECT_GE(over, 1);
  EXPECT_GE(tripped - over, 4);
  std::printf("[ measured ] %d trips, %d of them over the lip\n", tripped, over);
}

// Pressed against a lip by half-sine pulses, the box (mu_s 0.8 below its tan alpha 0.857: on the
// open plinth it slides first) cannot slide: the lip takes the push and the box rocks about the lip's
// edge as the planar body does (tilt at every sample to 1e-8, impacts, uplift, overturn).
TEST(Rocking3DLip, PressedAgainstALipTheBoxRocksAsThePlanarBody) {
  BodyParameters planar;
  planar.width = 2 * kHalfX;
  planar.cg_height = kH;
  planar.nu1 = 0.5;
  planar.radius_of_gyration = std::sqrt((0.36 + 4 * kH * kH) / 12);
  int compared = 0, overturned = 0, impacts = 0;
  for (double amp : {0.9, 1.0, 1.2, 1.5, 2.0})
    for (double f : {1.0, 2.0}) {
      BaseBodyParameters p = lip_box(0.8);
      p.support = {{-0.5, -0.4}, {kHalfX, -0.4}, {kHalfX, 0.4}, {-0.5, 0.4}};
      BaseBodyParameters open = p;
      p.support_lips = {1};
      Rocking3DModel solid(BaseBody(p), lip_settings()), slider(BaseBody(open), lip_settings());
      RockingModel ref(planar, lip_settings());
      const std::string label = std::to_string(amp) + " g " + std::to_string(f) + " Hz";
      for (double t = 0.01; t < 6.0; t += 0.01) {
        const double a = t < 0.5 / f ? -amp * kGravity * std::sin(2 * kPi * f * t) : 0.0;  // pushes it towards +x
        ref.step(a, 0.0, 0.01);
        solid.step(Eigen::Vector3d(a, 0.0, 0.0), 0.01);
        slider.step(Eigen::Vector3d(a, 0.0, 0.0), 0.01);
        ASSERT_NEAR(solid.tilt(), ref.mode() == Mode::Overturned ? solid.tilt() : std::abs(ref.theta()), 1e-8) << label << " " << t;
      }
      EXPECT_EQ(solid.outcome_3d().slides, 0) << label;
      EXPECT_GT(slider.outcome_3d().slides, 0) << label;  // without the lip it slides first
      EXPECT_EQ(ref.outcome().impacts, solid.outcome().impacts) << label;
      EXPECT_EQ(ref.outcome().overturned, solid.outcome().overturned) << label;
      EXPECT_NEAR(ref.outcome().uplift_time, solid.outcome().uplift_time, 1e-9) << label;
      if (ref.outcome().overturned) {
        EXPECT_NEAR(ref.outcome().overturn_time, solid.outcome().overturn_time, 1e-8) << label;
        EXPECT_TRUE(solid.outcome_3d().fell_off_support) << label;
      }
      ++compared;
      overturned += ref.outcome().overturned;
      impacts += static_cast<int>(ref.outcome().impacts);
    }
  EXPECT_GE(overturned, 1);
  EXPECT_GE(impacts, 5);
  std::printf("[ measured ] %d cases, %d overturned, %d impacts\n", compared, overturned, impacts);
}

// Pressed into the lip (0.4 g) and pulled along it (0.5 g, mu 0.3): it slides along the lip as the
// 1-D slider of the pull along it, y = (0.5 - 0.3) g t^2 / 2, x fixed (on the open plinth it slides
// diagonally). When the push turns away (the input crosses zero inside a sample) the lip lets go at
// that instant. A snapshot taken while the lip holds it resumes exactly.
TEST(Rocking3DLip, PressedAndPulledAlongALipItSlidesAlongItAsTheOneDimensionalSlider) {
  BaseBodyParameters p = lip_box(0.3);
  p.support = {{-0.5, -2.0}, {kHalfX, -2.0}, {kHalfX, 2.0}, {-0.5, 2.0}};
  p.support_lips = {1};
  const double dt = 0.01, ax = -0.4 * kGravity, ay = -0.5 * kGravity;
  Rocking3DModel m(BaseBody(p), lip_settings());
  m.reset(0.0, Eigen::Vector3d(ax, ay, 0.0));
  std::vector<Rocking3DModel::Saved> saved(100);
  std::vector<Eigen::Vector2d> slip(100);
  for (int i = 0; i < 100; ++i) {
    m.step(Eigen::Vector3d(ax, ay, 0.0), dt);
    const double t = (i + 1) * dt;
    ASSERT_EQ(m.mode(), Mode3D::Slide) << i;
    ASSERT_NEAR(m.slip().y(), 0.5 * 0.2 * kGravity * t * t, 1e-9) << i;
    ASSERT_NEAR(m.slip().x(), 0.0, 1e-12) << i;
    ASSERT_NEAR(m.spin(), 0.0, 1e-15) << i;
    m.save(saved[static_cast<std::size_t>(i)]);
    slip[static_cast<std::size_t>(i)] = m.slip();
  }
  EXPECT_EQ(m.outcome_3d().lip_holds, 1);
  EXPECT_EQ(m.transition(1).reason, Transition3D::HeldByLip);
  // the snapshot resumes the held slide
  for (int k : {10, 50}) {
    Rocking3DModel resumed(BaseBody(p), lip_settings());
    resumed.restore(saved[static_cast<std::size_t>(k)]);
    for (int i = k + 1; i < 100; ++i) {
      resumed.step(Eigen::Vector3d(ax, ay, 0.0), dt);
      ASSERT_EQ(resumed.slip(), slip[static_cast<std::size_t>(i)]) << k << " " << i;
    }
  }
  // the push turns away halfway through the next sample: the lip lets go there
  m.step(Eigen::Vector3d(-ax, ay, 0.0), dt);
  bool left = false;
  for (int i = 0; i < m.transition_records(); ++i)
    if (m.transition(i).reason == Transition3D::LeavesLip) {
      left = true;
      EXPECT_NEAR(m.transition(i).time, 1.0 + 0.5 * dt, 1e-12);
    }
  EXPECT_TRUE(left);
  for (int i = 0; i < 20; ++i) m.step(Eigen::Vector3d(-ax, ay, 0.0), dt);
  EXPECT_LT(m.slip().x(), -0.01);  // sliding away from the lip
  // on the open plinth the same pull slides it diagonally
  BaseBodyParameters open = p;
  open.support_lips.clear();
  Rocking3DModel diagonal(BaseBody(open), lip_settings());
  diagonal.reset(0.0, Eigen::Vector3d(ax, ay, 0.0));
  for (int i = 0; i < 100; ++i) diagonal.step(Eigen::Vector3d(ax, ay, 0.0), dt);
  EXPECT_GT(diagonal.slip().x(), 0.1);
}

// A plinth lipped all round under bidirectional shaking (the base 0.15 m from each lip, mu 0.3, square
// and turned 0.3 rad): no slide carries a base corner further over a lip than it already lay (a corner
// the rocking swings over a low lip in the air lands on it: measured), and nothing slides off; on the
// same plinth without lips the box slides off in some of the cases.
TEST(Rocking3DLip, UnderBidirectionalShakingNoSlideCarriesACornerOverALip) {
  int trips = 0, holds = 0, fell_unlipped = 0, overturned = 0, cases = 0, flat_steps = 0;
  double overhang = 0.0;  // m: the most a corner lay beyond a lip
  for (double amp : {0.4, 0.6, 0.8, 1.0})
    for (double f : {0.7, 1.5})
      for (double yaw : {0.0, 0.3}) {
        BaseBodyParameters p = lip_box(0.3);
        const double c = std::cos(yaw), s = std::sin(yaw);
        for (Eigen::Vector2d& b : p.base) b = Eigen::Vector2d(c * b.x() - s * b.y(), s * b.x() + c * b.y());
        const Eigen::Matrix3d rz = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        p.central_inertia = rz * p.central_inertia * rz.transpose();
        p.support = {{-0.5, -0.45}, {0.5, -0.45}, {0.5, 0.45}, {-0.5, 0.45}};
        BaseBodyParameters open = p;
        p.support_lips = {0, 1, 2, 3};
        Rocking3DModel m(BaseBody(p), lip_settings()), free_box(BaseBody(open), lip_settings());
        const std::string label = std::to_string(amp) + " g " + std::to_string(f) + " Hz yaw " + std::to_string(yaw);
        for (double t = 0.01; t < 8.0; t += 0.01) {
          const double env = t < 5.0 ? 1.0 : 0.0;
          const Eigen::Vector3d a(env * amp * kGravity * std::sin(2 * kPi * f * t),
                                  env * 0.8 * amp * kGravity * std::sin(2 * kPi * 1.37 * f * t + 1.0), 0.0);
          const bool flat = m.mode() == Mode3D::Rest || m.mode() == Mode3D::Slide;
          const Mode3D before = m.mode();
          const double inside = flat ? corners_inside_lips(m, p) : 0.0;
          const long impacts = m.outcome().impacts, lifts = m.outcome_3d().lip_trips + m.outcome_3d().slide_to_rock;
          m.step(a, 0.01);
          free_box.step(a, 0.01);
          ASSERT_FALSE(before == Mode3D::Slide && m.mode() == Mode3D::Overturned) << label << " " << t;  // slid off
          if (!(m.mode() == Mode3D::Rest || m.mode() == Mode3D::Slide)) continue;
          const double now = corners_inside_lips(m, p);
          overhang = std::max(overhang, -now);
          if (flat && m.outcome().impacts == impacts && m.outcome_3d().lip_trips + m.outcome_3d().slide_to_rock == lifts) {
            ++flat_steps;  // flat all through the sample: the slide alone moved it
            ASSERT_GT(now, std::min(inside, 0.0) - 1e-6) << label << " " << t;
          }
        }
        EXPECT_EQ(m.outcome_3d().forced_overturns + m.outcome().forced_rest_captures, 0) << label;
        ++cases;
        trips += static_cast<int>(m.outcome_3d().lip_trips);
        holds += static_cast<int>(m.outcome_3d().lip_holds);
        overturned += m.outcome().overturned;
        fell_unlipped += free_box.outcome_3d().fell_off_support;
      }
  EXPECT_GT(trips, 0);
  EXPECT_GT(holds, 0);
  EXPECT_GT(flat_steps, 1000);
  EXPECT_GT(fell_unlipped, overturned);
  std::printf("[ measured ] %d cases: %d trips, %d holds, %d overturned; without lips %d fell off; corners swung "
              "over a lip by up to %.2g m\n", cases, trips, holds, overturned, fell_unlipped, overhang);
}

// Pivoting on the corner at a lip, the box turns about the vertical so that its other corner on the
// lip's side (lifted 1 cm) swings into the lip. A lip 3 cm high stops it: the plastic frictionless
// impact at the corner takes its motion into the lip (its velocity into the lip is 0 after, and the
// energy falls); the corner never lies beyond the lip while lower than it. A low lip (no height) lets
// it pass over.
TEST(Rocking3DLip, ACornerLowerThanTheLipMeetsItsFace) {
  for (double height : {0.03, 0.0}) {
    BaseBodyParameters p = lip_box(0.8);
    p.support = {{-0.5, -0.4}, {kHalfX, -0.4}, {kHalfX, 0.4}, {-0.5, 0.4}};
    p.support_lips = {1};
    p.support_lip_height = height;
    Rocking3DModel m(BaseBody(p), lip_settings());
    m.reset(0.0);
    // tilted about (1, 1, 0) through the corner (0.3, -0.25): every other corner up, (0.3, 0.25) by 1 cm
    const double tilt = std::asin(0.01 * std::sqrt(2.0) / (2 * kHalfY));
    m.set_vertex_state(1, Eigen::Quaterniond(Eigen::AngleAxisd(tilt, Eigen::Vector3d(1, 1, 0).normalized())),
                       Eigen::Vector3d(0.0, 0.0, -1.0));
    auto energy = [&] { return m.kinetic_energy() + kGravity * (m.rotation() * p.centre_of_mass + m.translation()).z(); };
    auto corner = [&]() -> Eigen::Vector3d { return m.rotation() * Eigen::Vector3d(kHalfX, kHalfY, 0.0) + m.translation(); };
    const double e0 = energy(), start = corner().x() - kHalfX;  // (the tilt about the diagonal: 1e-4 m out)
    double beyond = 0.0;
    for (int i = 0; i < 20 && m.mode() == Mode3D::Vertex; ++i) {
      m.step(Eigen::Vector3d::Zero(), 0.001);
      if (corner().z() < height || height == 0.0) beyond = std::max(beyond, corner().x() - kHalfX);
    }
    if (height > 0.0) {
      ASSERT_GE(m.outcome_3d().lip_face_impacts, 1);
      EXPECT_LT(beyond, start + 1e-9);  // no further out than it started
      EXPECT_LT(m.outcome_3d().max_impact_energy_ratio, 1.0 + 1e-12);
      // (the face impact alone: before any landing, the energy fell)
      int landings = 0;
      for (int i = 0; i < m.transition_records(); ++i) landings += m.transition(i).reason == Transition3D::Landing;
      if (landings == 0) EXPECT_LT(energy(), e0);
    } else {
      EXPECT_EQ(m.outcome_3d().lip_face_impacts, 0);
      EXPECT_GT(beyond, start + 1e-3);  // over the low lip
    }
    std::printf("[ measured ] lip %.2f m: the corner beyond the lip's line by up to %.3g m, %ld face impacts\n", height,
                beyond, m.outcome_3d().lip_face_impacts);
  }
}

// A corner rocked over a low lip lies beyond the lipped edge: the contact is then cut where the base
// lies on the support as for any edge (the load check that the base lies within the lips is the
// catalogue's, not the cut's; refusing the cut had kept the last one, the whole base in the air).
TEST(Rocking3DLip, TheContactIsCutWhereACornerLiesOverALip) {
  BaseBodyParameters p = lip_box(0.3);
  p.support = {{-0.5, -0.4}, {kHalfX, -0.4}, {kHalfX, 0.4}, {-0.5, 0.4}};
  p.support_lips = {1};
  const BaseBody body(p);
  std::vector<Eigen::Vector2d> placed = p.support;
  for (Eigen::Vector2d& v : placed) v.x() -= 0.05;  // the item slid 5 cm over the lipped edge
  const BaseBody cut = body.on_support(placed);
  double max_x = -1.0;
  for (int i = 0; i < cut.vertex_count(); ++i) max_x = std::max(max_x, cut.vertex(i).position.x());
  EXPECT_NEAR(max_x, kHalfX - 0.05, 1e-12);
  EXPECT_EQ(cut.parameters().support_lips, p.support_lips);
  EXPECT_EQ(cut.parameters().support, p.support);
}

std::string lip_error(const nlohmann::json& entry) { return testing::catalogue_item_error(entry); }

TEST(Rocking3DLip, BadLipsAreRefusedNamingTheItemAndField) {
  auto item = [] {
    return nlohmann::json::parse(R"({"id": "vase", "width": 0.2, "cg_height": 0.3, "mass": 12.0,
      "centre_of_mass": [0.1, 0.05, 0.3], "central_inertia": [[0.5, 0, 0], [0, 0.6, 0], [0, 0, 0.2]],
      "base_polygon": [[0, 0], [0.2, 0], [0.2, 0.1], [0.0, 0.1]], "support": [[-0.1, -0.1], [0.3, -0.1], [0.3, 0.2], [-0.1, 0.2]],
      "support_lips": [2, 4]})");
  };
  const auto items = parse_catalogue_items(nlohmann::json::array({item()}));
  ASSERT_EQ(items[0].spec.solid->support_lips, (std::vector<int>{1, 3}));  // numbered from 1 in the catalogue
  struct Bad { const char* lips; const char* says; };
  for (const Bad& c : {Bad{"[5]", "edge 5 is not an edge of the support (1 to 4)"}, Bad{"[0]", "edge 0 is not an edge"},
                       Bad{"[2, 2]", "edge 2 is listed twice"}, Bad{"[1.5]", "must be an edge number"},
                       Bad{R"("all")", "must be a list"}}) {
    nlohmann::json e = item();
    e["support_lips"] = nlohmann::json::parse(c.lips);
    const std::string err = lip_error(e);
    EXPECT_NE(err.find("vase"), std::string::npos) << err;
    EXPECT_NE(err.find("support_lips"), std::string::npos) << err;
    EXPECT_NE(err.find(c.says), std::string::npos) << err;
  }
  nlohmann::json under = item();  // a plinth edge under the base: its lip would stand under the item
  under["support"] = nlohmann::json::parse("[[-0.1, -0.1], [0.15, -0.1], [0.15, 0.2], [-0.1, 0.2]]");
  std::string err = lip_error(under);
  EXPECT_NE(err.find("support_lips: edge 2: base_polygon vertex 2 lies beyond it"), std::string::npos) << err;
  nlohmann::json high = item();
  high["support_lip_height"] = -0.01;
  EXPECT_NE(lip_error(high).find("support_lip_height: must be a finite value >= 0 m"), std::string::npos) << lip_error(high);
  high.erase("support_lips");
  high["support_lip_height"] = 0.02;
  EXPECT_NE(lip_error(high).find("support_lip_height: needs support_lips"), std::string::npos) << lip_error(high);
  nlohmann::json bare = item();
  bare.erase("support");
  EXPECT_NE(lip_error(bare).find("support_lips: needs a support"), std::string::npos) << lip_error(bare);
}

}  // namespace
}  // namespace rocking_monitor::core
