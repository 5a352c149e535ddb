// Two-plane items in the study (issue 11, part 2): catalogue items with a depth run on both
// horizontals of a station rotated to azimuths. Oracles: the single-plane cases of the same
// components (run_study), the rotation's exact relations at multiples of 90 deg, a zero horizontal,
// combine() and an independent recount of the plane verdicts, and the loader's messages.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/study/study.hpp"
#include "rocking_monitor/study/study_io.hpp"

#include "temp_root.hpp"

namespace rocking_monitor::core::study {
namespace {

namespace fs = std::filesystem;

// Scratch files of this binary, removed when it ends.
const rocking_monitor::core::testing::TempRoot& kTwoPlanesTemp = rocking_monitor::core::testing::TempRoot::registered("rocking_two_planes_test_");
const fs::path& two_planes_root() { return kTwoPlanesTemp.path(); }

fs::path write_items_yaml(const std::string& tag, const std::string& text) {
  const fs::path d = two_planes_root() / tag;
  fs::create_directories(d);
  const fs::path p = d / "items.yaml";
  std::ofstream(p) << text;
  return p;
}

bool same_or_both_nan(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

// A one-sine pulse (Zhang & Makris) of `amplitude` m/s^2 at `hz`, starting after `delay` s, 6 s long.
Component pulse(const std::string& label, double amplitude, double hz, double delay = 0.0, bool vertical = false,
                std::size_t n = 601, double dt = 0.01) {
  Component c;
  c.file = "synthetic/" + label + ".csv";
  c.label = label;
  c.vertical = vertical;
  c.dt = dt;
  c.accel.resize(n, 0.0);
  const double w = 2.0 * kPi * hz;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt - delay;
    if (t >= 0.0 && t <= 1.0 / hz) c.accel[i] = amplitude * std::sin(w * t);
  }
  return c;
}

// One station's horizontals (and vertical) as the records loader makes them.
std::vector<StudyRecord> station(const std::vector<Component>& horizontals, const Component* vertical,
                                 const std::string& name = "sta") {
  std::vector<StudyRecord> out;
  for (const Component& h : horizontals) {
    out.push_back(make_study_record(h, vertical, "synthetic", name, h.label, h.file));
    if (vertical) out.back().vertical_component = vertical->label;
  }
  return out;
}

StudyItem make_item(const std::string& name, double width, double depth, double h, double nu, double nu_y,
                    double rg_y = std::numeric_limits<double>::quiet_NaN()) {
  StudyItem it;
  it.name = name;
  it.x.width = width;
  it.x.cg_height = h;
  it.x.nu1 = nu;
  it.x.radius_of_gyration = Body::homogeneous_radius_of_gyration(width, h);
  it.depth.depth = depth;
  it.depth.eccentricity_y = nu_y;
  it.depth.radius_of_gyration_y = rg_y;
  it.y = y_plane_body(it.x, it.depth);
  return it;
}

// Two plane runs are the same simulation: every outcome field equal (bitwise for the numbers).
// `mirror`: the second ran the reversed input on a symmetric body, so its pivots are swapped.
void expect_same(const CaseResult& a, const CaseResult& b, const std::string& what, bool mirror = false) {
  const RockingOutcome &p = a.outcome, &q = b.outcome;
  EXPECT_EQ(p.overturned, q.overturned) << what;
  EXPECT_EQ(p.committed, q.committed) << what;
  EXPECT_EQ(p.beyond_tipping, q.beyond_tipping) << what;
  EXPECT_EQ(p.impacts, q.impacts) << what;
  EXPECT_EQ(p.integrator_steps, q.integrator_steps) << what;
  EXPECT_EQ(p.samples, q.samples) << what;
  EXPECT_EQ(p.max_rotation_side, mirror ? -q.max_rotation_side : q.max_rotation_side) << what;
  EXPECT_TRUE(same_or_both_nan(p.max_rotation_ratio, q.max_rotation_ratio)) << what << ": " << p.max_rotation_ratio
                                                                       << " vs " << q.max_rotation_ratio;
  EXPECT_TRUE(same_or_both_nan(p.uplift_time, q.uplift_time)) << what;
  EXPECT_TRUE(same_or_both_nan(p.beyond_tipping_time, q.beyond_tipping_time)) << what;
  EXPECT_TRUE(same_or_both_nan(p.committed_time, q.committed_time)) << what;
  EXPECT_TRUE(same_or_both_nan(p.overturn_time, q.overturn_time)) << what;
  EXPECT_EQ(a.vertical, b.vertical) << what;
}

const ItemCaseResult& find(const std::vector<ItemCaseResult>& r, std::size_t item, double azimuth, int polarity,
                           std::size_t pair = 0) {
  for (const auto& c : r)
    if (c.item == item && c.pair == pair && c.azimuth_deg == azimuth && c.polarity == polarity) return c;
  throw std::runtime_error("no such item case");
}

std::string describe(const ItemCaseResult& c) {
  std::ostringstream os;
  os << "item " << c.item << " pair " << c.pair << " azimuth " << c.azimuth_deg << " polarity " << c.polarity;
  return os.str();
}

ItemStudyOptions options(std::vector<double> azimuths, int threads = 2) {
  ItemStudyOptions o;
  o.azimuths = std::move(azimuths);
  o.threads = threads;
  return o;
}

// ------------------------------------------------------------------ loader

TEST(TwoPlaneItemsYaml, ReadsAMonitorCatalogueIgnoringTheNodesKeys) {
  const fs::path p = write_items_yaml("catalogue",
                                "sensors:\n"
                                "  - {name: ground, topic: /ground/imu, type: imu}\n"
                                "items:\n"
                                "  - id: cabinet\n"
                                "    description: \"Cabinet, ward 2\"\n"
                                "    sensor: ground\n"
                                "    frame: cabinet_link\n"
                                "    width: 0.5\n"
                                "    depth: 0.4\n"
                                "    cg_height: 0.9\n"
                                "    eccentricity: 0.4\n"
                                "    eccentricity_y: 0.45\n"
                                "    mu_s: 0.6\n"
                                "    mu_k: 0.5\n"
                                "    pose: {parent_frame: accelerometer, x: 2.0, yaw: 0.3}\n"
                                "  - {id: cart, sensor: ground, width: 0.55, cg_height: 0.75, restitution: 0.9}\n"
                                "  - {id: vase, shape: cylinder, width: 0.15, depth: 0.15, cg_height: 0.35,\n"
                                "     overturn_angle: 1.2, radius_of_gyration_y: 0.2}\n");
  const BodyFile f = load_body_file(p.string());
  ASSERT_EQ(f.bodies.size(), 1u);  // the cart: no depth, a single-plane body
  ASSERT_EQ(f.items.size(), 2u);
  EXPECT_EQ(f.bodies[0].name, "cart");
  EXPECT_DOUBLE_EQ(f.bodies[0].parameters.restitution, 0.9);
  EXPECT_DOUBLE_EQ(f.bodies[0].parameters.radius_of_gyration, Body::homogeneous_radius_of_gyration(0.55, 0.75));
  const StudyItem& cab = f.items[0];
  EXPECT_EQ(cab.name, "cabinet");
  EXPECT_DOUBLE_EQ(cab.x.width, 0.5);
  EXPECT_DOUBLE_EQ(cab.x.nu1, 0.4);
  EXPECT_DOUBLE_EQ(cab.x.mu_s, 0.6);
  EXPECT_DOUBLE_EQ(cab.x.mu_k, 0.5);
  // The y plane is the core's y_plane_body() of the x plane and the depth.
  const BodyParameters y = y_plane_body(cab.x, cab.depth);
  EXPECT_DOUBLE_EQ(cab.y.width, 0.4);
  EXPECT_DOUBLE_EQ(cab.y.nu1, 0.45);
  EXPECT_DOUBLE_EQ(cab.y.radius_of_gyration, y.radius_of_gyration);
  // Plan-uniform box: the y plane's radius of gyration is that of a homogeneous D x 2h rectangle.
  EXPECT_NEAR(cab.y.radius_of_gyration, Body::homogeneous_radius_of_gyration(0.4, 0.9), 1e-15);
  const StudyItem& vase = f.items[1];
  EXPECT_DOUBLE_EQ(vase.x.radius_of_gyration, std::sqrt(0.15 * 0.15 / 16.0 + 0.35 * 0.35 / 3.0));  // cylinder
  EXPECT_DOUBLE_EQ(vase.y.radius_of_gyration, 0.2);
  EXPECT_DOUBLE_EQ(vase.y.overturn_angle, 1.2);
  // The older reader refuses a file with items rather than dropping them.
  EXPECT_THROW(load_bodies_yaml(p.string()), StudyError);
  // A study body with a depth is an item too.
  const BodyFile g = load_body_file(
      write_items_yaml("bodies_depth", "bodies:\n  - {name: shelf, width: 0.3, depth: 0.6, cg_height: 0.9, nu1: [0.5, 0.3]}\n")
          .string());
  ASSERT_EQ(g.items.size(), 2u);
  EXPECT_EQ(g.items[1].name, "shelf_nu0.3");
  EXPECT_DOUBLE_EQ(g.items[1].y.width, 0.6);
  EXPECT_DOUBLE_EQ(g.items[1].y.nu1, 0.5);
}

TEST(TwoPlaneItemsYaml, ErrorsNameTheFileItemAndField) {
  struct Bad {
    std::string text;
    std::vector<std::string> expect;
  };
  const std::string ok = "items:\n  - {id: ok, width: 0.5, depth: 0.5, cg_height: 1}\n";
  const std::vector<Bad> cases{
      {ok + "  - {id: vase, width: 0.5, depth: -1, cg_height: 1}\n", {"items[1] 'vase'", "depth", "-1"}},
      {ok + "  - {id: vase, width: 0.5, depth: 0.3, eccentricity_y: 1.0, cg_height: 1}\n",
       {"items[1] 'vase'", "eccentricity_y", "= 1 "}},
      {ok + "  - {id: vase, width: 0.5, depth: .nan, cg_height: 1}\n", {"items[1] 'vase'", "depth", "must be finite"}},
      {ok + "  - {id: vase, width: 0.5, eccentricity_y: 0.3, cg_height: 1}\n",
       {"items[1] 'vase'", "eccentricity_y", "needs depth"}},
      {ok + "  - {id: vase, width: 0.5, dpeth: 0.3, cg_height: 1}\n", {"items[1] 'vase'", "dpeth", "unknown key"}},
      {ok + "  - {id: vase, width: 0.5, cg_height: 1, eccentricity: 1.5}\n", {"items[1] 'vase'", "eccentricity", "1.5"}},
      {ok + "  - {id: vase, width: 0.5, cg_height: 1, shape: cone}\n", {"items[1] 'vase'", "shape", "cone"}},
      {ok + "  - {width: 0.5, cg_height: 1}\n", {"items[1]", "id", "missing"}},
      {ok + "  - {id: ok, width: 0.4, cg_height: 1}\n", {"items[1] 'ok'", "duplicate id"}},
      {"bodies:\n  - {name: a, width: 0.5, cg_height: 1, depth: 0}\n", {"bodies[0] (a)", "depth", "= 0"}},
      {"sensors: []\nitems: []\n", {"non-empty list"}},
      {"sensors: []\nbodies:\n  - {width: 0.5, cg_height: 1}\n", {"unknown top-level key 'sensors'"}},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const fs::path p = write_items_yaml("bad" + std::to_string(i), cases[i].text);
    try {
      load_body_file(p.string());
      ADD_FAILURE() << "no error for: " << cases[i].text;
    } catch (const StudyError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(p.string() + ": "), std::string::npos) << msg;
      for (const auto& s : cases[i].expect) EXPECT_NE(msg.find(s), std::string::npos) << msg << " lacks " << s;
    }
  }
}

// ------------------------------------------------------------------ rotation oracles

// The x plane at a component's own azimuth runs exactly that component's single-plane case (same
// runner, samples copied by the rotation: cos 0 = 1, cos 90 = 0 exactly); the y plane at azimuth 0
// is the west, i.e. the east component reversed.
TEST(TwoPlaneItems, PlanesAtTheComponentsAzimuthsAreTheSinglePlaneCases) {
  const Component north = pulse("000", 3.0, 1.0), east = pulse("090", 2.6, 1.4, 0.3);
  const Component up = pulse("UP", 2.0, 2.0, 0.0, true);
  const std::vector<StudyRecord> records = station({north, east}, &up);
  const StationPairs pairs = pair_stations(records);
  ASSERT_EQ(pairs.pairs.size(), 1u);
  const StudyItem item = make_item("cab", 0.3, 0.36, 0.6, 0.4, 0.35);
  const std::vector<StudyBody> bodies{{"x", item.x}, {"y", item.y}};
  StudyOptions single;
  single.threads = 2;
  single.trig = BatchTrig::Exact;  // compared to the bit with the item study: the exact path
  const std::vector<CaseResult> cases = run_study(bodies, records, single);
  auto single_case = [&](std::size_t body, std::size_t record, int polarity) -> const CaseResult& {
    for (const auto& c : cases)
      if (c.body == body && c.record == record && c.polarity == polarity && c.vertical) return c;
    throw std::runtime_error("no such case");
  };
  const std::vector<ItemCaseResult> items = run_item_study({item}, records, pairs, options({0.0, 90.0}));
  ASSERT_EQ(items.size(), 4u);
  int rocked = 0;
  for (int p : {1, -1}) {
    const std::string s = " polarity " + std::to_string(p);
    expect_same(find(items, 0, 0.0, p).planes[0], single_case(0, 0, p), "x at 0 = north" + s);
    expect_same(find(items, 0, 0.0, p).planes[1], single_case(1, 1, -p), "y at 0 = -east" + s);
    expect_same(find(items, 0, 90.0, p).planes[0], single_case(0, 1, p), "x at 90 = east" + s);
    expect_same(find(items, 0, 90.0, p).planes[1], single_case(1, 0, p), "y at 90 = north" + s);
    for (const auto& pl : find(items, 0, 0.0, p).planes) rocked += pl.outcome.impacts > 0 || pl.outcome.overturned;
    EXPECT_TRUE(find(items, 0, 0.0, p).vertical);
  }
  EXPECT_GT(rocked, 0);  // the pulses make the planes rock, so the comparison is not of two rests
}

// Azimuth 0 vs 90 with identical planes (width = depth, eccentricity_y = eccentricity): rotate() gives
// x(90) = east = -y(0) and y(90) = north = x(0) exactly, so x(90, p) = y(0, -p) and y(90, p) = x(0, p).
// A symmetric body rocks the same under both polarities, so for it the planes simply swap.
TEST(TwoPlaneItems, AzimuthsZeroAndNinetySwapThePlanes) {
  const std::vector<StudyRecord> records = station({pulse("N", 3.2, 1.1), pulse("E", 2.4, 0.9, 0.2)}, nullptr);
  const StationPairs pairs = pair_stations(records);
  const StudyItem eccentric = make_item("ecc", 0.3, 0.3, 0.6, 0.4, 0.4);
  const StudyItem symmetric = make_item("sym", 0.3, 0.3, 0.6, 0.5, 0.5);
  const std::vector<ItemCaseResult> r = run_item_study({eccentric, symmetric}, records, pairs, options({0.0, 90.0}));
  ASSERT_EQ(r.size(), 8u);
  for (std::size_t it : {0u, 1u}) {
    for (int p : {1, -1}) {
      const std::string s = " item " + std::to_string(it) + " polarity " + std::to_string(p);
      expect_same(find(r, it, 90.0, p).planes[0], find(r, it, 0.0, -p).planes[1], "x(90, p) = y(0, -p)" + s);
      expect_same(find(r, it, 90.0, p).planes[1], find(r, it, 0.0, p).planes[0], "y(90, p) = x(0, p)" + s);
    }
  }
  for (int p : {1, -1})
    expect_same(find(r, 1, 90.0, p).planes[0], find(r, 1, 0.0, p).planes[1], "symmetric: x(90) = y(0)", true);
  // The eccentric item does tell the polarities apart here (else the sign check above proves little).
  EXPECT_FALSE(find(r, 0, 0.0, 1).planes[0].outcome.max_rotation_ratio ==
               find(r, 0, 0.0, -1).planes[0].outcome.max_rotation_ratio);
}

// Equal north and east components s: the ground moves along 45 deg. At azimuth 0 both planes see s up
// to the sign (x = north = s, y = west = -s), at 90 the same s (x = east, y = north), so an item with
// identical planes gives identical plane results (at 0: x with polarity p = y with -p, and for a
// symmetric item also with the same p; at 90: x = y). At 45 deg the whole motion is along x: y sees
// nothing (to rounding) and never uplifts.
TEST(TwoPlaneItems, EqualHorizontalsGiveBothPlanesTheSameMotion) {
  const Component n = pulse("000", 3.0, 1.0), e = pulse("090", 3.0, 1.0);
  const std::vector<StudyRecord> records = station({n, e}, nullptr);
  const StationPairs pairs = pair_stations(records);
  const StudyItem eccentric = make_item("ecc", 0.3, 0.3, 0.6, 0.4, 0.4);
  const StudyItem symmetric = make_item("sym", 0.3, 0.3, 0.6, 0.5, 0.5);
  const std::vector<ItemCaseResult> r =
      run_item_study({eccentric, symmetric}, records, pairs, options({0.0, 90.0, 45.0}));
  for (int p : {1, -1}) {
    for (std::size_t it : {0u, 1u}) {
      const std::string s = " item " + std::to_string(it) + " p " + std::to_string(p);
      // Azimuth 0: x = north = s, y = west = -east = -s.
      expect_same(find(r, it, 0.0, p).planes[0], find(r, it, 0.0, -p).planes[1], "at 0: x(p) = y(-p)" + s);
      // Azimuth 90: x = east = s, y = north = s.
      expect_same(find(r, it, 90.0, p).planes[0], find(r, it, 90.0, p).planes[1], "at 90: x(p) = y(p)" + s);
    }
    expect_same(find(r, 1, 0.0, p).planes[0], find(r, 1, 0.0, p).planes[1], "symmetric at 0: x = y", true);
  }
  const PlaneInputs in = plane_inputs(pairs.pairs[0], records, 45.0);
  double y_peak = 0.0;
  for (std::size_t i = 0; i < in.x.size(); ++i) {
    EXPECT_NEAR(in.x[i], std::sqrt(2.0) * n.accel[i], 1e-12);
    y_peak = std::max(y_peak, std::abs(in.y[i]));
  }
  EXPECT_LT(y_peak, 1e-14);
  for (std::size_t it : {0u, 1u}) {
    for (int p : {1, -1}) {
      const ItemCaseResult& c = find(r, it, 45.0, p);
      EXPECT_TRUE(std::isnan(c.planes[1].outcome.uplift_time)) << describe(c);
      EXPECT_EQ(c.planes[1].outcome.max_rotation_ratio, 0.0) << describe(c);
      EXPECT_FALSE(std::isnan(c.planes[0].outcome.uplift_time)) << describe(c);  // x takes it all
      if (c.verdict.levels.reached(Level::BeyondTipping))
        EXPECT_EQ(c.verdict.plane[static_cast<int>(Level::BeyondTipping)], Plane::X);
    }
  }
}

// A station whose east component is zero: the plane that sees it (y at azimuth 0, x at 90) never
// uplifts, even with the vertical, while the other plane rocks.
TEST(TwoPlaneItems, APlaneUnderAZeroHorizontalNeverUplifts) {
  Component e = pulse("090", 0.0, 1.0);
  const Component up = pulse("UP", 3.0, 2.0, 0.0, true);
  const std::vector<StudyRecord> records = station({pulse("000", 3.0, 1.0), e}, &up);
  const StationPairs pairs = pair_stations(records);
  const StudyItem item = make_item("cab", 0.3, 0.25, 0.6, 0.4, 0.3);
  const std::vector<ItemCaseResult> r = run_item_study({item}, records, pairs, options({0.0, 90.0}));
  for (int p : {1, -1}) {
    const CaseResult& y0 = find(r, 0, 0.0, p).planes[1];
    const CaseResult& x90 = find(r, 0, 90.0, p).planes[0];
    for (const CaseResult* c : {&y0, &x90}) {
      EXPECT_TRUE(c->vertical);
      EXPECT_TRUE(std::isnan(c->outcome.uplift_time));
      EXPECT_EQ(c->outcome.max_rotation_ratio, 0.0);
      EXPECT_EQ(c->outcome.impacts, 0);
      EXPECT_FALSE(c->outcome.beyond_tipping);
    }
    EXPECT_FALSE(std::isnan(find(r, 0, 0.0, p).planes[0].outcome.uplift_time));
    EXPECT_EQ(find(r, 0, 0.0, p).pga[1], 0.0);
  }
}

// The item's verdict is combine() of its planes, and agrees with a recount from the plane outcomes:
// it overturns when a plane does, at the earliest plane's time, named by that plane (tie: x).
TEST(TwoPlaneItems, ItemVerdictIsCombineOfThePlanes) {
  const std::vector<StudyRecord> records = station({pulse("000", 4.0, 0.9), pulse("090", 3.5, 1.2, 0.4)}, nullptr);
  const StationPairs pairs = pair_stations(records);
  const std::vector<StudyItem> items{make_item("a", 0.3, 0.24, 0.6, 0.5, 0.5), make_item("b", 0.25, 0.35, 0.6, 0.35, 0.4),
                                     make_item("c", 0.5, 0.45, 0.6, 0.5, 0.3)};
  std::vector<double> az;
  for (double a = 0.0; a < 360.0; a += 30.0) az.push_back(a);
  const std::vector<ItemCaseResult> r = run_item_study(items, records, pairs, options(az));
  ASSERT_EQ(r.size(), items.size() * az.size() * 2);
  long by_x = 0, by_y = 0, stayed = 0;
  for (const ItemCaseResult& c : r) {
    const LevelTimes x = level_times(c.planes[0].outcome), y = level_times(c.planes[1].outcome);
    const ItemVerdict v = combine(x, &y);
    for (int l = 0; l < kLevelCount; ++l) {
      EXPECT_TRUE(same_or_both_nan(v.levels.time[l], c.verdict.levels.time[l])) << describe(c);
      EXPECT_EQ(v.plane[l], c.verdict.plane[l]) << describe(c);
    }
    const RockingOutcome &ox = c.planes[0].outcome, &oy = c.planes[1].outcome;
    EXPECT_EQ(c.verdict.overturned(), ox.overturned || oy.overturned) << describe(c);
    if (!c.verdict.overturned()) {
      ++stayed;
      continue;
    }
    const double tx = ox.overturned ? ox.overturn_time : INFINITY, ty = oy.overturned ? oy.overturn_time : INFINITY;
    EXPECT_EQ(c.verdict.levels.at(Level::Overturned), std::min(tx, ty)) << describe(c);
    const Plane decided = ty < tx ? Plane::Y : Plane::X;
    EXPECT_EQ(c.verdict.plane[static_cast<int>(Level::Overturned)], decided) << describe(c);
    (decided == Plane::X ? by_x : by_y) += 1;
  }
  // Every branch is exercised.
  EXPECT_GT(by_x, 0);
  EXPECT_GT(by_y, 0);
  EXPECT_GT(stayed, 0);
  // The summary counts what the cases say.
  const ItemSummary s = summarize_items(r, items, pairs, az);
  EXPECT_EQ(s.all.cases, static_cast<long>(r.size()));
  EXPECT_EQ(s.all.overturned, by_x + by_y);
  EXPECT_EQ(s.all.overturned_decided_by_y, by_y);
  EXPECT_EQ(s.all.overturned_x_only + s.all.overturned_y_only + s.all.overturned_both, by_x + by_y);
  long per_azimuth = 0;
  for (const auto& t : s.by_azimuth) per_azimuth += t.overturned;
  EXPECT_EQ(per_azimuth, by_x + by_y);
}

// ------------------------------------------------------------------ pairing, order, outputs

TEST(TwoPlaneItems, PairingCountsAndNotesWhatItCannotRotate) {
  std::vector<StudyRecord> records;
  auto add = [&](const std::vector<Component>& h, const std::string& name) {
    for (auto& r : station(h, nullptr, name)) records.push_back(std::move(r));
  };
  add({pulse("000", 1.0, 1.0), pulse("090", 1.0, 1.0)}, "good");
  add({pulse("000", 1.0, 1.0)}, "single");
  add({pulse("000", 1.0, 1.0), pulse("090", 1.0, 1.0, 0.0, false, 301, 0.02)}, "dt");
  add({pulse("H1", 1.0, 1.0), pulse("H2", 1.0, 1.0)}, "nodir");
  add({pulse("000", 1.0, 1.0), pulse("005", 1.0, 1.0)}, "parallel");
  add({pulse("000", 1.0, 1.0, 0.0, false, 601), pulse("270", 1.0, 1.0, 0.0, false, 650)}, "short");
  const StationPairs p = pair_stations(records);
  ASSERT_EQ(p.pairs.size(), 2u);
  EXPECT_EQ(p.pairs[0].station, "good");
  EXPECT_EQ(p.pairs[1].station, "short");
  EXPECT_EQ(p.single_horizontal, 1);
  EXPECT_EQ(p.different_dt, 1);
  EXPECT_EQ(p.no_azimuth, 1);
  EXPECT_EQ(p.not_resolvable, 1);
  EXPECT_EQ(p.zero_padded, 1);
  ASSERT_EQ(p.notes.size(), 5u);  // four skipped stations and the padded one, each named
  for (const char* name : {"single", "dt", "nodir", "parallel", "short"}) {
    EXPECT_TRUE(std::any_of(p.notes.begin(), p.notes.end(),
                            [&](const std::string& n) { return n.find(std::string("synthetic/") + name + ":") == 0; }))
        << name;
  }
  // The shorter horizontal is zero-padded to the longer: north at azimuth 0 is the padded one.
  const PlaneInputs in = plane_inputs(p.pairs[1], records, 0.0);
  ASSERT_EQ(in.x.size(), 650u);
  for (std::size_t i = 601; i < 650; ++i) EXPECT_EQ(in.x[i], 0.0);
  // y at azimuth 0 is west: the 270 component as recorded.
  for (std::size_t i = 0; i < 650; ++i) EXPECT_EQ(in.y[i], records[records.size() - 1].horizontal[i]);
}

TEST(TwoPlaneItems, CaseOrderTableAndSummaryDoNotDependOnThreads) {
  const Component up = pulse("UP", 1.5, 2.0, 0.0, true);
  std::vector<StudyRecord> records = station({pulse("000", 4.0, 0.9), pulse("090", 3.0, 1.2, 0.4)}, &up, "s1");
  for (auto& r : station({pulse("045", 2.0, 1.5), pulse("135", 3.5, 0.8)}, nullptr, "s2")) records.push_back(r);
  const StationPairs pairs = pair_stations(records);
  ASSERT_EQ(pairs.pairs.size(), 2u);
  const std::vector<StudyItem> items{make_item("a", 0.3, 0.24, 0.6, 0.4, 0.5), make_item("b", 0.4, 0.5, 0.8, 0.5, 0.3)};
  const std::vector<double> az{0.0, 30.0, 90.0};
  std::string tables[2];
  for (int threads : {1, 2}) {
    const std::vector<ItemCaseResult> r = run_item_study(items, records, pairs, options(az, threads));
    ASSERT_EQ(r.size(), item_case_count(items.size(), pairs.pairs.size(), options(az)));
    ASSERT_EQ(r.size(), 2u * 2u * 3u * 2u);
    // item, pair, azimuth (given order), polarity +1 then -1.
    std::size_t i = 0;
    for (std::size_t it = 0; it < 2; ++it)
      for (std::size_t pr = 0; pr < 2; ++pr)
        for (double a : az)
          for (int p : {1, -1}) {
            EXPECT_EQ(r[i].index, i);
            EXPECT_EQ(r[i].item, it);
            EXPECT_EQ(r[i].pair, pr);
            EXPECT_EQ(r[i].azimuth_deg, a);
            EXPECT_EQ(r[i].polarity, p);
            EXPECT_EQ(r[i].vertical, pr == 0);  // s1 has a vertical, s2 none
            ++i;
          }
    std::ostringstream os;
    write_item_cases_csv(os, r, items, records, pairs);
    tables[threads - 1] = os.str();
    if (threads == 2) {
      const ItemSummary s = summarize_items(r, items, pairs, az);
      const auto j = nlohmann::json::parse(summary_json(summarize({}), StudyRunInfo{}, &s));
      EXPECT_EQ(j["two_plane_items"]["all"]["cases"].get<long>(), 24);
      EXPECT_EQ(j["two_plane_items"]["station_pairs"].get<long>(), 2);
      EXPECT_EQ(j["two_plane_items"]["by_item"].size(), 2u);
      EXPECT_NE(j["run"]["rocking_model"].get<std::string>().find("pure rocking (paper)"), std::string::npos);
    }
  }
  EXPECT_EQ(tables[0], tables[1]);
  const std::string& t = tables[0];
  EXPECT_EQ(std::count(t.begin(), t.end(), '\n'), 1 + 24);
  std::string header = t.substr(0, t.find('\n'));
  std::string expected;
  for (const auto& c : item_case_csv_columns()) expected += (expected.empty() ? "" : ",") + c;
  EXPECT_EQ(header, expected);
}

// The same on a real station whose horizontals are not north and east (Rinaldi 228 and 318, with its
// vertical): at azimuth 228 the x plane is the 228 component's single-plane case with the vertical,
// bit for bit, and at 318 the x plane is the 318 component's and the y plane (318 - 90 = 228) the
// 228 component's.
TEST(TwoPlaneItemsRealRecords, RinaldiPlanesAtItsComponentsAzimuthsAreItsSinglePlaneCases) {
  const fs::path dir(ROCKING_RECORDS_DIR);
  if (!fs::exists(dir / "MANIFEST.csv")) GTEST_SKIP() << "no records at " << dir;
  const StudyRecords recs = load_study_records(dir.string(), {{"Rinaldi"}, {}});
  ASSERT_EQ(recs.records.size(), 2u);
  ASSERT_EQ(recs.records[0].component, "228");
  const StationPairs pairs = pair_stations(recs.records);
  ASSERT_EQ(pairs.pairs.size(), 1u);
  EXPECT_EQ(pairs.zero_padded, 0);
  const StudyItem item = make_item("cab", 0.35, 0.5, 0.8, 0.4, 0.45);
  const std::vector<StudyBody> bodies{{"x", item.x}, {"y", item.y}};
  StudyOptions single;
  single.threads = 2;
  single.trig = BatchTrig::Exact;  // compared to the bit with the item study: the exact path
  const std::vector<CaseResult> cases = run_study(bodies, recs.records, single);
  auto single_case = [&](std::size_t body, std::size_t record, int polarity) -> const CaseResult& {
    for (const auto& c : cases)
      if (c.body == body && c.record == record && c.polarity == polarity && c.vertical) return c;
    throw std::runtime_error("no such case");
  };
  const std::vector<ItemCaseResult> r = run_item_study({item}, recs.records, pairs, options({228.0, 318.0}));
  long rocked = 0;
  for (int p : {1, -1}) {
    const std::string s = " polarity " + std::to_string(p);
    expect_same(find(r, 0, 228.0, p).planes[0], single_case(0, 0, p), "x at 228" + s);
    expect_same(find(r, 0, 318.0, p).planes[0], single_case(0, 1, p), "x at 318" + s);
    expect_same(find(r, 0, 318.0, p).planes[1], single_case(1, 0, p), "y at 318 = 228" + s);
    rocked += find(r, 0, 228.0, p).planes[0].outcome.impacts > 0 || find(r, 0, 228.0, p).planes[0].outcome.overturned;
  }
  EXPECT_GT(rocked, 0);
}

// The 3-D model beside the planes (issue 27): a box under one horizontal along its x axis (the y
// horizontal zero) and the vertical rocks about its x edges exactly as the x plane (the model's
// reduction, tested on the model itself in test_rocking_3d.cpp; here the study's inputs, polarity and
// vertical reach it as they reach the planes): every decision, time and peak to 1e-9. Under both
// horizontals at 45 deg the box is no longer a plane problem, and the columns say which model ran.
TEST(TwoPlaneItems, ABoxUnderOneHorizontalRocksIn3DAsItsXPlane) {
  const Component up = pulse("UP", 2.0, 2.0, 0.0, true);
  for (double amplitude : {3.0, 6.0}) {
    const std::vector<StudyRecord> records = station({pulse("000", amplitude, 1.0), pulse("090", 0.0, 1.0)}, &up);
    const StationPairs pairs = pair_stations(records);
    StudyItem item = make_item("box", 0.3, 0.25, 0.6, 0.4, 0.3);
    item.solid = box_base_body(item.x, item.depth.depth, item.depth.eccentricity_y, item.y.radius_of_gyration);
    const StudyItem planar_only = make_item("planar", 0.3, 0.25, 0.6, 0.4, 0.3);
    const std::vector<ItemCaseResult> r = run_item_study({item, planar_only}, records, pairs, options({0.0, 45.0}));
    long overturned = 0;
    for (int p : {1, -1}) {
      const ItemCaseResult& c = find(r, 0, 0.0, p);
      const std::string what = describe(c) + " amplitude " + std::to_string(amplitude);
      ASSERT_TRUE(c.solid_run) << what;
      const RockingOutcome &s = c.solid, &x = c.planes[0].outcome;
      EXPECT_GT(x.impacts + x.overturned, 0) << what << ": the x plane must rock for this to test anything";
      EXPECT_EQ(s.overturned, x.overturned) << what;
      EXPECT_EQ(s.committed, x.committed) << what;
      EXPECT_EQ(s.beyond_tipping, x.beyond_tipping) << what;
      EXPECT_EQ(s.impacts, x.impacts) << what;
      EXPECT_NEAR(s.max_rotation_ratio, x.max_rotation_ratio, 1e-9) << what;
      EXPECT_NEAR(s.uplift_time, x.uplift_time, 1e-9) << what;
      if (x.overturned) EXPECT_NEAR(s.overturn_time, x.overturn_time, 1e-9) << what;
      EXPECT_EQ(c.solid_3d.edge_to_vertex, 0) << what << ": no corner wobble under one component along a side";
      overturned += x.overturned;
      EXPECT_FALSE(find(r, 1, 0.0, p).solid_run) << "an item without a 3-D description runs the planes only";
      // at 45 deg both horizontals shake it: the 3-D model is run (what it says is the model's own test)
      EXPECT_TRUE(find(r, 0, 45.0, p).solid_run);
    }
    if (amplitude > 5.0) EXPECT_GT(overturned, 0) << "the strong pulse must overturn it in some polarity";
    const ItemSummary sum = summarize_items(r, {item, planar_only}, pairs, {0.0, 45.0});
    EXPECT_EQ(sum.by_item[0].solid_cases, 4);
    EXPECT_EQ(sum.by_item[1].solid_cases, 0);
    std::ostringstream os;
    write_item_cases_csv(os, r, {item, planar_only}, records, pairs);
    std::istringstream lines(os.str());
    std::string header, first;
    std::getline(lines, header);
    std::getline(lines, first);
    EXPECT_NE(header.find("solid_overturned"), std::string::npos);
    EXPECT_EQ(std::count(header.begin(), header.end(), ','), std::count(first.begin(), first.end(), ','));
  }
}

// --one-polarity and --no-vertical apply to the items too.
TEST(TwoPlaneItems, OnePolarityAndNoVerticalOptions) {
  const Component up = pulse("UP", 1.5, 2.0, 0.0, true);
  const std::vector<StudyRecord> records = station({pulse("000", 3.0, 1.0), pulse("090", 2.0, 1.3)}, &up);
  const StationPairs pairs = pair_stations(records);
  ItemStudyOptions o = options({0.0, 45.0, 90.0});
  o.both_polarities = false;
  o.verticals = false;
  const std::vector<ItemCaseResult> r =
      run_item_study({make_item("a", 0.3, 0.3, 0.6, 0.4, 0.4)}, records, pairs, o);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(item_case_count(1, 1, o), 3u);
  for (const auto& c : r) {
    EXPECT_EQ(c.polarity, 1);
    EXPECT_FALSE(c.vertical);
    EXPECT_FALSE(c.planes[0].vertical);
  }
}

}  // namespace
}  // namespace rocking_monitor::core::study
