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
// Granite SP1 and SP2 (../shared/experiments/granite_pbr, skipped without it) on six real tests:
// with Bullet on the core's own geometry (the base polygon as a prism) the overturn decision
// agrees on 12 of 12; with Bullet on the scanned hull it does not where the rock would roll onto
// its hull beyond the 1 mm contact patch (the core overturns, Bullet stands). See the tests.
#include <gtest/gtest.h>

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "bullet_rocking.hpp"
#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/study/shaking_table_experiments.hpp"

#ifndef ROCKING_EXPERIMENTS_DIR
#define ROCKING_EXPERIMENTS_DIR "../shared/experiments"
#endif
#ifndef ROCKING_SOURCE_DIR
#define ROCKING_SOURCE_DIR "."
#endif
#ifndef ROCKING_PYTHON
#define ROCKING_PYTHON "python3"
#endif

namespace rocking_monitor {
namespace {

namespace fs = std::filesystem;
using namespace core;
using reference::BulletBody;
using reference::BulletRocking;
using reference::BulletSettings;

struct Result {
  bool overturned = false;
  double overturn_time = std::nan("");
  double max_tilt = 0.0;
  double first_impact_time = std::nan("");
  double uplift_time = std::nan("");
  long impacts = 0;
  bool vertex = false;  // core: pivoted on a hull vertex at some sample (the corner wobble)
  long forced_rests = 0;  // core: samples that hit the event bound and were put down flat
};

// ---------------------------------------------------------------- bodies

struct Pair {
  BaseBodyParameters core;
  BulletBody bullet;
};

// A homogeneous B x D x 2h box, mass m, its base corner at the origin.
Pair box(double b, double d, double h, double mass, double overturn) {
  BodyParameters x;
  x.width = b;
  x.cg_height = h;
  x.nu1 = 0.5;
  Pair p;
  p.core = box_base_body(x, d, 0.5, std::nan(""));
  p.core.mass = mass;
  p.core.central_inertia *= mass;  // box_base_body gives it per unit mass
  p.core.overturn_angle = overturn;
  p.bullet.mass = mass;
  p.bullet.centre_of_mass = p.core.centre_of_mass;
  p.bullet.central_inertia = p.core.central_inertia;
  for (double z : {0.0, 2.0 * h})
    for (const Eigen::Vector2d& c : p.core.base) p.bullet.points.emplace_back(c.x(), c.y(), z);
  return p;
}

// ---------------------------------------------------------------- the granite specimens

const fs::path kGranite = fs::path(ROCKING_EXPERIMENTS_DIR) / "granite_pbr";

std::vector<std::string> gz_lines(const std::string& path) {
  gzFile f = gzopen(path.c_str(), "rb");
  if (!f) throw std::runtime_error("cannot open " + path);
  std::vector<std::string> lines;
  std::string cur;
  char buf[4096];
  while (gzgets(f, buf, sizeof buf)) {
    cur += buf;
    if (!cur.empty() && cur.back() == '\n') {
      lines.push_back(cur);
      cur.clear();
    }
  }
  if (!cur.empty()) lines.push_back(cur);
  gzclose(f);
  return lines;
}

// The mesh's vertices used by its faces (the scan has unused ones), mesh frame, m.
std::vector<Eigen::Vector3d> read_obj_used_vertices(const std::string& path) {
  std::vector<Eigen::Vector3d> v;
  std::vector<char> used;
  std::vector<long> refs;
  for (const std::string& line : gz_lines(path)) {
    if (line.size() < 2) continue;
    std::istringstream in(line);
    std::string tag;
    in >> tag;
    if (tag == "v") {
      double x, y, z;
      in >> x >> y >> z;
      v.emplace_back(x, y, z);
    } else if (tag == "f") {
      std::string item;
      while (in >> item) refs.push_back(std::stol(item.substr(0, item.find('/'))));
    }
  }
  used.assign(v.size(), 0);
  for (long r : refs) used[static_cast<std::size_t>(r > 0 ? r - 1 : static_cast<long>(v.size()) + r)] = 1;
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (used[i]) out.push_back(v[i]);
  return out;
}

// scripts/rocking_geometry.py --granite: every number (floor frame), once per process. Derived
// here from the shared meshes rather than kept in the repository: the catalogue the 3-D model
// gets is the script's, whatever it currently writes.
const nlohmann::json& granite_geometry() {
  static nlohmann::json j;
  if (!j.is_null()) return j;
  const fs::path out = fs::temp_directory_path() / ("bullet_granite_" + std::to_string(::getpid()) + ".json");
  const std::string cmd = std::string(ROCKING_PYTHON) + " " + ROCKING_SOURCE_DIR +
                          "/scripts/rocking_geometry.py --granite " + kGranite.string() + " --json " +
                          out.string() + " > /dev/null";
  if (std::system(cmd.c_str()) != 0) throw std::runtime_error("failed: " + cmd);
  std::ifstream in(out);
  in >> j;
  fs::remove(out);
  return j;
}

// The contact hull as the 3-D model wants it: counter-clockwise (the script's hull is), vertices
// within 1 um of their neighbours' chord dropped (collinear: not a pivot of their own).
std::vector<Eigen::Vector2d> base_polygon(const nlohmann::json& hull) {
  std::vector<Eigen::Vector2d> pts;
  for (const auto& p : hull) pts.emplace_back(p[0].get<double>(), p[1].get<double>());
  bool changed = true;
  while (changed && pts.size() > 3) {
    changed = false;
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const Eigen::Vector2d& a = pts[(k + pts.size() - 1) % pts.size()];
      const Eigen::Vector2d& b = pts[k];
      const Eigen::Vector2d& c = pts[(k + 1) % pts.size()];
      const Eigen::Vector2d chord = c - a;
      const double off = std::abs(chord.x() * (b - a).y() - chord.y() * (b - a).x()) / chord.norm();
      if ((b - a).norm() < 1e-6 || off < 1e-6) {
        pts.erase(pts.begin() + static_cast<long>(k));
        changed = true;
        break;
      }
    }
  }
  return pts;
}

const char* const kSpecimenMesh[] = {"specimens/SP1_pca.obj.gz", "specimens/SP2.obj.gz"};

// Bullet's body for a specimen:
//   Scanned   the mesh as placed (the script's rotation: quaternion and settling), lowest vertex on
//             the floor: a 1 mm contact patch that is not one plane, and the hull beyond it.
//   Flattened the same, its vertices within the script's contact tolerance (1 mm) put on the floor:
//             Bullet's base is then the core's base polygon, and the scanned hull rises beyond it.
//   Prism     the core's base polygon extruded up to twice the centre of mass's height (with the
//             specimen's mass, centre of mass and inertia): nothing but the base touches the floor
//             before the overturn, as the core assumes. Only the dynamics then differ.
enum class Geometry { Scanned, Flattened, Prism };

// Specimen `name` (SP1, SP2) for both codes: the catalogue entry (hull, centre of mass, inertia
// from the script) for the core, and `geometry` for Bullet.
Pair granite(const std::string& name, double overturn, Geometry geometry) {
  const nlohmann::json& g = granite_geometry().at(name);
  Pair p;
  p.core.mass = g.at("mass").get<double>();
  const auto& c = g.at("com");
  p.core.centre_of_mass = Eigen::Vector3d(c[0], c[1], c[2]);
  const auto& in = g.at("inertia");
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) p.core.central_inertia(i, k) = in[i][k].get<double>();
  p.core.base = base_polygon(g.contains("base_polygon") ? g.at("base_polygon") : g.at("hull"));
  p.core.overturn_angle = overturn;
  Eigen::Matrix3d r;
  const auto& rot = g.at("rotation");
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) r(i, k) = rot[i][k].get<double>();
  const std::string mesh = (kGranite / kSpecimenMesh[name == "SP1" ? 0 : 1]).string();
  double floor = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& v : read_obj_used_vertices(mesh)) {
    p.bullet.points.push_back(r * v);
    floor = std::min(floor, p.bullet.points.back().z());
  }
  const double tol = g.at("contact_tolerance").get<double>();
  for (Eigen::Vector3d& v : p.bullet.points) {
    v.z() -= floor;
    if (geometry != Geometry::Scanned && v.z() <= tol) v.z() = 0.0;
  }
  if (geometry == Geometry::Prism) {
    p.bullet.points.clear();
    for (double z : {0.0, 2.0 * p.core.centre_of_mass.z()})
      for (const Eigen::Vector2d& c : p.core.base) p.bullet.points.emplace_back(c.x(), c.y(), z);
  }
  p.bullet.mass = p.core.mass;
  p.bullet.centre_of_mass = p.core.centre_of_mass;
  p.bullet.central_inertia = p.core.central_inertia;
  return p;
}

// ---------------------------------------------------------------- runs

using Series = std::vector<Eigen::Vector3d>;  // ground acceleration at t = k dt, m/s^2

Result run_core(const BaseBodyParameters& params, const Series& a, double dt) {
  SolverSettings s;
  s.tol = 1e-8;
  Rocking3DModel m(BaseBody(params), s);
  m.reset(0.0, a.front());
  Result r;
  for (std::size_t k = 1; k < a.size(); ++k) {
    const StepReport& rep = m.step(a[k], dt);
    if (rep.impacts > 0 && std::isnan(r.first_impact_time)) r.first_impact_time = rep.first_impact_time;
    r.vertex = r.vertex || m.mode() == Mode3D::Vertex;
    if (m.outcome().overturned) break;
  }
  r.overturned = m.outcome().overturned;
  r.overturn_time = m.outcome().overturn_time;
  r.max_tilt = m.outcome_3d().max_tilt;
  r.uplift_time = m.outcome().uplift_time;
  r.impacts = m.outcome().impacts;
  r.forced_rests = m.outcome().forced_rest_captures;
  return r;
}

// First impact in Bullet: the first time the tilt comes back down to `floor_ratio` of the first
// excursion's peak (Bullet has no impact event; the base lands where the tilt returns to ~0).
double bullet_first_return(const std::vector<Eigen::Vector2d>& h, double floor_ratio) {
  double peak = 0.0;
  std::size_t k = 0;
  for (; k < h.size(); ++k) {
    if (h[k].y() > peak) peak = h[k].y();
    else if (peak > 1e-3 && h[k].y() < 0.5 * peak) break;  // past the first peak
  }
  for (; k < h.size(); ++k)
    if (h[k].y() <= floor_ratio * peak) return h[k].x();
  return std::nan("");
}

Result run_bullet(const BulletBody& body, const BulletSettings& settings, const Series& a, double dt,
               std::vector<Eigen::Vector2d>* history = nullptr) {
  BulletRocking b(body, settings);
  b.set_input(a.front());
  b.record_history(history != nullptr);
  for (std::size_t k = 1; k < a.size(); ++k) {
    b.step(a[k], dt);
    if (b.outcome().overturned) break;
  }
  Result r;
  r.overturned = b.outcome().overturned;
  r.overturn_time = b.outcome().overturn_time;
  r.max_tilt = b.outcome().max_tilt;
  if (history) *history = b.history();
  return r;
}

// One-sine pulse of amplitude amp (m/s^2) and frequency f along `direction`, then rest to t_end.
Series sine_pulse(const Eigen::Vector3d& direction, double amp, double f, double dt, double t_end) {
  Series s;
  for (long k = 0; k * dt <= t_end + 1e-12; ++k) {
    const double t = k * dt;
    const double v = t < 1.0 / f ? amp * std::sin(2.0 * kPi * f * t) : 0.0;
    s.push_back(v * direction.normalized());
  }
  return s;
}

// Both codes count a body overturned at a tilt of 1.2 rad (69 deg): far past every tipping angle
// here (the box's corner 25 deg, the specimens' base edges <= 48 deg), so nothing brings it back,
// and short of 90 deg, where a box lies on its side and Bullet's compliant contact would make
// "reached 90 deg" a matter of microns.
constexpr double kOverturn = 1.2;  // rad
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

// ---------------------------------------------------------------- granite specimens, real tests

#define REQUIRE_GRANITE()                                                                         \
  if (!fs::exists(kGranite / "outcomes.csv"))                                                     \
  GTEST_SKIP() << kGranite << " not found (see ../shared/experiments/granite_pbr/README.md)"

// A handful of the shaking-table tests (800 Hz, along the floor frame's x): two quiet ones, the
// rest chosen near the specimens' overturning boundary, both ways in the experiment.
const int kTests[] = {11, 61, 110, 253, 281, 519};
constexpr int kQuiet[] = {11, 253};
// Bullet's step on the records: 1/2000 s. On the prism the outcomes are the same at 1/4000 s (12
// of 12 agree at both); on the scanned hull SP1's Test061 is marginal for Bullet (it stands at
// 1/2000 s and overturns late, at 13.1 s, at 1/4000 s), which the hull test's assertions allow.
// Halving the step doubles the cost (1-2 s per 45 s record).
constexpr double kRecordStep = 1.0 / 2000;
constexpr double kRecordTail = 3.0;  // s of table at rest after each record

struct RecordRun {
  int test = 0, specimen = 0, measured = -1;
  Result core, bullet;
};

std::vector<RecordRun> run_records(Geometry geometry) {
  const auto outcomes = read_outcomes((kGranite / "outcomes.csv").string());
  std::vector<RecordRun> runs;
  for (int sp = 0; sp < 2; ++sp) {
    const std::string name = sp == 0 ? "SP1" : "SP2";
    const Pair p = granite(name, kOverturn, geometry);
    BulletSettings bs;
    bs.substep = kRecordStep;
    bs.overturn_tilt = kOverturn;
    for (int t : kTests) {
      char file[32];
      std::snprintf(file, sizeof file, "Test%03d.csv.gz", t);
      const TableTest tt = read_table_test((kGranite / "tests" / file).string());
      Series s;
      for (double a : tt.accel_mps2) s.emplace_back(a, 0.0, 0.0);
      s.resize(s.size() + static_cast<std::size_t>(kRecordTail / tt.dt), Eigen::Vector3d::Zero());
      RecordRun r;
      r.test = t;
      r.specimen = sp;
      r.measured = outcomes.by_test.count(t) ? outcomes.by_test.at(t)[static_cast<std::size_t>(sp)] : -1;
      r.core = run_core(p.core, s, tt.dt);
      r.bullet = run_bullet(p.bullet, bs, s, tt.dt);
      std::printf("%s Test%03d (measured %d): core overturned %d at %.3f s, peak tilt %.4f, %ld impacts, %ld forced "
                  "rests | Bullet overturned %d at %.3f s, peak tilt %.4f\n",
                  name.c_str(), t, r.measured, r.core.overturned, r.core.overturn_time, r.core.max_tilt,
                  r.core.impacts, r.core.forced_rests, r.bullet.overturned, r.bullet.overturn_time, r.bullet.max_tilt);
      runs.push_back(r);
    }
  }
  return runs;
}

bool quiet(int test) { return std::find(std::begin(kQuiet), std::end(kQuiet), test) != std::end(kQuiet); }

// The specimens as the core sees them (base polygon, centre of mass, inertia from the catalogue),
// Bullet on the same geometry (Prism): the overturn decision agrees on every record (measured 12
// of 12, at 1/2000 and 1/4000 s). One disagreement is allowed: after tens of impacts the response
// is chaotic and the two impact treatments differ, so a marginal record may flip. Overturn times
// and peak tilts of survivors are printed, not compared (measured: overturn times 0.01-2 s apart
// after many impacts, wobble peaks a factor 2-4 apart, and Bullet's own change with its step).
TEST(Bullet3D, GraniteCatalogueBodiesOverturnAlikeOnRealTests) {
  REQUIRE_GRANITE();
  const std::vector<RecordRun> runs = run_records(Geometry::Prism);
  int agree = 0;
  for (const RecordRun& r : runs) {
    agree += r.core.overturned == r.bullet.overturned;
    if (quiet(r.test)) {  // the quiet records barely rock either (peak tilt < 1 % of any alpha)
      EXPECT_FALSE(r.core.overturned || r.bullet.overturned) << r.test;
      EXPECT_LT(std::max(r.core.max_tilt, r.bullet.max_tilt), 0.02) << r.test;
    }
  }
  std::printf("catalogue bodies: overturn decision agrees on %d of %zu\n", agree, runs.size());
  EXPECT_GE(agree, static_cast<int>(runs.size()) - 1);
}

// Bullet on the scanned hull (contact patch flattened to the base polygon): the rock's hull rises
// gently beyond the 1 mm contact patch, so tipping over it takes far more tilt than over the base
// polygon's edge (toward +x: SP1 0.26 rad against alpha 0.050, SP2 0.39 against 0.23). The core
// knows only the base polygon: where the codes disagree, the core overturns and Bullet stands
// (measured: 5 of 12 disagree at 1/2000 s, 4 at 1/4000 s, all that way), never the reverse.
TEST(Bullet3D, GraniteScannedHullOnlyAddsStability) {
  REQUIRE_GRANITE();
  const std::vector<RecordRun> runs = run_records(Geometry::Flattened);
  int agree = 0;
  for (const RecordRun& r : runs) {
    agree += r.core.overturned == r.bullet.overturned;
    EXPECT_FALSE(r.bullet.overturned && !r.core.overturned) << "SP" << r.specimen + 1 << " test " << r.test;
    if (quiet(r.test)) {
      EXPECT_FALSE(r.core.overturned || r.bullet.overturned) << r.test;
    }
  }
  std::printf("scanned hull: overturn decision agrees on %d of %zu\n", agree, runs.size());
  EXPECT_LE(agree, static_cast<int>(runs.size()) - 2);  // the hull's extra support shows
}

// The catalogue's rest pose is a 1 mm contact patch, not one face of the scanned hull: Bullet puts
// SP1 as scanned down on a neighbouring face, 2 deg from it (measured 0.036 rad); flattened to
// the patch it stays within 0.002 rad (the contact's compliance on a sliver of a base).
TEST(Bullet3D, GraniteScannedContactPatchIsNotOneFace) {
  REQUIRE_GRANITE();
  BulletSettings bs;
  bs.substep = kRecordStep;
  const double scanned = BulletRocking(granite("SP1", kOverturn, Geometry::Scanned).bullet, bs).settle_tilt();
  const double flat = BulletRocking(granite("SP1", kOverturn, Geometry::Flattened).bullet, bs).settle_tilt();
  std::printf("SP1 settles %.4f rad (scanned), %.4f rad (flattened patch)\n", scanned, flat);
  EXPECT_GT(scanned, 0.02);
  EXPECT_LT(flat, 0.003);
}

}  // namespace
}  // namespace rocking_monitor
