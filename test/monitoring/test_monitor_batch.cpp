// MonitorBatch: items stepped together, quiet samples deferred, must end every sample exactly as the
// same items stepped one by one by ItemMonitor::step (the oracle: an independent copy of every item).
// Real records at several scales (so that items rest, rock, slide, overturn), all fidelities,
// friction given or not, the linearized tier, one and two planes, random subsets stepped (items
// without a transform in the node), ranges of every size.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/monitoring/item_monitor.hpp"
#include "rocking_monitor/monitoring/item_summary.hpp"
#include "rocking_monitor/monitoring/monitor_batch.hpp"
#include "rocking_monitor/motion/record_reader.hpp"

namespace rocking_monitor::core {
namespace {

struct BatchCatalogue {
  std::vector<ItemSpec> specs;
  std::vector<ItemMonitor::Options> options;
};

BatchCatalogue random_catalogue(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  BatchCatalogue c;
  for (std::size_t i = 0; i < n; ++i) {
    ItemSpec s;
    s.id = "item" + std::to_string(i);
    s.sensor = "floor";
    s.frame = "item";
    s.body.cg_height = 0.2 + 1.0 * u(rng);
    s.body.width = std::min(0.15 + 0.65 * u(rng), 1.5 * s.body.cg_height);
    s.body.nu1 = 0.25 + 0.25 * u(rng);
    const double f = u(rng);
    if (f < 0.7) s.body.mu_s = 0.3 + 0.5 * u(rng);  // else: friction not given (pure rocking)
    if (u(rng) < 0.7) {
      s.depth.depth = std::min(0.15 + 0.85 * u(rng), 1.5 * s.body.cg_height);
      s.depth.eccentricity_y = 0.25 + 0.25 * u(rng);
    }
    ItemMonitor::Options o;
    const double g = u(rng);
    o.fidelity = g < 0.7 ? Fidelity::Adaptive : g < 0.85 ? Fidelity::Rocking : Fidelity::Contact;
    if (u(rng) < 0.2) o.linearized_max_alpha = 0.35;  // the linearized tier for slender items
    if (u(rng) < 0.1) o.solver.model = ModelKind::Linearized;
    if (u(rng) < 0.1) o.scene = SceneEnvelope{4.0, 3.0};
    c.specs.push_back(s);
    c.options.push_back(o);
  }
  return c;
}

void expect_same_events(const ItemEvents& a, const ItemEvents& b, std::size_t k, std::size_t i) {
  ASSERT_EQ(a.change_count, b.change_count) << "item " << k << " sample " << i;
  ASSERT_EQ(a.alarm_count, b.alarm_count) << "item " << k << " sample " << i;
  for (int j = 0; j < a.change_count; ++j) {
    EXPECT_EQ(a.changes[j].id, b.changes[j].id);
    EXPECT_EQ(a.changes[j].exceeded, b.changes[j].exceeded);
    EXPECT_EQ(a.changes[j].plane, b.changes[j].plane);
    EXPECT_EQ(a.changes[j].value, b.changes[j].value);
  }
  for (int j = 0; j < a.alarm_count; ++j) {
    EXPECT_EQ(a.alarms[j].level, b.alarms[j].level);
    EXPECT_EQ(a.alarms[j].time, b.alarms[j].time) << "item " << k << " sample " << i;
    EXPECT_EQ(a.alarms[j].plane, b.alarms[j].plane);
  }
}

void expect_same_state(const ItemMonitor& a, const ItemMonitor& b, std::size_t k, std::size_t i) {
  ASSERT_EQ(a.mode(), b.mode()) << "item " << k << " sample " << i;
  ASSERT_EQ(a.solid() != nullptr, b.solid() != nullptr);
  if (a.solid() != nullptr) {
    const Rocking3DModel& x = *a.solid();
    const Rocking3DModel& y = *b.solid();
    EXPECT_EQ(a.solid_active(), b.solid_active()) << "item " << k << " sample " << i;
    EXPECT_EQ(x.mode(), y.mode()) << "item " << k << " sample " << i;
    EXPECT_EQ(x.time(), y.time()) << "item " << k << " sample " << i;
    EXPECT_EQ(x.outcome().samples, y.outcome().samples) << "item " << k << " sample " << i;
    EXPECT_EQ(x.outcome().impacts, y.outcome().impacts);
    EXPECT_EQ(x.rotation_ratio(), y.rotation_ratio()) << "item " << k << " sample " << i;
    EXPECT_EQ(x.tilt(), y.tilt());
    EXPECT_EQ(x.last_report().uplift, y.last_report().uplift);
  }
  for (int p = 0; p < a.plane_count(); ++p) {
    const PlaneMonitor& x = a.plane(static_cast<Plane>(p));
    const PlaneMonitor& y = b.plane(static_cast<Plane>(p));
    EXPECT_EQ(x.side(), y.side()) << "item " << k << " plane " << p << " sample " << i;
    EXPECT_EQ(x.theta(), y.theta()) << "item " << k << " plane " << p << " sample " << i;
    EXPECT_EQ(x.omega(), y.omega()) << "item " << k << " plane " << p << " sample " << i;
    EXPECT_EQ(x.slip(), y.slip());
    EXPECT_EQ(x.impacts(), y.impacts());
    EXPECT_EQ(x.pga(), y.pga());
    EXPECT_EQ(x.pgv(), y.pgv()) << "item " << k << " plane " << p << " sample " << i;
    EXPECT_EQ(x.housner_demand(), y.housner_demand()) << "item " << k << " plane " << p << " sample " << i;
    EXPECT_EQ(x.contact_mode(), y.contact_mode());
    EXPECT_EQ(x.violations(), y.violations());
    EXPECT_EQ(x.model().time(), y.model().time());
    if (x.adaptive() != nullptr) {
      // What the rocking lanes rebuild when they apply deferred samples: the rocking model's state,
      // integrator state, report and counters, the adaptive model's clock, report and counters.
      AdaptiveModel::Saved sx, sy;
      x.adaptive()->save(sx);
      y.adaptive()->save(sy);
      const RockingModel::Saved& rx = sx.rock;
      const RockingModel::Saved& ry = sy.rock;
      const std::string at = "item " + std::to_string(k) + " plane " + std::to_string(p) + " sample " + std::to_string(i);
      EXPECT_EQ(rx.mode, ry.mode) << at;
      EXPECT_EQ(rx.side, ry.side) << at;
      EXPECT_EQ(rx.t, ry.t) << at;
      EXPECT_EQ(rx.ax_prev, ry.ax_prev) << at;
      EXPECT_EQ(rx.ay_prev, ry.ay_prev) << at;
      EXPECT_EQ(rx.violations, ry.violations) << at;
      EXPECT_EQ(rx.report.integrator_steps, ry.report.integrator_steps) << at;
      EXPECT_EQ(rx.report.violation_onsets, ry.report.violation_onsets) << at;
      EXPECT_EQ(rx.report.peak_ratio, ry.report.peak_ratio) << at;
      EXPECT_EQ(rx.outcome.max_rotation_ratio, ry.outcome.max_rotation_ratio) << at;
      EXPECT_EQ(rx.outcome.max_rotation_side, ry.outcome.max_rotation_side) << at;
      EXPECT_EQ(rx.outcome.integrator_steps, ry.outcome.integrator_steps) << at;
      EXPECT_EQ(rx.outcome.samples, ry.outcome.samples) << at;
      EXPECT_EQ(rx.outcome.committed, ry.outcome.committed) << at;
      EXPECT_EQ(rx.dopri5.h, ry.dopri5.h) << at;
      EXPECT_EQ(rx.dopri5.fsal_valid, ry.dopri5.fsal_valid) << at;
      EXPECT_EQ(rx.dopri5.k1_theta, ry.dopri5.k1_theta) << at;
      EXPECT_EQ(rx.dopri5.k1_omega, ry.dopri5.k1_omega) << at;
      EXPECT_EQ(sx.t, sy.t) << at;
      EXPECT_EQ(sx.ax_prev, sy.ax_prev) << at;
      EXPECT_EQ(sx.ay_prev, sy.ay_prev) << at;
      EXPECT_EQ(sx.hold, sy.hold) << at;
      EXPECT_EQ(sx.scene_guarantee, sy.scene_guarantee) << at;
      EXPECT_EQ(sx.lin_active, sy.lin_active) << at;
      EXPECT_EQ(sx.report.model, sy.report.model) << at;
      EXPECT_EQ(sx.report.rocking_samples, sy.report.rocking_samples) << at;
      EXPECT_EQ(sx.report.rocking_steps, sy.report.rocking_steps) << at;
      EXPECT_EQ(sx.report.contact_samples, sy.report.contact_samples) << at;
      EXPECT_EQ(sx.report.integrator_steps, sy.report.integrator_steps) << at;
      EXPECT_EQ(sx.outcome.rocking_steps, sy.outcome.rocking_steps) << at;
      EXPECT_EQ(sx.outcome.contact_steps, sy.outcome.contact_steps) << at;
      const AdaptiveOutcome& ox = x.adaptive()->outcome();
      const AdaptiveOutcome& oy = y.adaptive()->outcome();
      EXPECT_EQ(x.adaptive()->time(), y.adaptive()->time()) << "item " << k << " sample " << i;
      EXPECT_EQ(ox.samples, oy.samples);
      EXPECT_EQ(ox.samples_rocking_model, oy.samples_rocking_model);
      EXPECT_EQ(ox.samples_contact_model, oy.samples_contact_model);
      EXPECT_EQ(ox.model_switches, oy.model_switches);
      EXPECT_EQ(ox.samples_outside_scene, oy.samples_outside_scene);
      EXPECT_EQ(ox.max_rotation_ratio, oy.max_rotation_ratio);
    } else {
      EXPECT_EQ(x.model().outcome().samples, y.model().outcome().samples);
    }
  }
}

struct BatchRun {
  std::size_t deferred = 0, samples = 0, overturned = 0, rocked = 0, revisions = 0;
  std::size_t plane_deferred = 0;  // item-samples stepped for one plane while the other was deferred
  long rocking_deferred = 0;       // plane-samples deferred in rocking lanes
  std::size_t solid_rocked = 0, solid_overturned = 0;  // items whose 3-D model decided and lifted / fell
  std::size_t solid_flew = 0;  // ... and flew (the floor dropping faster than gravity)
};

// Steps a batch and an independent copy of each item (ItemMonitor::step) through one record scaled by
// `scale` (x: the record, y: 0.7 x the record reversed in time, z: 0.3 x the record), every
// `active_share` of items active per sample, the batch cut into ranges of `range` items; y is 0 for the
// first y_start of the record; z is z_share x the record.
// Summaries are read every `summary_every` samples (1: every sample, as the node's changed-items topic
// at its fastest; more: deferred rocking samples accumulate between reads).
BatchRun compare(const BatchCatalogue& cat, const Component& rec, double scale, double active_share, std::size_t range,
            unsigned seed, double y_start = 0.0, std::size_t summary_every = 1, double z_share = 0.3) {
  const std::size_t n = cat.specs.size();
  std::vector<std::unique_ptr<ItemMonitor>> batched, alone;
  std::vector<ItemMonitor*> ptrs;
  for (std::size_t k = 0; k < n; ++k) {
    batched.push_back(std::make_unique<ItemMonitor>(cat.specs[k], cat.options[k]));
    alone.push_back(std::make_unique<ItemMonitor>(cat.specs[k], cat.options[k]));
  }
  const std::vector<double>& a = rec.accel;
  const std::size_t m = a.size();
  auto input = [&](std::size_t i, double& x, double& y, double& z) {
    x = scale * a[i];
    y = i < y_start * m ? 0.0 : 0.7 * scale * a[m - 1 - i];
    z = z_share * scale * a[(i * 7) % m];
  };
  double x, y, z;
  input(0, x, y, z);
  for (std::size_t k = 0; k < n; ++k) {
    batched[k]->start(0.0, x, y, z, rec.dt);
    alone[k]->start(0.0, x, y, z, rec.dt);
    ptrs.push_back(batched[k].get());
  }
  MonitorBatch batch(ptrs);
  std::vector<ItemSummary> last(n);  // the summaries as a publisher last saw them
  for (std::size_t k = 0; k < n; ++k) last[k] = batch.summary(k);
  std::vector<double> ax(n), ay(n), az(n);
  std::vector<std::uint8_t> active(n, 1);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  BatchRun run;
  for (std::size_t i = 1; i < m; ++i) {
    input(i, x, y, z);
    for (std::size_t k = 0; k < n; ++k) {
      ax[k] = x;
      ay[k] = y;
      az[k] = z;
      active[k] = u(rng) < active_share ? 1 : 0;
    }
    for (std::size_t b = 0; b < n; b += range)
      run.deferred += batch.step(b, std::min(n, b + range), ax.data(), ay.data(), az.data(), rec.dt,
                                 active_share < 1.0 ? active.data() : nullptr);
    for (std::size_t k = 0; k < n; ++k) {
      if (!active[k]) {
        EXPECT_EQ(batch.event_flags(k), 0) << "item " << k << " not stepped in sample " << i;
        continue;
      }
      ++run.samples;
      const unsigned stepped = batch.stepped_planes(k);
      run.plane_deferred += stepped != 0 && stepped != (1u << batched[k]->plane_count()) - 1;
      const ItemEvents& oracle = alone[k]->step(x, y, z, rec.dt);
      expect_same_events(batch.events(k), oracle, k, i);
      // The compact flags a node scans instead of every item's events.
      EXPECT_EQ(batch.event_flags(k), (oracle.change_count > 0 ? MonitorBatch::kHasChanges : 0) |
                                          (oracle.alarm_count > 0 ? MonitorBatch::kHasAlarms : 0))
          << "item " << k << " sample " << i;
    }
    // The summary (what ~states and markers read without a sync) equals the item stepped alone, read
    // in full, every sample; its revision moves exactly when a field changed (changed-items topics).
    for (std::size_t k = 0; k < n && i % summary_every == 0; ++k) {
      ItemSummary oracle;
      summarize(*alone[k], oracle);
      const ItemSummary& s = batch.summary(k);
      // The summary's own derivation of the item's levels, against the monitor's.
      EXPECT_EQ(oracle.mode, alone[k]->mode()) << "item " << k << " sample " << i;
      EXPECT_EQ(oracle.worst, alone[k]->worst_plane()) << "item " << k << " sample " << i;
      for (int p = 0; p < alone[k]->plane_count(); ++p)
        EXPECT_EQ(oracle.plane[p].mode, alone[k]->plane(static_cast<Plane>(p)).mode()) << "item " << k;
      EXPECT_TRUE(s.same_state(oracle)) << "item " << k << " sample " << i << " mode " << static_cast<int>(s.mode)
                                        << " vs " << static_cast<int>(oracle.mode) << " theta " << s.plane[0].theta
                                        << " vs " << oracle.plane[0].theta;
      EXPECT_EQ(s.revision != last[k].revision, !s.same_state(last[k])) << "item " << k << " sample " << i;
      run.revisions += s.revision != last[k].revision;
      last[k] = s;
      if (::testing::Test::HasFailure()) return run;
    }
    if (i % 97 == 0 || i + 1 == m) {  // read the items as the node's state publication does
      for (std::size_t k = 0; k < n; ++k) {
        batch.sync(k);
        EXPECT_EQ(batch.pending(k), 0);
        expect_same_state(*batched[k], *alone[k], k, i);
      }
      if (::testing::Test::HasFailure()) return run;
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    run.rocking_deferred += batch.rocking_deferred(k);
    if (const Rocking3DModel* solid = alone[k]->solid(); solid != nullptr && alone[k]->solid_active()) {
      run.solid_rocked += !std::isnan(solid->outcome().uplift_time);
      run.solid_overturned += solid->mode() == Mode3D::Overturned;
      run.solid_flew += solid->outcome_3d().flights > 0;
    }
    run.overturned += alone[k]->mode() == ItemMode::Overturned;
    run.rocked += !std::isnan(alone[k]->plane(Plane::X).adaptive()
                                  ? alone[k]->plane(Plane::X).adaptive()->outcome().uplift_time
                                  : alone[k]->plane(Plane::X).model().outcome().uplift_time);
  }
  return run;
}

// Items with a 3-D description (ItemSpec::solid): boxes on their four corners and irregular
// four-sided bases, the 3-D model taking over once the shaking is bidirectional (auto) or always.
BatchCatalogue solid_catalogue(std::size_t n, unsigned seed) {
  BatchCatalogue c = random_catalogue(n, seed);
  std::mt19937_64 rng(seed + 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    ItemSpec& s = c.specs[i];
    if (!(s.depth.depth > 0.0)) {
      s.depth.depth = std::min(0.15 + 0.85 * u(rng), 1.5 * s.body.cg_height);
      s.depth.eccentricity_y = 0.25 + 0.25 * u(rng);
    }
    s.solid = box_base_body(s.body, s.depth.depth, s.depth.eccentricity_y, std::nan(""));
    const double b = s.body.width, d = s.depth.depth;
    if (i % 3 == 2)  // not an axis-aligned rectangle: the 3-D model from the start
      s.solid->base = {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(b, 0.1 * d), Eigen::Vector2d(0.9 * b, d),
                       Eigen::Vector2d(0.05 * b, 0.95 * d)};
    c.options[i].solid = i % 3 == 1 ? SolidChoice::Solid : SolidChoice::Auto;
  }
  return c;
}

Component record(const std::string& file) { return read_record(std::string(ROCKING_RECORDS_DIR) + "/" + file).front(); }

TEST(MonitorBatch, EveryItemEqualsItselfSteppedAloneOnRealRecords) {
  const BatchCatalogue cat = random_catalogue(60, 7);
  const Component rinaldi = record("northridge_1994/Rinaldi228.AT2");
  std::size_t deferred = 0, samples = 0, overturned = 0, rocked = 0, plane_deferred = 0;
  for (double scale : {0.05, 0.3, 1.0}) {
    const BatchRun r = compare(cat, rinaldi, scale, 1.0, 64, 1);
    ASSERT_FALSE(HasFailure()) << "scale " << scale;
    deferred += r.deferred;
    plane_deferred += r.plane_deferred;
    samples += r.samples;
    overturned += r.overturned;
    rocked += r.rocked;
  }
  // The comparison covers every path: deferred samples, one plane deferred while the other rocks,
  // rocking, overturns.
  EXPECT_GT(deferred, samples / 4);
  EXPECT_GT(plane_deferred, samples / 50) << plane_deferred << " of " << samples;
  EXPECT_LT(deferred, samples);
  EXPECT_GT(overturned, 5u);
  EXPECT_GT(rocked, overturned);
}

// Rocking planes of the adaptive model go through the rocking lanes (BatchRocking's kernel with exact
// trigonometry) when their sample has no event and its end changes nothing but the rocking state;
// the samples accumulate there until the item is read (here every 13 samples, and in full every 97).
// Bit for bit as stepped alone: the model's clock, integrator state, counters and maxima.
TEST(MonitorBatch, RockingLanesCatchUpExactlyWhenRead) {
  BatchCatalogue cat = random_catalogue(80, 11);
  for (std::size_t i = 0; i < cat.options.size(); ++i)
    if (i % 2 == 0) cat.options[i].fidelity = Fidelity::Adaptive;  // more rocking lanes
  const Component rinaldi = record("northridge_1994/Rinaldi228.AT2");
  long rocking = 0;
  std::size_t samples = 0;
  for (double scale : {0.3, 1.0}) {
    const BatchRun r = compare(cat, rinaldi, scale, 1.0, 80, 3, 0.0, 13);
    ASSERT_FALSE(HasFailure()) << "scale " << scale;
    rocking += r.rocking_deferred;
    samples += r.samples;
  }
  // Plane-samples deferred while rocking: the path is taken, not only the rest and overturned ones.
  EXPECT_GT(rocking, static_cast<long>(samples / 100)) << rocking << " of " << samples;
}

// An item with a 3-D model is deferred as a whole: its planes quiet, and the 3-D model at rest with no
// edge lifting (or on its side), or, before it takes over, no running peak of the bidirectional test
// growing. Bit for bit as stepped alone, the 3-D model's clock and sample count included.
TEST(MonitorBatch, ItemsWithA3DModelEqualThemselvesSteppedAlone) {
  const BatchCatalogue cat = solid_catalogue(45, 23);
  const Component rec = record("kobe_1995/RSN1120_KOBE_TAK090.AT2");
  std::size_t deferred = 0, samples = 0, rocked = 0, solid_rocked = 0, solid_overturned = 0;
  for (double scale : {0.05, 0.4, 1.0}) {
    // y starts later: the 3-D model of an `auto` item takes over during the record, not at its start.
    const BatchRun r = compare(cat, rec, scale, 1.0, 64, 5, 0.3);
    ASSERT_FALSE(HasFailure()) << "scale " << scale;
    deferred += r.deferred;
    samples += r.samples;
    rocked += r.rocked;
    EXPECT_EQ(r.plane_deferred, 0u) << "an item with a 3-D model is deferred as a whole only";
    solid_rocked += r.solid_rocked;
    solid_overturned += r.solid_overturned;
  }
  EXPECT_GT(deferred, samples / 4);
  EXPECT_LT(deferred, samples);
  EXPECT_GT(rocked, 5u);
  // The 3-D models rocked, came back to rest (deferred again) and overturned (deferred on their side).
  EXPECT_GT(solid_rocked, 10u);
  EXPECT_GT(solid_overturned, 5u);
  EXPECT_GT(solid_rocked, solid_overturned);
}

// The floor dropping faster than gravity (a vertical of up to 2.2 g, the record's own shape): items with
// a friction coefficient fly in 3-D, each as stepped alone, the lift-offs that quiet samples could hide
// included (a quiet sample needs g + a_z > 0).
TEST(MonitorBatch, ItemsWithA3DModelFlyAsSteppedAlone) {
  const BatchCatalogue cat = solid_catalogue(30, 29);
  const Component rec = record("kobe_1995/RSN1120_KOBE_TAK090.AT2");
  const BatchRun r = compare(cat, rec, 0.4, 1.0, 64, 5, 0.3, 1, 5.5);
  ASSERT_FALSE(HasFailure());
  std::printf("[ measure ] %zu of %zu 3-D items flew; %zu deferred of %zu item-samples\n", r.solid_flew, cat.specs.size(),
              r.deferred, r.samples);
  EXPECT_GT(r.solid_flew, 3u);
  EXPECT_GT(r.deferred, 0u);
}

// The summaries change only for items that move: at rest or overturned an item's summary stays put
// (what makes a changed-items publication small), while rocking items change every sample.
TEST(MonitorBatch, SummariesChangeOnlyWhenItemsMove) {
  const BatchCatalogue cat = random_catalogue(40, 17);
  const Component rinaldi = record("northridge_1994/Rinaldi228.AT2");
  const BatchRun quiet = compare(cat, rinaldi, 0.02, 1.0, 64, 3);
  ASSERT_FALSE(HasFailure());
  const BatchRun strong = compare(cat, rinaldi, 1.0, 1.0, 64, 3);
  ASSERT_FALSE(HasFailure());
  EXPECT_LT(quiet.revisions, quiet.samples / 20);
  EXPECT_GT(strong.revisions, 5 * quiet.revisions + 10);
  EXPECT_LT(strong.revisions, strong.samples);
}

TEST(MonitorBatch, SubsetsAndRangesDoNotMatter) {
  const BatchCatalogue cat = random_catalogue(23, 11);
  const Component rec = record("kobe_1995/RSN1120_KOBE_TAK090.AT2");
  for (std::size_t range : {1u, 7u, 8u, 9u, 23u}) {
    const BatchRun r = compare(cat, rec, 0.4, 0.8, range, static_cast<unsigned>(range));
    ASSERT_FALSE(HasFailure()) << "range " << range;
    EXPECT_GT(r.deferred, 0u);
  }
}

// The step loop works in blocks of 64 items (quiet test, then the others with their objects
// prefetched ahead): ranges across and inside block boundaries give the same bits.
TEST(MonitorBatch, BlocksOfTheStepLoopDoNotMatter) {
  const BatchCatalogue cat = random_catalogue(150, 13);
  const Component rec = record("kobe_1995/RSN1120_KOBE_TAK090.AT2");
  for (std::size_t range : {150u, 65u, 63u}) {
    const BatchRun r = compare(cat, rec, 0.5, 0.9, range, static_cast<unsigned>(range));
    ASSERT_FALSE(HasFailure()) << "range " << range;
    EXPECT_GT(r.deferred, 0u);
    EXPECT_GT(r.plane_deferred, 0u);
    EXPECT_GT(r.rocked, 10u);
  }
}

TEST(MonitorBatch, InvalidSamplesAreRejectedAsByTheItem) {
  const BatchCatalogue cat = random_catalogue(3, 5);
  std::vector<std::unique_ptr<ItemMonitor>> items;
  std::vector<ItemMonitor*> ptrs;
  for (std::size_t k = 0; k < 3; ++k) {
    items.push_back(std::make_unique<ItemMonitor>(cat.specs[k], cat.options[k]));
    items.back()->start(0.0, 0.0, 0.0, 0.0, 0.01);
    ptrs.push_back(items.back().get());
  }
  MonitorBatch batch(ptrs);
  const double zero[3] = {0.0, 0.0, 0.0}, bad[3] = {0.0, std::nan(""), 0.0};
  EXPECT_EQ(batch.step(0, 3, zero, zero, zero, 0.01), 3u);  // quiet: all deferred
  EXPECT_THROW(batch.step(0, 3, bad, bad, bad, 0.01), std::invalid_argument);
  EXPECT_THROW(batch.step(0, 3, zero, zero, zero, -0.01), std::invalid_argument);
}

}  // namespace
}  // namespace rocking_monitor::core
