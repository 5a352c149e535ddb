// Supports that end (issue 51): a box on a plinth falls off exactly when its slip carries its centre
// of mass past the plinth's edge, and the instant its braking would tip it over that edge is located
// (an exact 1-D slider locates both); one that slid part of the way over rocks about
// the plinth's edge as the planar body of the part still on it; a pedestal smaller than
// the base bounds the contact, and the body rocks about the pedestal's edge as the planar body of the
// pedestal's width, a scanned body (a hull) on a pedestal within its base too; bad supports are
// refused naming the item and the field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/model/rocking_model.hpp"
#include "rocking_monitor/monitoring/catalogue.hpp"
#include "catalogue_error.hpp"
#include "rocking_monitor/physics/support_polygon.hpp"

namespace rocking_monitor::core {
namespace {

SolverSettings support_settings() {
  SolverSettings s;
  s.tol = 1e-10;
  return s;
}

// Exact sliding of a block under a(t) linear in each sample (one component, mu_k = mu_s = mu): the
// slip velocity is quadratic in time between onsets and stops (roots of linear and quadratic
// functions); the first time the displacement reaches `edge` or -`edge_neg`, s (NaN: never).
double plinth_fall_time(const std::vector<double>& ax, double dt, double mu, double edge, double edge_neg) {
  const double n = mu * kGravity;
  double u = 0.0, x = 0.0;
  int s = 0;
  for (std::size_t i = 1; i < ax.size(); ++i) {
    const double a0 = ax[i - 1], sa = (ax[i] - a0) / dt;
    double tau = 0.0;
    for (int guard = 0; guard < 50 && tau < dt; ++guard) {
      if (s == 0) {
        double best = INFINITY;
        for (int sg : {1, -1}) {
          const double f0 = sg * (a0 + sa * tau) - n, f1 = sg * (a0 + sa * dt) - n;
          const double when = f0 > 0.0 ? tau : f1 > 0.0 ? tau + (dt - tau) * (-f0) / (f1 - f0) : INFINITY;
          if (when < best) { best = when; s = -sg; }
        }
        if (!std::isfinite(best)) { s = 0; break; }
        tau = best;
      }
      // from tau: u(tau + d) = u + B d + A d^2, x(tau + d) = x + u d + B d^2 / 2 + A d^3 / 3
      const double B = -(a0 + sa * tau) - s * n, A = -0.5 * sa;
      double end = dt;
      const double disc = B * B - 4 * A * u;
      if (disc >= 0.0)
        for (double d : {A == 0.0 ? -u / B : (-B - std::sqrt(disc)) / (2 * A), A == 0.0 ? -1.0 : (-B + std::sqrt(disc)) / (2 * A)})
          if (d > 1e-15 && tau + d < end) end = tau + d;
      auto pos = [&](double q) { const double d = q - tau; return x + u * d + 0.5 * B * d * d + A * d * d * d / 3.0; };
      // the edge inside [tau, end]: scan, then bisect
      double q0 = tau;
      for (int k = 1; k <= 64; ++k) {
        double lo = q0, hi = tau + (end - tau) * k / 64;
        if (pos(hi) >= edge || pos(hi) <= -edge_neg) {
          const double target = pos(hi) >= edge ? edge : -edge_neg;
          const double side = pos(hi) - target;
          for (int it = 0; it < 100; ++it) {
            const double mid = 0.5 * (lo + hi);
            ((pos(mid) - target) * side > 0.0 ? hi : lo) = mid;
          }
          return (i - 1) * dt + 0.5 * (lo + hi);
        }
        q0 = hi;
      }
      const double d = end - tau;
      x = pos(end);
      u = end < dt ? 0.0 : u + B * d + A * d * d;
      tau = end;
      if (end < dt) {
        const double a = a0 + sa * tau;
        s = std::abs(a) <= n ? 0 : (a > 0.0 ? -1 : 1);
      }
    }
  }
  return NAN;
}

BaseBodyParameters plinth_box(double mu) {
  BaseBodyParameters p;
  p.centre_of_mass = {0.0, 0.0, 0.35};
  p.base = {{-0.3, -0.25}, {0.3, -0.25}, {0.3, 0.25}, {-0.3, 0.25}};
  p.central_inertia = Eigen::Vector3d((0.25 + 4 * 0.1225) / 12, (0.36 + 4 * 0.1225) / 12, (0.36 + 0.25) / 12).asDiagonal();
  p.mu_s = mu;
  return p;
}

// A box sliding on a plinth falls off when its slip carries its centre of mass past the plinth's
// edge (an exact 1-D slider locates the instant). Braking on the way, its friction (mu_k g, at the
// floor, h below the centre of mass) would start to tip it over the plinth's edge once the centre of
// mass is within mu_k h of it (eq. 19 about that edge): that instant is located and recorded (the
// slide-rock over the edge is followed as sliding), at the slider's reaching 0.4 - mu h.
TEST(Rocking3DSupport, ABoxOnAPlinthFallsOffWhenItsSlipReachesTheEdge) {
  // A plinth 0.4 m beyond the centre of mass towards +x, 0.5 m towards -x (larger than the base).
  const double mu = 0.3, h = 0.35;
  int fell = 0, stayed = 0, braked = 0;
  for (double amp : {0.4, 0.5, 0.6, 0.7, 0.8})
    for (double f : {0.5, 0.75, 1.0}) {
      std::vector<double> ax;
      const double dt = 0.01;
      for (double t = 0.0; t < 1.0 / f; t += dt) ax.push_back(-amp * kGravity * std::sin(2 * kPi * f * t));
      ax.resize(ax.size() + 300, 0.0);
      BaseBodyParameters p = plinth_box(mu);
      p.support = {{-0.5, -0.4}, {0.4, -0.4}, {0.4, 0.4}, {-0.5, 0.4}};
      Rocking3DModel m(BaseBody(p), support_settings());
      m.reset(0.0);
      for (std::size_t i = 1; i < ax.size(); ++i) m.step(Eigen::Vector3d(ax[i], 0.0, 0.0), dt);
      const double expected = plinth_fall_time(ax, dt, mu, 0.4, 0.5);
      const double tips = plinth_fall_time(ax, dt, mu, 0.4 - mu * h, 0.5 - mu * h);
      const std::string label = std::to_string(amp) + " g " + std::to_string(f) + " Hz";
      ASSERT_EQ(m.outcome_3d().slides_over_support_edge > 0, !std::isnan(tips)) << label;
      if (!std::isnan(tips)) {
        ++braked;
        const Transition3DRecord* first = nullptr;
        for (int i = 0; i < m.transition_records() && first == nullptr; ++i)
          if (m.transition(i).reason == Transition3D::SlidesOverSupportEdge) first = &m.transition(i);
        ASSERT_NE(first, nullptr) << label;
        EXPECT_NEAR(first->time, tips, 1e-9) << label;
        EXPECT_EQ(first->from, Mode3D::Slide);
        EXPECT_EQ(first->to, Mode3D::Slide);
      }
      ASSERT_EQ(m.outcome_3d().fell_off_support, !std::isnan(expected)) << label;
      if (std::isnan(expected)) {
        ++stayed;
        EXPECT_GT(m.support_margin(), 0.0) << label;
        continue;
      }
      ++fell;
      EXPECT_EQ(m.mode(), Mode3D::Overturned) << label;
      EXPECT_TRUE(m.outcome().overturned) << label;
      EXPECT_NEAR(m.outcome_3d().fell_off_time, expected, 1e-9) << label;
      EXPECT_NEAR(m.outcome().overturn_time, expected, 1e-9) << label;
      EXPECT_NEAR(m.support_margin(), 0.0, 1e-9) << label;
      EXPECT_EQ(m.transition(m.transition_records() - 1).reason, Transition3D::FellOffSupport) << label;
    }
  EXPECT_GE(fell, 2);
  EXPECT_GE(stayed, 1);
  EXPECT_GT(braked, fell);  // some braked near the edge and stayed
  std::printf("[ measured ] %d fell off, %d stayed; %d braked within mu h of the edge\n", fell, stayed, braked);
}

// The contact follows the item: a box that slid part of the way over the plinth's edge and stopped
// stands on the base's part still on the plinth, and rocks about the plinth's edge as the planar body
// of that part's width (the box's inertia) does: tilt at every sample, impacts, uplift and overturn.
// (mu_k 0.3 below mu_s 0.6: it slides without tipping, then a pulse below mu_s g rocks it.)
TEST(Rocking3DSupport, ABoxThatSlidPartlyOverThePlinthsEdgeRocksAboutThatEdge) {
  const double h = 0.35, dt = 0.01;
  int compared = 0, overturned = 0, impacts = 0;
  for (double amp1 = 0.61; amp1 < 1.05; amp1 += 0.01)
    for (double f : {0.8, 1.5}) {
      BaseBodyParameters p = plinth_box(0.6);
      p.mu_k = 0.3;
      p.support = {{-0.5, -0.4}, {0.4, -0.4}, {0.4, 0.4}, {-0.5, 0.4}};
      Rocking3DModel m(BaseBody(p), support_settings());
      m.reset(0.0);
      double t = 0.0;
      for (; t < 3.0 - 1e-9; t += dt) {  // a half-sine towards -x: it slides towards +x, then stops
        const double a = t + dt < 0.3 ? -amp1 * kGravity * std::sin(kPi * (t + dt) / 0.3) : 0.0;
        m.step(Eigen::Vector3d(a, 0.0, 0.0), dt);
      }
      if (m.mode() != Mode3D::Rest || m.outcome_3d().slide_to_rock > 0) continue;  // it tipped (the test above)
      const double b = 0.4 - m.slip().x();  // how far the plinth's edge is from the centre of mass
      ASSERT_NEAR(m.slip().y(), 0.0, 1e-12);
      if (!(b / h < 0.56 && b > 0.3 * h)) continue;  // rocks under 0.58 g (below mu_s g), did not tip sliding
      // The cut: [-0.3, b] x [-0.25, 0.25] about the centre of mass.
      ASSERT_EQ(m.body().vertex_count(), 4);
      EXPECT_NEAR(m.body().min_alpha(), std::atan(b / h), 1e-12);
      BodyParameters planar;
      planar.width = 0.3 + b;
      planar.cg_height = h;
      planar.nu1 = 0.3 / (0.3 + b);  // the centre of mass 0.3 m from the -x edge
      planar.radius_of_gyration = std::sqrt(m.body().central_inertia_per_mass()(1, 1));
      RockingModel ref(planar, support_settings());
      for (double s = dt; s < 4.0; s += dt) {
        const double a = s < 1.0 / f ? -0.58 * kGravity * std::sin(2 * kPi * f * s) : 0.0;
        ref.step(a, 0.0, dt);
        m.step(Eigen::Vector3d(a, 0.0, 0.0), dt);
        ASSERT_NEAR(m.tilt(), ref.mode() == Mode::Overturned ? m.tilt() : std::abs(ref.theta()), 1e-8) << amp1 << " " << s;
        // about the base's own -x edge (the catalogue's edge 3) or the plinth's edge (-1: not the base's)
        if (m.mode() == Mode3D::Edge)
          ASSERT_EQ(m.base_contact(), ref.theta() > 0.0 || (ref.theta() == 0.0 && ref.omega() > 0.0) ? 3 : -1) << s;
      }
      EXPECT_EQ(ref.outcome().overturned, m.outcome().overturned);
      EXPECT_EQ(ref.outcome().impacts, m.outcome().impacts);
      ASSERT_FALSE(std::isnan(ref.outcome().uplift_time));
      EXPECT_NEAR(ref.outcome().uplift_time + t, m.outcome().uplift_time, 1e-9);
      if (ref.outcome().overturned) {
        EXPECT_NEAR(ref.outcome().overturn_time + t, m.outcome().overturn_time, 1e-8);
        EXPECT_TRUE(m.outcome_3d().fell_off_support) << "over the plinth's edge";
      }
      ++compared;
      overturned += ref.outcome().overturned;
      impacts += static_cast<int>(ref.outcome().impacts);
    }
  EXPECT_GE(compared, 8);
  EXPECT_GE(overturned, 1);
  EXPECT_GE(impacts, 3);
  std::printf("[ measured ] %d cases compared, %d overturned, %d impacts\n", compared, overturned, impacts);
}

// A snapshot carries the footprint the contact was cut for: a model restored while the box slides
// over the plinth's edge, stands there, or rocks about that edge goes on exactly as the live one.
TEST(Rocking3DSupport, ASnapshotResumesTheContactWhereTheItemSlidExactly) {
  BaseBodyParameters p = plinth_box(0.6);
  p.mu_k = 0.3;
  p.support = {{-0.5, -0.4}, {0.4, -0.4}, {0.4, 0.4}, {-0.5, 0.4}};
  const double dt = 0.01;
  std::vector<Eigen::Vector3d> in;
  for (double t = dt; t < 6.0; t += dt) {
    const double s = t - 3.0;
    const double a = t < 0.3 ? -0.92 * kGravity * std::sin(kPi * t / 0.3)
                     : s > 0.0 && s < 1.25 ? -0.58 * kGravity * std::sin(2 * kPi * 0.8 * s) : 0.0;
    in.emplace_back(a, 0.1 * a, 0.0);
  }
  Rocking3DModel live(BaseBody(p), support_settings());
  live.reset(0.0);
  std::vector<Rocking3DModel::Saved> saved(in.size());
  std::vector<double> tilt(in.size()), slip(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    live.step(in[i], dt);
    live.save(saved[i]);
    tilt[i] = live.tilt();
    slip[i] = live.slip().x();
  }
  ASSERT_GT(live.outcome().impacts, 0);  // it rocked about the plinth's edge after sliding over it
  int cut = 0;
  for (std::size_t k : {10, 20, 100, 305, 330, 360}) {
    Rocking3DModel resumed(BaseBody(p), support_settings());
    resumed.restore(saved[k]);
    Rocking3DModel::Saved copy;
    resumed.save(copy);
    cut += copy.fit_shift.x() > 0.1;  // the base then overhung the plinth
    for (std::size_t i = k + 1; i < in.size(); ++i) {
      resumed.step(in[i], dt);
      ASSERT_EQ(resumed.tilt(), tilt[i]) << k << " " << i;
      ASSERT_EQ(resumed.slip().x(), slip[i]) << k << " " << i;
    }
    EXPECT_EQ(resumed.outcome().impacts, live.outcome().impacts) << k;
    EXPECT_EQ(resumed.slip().x(), live.slip().x()) << k;
    EXPECT_EQ(resumed.body().vertex_count(), live.body().vertex_count()) << k;
    EXPECT_EQ(resumed.outcome().overturned, live.outcome().overturned) << k;
  }
  EXPECT_GE(cut, 3);
}

// The 3-D body on its pedestal against the planar body of the pedestal's width (width, cg_height h,
// the body's radius of gyration about the edge) under one-sine pulses along x (amplitudes in g, 1 and
// 2 Hz): tilt at every sample to 1e-8, impacts, uplift to 1e-9 s, overturn time to 1e-8 s.
struct PlanarAgreement {
  int overturned = 0, impacts = 0;
};
PlanarAgreement rocks_as_the_planar_body(const BaseBody& body, double width, double h, double radius_of_gyration,
                                         std::initializer_list<double> amplitudes) {
  BodyParameters planar;
  planar.width = width;
  planar.cg_height = h;
  planar.nu1 = 0.5;
  planar.radius_of_gyration = radius_of_gyration;
  PlanarAgreement out;
  for (double amp : amplitudes)
    for (double f : {1.0, 2.0}) {
      RockingModel ref(planar, support_settings());
      Rocking3DModel solid(body, support_settings());
      for (double t = 0.01; t < 8.0; t += 0.01) {
        const double a = t < 1.0 / f ? amp * kGravity * std::sin(2 * kPi * f * t) : 0.0;
        ref.step(a, 0.0, 0.01);
        solid.step(Eigen::Vector3d(a, 0.0, 0.0), 0.01);
        EXPECT_NEAR(solid.tilt(), ref.mode() == Mode::Overturned ? solid.tilt() : std::abs(ref.theta()), 1e-8) << t;
        if (::testing::Test::HasFailure()) return out;
      }
      const std::string label = std::to_string(amp) + " g " + std::to_string(f) + " Hz";
      EXPECT_EQ(ref.outcome().overturned, solid.outcome().overturned) << label;
      EXPECT_EQ(ref.outcome().impacts, solid.outcome().impacts) << label;
      EXPECT_EQ(std::isnan(ref.outcome().uplift_time), std::isnan(solid.outcome().uplift_time)) << label;
      if (!std::isnan(ref.outcome().uplift_time)) EXPECT_NEAR(ref.outcome().uplift_time, solid.outcome().uplift_time, 1e-9);
      EXPECT_EQ(solid.outcome_3d().hull_landings, 0) << label;
      if (ref.outcome().overturned) {
        EXPECT_NEAR(ref.outcome().overturn_time, solid.outcome().overturn_time, 1e-8) << label;
        EXPECT_TRUE(solid.outcome_3d().fell_off_support) << label;  // over the pedestal's edge
      }
      out.overturned += ref.outcome().overturned;
      out.impacts += static_cast<int>(ref.outcome().impacts);
    }
  return out;
}

TEST(Rocking3DSupport, APedestalSmallerThanTheBaseRocksItAsThePlanarBodyOfThePedestalsWidth) {
  // A box 0.6 m wide on a pedestal 0.4 m wide under its centre (wider than its depth): the contact is
  // the pedestal's width, the inertia the box's. The planar body: width 0.4, the box's i_g.
  const double b = 0.6, d = 0.3, h = 0.6;
  BaseBodyParameters p;
  p.centre_of_mass = {0.0, 0.0, h};
  p.base = {{-b / 2, -d / 2}, {b / 2, -d / 2}, {b / 2, d / 2}, {-b / 2, d / 2}};
  const double ig2 = (b * b + 4 * h * h) / 12;
  p.central_inertia = Eigen::Vector3d((d * d + 4 * h * h) / 12, ig2, (b * b + d * d) / 12).asDiagonal();
  p.support = {{-0.2, -0.4}, {0.2, -0.4}, {0.2, 0.4}, {-0.2, 0.4}};
  const BaseBody body(p);
  ASSERT_EQ(body.vertex_count(), 4);
  EXPECT_NEAR(body.min_alpha(), std::atan(0.15 / h), 1e-12);  // the depth's edges: 0.15 / h
  const PlanarAgreement r = rocks_as_the_planar_body(body, 0.4, h, std::sqrt(ig2), {0.3, 0.45, 0.6});
  EXPECT_GE(r.overturned, 1);
  EXPECT_GT(r.impacts, 5);
}

// A scanned body (a hull) on a pedestal within its base: a bust 0.3 m square at the base, widening
// to 0.5 m at its top. Tipping about the pedestal's edge, every hull point that comes down lies beyond
// the pedestal (rotation about a line on the pedestal's top keeps each point's side of it below 90
// degrees), so the body rocks exactly as the planar body of the pedestal's width with the body's
// inertia. On the open floor the same body tips onto its flared side (a hull landing) instead.
BaseBodyParameters flared_bust(double h) {
  BaseBodyParameters p;
  p.centre_of_mass = {0.0, 0.0, h};
  p.base = {{-0.15, -0.15}, {0.15, -0.15}, {0.15, 0.15}, {-0.15, 0.15}};
  for (double x : {-0.25, 0.25})
    for (double y : {-0.25, 0.25}) p.hull.emplace_back(x, y, 0.6);
  p.central_inertia = Eigen::Vector3d(0.035, 0.03, 0.025).asDiagonal();
  return p;
}

TEST(Rocking3DSupport, AScannedBodyOnAPedestalWithinItsBaseRocksAsThePlanarBodyOfThePedestalsWidth) {
  const double h = 0.3;
  BaseBodyParameters p = flared_bust(h);
  p.support = {{-0.1, -0.12}, {0.1, -0.12}, {0.1, 0.12}, {-0.1, 0.12}};
  const BaseBody body(p);
  EXPECT_FALSE(body.contact_hull().from_hull);  // the pedestal's top is the contact
  const PlanarAgreement r = rocks_as_the_planar_body(body, 0.2, h, std::sqrt(0.03), {0.25, 0.35, 0.5});
  int floor_hull_landings = 0;
  for (double amp : {0.6, 0.8, 1.0}) {
    Rocking3DModel floor(BaseBody(flared_bust(h)), support_settings());
    for (double t = 0.01; t < 4.0; t += 0.01)
      floor.step(Eigen::Vector3d(t < 1.0 ? amp * kGravity * std::sin(2 * kPi * t) : 0.0, 0.0, 0.0), 0.01);
    floor_hull_landings += static_cast<int>(floor.outcome_3d().hull_landings);
  }
  std::printf("[ measure ] on the pedestal %d overturns (falls off it), %d impacts as the planar body; on the open "
              "floor %d landings on its flared side\n", r.overturned, r.impacts, floor_hull_landings);
  EXPECT_GE(r.overturned, 1);
  EXPECT_GT(r.impacts, 5);
  EXPECT_GT(floor_hull_landings, 0);  // the hull matters off the pedestal
}

// Sliding on its pedestal, a scanned body whose base slid so far that the pedestal reaches beyond
// its edge is counted: pivoting there, its hull across that edge could land on the pedestal.
TEST(Rocking3DSupport, AScannedBodyThatSlidUntilItsPedestalReachesBeyondItsBaseIsCounted) {
  const double mu = 0.3;
  int beyond = 0, within = 0;
  for (double amp : {0.35, 0.4, 0.45, 0.5}) {
    BaseBodyParameters p = flared_bust(0.12);  // tan alpha 0.1 / 0.12 > mu: it slides before it tips
    p.mu_s = mu;
    p.support = {{-0.1, -0.1}, {0.1, -0.1}, {0.1, 0.1}, {-0.1, 0.1}};
    Rocking3DModel m(BaseBody(p), support_settings());
    m.reset(0.0);
    double most = 0.0;
    for (double t = 0.01; t < 3.0; t += 0.01) {
      m.step(Eigen::Vector3d(t < 0.5 ? amp * kGravity * std::sin(2 * kPi * t) : 0.0, 0.0, 0.0), 0.01);
      if (m.mode() == Mode3D::Rest) most = std::max(most, std::abs(m.slip().x()));
    }
    ASSERT_FALSE(m.outcome().overturned) << amp;
    const bool reached = most > 0.05 + 1e-9;  // the pedestal's edge 0.1 m out, the base's 0.15 m
    EXPECT_EQ(m.outcome_3d().pedestal_beyond_base > 0, reached) << amp << " " << most;
    (reached ? beyond : within) += 1;
  }
  EXPECT_GE(beyond, 1);
  EXPECT_GE(within, 1);
}

TEST(Rocking3DSupport, ClippingAndMarginsAreExact) {
  const std::vector<Eigen::Vector2d> base = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  // a support turned 45 degrees through the square's centre: their intersection is an octagon
  const double r = 0.6;
  std::vector<Eigen::Vector2d> diamond;
  for (int k = 0; k < 4; ++k) diamond.emplace_back(0.5 + r * std::cos(kPi / 2 * k), 0.5 + r * std::sin(kPi / 2 * k));
  const auto oct = clip_convex(base, diamond);
  EXPECT_EQ(oct.size(), 8u);
  EXPECT_TRUE(polygon_problem(oct).empty());
  // a support sharing the base's edge x = 0 leaves no repeated or collinear vertex
  const auto half = clip_convex(base, {{0, -1}, {0.5, -1}, {0.5, 2}, {0, 2}});
  ASSERT_EQ(half.size(), 4u);
  EXPECT_TRUE(polygon_problem(half).empty());
  EXPECT_NEAR(inside_margin(base, {0.3, 0.6}), 0.3, 1e-15);
  EXPECT_NEAR(inside_margin(base, {1.2, 0.6}), -0.2, 1e-15);
  EXPECT_TRUE(clip_convex(base, {{2, 2}, {3, 2}, {3, 3}}).empty());
}

std::string support_error(const nlohmann::json& entry) { return testing::catalogue_item_error(entry); }

TEST(Rocking3DSupport, BadSupportsAreRefusedNamingTheItemAndField) {
  auto item = [] {
    return nlohmann::json::parse(R"({"id": "statue", "width": 0.2, "cg_height": 0.3, "mass": 12.0,
      "centre_of_mass": [0.1, 0.05, 0.3], "central_inertia": [[0.5, 0, 0], [0, 0.6, 0], [0, 0, 0.2]],
      "base_polygon": [[0, 0], [0.2, 0], [0.2, 0.1], [0.0, 0.1]], "support": [[-0.1, -0.1], [0.3, -0.1], [0.3, 0.2], [-0.1, 0.2]]})");
  };
  const auto items = parse_catalogue_items(nlohmann::json::array({item()}));
  ASSERT_EQ(items[0].spec.solid->support.size(), 4u);
  EXPECT_EQ(items[0].spec.solid->support[1].x(), 0.3);
  struct Bad { const char* support; const char* says; };
  for (const Bad& c : {Bad{R"([[0, 0], [0.3, 0.2], [0.3, 0], [0, 0.2]])", "not strictly convex"},
                       Bad{R"([[0.15, -0.1], [0.3, -0.1], [0.3, 0.2], [0.15, 0.2]])", "lies off the support"},
                       Bad{R"([[0, 0], [1, 0]])", "at least 3 vertices"},
                       Bad{R"("plinth")", "must be a list"}}) {
    nlohmann::json e = item();
    e["support"] = nlohmann::json::parse(c.support);
    const std::string err = support_error(e);
    EXPECT_NE(err.find("statue"), std::string::npos) << err;
    EXPECT_NE(err.find("support"), std::string::npos) << err;
    EXPECT_NE(err.find(c.says), std::string::npos) << err;
  }
  // a scanned body (hull) only on a pedestal within its base
  nlohmann::json scanned = item();
  scanned["hull"] = nlohmann::json::parse("[[0, 0, 0.6], [0.2, 0, 0.6], [0.2, 0.1, 0.6], [0, 0.1, 0.6]]");
  std::string err = support_error(scanned);
  EXPECT_NE(err.find("statue"), std::string::npos) << err;
  EXPECT_NE(err.find("support: with a hull, the support must lie within base_polygon"), std::string::npos) << err;
  scanned["support"] = nlohmann::json::parse("[[0.05, 0.02], [0.15, 0.02], [0.15, 0.08], [0.05, 0.08]]");
  EXPECT_EQ(support_error(scanned), "");
  // The overturn angle is the pedestal's matter: 0.25 rad exceeds its edges' tipping angles (atan(0.03 /
  // 0.3) and atan(0.05 / 0.3)), not the whole base's (atan(0.1 / 0.3) = 0.32), which the body never
  // rocks on (it was refused). Beyond 90 degrees its other faces could land on the pedestal's top.
  // (The planar pair, the screening planes, tips at atan(width / 2 / cg_height): here the pedestal's.)
  scanned["width"] = 0.1;
  scanned["overturn_angle"] = 0.25;
  EXPECT_EQ(support_error(scanned), "");
  scanned["overturn_angle"] = 0.15;
  EXPECT_NE(support_error(scanned).find("must exceed the tipping angle"), std::string::npos) << support_error(scanned);
  scanned["overturn_angle"] = 2.0;
  err = support_error(scanned);
  EXPECT_NE(err.find("statue"), std::string::npos) << err;
  EXPECT_NE(err.find("overturn_angle: with a hull on a support, must be at most pi/2"), std::string::npos) << err;
  nlohmann::json planar = item();
  for (const char* k : {"mass", "centre_of_mass", "central_inertia", "base_polygon"}) planar.erase(k);
  EXPECT_NE(support_error(planar).find("needs the 3-D description"), std::string::npos);
}

}  // namespace
}  // namespace rocking_monitor::core
