// State snapshots (issue 29): an item snapshotted at sample k, written to bytes, read back into a fresh
// monitor and continued must equal the unbroken run exactly (every later sample's events, and the
// whole state at the end, compared as the bytes of a second snapshot); damaged, truncated, foreign
// and old-format files are refused with a message naming what is wrong; a snapshot that cannot be
// written (disk full) is reported and the previous one stays.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "rocking_monitor/monitoring/item_ensemble.hpp"
#include "rocking_monitor/monitoring/monitor_batch.hpp"
#include "rocking_monitor/monitoring/state_snapshot.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "temp_root.hpp"

namespace rocking_monitor::core {
namespace {

const testing::TempRoot& kTemp = testing::TempRoot::registered("rocking_snapshot_test_");

std::string scratch(const std::string& name) {
  const std::filesystem::path p = kTemp.path() / name;
  std::filesystem::create_directories(p);
  return p.string();
}

// The Rinaldi records (Northridge 1994): 228 and 318 deg horizontal, UP vertical; dt 0.01 s, PGA at 2.56 s.
struct Motion {
  std::vector<double> x, y, z;
  double dt = 0.0;
  std::size_t size() const { return x.size(); }
};

Motion rinaldi(double scale) {
  const std::string dir = std::string(ROCKING_RECORDS_DIR) + "/northridge_1994/";
  const Component a = read_record(dir + "Rinaldi228.AT2").front();
  const Component b = read_record(dir + "Rinaldi318.AT2").front();
  const Component c = read_record(dir + "RinaldiUP.AT2").front();
  Motion m;
  m.dt = a.dt;
  const std::size_t n = std::min({a.accel.size(), b.accel.size(), c.accel.size()});
  for (std::size_t i = 0; i < n; ++i) {
    m.x.push_back(scale * a.accel[i]);
    m.y.push_back(scale * b.accel[i]);
    m.z.push_back(scale * c.accel[i]);
  }
  return m;
}

ItemSpec box(const std::string& id, double b, double d, double h, double mu) {
  ItemSpec s;
  s.id = id;
  s.sensor = "floor";
  s.frame = id;
  s.body.width = b;
  s.body.cg_height = h;
  s.body.mu_s = mu;
  if (d > 0.0) s.depth.depth = d;
  return s;
}

// One item's snapshot file, as the node writes it (no sensors).
std::vector<std::uint8_t> snapshot_of(const ItemMonitor& m, const ItemEnsemble* e = nullptr,
                                      std::uint32_t fingerprint = 7) {
  SnapshotEncoder enc;
  std::vector<std::uint8_t> bytes;
  enc.begin(bytes, fingerprint, 1.5e9, 0, 1);
  enc.item(m.spec().id, m, e);
  enc.finish();
  return bytes;
}

void expect_same_events(const ItemEvents& a, const ItemEvents& b, std::size_t i) {
  ASSERT_EQ(a.change_count, b.change_count) << "sample " << i;
  ASSERT_EQ(a.alarm_count, b.alarm_count) << "sample " << i;
  for (int j = 0; j < a.change_count; ++j) {
    EXPECT_EQ(a.changes[j].id, b.changes[j].id) << "sample " << i;
    EXPECT_EQ(a.changes[j].exceeded, b.changes[j].exceeded) << "sample " << i;
    EXPECT_EQ(a.changes[j].value, b.changes[j].value) << "sample " << i;
  }
  for (int j = 0; j < a.alarm_count; ++j) {
    EXPECT_EQ(a.alarms[j].level, b.alarms[j].level) << "sample " << i;
    EXPECT_EQ(a.alarms[j].time, b.alarms[j].time) << "sample " << i;
    EXPECT_EQ(a.alarms[j].plane, b.alarms[j].plane) << "sample " << i;
    EXPECT_EQ(a.alarms[j].cause, b.alarms[j].cause) << "sample " << i;
  }
}

// Rocking, or sliding on its base (the contact model: ItemMode says REST while both corners are down).
bool moving(const ItemMonitor& m) {
  return m.mode() != ItemMode::Rest || m.plane(Plane::X).contact_mode() != ContactMode::Rest;
}

struct Outcome {
  std::size_t resumed_moving = 0;  // snapshots taken while the item was not at rest
  std::size_t alarms_after = 0;    // alarms raised after a snapshot (compared)
};

// Unbroken run vs. a run snapshotted at each sample in `at`, restored into a fresh monitor and continued.
Outcome resume_equals_unbroken(const ItemSpec& spec, const ItemMonitor::Options& opt, const Motion& m,
                               const std::vector<std::size_t>& at) {
  Outcome out;
  for (std::size_t k : at) {
    ItemMonitor ref(spec, opt);
    ref.start(0.0, m.x[0], m.y[0], m.z[0], m.dt);
    for (std::size_t i = 1; i <= k; ++i) ref.step(m.x[i], m.y[i], m.z[i], m.dt);
    const std::vector<std::uint8_t> bytes = snapshot_of(ref);
    StateSnapshot snap;
    EXPECT_EQ(decode_snapshot(bytes.data(), bytes.size(), snap), "");
    EXPECT_EQ(snap.items.size(), 1u);
    if (snap.items.size() != 1) return out;
    if (moving(ref)) ++out.resumed_moving;
    ItemMonitor resumed(spec, opt);  // fresh: never started
    resumed.restore(snap.items[0].monitor);
    EXPECT_EQ(snapshot_of(resumed), bytes) << "restored state differs at sample " << k;
    for (std::size_t i = k + 1; i < m.size(); ++i) {
      const ItemEvents& a = ref.step(m.x[i], m.y[i], m.z[i], m.dt);
      const ItemEvents& b = resumed.step(m.x[i], m.y[i], m.z[i], m.dt);
      expect_same_events(a, b, i);
      out.alarms_after += static_cast<std::size_t>(a.alarm_count);
      if (::testing::Test::HasFailure()) return out;
    }
    EXPECT_EQ(snapshot_of(resumed), snapshot_of(ref)) << "state at the end differs (snapshot at " << k << ")";
  }
  return out;
}

// Samples at which to snapshot: early, two during the strong motion (after the first uplift), late.
std::vector<std::size_t> snapshot_samples(const ItemSpec& spec, const ItemMonitor::Options& opt, const Motion& m) {
  ItemMonitor probe(spec, opt);
  probe.start(0.0, m.x[0], m.y[0], m.z[0], m.dt);
  std::size_t uplift = 0;
  for (std::size_t i = 1; i < m.size() && uplift == 0; ++i) {
    probe.step(m.x[i], m.y[i], m.z[i], m.dt);
    if (moving(probe)) uplift = i;
  }
  EXPECT_GT(uplift, 0u) << spec.id << " never moves: the test would not test a moving item";
  return {50, uplift + 3, uplift + 41, m.size() - 200};
}

TEST(StateSnapshot, ResumedItemEqualsTheUnbrokenRunForEveryFidelity) {
  const Motion m = rinaldi(1.0);
  struct Case {
    ItemSpec spec;
    Fidelity fidelity;
    double linearized;
  };
  const std::vector<Case> cases = {
      {box("slender_vase", 0.20, 0.20, 0.40, 0.6), Fidelity::Adaptive, 0.0},   // overturns
      {box("cabinet", 0.80, 0.50, 0.90, 0.5), Fidelity::Adaptive, 0.0},        // rocks, survives
      {box("sliding_crate", 0.60, 0.0, 0.45, 0.15), Fidelity::Adaptive, 0.0},  // slides: contact model
      {box("rack", 0.30, 0.25, 0.80, 0.0), Fidelity::Rocking, 0.0},
      {box("contact_box", 0.25, 0.30, 0.50, 0.4), Fidelity::Contact, 0.0},
      {box("slender_rod", 0.10, 0.12, 0.60, 0.7), Fidelity::Adaptive, 0.35},   // linearized tier
  };
  std::size_t moving = 0, alarms = 0;
  for (const Case& c : cases) {
    ItemSpec spec = c.spec;
    if (c.fidelity == Fidelity::Rocking) spec.body.mu_s = std::numeric_limits<double>::infinity();
    ItemMonitor::Options opt;
    opt.fidelity = c.fidelity;
    opt.linearized_max_alpha = c.linearized;
    const Outcome o = resume_equals_unbroken(spec, opt, m, snapshot_samples(spec, opt, m));
    ASSERT_FALSE(HasFailure()) << spec.id;
    moving += o.resumed_moving;
    alarms += o.alarms_after;
  }
  EXPECT_GE(moving, 2 * cases.size());  // every item was snapshotted while it rocked
  EXPECT_GT(alarms, 5u);                // and alarms after the restore were compared
}

TEST(StateSnapshot, ResumedThreeDModelEqualsTheUnbrokenRun) {
  const Motion m = rinaldi(0.8);
  ItemSpec spec = box("granite_block", 0.30, 0.25, 0.45, 0.0);
  spec.body.mu_s = std::numeric_limits<double>::infinity();
  spec.solid = box_base_body(spec.body, spec.depth.depth, 0.5, std::nan(""));
  ItemMonitor::Options opt;
  opt.solid = SolidChoice::Solid;
  {
    ItemMonitor probe(spec, opt);
    ASSERT_TRUE(probe.solid() != nullptr);
  }
  const Outcome o = resume_equals_unbroken(spec, opt, m, snapshot_samples(spec, opt, m));
  ASSERT_FALSE(HasFailure());
  EXPECT_GE(o.resumed_moving, 2u);
}

// The crate as a 3-D item, and three samples (at least `gap` apart) at which its 3-D model is in `mode`.
ItemSpec crate_3d(ItemMonitor::Options& opt) {
  ItemSpec spec = box("crate_3d", 0.60, 0.50, 0.35, 0.2);
  spec.solid = box_base_body(spec.body, spec.depth.depth, 0.5, std::nan(""));
  opt.solid = SolidChoice::Solid;
  return spec;
}

std::vector<std::size_t> samples_in_mode(const ItemSpec& spec, const ItemMonitor::Options& opt, const Motion& m,
                                         Mode3D mode, std::size_t gap) {
  std::vector<std::size_t> at;
  ItemMonitor probe(spec, opt);
  probe.start(0.0, m.x[0], m.y[0], m.z[0], m.dt);
  for (std::size_t i = 1; i < m.size() && at.size() < 3; ++i) {
    probe.step(m.x[i], m.y[i], m.z[i], m.dt);
    if (probe.solid()->mode() == mode && (at.empty() || i > at.back() + gap)) at.push_back(i);
  }
  return at;
}

// The crate snapshotted at three samples in `mode` resumes exactly (`what` it did there, for the message).
void expect_crate_resumes_in_mode(const Motion& m, Mode3D mode, std::size_t gap, const char* what) {
  ItemMonitor::Options opt;
  const ItemSpec spec = crate_3d(opt);
  const std::vector<std::size_t> at = samples_in_mode(spec, opt, m, mode, gap);
  ASSERT_EQ(at.size(), 3u) << "the crate never " << what << ": the test would not test it";
  resume_equals_unbroken(spec, opt, m, at);
}

// A 3-D item that slides (issue 51, snapshot format 4): snapshots taken while it slides resume exactly.
TEST(StateSnapshot, ResumedSlidingThreeDItemEqualsTheUnbrokenRun) {
  expect_crate_resumes_in_mode(rinaldi(0.8), Mode3D::Slide, 50, "slid");
  ASSERT_FALSE(HasFailure());
}

// Rinaldi with its vertical doubled (1.7 g up): the crate leaves the floor. Snapshotted in flight
// (format 10), it resumes through the landing with the unbroken run's events and ends in its state.
TEST(StateSnapshot, ResumedFlyingThreeDItemEqualsTheUnbrokenRun) {
  Motion m = rinaldi(0.5);
  for (double& z : m.z) z *= 4.0;
  expect_crate_resumes_in_mode(m, Mode3D::Flight, 20, "flew");
  ASSERT_FALSE(HasFailure());
}

// A 3-D item on a plinth (issue 51): snapshotted while it slides towards the edge, it resumes and falls
// off at the unbroken run's instant with the same alarms and cause (expect_same_events); snapshotted
// after the fall, it resumes still fallen off its support.
TEST(StateSnapshot, ResumedItemOnAPlinthFallsOffAsTheUnbrokenRun) {
  const Motion m = rinaldi(0.8);
  ItemSpec spec = box("crate_on_plinth", 0.60, 0.50, 0.35, 0.2);
  spec.solid = box_base_body(spec.body, spec.depth.depth, 0.5, std::nan(""));
  // the base is (0, 0)-(B, D), the centre of mass above (0.3, 0.25): a plinth edge 0.1 m beyond it
  // towards +x (the contact ends there: tan = 0.1 / 0.35 > mu_s, so it slides before it rocks)
  spec.solid->mu_s = 0.2;
  spec.solid->support = {{-0.2, -0.2}, {0.4, -0.2}, {0.4, 0.7}, {-0.2, 0.7}};
  ItemMonitor::Options opt;
  opt.solid = SolidChoice::Solid;
  std::vector<std::size_t> at;
  std::size_t fell = 0;
  {
    ItemMonitor probe(spec, opt);
    probe.start(0.0, m.x[0], m.y[0], m.z[0], m.dt);
    for (std::size_t i = 1; i < m.size() && fell == 0; ++i) {
      probe.step(m.x[i], m.y[i], m.z[i], m.dt);
      if (probe.solid()->outcome_3d().fell_off_support) fell = i;
      else if (probe.solid()->mode() == Mode3D::Slide && (at.empty() || i > at.back() + 20)) at.push_back(i);
    }
  }
  ASSERT_GT(fell, 0u) << "the crate never fell off its plinth: the test would not test a fall";
  ASSERT_FALSE(at.empty()) << "never snapshotted while it slid";
  at.resize(std::min<std::size_t>(at.size(), 2));
  at.push_back(fell + 10);
  const Outcome o = resume_equals_unbroken(spec, opt, m, at);
  ASSERT_FALSE(HasFailure());
  EXPECT_GE(o.alarms_after, 2u * (at.size() - 1));  // COMMITTED and OVERTURNED after each earlier snapshot
  ItemMonitor ref(spec, opt);
  ref.start(0.0, m.x[0], m.y[0], m.z[0], m.dt);
  for (std::size_t i = 1; i <= fell + 10; ++i) ref.step(m.x[i], m.y[i], m.z[i], m.dt);
  const std::vector<std::uint8_t> bytes = snapshot_of(ref);
  StateSnapshot snap;
  ASSERT_EQ(decode_snapshot(bytes.data(), bytes.size(), snap), "");
  ItemMonitor resumed(spec, opt);
  resumed.restore(snap.items[0].monitor);
  EXPECT_TRUE(resumed.solid()->outcome_3d().fell_off_support);
  EXPECT_EQ(resumed.solid()->outcome_3d().fell_off_time, ref.solid()->outcome_3d().fell_off_time);
  EXPECT_TRUE(resumed.alarmed(ItemMode::Overturned));
}

// A body on its hull (issue 40 part 3): an octagonal prism lying on a side rolls onto other sides
// under Rinaldi; snapshots taken while it rocks on a side other than its base resume exactly.
TEST(StateSnapshot, ResumedBodyOnItsHullEqualsTheUnbrokenRun) {
  const Motion m = rinaldi(1.0);
  const double a = 0.15, length = 0.6, half = a * std::sin(kPi / 8.0), ap = a * std::cos(kPi / 8.0);
  ItemSpec spec = box("octagonal_log", 2.0 * half, length, ap, 0.0);
  spec.body.mu_s = std::numeric_limits<double>::infinity();
  BaseBodyParameters b;
  b.centre_of_mass = {0.0, length / 2.0, ap};
  const double ix = a * a / 4.0 * (1.0 + 2.0 * std::cos(kPi / 4.0) * std::cos(kPi / 4.0) / 3.0) ;
  b.central_inertia = Eigen::Vector3d(ix + length * length / 12.0, 2.0 * ix, ix + length * length / 12.0).asDiagonal();
  b.base = {{-half, 0.0}, {half, 0.0}, {half, length}, {-half, length}};
  for (double y : {0.0, length})
    for (int k = 0; k < 8; ++k) {
      const double phi = -kPi / 2.0 - kPi / 8.0 + k * kPi / 4.0;  // corners of the octagon in x-z
      b.hull.emplace_back(a * std::cos(phi), y, ap + a * std::sin(phi));
    }
  b.overturn_angle = kPi;
  spec.solid = b;
  ItemMonitor::Options opt;
  opt.solid = SolidChoice::Solid;
  std::vector<std::size_t> at;
  {
    ItemMonitor probe(spec, opt);
    ASSERT_TRUE(probe.solid() != nullptr);
    probe.start(0.0, m.x[0], m.y[0], m.z[0], m.dt);
    for (std::size_t i = 1; i < m.size() && at.size() < 2; ++i) {
      probe.step(m.x[i], m.y[i], m.z[i], m.dt);
      if (probe.solid()->face() != 0 && probe.solid()->mode() != Mode3D::Rest &&
          (at.empty() || i > at.back() + 20))
        at.push_back(i);
    }
    ASSERT_EQ(at.size(), 2u) << "the prism never rocks on another side: the test would not test the hull";
    for (std::size_t i = at.back() + 1; i < m.size(); ++i) probe.step(m.x[i], m.y[i], m.z[i], m.dt);
    EXPECT_GE(probe.solid()->outcome_3d().hull_landings, 1);
  }
  const Outcome o = resume_equals_unbroken(spec, opt, m, at);
  ASSERT_FALSE(HasFailure());
  EXPECT_EQ(o.resumed_moving, 2u);
}

TEST(StateSnapshot, ResumedEnsembleEqualsTheUnbrokenRun) {
  const Motion m = rinaldi(1.0);
  std::vector<ItemSpec> members;
  for (int i = 0; i < 8; ++i) members.push_back(box("vase", 0.18 + 0.01 * i, 0.2, 0.40, 0.6));
  ItemMonitor::Options opt;
  ItemEnsemble ref(members, opt), resumed(members, opt);
  ItemMonitor nominal(members[0], opt);
  ref.start(0.0, m.x[0], m.y[0], m.z[0], m.dt);
  nominal.start(0.0, m.x[0], m.y[0], m.z[0], m.dt);
  const std::size_t k = 230;  // within the strong motion (Rinaldi's PGA at sample 256)
  for (std::size_t i = 1; i <= k; ++i) ref.step(m.x[i], m.y[i], m.z[i], m.dt);
  const std::vector<std::uint8_t> bytes = snapshot_of(nominal, &ref);
  StateSnapshot snap;
  ASSERT_EQ(decode_snapshot(bytes.data(), bytes.size(), snap), "");
  ASSERT_TRUE(snap.items[0].has_ensemble);
  resumed.restore(snap.items[0].ensemble);
  int moving = 0;
  for (int i = 0; i < ref.size(); ++i) moving += ref.member(i).mode() != ItemMode::Rest;
  EXPECT_GT(moving, 0);
  int crossings = 0;
  for (std::size_t i = k + 1; i < m.size(); ++i) {
    const EnsembleEvents& a = ref.step(m.x[i], m.y[i], m.z[i], m.dt);
    const EnsembleEvents& b = resumed.step(m.x[i], m.y[i], m.z[i], m.dt);
    ASSERT_EQ(a.count, b.count) << "sample " << i;
    for (int j = 0; j < a.count; ++j) {
      EXPECT_EQ(a.crossings[j].time, b.crossings[j].time);
      EXPECT_EQ(a.crossings[j].probability, b.crossings[j].probability);
    }
    crossings += a.count;
  }
  EXPECT_GT(crossings, 0);
  for (Level l : {Level::BeyondTipping, Level::Committed, Level::Overturned}) EXPECT_EQ(ref.reached(l), resumed.reached(l));
  EXPECT_EQ(snapshot_of(nominal, &resumed), snapshot_of(nominal, &ref));
}

// The node steps its items as a MonitorBatch (quiet samples deferred): it syncs them before the
// snapshot, and a fresh batch over the restored items continues exactly.
TEST(StateSnapshot, BatchSteppedItemsResumeExactly) {
  const Motion m = rinaldi(1.0);
  std::vector<ItemSpec> specs;
  for (int i = 0; i < 12; ++i) specs.push_back(box("item" + std::to_string(i), 0.15 + 0.05 * i, 0.2 + 0.03 * i, 0.5, 0.5));
  ItemMonitor::Options opt;
  auto make = [&](std::vector<std::unique_ptr<ItemMonitor>>& v) {
    std::vector<ItemMonitor*> p;
    for (const ItemSpec& s : specs) {
      v.push_back(std::make_unique<ItemMonitor>(s, opt));
      p.push_back(v.back().get());
    }
    return p;
  };
  std::vector<std::unique_ptr<ItemMonitor>> ref_items, resumed_items;
  std::vector<ItemMonitor*> ref_ptrs = make(ref_items), resumed_ptrs = make(resumed_items);
  for (ItemMonitor* im : ref_ptrs) im->start(0.0, m.x[0], m.y[0], m.z[0], m.dt);
  MonitorBatch ref(ref_ptrs);
  const std::size_t n = specs.size(), k = 240;  // within the strong motion
  std::vector<double> x(n), y(n), z(n);
  auto fill = [&](std::size_t i) {
    std::fill(x.begin(), x.end(), m.x[i]);
    std::fill(y.begin(), y.end(), m.y[i]);
    std::fill(z.begin(), z.end(), m.z[i]);
  };
  for (std::size_t i = 1; i <= k; ++i) {
    fill(i);
    ref.step(0, n, x.data(), y.data(), z.data(), m.dt);
  }
  ref.sync_all();
  SnapshotEncoder enc;
  std::vector<std::uint8_t> bytes;
  enc.begin(bytes, 1, 0.0, 0, n);
  for (ItemMonitor* im : ref_ptrs) enc.item(im->spec().id, *im, nullptr);
  enc.finish();
  StateSnapshot snap;
  ASSERT_EQ(decode_snapshot(bytes.data(), bytes.size(), snap), "");
  for (std::size_t j = 0; j < n; ++j) resumed_ptrs[j]->restore(snap.items[j].monitor);
  MonitorBatch resumed(resumed_ptrs);
  std::size_t compared = 0;
  for (std::size_t i = k + 1; i < m.size(); ++i) {
    fill(i);
    ref.step(0, n, x.data(), y.data(), z.data(), m.dt);
    resumed.step(0, n, x.data(), y.data(), z.data(), m.dt);
    for (std::size_t j = 0; j < n; ++j) {
      expect_same_events(ref.events(j), resumed.events(j), i);
      compared += static_cast<std::size_t>(ref.events(j).alarm_count);
    }
    ASSERT_FALSE(HasFailure());
  }
  ref.sync_all();
  resumed.sync_all();
  for (std::size_t j = 0; j < n; ++j) EXPECT_EQ(snapshot_of(*resumed_ptrs[j]), snapshot_of(*ref_ptrs[j])) << j;
  EXPECT_GT(compared, 0u);
}

// Levels the journal marked alarmed (mark_alarmed, before the restore) stay alarmed after it.
TEST(StateSnapshot, RestoreKeepsLevelsMarkedFromTheJournal) {
  const Motion m = rinaldi(1.0);
  ItemMonitor ref(box("vase", 0.2, 0.2, 0.4, 0.6), ItemMonitor::Options{});
  ref.start(0.0, m.x[0], m.y[0], m.z[0], m.dt);
  for (std::size_t i = 1; i < 200; ++i) ref.step(m.x[i], m.y[i], m.z[i], m.dt);
  ASSERT_FALSE(ref.alarmed(ItemMode::Overturned));
  const std::vector<std::uint8_t> bytes = snapshot_of(ref);
  StateSnapshot snap;
  ASSERT_EQ(decode_snapshot(bytes.data(), bytes.size(), snap), "");
  ItemMonitor resumed(ref.spec(), ItemMonitor::Options{});
  resumed.mark_alarmed(ItemMode::Overturned);
  resumed.restore(snap.items[0].monitor);
  EXPECT_TRUE(resumed.alarmed(ItemMode::Overturned));
  EXPECT_FALSE(resumed.alarmed(ItemMode::Committed));
}

class SnapshotFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const Motion m = rinaldi(1.0);
    ItemMonitor im(box("vase", 0.2, 0.2, 0.4, 0.6), ItemMonitor::Options{});
    im.start(0.0, m.x[0], m.y[0], m.z[0], m.dt);
    for (std::size_t i = 1; i < 300; ++i) im.step(m.x[i], m.y[i], m.z[i], m.dt);
    SnapshotEncoder enc;
    enc.begin(bytes, 42, 1.5e9, 1, 1);
    SnapshotSensor s;
    s.name = "floor";
    s.last_stamp_ns = 758809861000000000;
    s.epoch_ns = 758809855000000000;
    s.last_t = 6.5;
    s.dt_nominal = 0.005;
    s.baseline_initialized = true;
    s.baseline[2] = 9.81;
    s.samples = 1299;
    enc.sensor(s);
    enc.item("vase", im, nullptr);
    enc.finish();
  }
  std::vector<std::uint8_t> bytes;
};

TEST_F(SnapshotFiles, AWholeFileReadsBack) {
  StateSnapshot snap;
  ASSERT_EQ(decode_snapshot(bytes.data(), bytes.size(), snap), "");
  EXPECT_EQ(snap.fingerprint, 42u);
  EXPECT_EQ(snap.written, 1.5e9);
  ASSERT_EQ(snap.sensors.size(), 1u);
  EXPECT_EQ(snap.sensors[0].name, "floor");
  EXPECT_EQ(snap.sensors[0].last_stamp_ns, 758809861000000000);
  EXPECT_EQ(snap.sensors[0].epoch_ns, 758809855000000000);
  EXPECT_EQ(snap.sensors[0].last_t, 6.5);
  EXPECT_EQ(snap.sensors[0].baseline[2], 9.81);
  EXPECT_EQ(snap.sensors[0].samples, 1299u);
  ASSERT_EQ(snap.items.size(), 1u);
  EXPECT_EQ(snap.items[0].id, "vase");
  EXPECT_TRUE(snap.items[0].monitor.started);
  EXPECT_TRUE(snap.items[0].monitor.two_planes);
  EXPECT_EQ(foreign_snapshot(snap, 42, {"floor"}, {"vase"}), "");
}

TEST_F(SnapshotFiles, EveryFlippedByteIsRefused) {
  // Each byte of the header and a spread of payload bytes, one bit each: never accepted.
  std::vector<std::size_t> positions;
  for (std::size_t i = 0; i < kSnapshotHeaderBytes; ++i) positions.push_back(i);
  for (std::size_t i = kSnapshotHeaderBytes; i < bytes.size(); i += 97) positions.push_back(i);
  positions.push_back(bytes.size() - 1);
  for (std::size_t pos : positions) {
    for (int bit : {0, 7}) {
      std::vector<std::uint8_t> bad = bytes;
      bad[pos] ^= static_cast<std::uint8_t>(1u << bit);
      StateSnapshot snap;
      const std::string e = decode_snapshot(bad.data(), bad.size(), snap);
      EXPECT_NE(e, "") << "byte " << pos << " bit " << bit << " flipped and accepted";
      EXPECT_TRUE(snap.items.empty());
    }
  }
  std::vector<std::uint8_t> bad = bytes;
  bad[bytes.size() / 2] ^= 0x10;
  StateSnapshot snap;
  EXPECT_EQ(decode_snapshot(bad.data(), bad.size(), snap), "payload checksum mismatch: the file is damaged");
  bad = bytes;
  bad[9] ^= 0x01;  // in the version field
  EXPECT_EQ(decode_snapshot(bad.data(), bad.size(), snap), "header checksum mismatch: the header is damaged");
}

TEST_F(SnapshotFiles, TruncatedAndForeignFilesAreRefused) {
  StateSnapshot snap;
  EXPECT_EQ(decode_snapshot(bytes.data(), 20, snap), "truncated: 20 bytes, shorter than the 32-byte header");
  const std::string cut = decode_snapshot(bytes.data(), bytes.size() - 100, snap);
  EXPECT_NE(cut.find("truncated or extended: the header says " + std::to_string(bytes.size() - 32) +
                     " payload bytes, the file has " + std::to_string(bytes.size() - 132)),
            std::string::npos)
      << cut;
  std::vector<std::uint8_t> text(bytes.size(), 'x');
  EXPECT_EQ(decode_snapshot(text.data(), text.size(), snap), "not a state snapshot (no RMSNAPSH magic)");

  ASSERT_EQ(decode_snapshot(bytes.data(), bytes.size(), snap), "");
  EXPECT_EQ(foreign_snapshot(snap, 42, {"floor"}, {"cabinet"}), "item 1 is 'vase', this catalogue's is 'cabinet'");
  EXPECT_EQ(foreign_snapshot(snap, 42, {"floor"}, {"vase", "cabinet"}),
            "written for 1 items, this catalogue has 2");
  EXPECT_EQ(foreign_snapshot(snap, 42, {"wall"}, {"vase"}), "sensor 1 is 'floor', this catalogue's is 'wall'");
  EXPECT_NE(foreign_snapshot(snap, 43, {"floor"}, {"vase"}).find("written with another configuration"),
            std::string::npos);
}

TEST_F(SnapshotFiles, AnotherFormatVersionIsRefused) {
  std::vector<std::uint8_t> v2 = bytes;
  const std::uint32_t version = kSnapshotVersion + 1;
  std::memcpy(v2.data() + 8, &version, sizeof version);
  seal_snapshot(v2);  // a well-formed file of a later version
  StateSnapshot snap;
  EXPECT_EQ(decode_snapshot(v2.data(), v2.size(), snap),
            "format version " + std::to_string(version) + ", this monitor reads version " +
                std::to_string(kSnapshotVersion));
}

// A well-sealed file whose content is inconsistent (a bad enum, as a buggy writer would make) names
// the item and field.
TEST_F(SnapshotFiles, AnImpossibleValueNamesItsField) {
  // The first plane's adaptive rocking mode follows: fingerprint (8) written (8) counts (4 + 4), the
  // sensor ("floor": 4 + 5, 2 x 8, 3 x 8, 1, 3 x 8, 8), the id (4 + 4), started, two_planes, plane
  // started, dt_nominal, has_adaptive.
  const std::size_t at =
      kSnapshotHeaderBytes + 8 + 8 + 4 + 4 + (4 + 5 + 16 + 24 + 1 + 24 + 8) + (4 + 4) + 1 + 1 + 1 + 8 + 1;
  std::vector<std::uint8_t> bad = bytes;
  ASSERT_LT(bad[at], 3) << "layout changed: update the offset";
  bad[at] = 9;
  seal_snapshot(bad);
  StateSnapshot snap;
  EXPECT_EQ(decode_snapshot(bad.data(), bad.size(), snap),
            "item 'vase' (1 of 1): plane x: adaptive: rocking: mode: 9 is not one of the 3 values");
}

// Writes past `bytes` fail with EFBIG while it lives (RLIMIT_FSIZE, process-wide): a full disk stand-in.
struct FileSizeLimit {
  rlimit old{};
  explicit FileSizeLimit(rlim_t bytes) {
    std::signal(SIGXFSZ, SIG_IGN);  // the write fails with EFBIG instead of killing the process
    getrlimit(RLIMIT_FSIZE, &old);
    rlimit small = old;
    small.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &small);
  }
  ~FileSizeLimit() { setrlimit(RLIMIT_FSIZE, &old); }
};

bool snapshot_temp_left(const std::string& path) {
  const std::filesystem::path p(path);
  for (const auto& e : std::filesystem::directory_iterator(p.parent_path()))
    if (e.path().filename().string().rfind(p.filename().string() + ".tmp", 0) == 0) return true;
  return false;
}

TEST_F(SnapshotFiles, WrittenDurablyAndReadBackFromAFile) {
  const std::string dir = scratch("durable");
  const std::string path = dir + "/state.snapshot";
  ASSERT_EQ(write_file_durably(path, bytes.data(), bytes.size()), "");
  StateSnapshot snap;
  bool exists = false;
  EXPECT_EQ(read_snapshot(path, snap, &exists), "");
  EXPECT_TRUE(exists);
  EXPECT_EQ(snap.items.size(), 1u);
  EXPECT_FALSE(snapshot_temp_left(path));  // renamed into place
  EXPECT_EQ(read_snapshot(dir + "/none", snap, &exists), dir + "/none: no such file");
  EXPECT_FALSE(exists);
  {
    std::ofstream cut(path, std::ios::binary | std::ios::trunc);
    cut.write(reinterpret_cast<const char*>(bytes.data()), 100);
  }
  const std::string e = read_snapshot(path, snap, &exists);
  EXPECT_EQ(e.rfind(path + ": truncated or extended", 0), 0u) << e;
}

// A write that fails (the file size limit, as a full disk would: every write past 16 bytes fails
// with EFBIG): the error names the temporary file and the cause, the previous snapshot is untouched,
// no temporary file is left, and the writer thread goes on (the next write, once it can, succeeds).
// (Until issue 54 this planted a link to /dev/full at "<path>.tmp": temporary files no longer follow
// links, so a limit stands in.)
TEST_F(SnapshotFiles, AFailedWriteFailsLoudlyAndKeepsThePreviousSnapshot) {
  const std::string path = scratch("full") + "/state.snapshot";
  ASSERT_EQ(write_file_durably(path, bytes.data(), bytes.size()), "");
  const std::string prefix = "cannot write " + path + ".tmp.", cause = ": File too large";
  std::string e;
  {
    FileSizeLimit limit(16);
    e = write_file_durably(path, bytes.data(), bytes.size());
  }
  EXPECT_EQ(e.rfind(prefix, 0), 0u) << e;
  EXPECT_EQ(e.size() - e.rfind(cause), cause.size()) << e;
  EXPECT_FALSE(snapshot_temp_left(path));
  StateSnapshot snap;
  EXPECT_EQ(read_snapshot(path, snap), "");  // the previous one

  SnapshotFileWriter writer(path);
  std::vector<std::uint8_t>& buf = writer.buffer();
  buf = bytes;
  SnapshotFileWriter::Status st;
  {
    FileSizeLimit limit(16);
    writer.submit();
    writer.flush();
    st = writer.status();
  }
  EXPECT_EQ(st.failed, 1u);
  EXPECT_EQ(st.written, 0u);
  EXPECT_EQ(st.last_error.rfind(prefix, 0), 0u) << st.last_error;
  writer.buffer() = bytes;  // room again
  writer.submit();
  writer.flush();
  st = writer.status();
  EXPECT_EQ(st.written, 1u);
  EXPECT_EQ(st.last_error, "");
  EXPECT_EQ(st.last_bytes, bytes.size());
}

}  // namespace
}  // namespace rocking_monitor::core
