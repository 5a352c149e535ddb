// Independent 3-D reference for Rocking3DModel (issue 27): Bullet Physics (bullet_rocking.hpp: a
// convex hull on a floor plane, friction 1.5 x 1, restitution 0, margin 0.2 mm, split impulse, 30
// solver iterations, fixed step). The core runs with the default SolverSettings, tol 1e-8. Both
// get the same samples (first-order hold) and count an overturn at a tilt of 1.2 rad.
//
// Box 0.3 x 0.3 m, centre of mass 0.45 m high, one-sine pulses (2 Hz), Bullet at 1/8000 s
// (measured at 1/4000 ... 1/32000 s: outcomes never change; peaks move < 2 % from 1/4000 to
// 1/8000 s and < 0.3 % beyond): same outcome at every amplitude; peak tilt within 0.1-0.5 %,
// first impact within 1 ms (Bullet's landing, where the tilt is back to 2 % of the peak, comes
// 0.2-0.9 ms early: its corners are rounded by the margin and its contact yields by microns),
// overturn time within 0.1-0.6 ms before any impact and 0.3-4 ms after one. Tolerances: 2 %,
// 2 ms, 5 ms, 10 ms. Bullet's contact settings hardly matter here: margin 0.05 mm with 0.2 mm
// thresholds moves the side pulse's peak by 1.5 %, split impulse off or friction 0.8 by < 0.1 %.
// The impacts agree this closely because the box lands on a whole edge (or flat on its diagonal)
// and Bullet's restitution-0 impulses at the landing edge, with no slip, conserve the angular
// momentum about it much as the core's law does (the peak after each landing: 0.71-0.72 of the
// one before in both, <= 1.9 % apart). They differ on the symmetric landing of a diagonal pulse
// (three corners at once: the core gives the impulse to the far corner, Bullet shares it by its
// solver's order; the next peak is 35 % higher in Bullet); BoxUnderAnObliquePulseIsNotPutDownWhileSwinging
// is the case that found the core's edge-to-vertex chatter (fixed).
//
// The granite specimens against Bullet: test_bullet_granite.cpp.
#include "bullet_reference_runs.hpp"

namespace rocking_monitor {
namespace {

constexpr double kBoxStep = 1.0 / 8000;  // s, Bullet's step for the box (converged: see BulletStepIsConverged)
constexpr double kPulseHz = 2.0;
constexpr double kSampleDt = 1e-3;  // s, the pulse's samples (both codes: first-order hold)

// Tolerances, from the measured agreement (box, Bullet at 1/8000 s; see the header):
constexpr double kPeakTol = 0.02;         // relative peak tilt: measured <= 0.5 %
constexpr double kImpactTimeTol = 2e-3;   // s, first impact: measured <= 1.0 ms
constexpr double kOverturnTimeTol = 5e-3;   // s, overturn before any impact: measured <= 0.6 ms
constexpr double kOverturnAfterImpactTol = 1e-2;  // s, after an impact: measured <= 4 ms (see below)
constexpr double kRestTilt = 1e-4;        // rad: "at rest" in Bullet (its settling noise < 1e-5)

Pair test_box() { return box(0.3, 0.3, 0.45, 100.0, kOverturn); }

struct Compared {
  Result core, bullet;
};

Compared compare_box_pulse(const Eigen::Vector3d& direction, double amp_g, double step = kBoxStep) {
  const Pair p = test_box();
  const Series s = sine_pulse(direction, amp_g * kGravity, kPulseHz, kSampleDt, 3.0);
  Compared c;
  c.core = run_core(p.core, s, kSampleDt);
  BulletSettings bs;
  bs.substep = step;
  bs.overturn_tilt = kOverturn;
  std::vector<Eigen::Vector2d> history;
  c.bullet = run_bullet(p.bullet, bs, s, kSampleDt, &history);
  c.bullet.first_impact_time = bullet_first_return(history, 0.02);
  std::printf("%.1f g along (%g, %g): core overturned %d at %.4f s, peak tilt %.5f rad, first impact %.4f s, "
              "%ld forced rests | "
              "Bullet (1/%.0f s) overturned %d at %.4f s, peak tilt %.5f rad, first return %.4f s\n",
              amp_g, direction.x(), direction.y(), c.core.overturned, c.core.overturn_time, c.core.max_tilt,
              c.core.first_impact_time, c.core.forced_rests, 1.0 / step, c.bullet.overturned, c.bullet.overturn_time,
              c.bullet.max_tilt, c.bullet.first_impact_time);
  return c;
}

// 0.3 x 0.3 m base, centre of mass 0.45 m high (homogeneous), one-sine pulse (2 Hz) along the
// base's diagonal: the ground's push acts on both edges at a corner at once, so the box lifts onto
// that corner (VERTEX in the core). The static uplift along the diagonal is g B / (2 h) sqrt 2 =
// 0.471 g.
TEST(Bullet3D, BoxUnderADiagonalPulse) {
  const Eigen::Vector3d diagonal(1.0, 1.0, 0.0);
  {
    SCOPED_TRACE("0.4 g: below uplift");
    const Compared c = compare_box_pulse(diagonal, 0.4);
    EXPECT_FALSE(c.core.overturned);
    EXPECT_EQ(c.core.max_tilt, 0.0);
    EXPECT_TRUE(std::isnan(c.core.uplift_time));
    EXPECT_FALSE(c.bullet.overturned);
    EXPECT_LT(c.bullet.max_tilt, kRestTilt);
  }
  {
    SCOPED_TRACE("0.6 g: rocks on the corner, lands, survives");
    const Compared c = compare_box_pulse(diagonal, 0.6);
    EXPECT_TRUE(c.core.vertex);
    EXPECT_FALSE(c.core.overturned);
    EXPECT_FALSE(c.bullet.overturned);
    EXPECT_GT(c.core.max_tilt, 0.08);  // a fifth of the corner's tipping angle (0.44 rad)
    EXPECT_NEAR(c.bullet.first_impact_time, c.core.first_impact_time, kImpactTimeTol);
    // The first landing is flat on three corners at once. The core's law (issue 40) gives eq. 34
    // of the body through the diagonal there (the far corner takes the impulse: Rocking3DLandings,
    // ImpactLaw tests); Bullet's sequential impulses activate the three corners one after another
    // and keep more energy (issue 40: ratio 0.861 against eq. 34's 0.721 in Siconos), so its driven
    // second swing is higher: measured 0.114 against the core's 0.093 rad (1/8000 s; 0.113 at 1/4000).
    // A time-stepping code is the reference for the free motion and single-contact landings here,
    // not for a landing on several contacts.
    EXPECT_GT(c.bullet.max_tilt / c.core.max_tilt, 1.0 + kPeakTol);
    EXPECT_LT(c.bullet.max_tilt / c.core.max_tilt, 1.35);
  }
  {
    // Overturns after landing flat on three corners at once. Bullet (sequential impulses) keeps
    // more energy at that landing than the law (eq. 34 of the diagonal body, issue 40) and
    // overturns on the return swing (1.24 s); the core loses eq. 34's share, swings again and
    // overturns at 2.38 s. The same first landing; the later overturn is the law's, not a defect.
    SCOPED_TRACE("0.8 g: lands flat on three corners, then overturns");
    const Compared c = compare_box_pulse(diagonal, 0.8);
    EXPECT_TRUE(c.core.overturned);
    EXPECT_TRUE(c.bullet.overturned);
    EXPECT_GE(c.core.impacts, 1);
    EXPECT_NEAR(c.bullet.first_impact_time, c.core.first_impact_time, kImpactTimeTol);
    EXPECT_GT(c.core.overturn_time, c.bullet.overturn_time + kOverturnAfterImpactTol);
  }
  {
    SCOPED_TRACE("2.0 g: overturns on the first swing");
    const Compared c = compare_box_pulse(diagonal, 2.0);
    EXPECT_TRUE(c.core.overturned);
    EXPECT_TRUE(c.bullet.overturned);
    EXPECT_EQ(c.core.impacts, 0);
    EXPECT_NEAR(c.bullet.overturn_time, c.core.overturn_time, kOverturnTimeTol);
  }
}

// The same box, the pulse along one side (x): it rocks about a base edge (static uplift g B / 2h
// = 0.333 g), both ends of the edge on the floor.
TEST(Bullet3D, BoxUnderAPulseAlongOneSide) {
  const Eigen::Vector3d side(1.0, 0.0, 0.0);
  {
    SCOPED_TRACE("0.3 g: below uplift");
    const Compared c = compare_box_pulse(side, 0.3);
    EXPECT_EQ(c.core.max_tilt, 0.0);
    EXPECT_LT(c.bullet.max_tilt, kRestTilt);
  }
  {
    SCOPED_TRACE("0.4 g: rocks about the edge, lands, survives");
    const Compared c = compare_box_pulse(side, 0.4);
    EXPECT_FALSE(c.core.vertex);
    EXPECT_FALSE(c.core.overturned);
    EXPECT_FALSE(c.bullet.overturned);
    EXPECT_GT(c.core.max_tilt, 0.03);
    EXPECT_NEAR(c.bullet.max_tilt / c.core.max_tilt, 1.0, kPeakTol);
    EXPECT_NEAR(c.bullet.first_impact_time, c.core.first_impact_time, kImpactTimeTol);
  }
  {
    SCOPED_TRACE("0.6 g: one landing, then overturns the other way");
    const Compared c = compare_box_pulse(side, 0.6);
    EXPECT_TRUE(c.core.overturned);
    EXPECT_TRUE(c.bullet.overturned);
    EXPECT_NEAR(c.bullet.first_impact_time, c.core.first_impact_time, kImpactTimeTol);
    EXPECT_NEAR(c.bullet.overturn_time, c.core.overturn_time, kOverturnAfterImpactTol);
  }
  {
    SCOPED_TRACE("1.5 g: overturns on the first swing");
    const Compared c = compare_box_pulse(side, 1.5);
    EXPECT_TRUE(c.core.overturned);
    EXPECT_TRUE(c.bullet.overturned);
    EXPECT_EQ(c.core.impacts, 0);
    EXPECT_NEAR(c.bullet.overturn_time, c.core.overturn_time, kOverturnTimeTol);
  }
}

// Bullet's step: halving it (1/4000 -> 1/8000 s) changes neither outcome, and the peak tilts and
// times by less than the tolerances above (measured: peak 1.8 % and 0.2 %, times <= 1.4 ms; at
// 1/16000 and 1/32000 s the peaks move by < 0.3 % more).
TEST(Bullet3D, BulletStepIsConverged) {
  struct Case { Eigen::Vector3d direction; double amp_g; };
  for (const Case& k : {Case{Eigen::Vector3d(1, 0, 0), 0.4}, Case{Eigen::Vector3d(1, 1, 0), 0.6},
                        Case{Eigen::Vector3d(1, 0, 0), 0.6}}) {
    const Compared fine = compare_box_pulse(k.direction, k.amp_g, kBoxStep);
    const Compared coarse = compare_box_pulse(k.direction, k.amp_g, 2.0 * kBoxStep);
    EXPECT_EQ(fine.bullet.overturned, coarse.bullet.overturned);
    if (!fine.bullet.overturned) {
      EXPECT_NEAR(coarse.bullet.max_tilt / fine.bullet.max_tilt, 1.0, kPeakTol);
    } else {
      EXPECT_NEAR(coarse.bullet.overturn_time, fine.bullet.overturn_time, kOverturnTimeTol);
    }
    EXPECT_NEAR(coarse.bullet.first_impact_time, fine.bullet.first_impact_time, kImpactTimeTol);
  }
}

// Peaks of the successive excursions of a sampled tilt history: its local maxima above `floor`
// (between two excursions the tilt dips to ~0 at a landing, which the samples may straddle).
std::vector<double> excursion_peaks(const std::vector<double>& tilt, double floor) {
  std::vector<double> peaks;
  for (std::size_t k = 1; k + 1 < tilt.size(); ++k)
    if (tilt[k] > floor && tilt[k] > tilt[k - 1] && tilt[k] >= tilt[k + 1]) peaks.push_back(tilt[k]);
  return peaks;
}

// The impacts themselves: after the side pulse of 0.4 g the box rocks freely, landing on a whole
// edge at every half cycle; each landing's loss sets the next peak. The core's law (angular
// momentum about the new edge) against Bullet's restitution-0 impulses: peak over the previous
// peak 0.711-0.720 in the core, 0.707-0.718 in Bullet (at most 1.9 % apart per landing; Bullet
// loses slightly more, so the peaks drift apart to 6.5 % by the 10th excursion). Tolerances 3 %
// per landing, 8 % on the peaks.
TEST(Bullet3D, BoxLandingsLoseEnergyAlike) {
  const Pair p = test_box();
  const Series s = sine_pulse(Eigen::Vector3d(1.0, 0.0, 0.0), 0.4 * kGravity, kPulseHz, kSampleDt, 4.0);
  SolverSettings settings;
  settings.tol = 1e-8;
  Rocking3DModel m(BaseBody(p.core), settings);
  m.reset(0.0, s.front());
  BulletSettings bs;
  bs.substep = kBoxStep;
  BulletRocking b(p.bullet, bs);
  std::vector<double> tc, tb;
  for (std::size_t k = 1; k < s.size(); ++k) {
    m.step(s[k], kSampleDt);
    b.step(s[k], kSampleDt);
    tc.push_back(m.tilt());
    tb.push_back(b.tilt());
  }
  const std::vector<double> pc = excursion_peaks(tc, 2e-4), pb = excursion_peaks(tb, 2e-4);
  ASSERT_GE(pc.size(), 12u);
  ASSERT_GE(pb.size(), 12u);
  EXPECT_GT(m.outcome().impacts, 10);
  for (std::size_t i = 0; i < 10; ++i) {
    std::printf("excursion %zu: core %.5f Bullet %.5f rad\n", i + 1, pc[i], pb[i]);
    EXPECT_NEAR(pb[i] / pc[i], 1.0, 0.08) << "excursion " << i + 1;
    // From the 3rd on, each peak follows one free landing: the energy kept by it (for a small tilt
    // the peak is proportional to the energy; Housner's 1 - 1.5 sin^2 alpha squared = 0.7225).
    if (i >= 2) {
      EXPECT_NEAR((pb[i] / pb[i - 1]) / (pc[i] / pc[i - 1]), 1.0, 0.03) << "landing before " << i + 1;
    }
  }
}

// The same box under 0.6 g along (1, 2): it rocks about edge 0 (y = 0) and is swinging back (tilt
// 0.0116 rad, -0.776 rad/s) when, at t = 0.357382 s, the floor's reaction at the x = 0 end of that
// edge comes to zero. Pivoting on the other end alone would turn the body about the vertical as well
// and drive that end into the floor (the real body slips there; Bullet: it yaws 0.01 rad on its
// edge). Found by this test: the core then alternated EDGE -> VERTEX -> impact ... without time
// advancing until the event bound put it down flat (0.09 J/kg lost; it survived while Bullet
// overturns at 1.47 s). Now an end lets go only when pivoting on the other end really lifts it, and
// the body keeps rocking on the edge; both overturn.
TEST(Bullet3D, BoxUnderAnObliquePulseIsNotPutDownWhileSwinging) {
  const Compared c = compare_box_pulse(Eigen::Vector3d(1.0, 2.0, 0.0), 0.6);
  EXPECT_EQ(c.core.forced_rests, 0);
  EXPECT_EQ(c.core.overturned, c.bullet.overturned);
}

}  // namespace
}  // namespace rocking_monitor
