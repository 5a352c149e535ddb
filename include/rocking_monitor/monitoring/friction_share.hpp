#pragma once
// The planar pair's one friction budget (issue 51 part 4). An item described by two planes (x and y)
// runs a planar model in each. Alone, each plane would resist with its full mu_s N: a square
// pyramid instead of Coulomb's cone, up to sqrt(2) too much resistance when both directions slide
// (docs/model.md). Here the two planes share one isotropic budget: before every sample each plane
// gets mu_s x share, with
//   * a base or pivot slipping (in either plane): the friction against the slip's direction through
//     the sample, taken implicitly: share_i = |w_i| / |w| with w = v - a_g dt, the slip velocity the
//     sample would reach without friction (a_g the ground's mean acceleration in it). A plane at rest
//     beside a fast slip gets almost none, as Coulomb's law has it; implicit, so that a slip slower
//     than mu g dt does not hand the whole budget from plane to plane sample by sample;
//   * nothing slipping, a demand nearing the cone (some plane's |R_x|/R_y >= mu_s / 2 at the
//     sample's start): 1 while the demand at its end is inside the cone (then q_i <= |q| <= mu_s and
//     no plane's own check can fire), else share_i = q_i / |q| there, so that each plane's check
//     q_i <= mu_s share_i is the cone's |q| <= mu_s, and the plane locates the onset in the sample;
//   * otherwise 1: no plane can reach the cone (|q| < mu_s), and each plane runs today's model.
// One component alone (the other plane's v and q zero) gives share 1 exactly: today's answer.
// The shares are set before the sample and held through it (the planes are stepped one after the
// other): a demand that jumps from below mu_s / 2 past the cone in one sample, or a slip that turns
// inside it, is followed a sample late. docs/model.md measures it against the 3-D
// model's exact cone.

#include "rocking_monitor/model/adaptive_model.hpp"

namespace rocking_monitor::core {

/// Engaged from this fraction of mu_s of a plane's demand at the sample's start: the pair's planes
/// then step together (MonitorBatch defers a plane only while its demand stays below it, so the item
/// stays not engaged). Below 1/sqrt(2), so that a demand rising to the cone along any direction
/// engages the pair a sample or more before its onset (at 45 deg the cone is q_x = mu_s / sqrt(2)).
constexpr double kShareEngage = 0.5;

struct FrictionShare {
  double share[2] = {1.0, 1.0};  ///< of mu_s (and mu_k), x and y plane, in [0, 1]
  bool engaged = false;          ///< some share may be below 1 (a plane slips or nears the cone)
};

/// v: each plane's slip velocity at the sample's start (m/s; 0 while its base or pivot sticks); w: v
/// minus the ground's mean acceleration in the sample times dt (m/s); q0, q1: each plane's friction
/// demand |R_x| / R_y at the sample's start and end (dimensionless, +inf without a normal force);
/// mu_s: the item's. Engaged depends on v and q0 alone.
FrictionShare friction_share(const double (&v)[2], const double (&w)[2], const double (&q0)[2],
                             const double (&q1)[2], double mu_s);

/// The shares of the x and y planes' models for the sample from their state at its start: each
/// plane's input (horizontal, vertical) there (x0, y0; the y plane's horizontal is the item's y) and
/// at its end, dt later (x1, y1), m/s^2 and s. mu_s: the x plane's (the item's).
FrictionShare friction_share(const AdaptiveModel& x, const AdaptiveModel& y, const double (&x0)[2],
                             const double (&y0)[2], const double (&x1)[2], const double (&y1)[2], double dt);

/// Whether the planes are engaged at a sample's start (their input there x0, y0): a plane slips, or
/// one demands mu_s * kShareEngage or more; friction_share's `engaged`, without the sample's end.
bool friction_engaged(const AdaptiveModel& x, const AdaptiveModel& y, const double (&x0)[2], const double (&y0)[2]);

}  // namespace rocking_monitor::core
