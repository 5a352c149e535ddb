// The planar pair's one friction budget (issue 51 part 4, monitoring/friction_share.hpp): the shares
// themselves; one component alone is today's pair bit for bit; a straight-line slide is the 1-D Coulomb
// block along the shaking's direction; under both horizontals of real records the pair against the 3-D
// model's exact cone, beside the old per-plane budgets (the square pyramid).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/monitoring/friction_share.hpp"
#include "rocking_monitor/monitoring/item_monitor.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "rocking_monitor/physics/base_body.hpp"
#include "rocking_monitor/physics/principal_planes.hpp"

namespace rocking_monitor::core {
namespace {

// The cabinet: base 0.6 x 0.5 m, centre of mass 0.35 m high, mu_s 0.3 < 0.25 / 0.35: it slides
// before it rocks (tan alpha 0.71 and 0.86 in its two planes).
ItemSpec cabinet(bool solid) {
  ItemSpec s;
  s.id = "cabinet";
  s.sensor = "floor";
  s.frame = "cabinet";
  s.body.width = 0.6;
  s.body.cg_height = 0.35;
  s.body.mu_s = 0.3;
  s.depth.depth = 0.5;
  if (solid) s.solid = box_base_body(s.body, s.depth.depth, 0.5, std::nan(""));
  return s;
}

struct Slips {
  std::vector<double> x, y;  // m, every sample
  double max_x = 0.0, max_y = 0.0;
};

// The pair (the item's two planes) or, with `solid`, the 3-D model, over the whole input.
Slips run_item(const ItemSpec& spec, SolidChoice choice, const std::vector<double>& ax, const std::vector<double>& ay,
               double dt) {
  ItemMonitor::Options o;
  o.solid = choice;
  ItemMonitor m(spec, o);
  m.start(0.0, ax[0], ay[0], 0.0, dt);
  Slips s;
  for (std::size_t i = 1; i < ax.size(); ++i) {
    m.step(ax[i], ay[i], 0.0, dt);
    double x, y;
    if (choice == SolidChoice::Solid) {
      x = m.solid()->slip().x();
      y = m.solid()->slip().y();
    } else {
      x = m.plane(Plane::X).slip();
      y = m.plane(Plane::Y).slip();
    }
    s.x.push_back(x);
    s.y.push_back(y);
    s.max_x = std::max(s.max_x, std::abs(x));
    s.max_y = std::max(s.max_y, std::abs(y));
  }
  return s;
}

// One plane alone with its full budget (the pair before issue 51 part 4: the square pyramid).
std::vector<double> run_plane(const BodyParameters& body, const std::vector<double>& a, double dt) {
  PlaneMonitor p(body, PlaneMonitor::Options{});
  p.start(0.0, a[0], 0.0, dt);
  std::vector<double> slip;
  for (std::size_t i = 1; i < a.size(); ++i) {
    p.step(a[i], 0.0, dt);
    slip.push_back(p.slip());
  }
  return slip;
}

// The same piecewise-linear ground motion sampled `factor` times as often (what the 3-D model and a
// plane alone see is unchanged; the pair's shares are then set `factor` times as often).
std::vector<double> finer(const std::vector<double>& a, int factor) {
  std::vector<double> out;
  for (std::size_t i = 0; i + 1 < a.size(); ++i)
    for (int k = 0; k < factor; ++k) out.push_back(a[i] + (a[i + 1] - a[i]) * k / factor);
  out.push_back(a.back());
  return out;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

TEST(FrictionShare, SharesFollowTheSlipThenTheDemand) {
  const double mu = 0.3, none[2] = {0.0, 0.0};
  // Slipping: along the slip the sample would reach without friction (w).
  FrictionShare f = friction_share({0.3, -0.4}, {0.3, -0.4}, none, none, mu);
  EXPECT_TRUE(f.engaged);
  EXPECT_NEAR(f.share[0], 0.6, 1e-15);
  EXPECT_NEAR(f.share[1], 0.8, 1e-15);
  f = friction_share({-0.2, 0.0}, {-0.2, 0.0}, {0.1, 0.25}, {0.1, 0.25}, mu);  // the other plane unpulled
  EXPECT_EQ(f.share[0], 1.0);
  EXPECT_EQ(f.share[1], 0.0);
  f = friction_share({-0.2, 0.0}, {-0.15, 0.2}, {0.1, 0.25}, {0.1, 0.25}, mu);  // ... pulled aside: it turns
  EXPECT_NEAR(f.share[0], 0.6, 1e-15);
  EXPECT_NEAR(f.share[1], 0.8, 1e-15);
  // Sticking, the demand nearing the cone: the whole budget while the sample ends inside it ...
  f = friction_share(none, none, {0.2, 0.1}, {0.25, 0.12}, mu);
  EXPECT_TRUE(f.engaged);
  EXPECT_EQ(f.share[0], 1.0);
  EXPECT_EQ(f.share[1], 1.0);
  // ... else the direction of the demand at its end, so that each plane's own test q_i <= mu share_i
  // is the cone's |q| <= mu.
  f = friction_share(none, none, {0.2, 0.1}, {0.3, 0.12}, mu);
  EXPECT_NEAR(f.share[0], 0.3 / std::hypot(0.3, 0.12), 1e-15);
  EXPECT_NEAR(f.share[1], 0.12 / std::hypot(0.3, 0.12), 1e-15);
  EXPECT_FALSE(0.3 <= mu * f.share[0]);
  f = friction_share(none, none, {0.14, 0.1}, {0.4, 0.1}, mu);  // below mu / 2 at the start: not engaged
  EXPECT_FALSE(f.engaged);
  EXPECT_EQ(f.share[0], 1.0);
  const double inf = std::numeric_limits<double>::infinity();
  f = friction_share(none, none, {0.29, inf}, {0.29, inf}, mu);  // a plane lifts off: its own model's
  EXPECT_FALSE(f.engaged);
  f = friction_share({0.1, 0.1}, {0.1, 0.1}, none, none, inf);  // no friction given
  EXPECT_FALSE(f.engaged);
}

TEST(FrictionShare, OneComponentAloneIsThePlaneAloneBitForBitOverAWholeRecord) {
  const Component k = read_record(std::string(ROCKING_RECORDS_DIR) + "/kobe_1995/RSN1120_KOBE_TAK000.AT2").front();
  const std::vector<double> zero(k.accel.size(), 0.0);
  const Slips pair = run_item(cabinet(false), SolidChoice::Planar, k.accel, zero, k.dt);
  const std::vector<double> alone = run_plane(cabinet(false).body, k.accel, k.dt);
  ASSERT_EQ(pair.x.size(), alone.size());
  for (std::size_t i = 0; i < alone.size(); ++i) {
    ASSERT_EQ(pair.x[i], alone[i]) << "sample " << i;
    ASSERT_EQ(pair.y[i], 0.0) << "sample " << i;
  }
  EXPECT_GT(max_abs(alone), 0.2);  // it slides (0.258 m, docs/model.md)
}

// A one-sine pulse along a fixed direction: the cone's slip stays on that line and is the 1-D Coulomb
// block under the pulse's magnitude (friction mu g against it); each plane carries its cosine. The 1-D
// block is one plane alone under the magnitude (ContactModel, itself checked against the closed forms).
TEST(FrictionShare, AStraightLineSlideIsTheOneDimensionalCoulombBlock) {
  const double dt = 0.005, period = 1.0, peak = 0.8 * kGravity;
  for (double deg : {20.0, 45.0, 70.0}) {
    const double c = std::cos(deg * kPi / 180.0), s = std::sin(deg * kPi / 180.0);
    std::vector<double> a, ax, ay;
    for (int i = 0; i <= 400; ++i) {
      const double t = i * dt;
      const double v = t < period ? peak * std::sin(2.0 * kPi * t / period) : 0.0;
      a.push_back(v);
      ax.push_back(v * c);
      ay.push_back(v * s);
    }
    const std::vector<double> line = run_plane(cabinet(false).body, a, dt);
    const Slips pair = run_item(cabinet(false), SolidChoice::Planar, ax, ay, dt);
    const Slips cone = run_item(cabinet(true), SolidChoice::Solid, ax, ay, dt);
    const std::vector<double> px = run_plane(cabinet(false).body, ax, dt);
    const double u = line.back();
    ASSERT_GT(std::abs(u), 0.05) << deg << " deg";
    for (std::size_t i = 0; i < line.size(); ++i) {
      ASSERT_NEAR(pair.x[i], line[i] * c, 1e-6 * std::abs(u)) << deg << " deg, sample " << i;
      ASSERT_NEAR(pair.y[i], line[i] * s, 1e-6 * std::abs(u)) << deg << " deg, sample " << i;
    }
    EXPECT_NEAR(cone.x.back(), u * c, 1e-6 * std::abs(u)) << deg << " deg: the 3-D model's cone";
    EXPECT_NEAR(cone.y.back(), u * s, 1e-6 * std::abs(u)) << deg << " deg";
    // The per-plane budget resists the x part with all of mu g: far less slip.
    EXPECT_LT(std::abs(px.back()), 0.8 * std::abs(u * c)) << deg << " deg";
    std::printf("[ measured ] %.0f deg pulse: slip %.6f m along it; pair x %.9f y %.9f, 3-D x %.9f y %.9f, "
                "x alone (pyramid) %.6f m\n", deg, u, pair.x.back(), pair.y.back(), cone.x.back(), cone.y.back(),
                px.back());
  }
}

// Both horizontals of real records: the pair's largest slip along each axis against the 3-D model's
// cone, beside the planes alone (the pyramid). The shared budget must come closer to the cone.
TEST(FrictionShare, UnderBothHorizontalsThePairComesCloserToTheConeThanThePyramid) {
  struct Pair {
    const char* x;
    const char* y;
  };
  const Pair records[] = {{"kobe_1995/RSN1120_KOBE_TAK000.AT2", "kobe_1995/RSN1120_KOBE_TAK090.AT2"},
                          {"northridge_1994/Rinaldi228.AT2", "northridge_1994/Rinaldi318.AT2"}};
  double err_pair = 0.0, err_pyramid = 0.0;
  for (const Pair& r : records) {
    const Component cx = read_record(std::string(ROCKING_RECORDS_DIR) + "/" + r.x).front();
    const Component cy = read_record(std::string(ROCKING_RECORDS_DIR) + "/" + r.y).front();
    const std::size_t n = std::min(cx.accel.size(), cy.accel.size());
    const std::vector<double> ax(cx.accel.begin(), cx.accel.begin() + static_cast<long>(n));
    const std::vector<double> ay(cy.accel.begin(), cy.accel.begin() + static_cast<long>(n));
    const Slips pair = run_item(cabinet(false), SolidChoice::Planar, ax, ay, cx.dt);
    const Slips cone = run_item(cabinet(true), SolidChoice::Solid, ax, ay, cx.dt);
    const ItemSpec c = cabinet(false);
    const double pyr_x = max_abs(run_plane(c.body, ax, cx.dt));
    const double pyr_y = max_abs(run_plane(y_plane_body(c.body, c.depth), ay, cx.dt));
    std::printf("[ measured ] %s + %s: max slip x / y: cone %.3f / %.3f m, shared pair %.3f / %.3f m, "
                "pyramid %.3f / %.3f m\n", r.x, r.y, cone.max_x, cone.max_y, pair.max_x, pair.max_y, pyr_x, pyr_y);
    err_pair += std::abs(pair.max_x - cone.max_x) + std::abs(pair.max_y - cone.max_y);
    err_pyramid += std::abs(pyr_x - cone.max_x) + std::abs(pyr_y - cone.max_y);
  }
  std::printf("[ measured ] summed |max slip - cone's|: shared pair %.3f m, pyramid %.3f m\n", err_pair, err_pyramid);
  EXPECT_LT(err_pair, 0.1 * err_pyramid);
}

// The shares are held through each sample: the pair converges to the cone as the same ground motion is
// sampled more often (the 3-D model's answer does not change; its slip is exact for the input).
TEST(FrictionShare, ThePairConvergesToTheConeAsTheSharesAreSetMoreOften) {
  const Component cx = read_record(std::string(ROCKING_RECORDS_DIR) + "/kobe_1995/RSN1120_KOBE_TAK000.AT2").front();
  const Component cy = read_record(std::string(ROCKING_RECORDS_DIR) + "/kobe_1995/RSN1120_KOBE_TAK090.AT2").front();
  const std::size_t n = std::min<std::size_t>({cx.accel.size(), cy.accel.size(), 1501});  // the strong part: 15 s
  const std::vector<double> ax(cx.accel.begin(), cx.accel.begin() + static_cast<long>(n));
  const std::vector<double> ay(cy.accel.begin(), cy.accel.begin() + static_cast<long>(n));
  const Slips cone = run_item(cabinet(true), SolidChoice::Solid, ax, ay, cx.dt);
  double err[3];
  const int factors[3] = {1, 4, 16};
  for (int f = 0; f < 3; ++f) {
    const Slips pair = run_item(cabinet(false), SolidChoice::Planar, finer(ax, factors[f]), finer(ay, factors[f]),
                                cx.dt / factors[f]);
    err[f] = std::hypot(pair.x.back() - cone.x.back(), pair.y.back() - cone.y.back());
    std::printf("[ measured ] Takatori, shares set every %.4f s: final slip (%.4f, %.4f) m, the cone's (%.4f, %.4f): "
                "%.2e m apart\n", cx.dt / factors[f], pair.x.back(), pair.y.back(), cone.x.back(), cone.y.back(), err[f]);
  }
  EXPECT_LT(err[1], 0.5 * err[0]);
  EXPECT_LT(err[2], 0.5 * err[1]);
}

}  // namespace
}  // namespace rocking_monitor::core
