// Independent 3-D reference for Rocking3DModel (issue 27), Bullet Physics (bullet_rocking.hpp; the
// settings and the box: test_bullet_reference.cpp), on the granite specimens.
//
// Granite SP1 and SP2 (../shared/experiments/granite_pbr, skipped without it) on six real tests:
// with Bullet on the core's own geometry (the base polygon as a prism) the overturn decision
// agrees on 12 of 12; with Bullet on the scanned hull it does not where the rock would roll onto
// its hull beyond the 1 mm contact patch (the core overturns, Bullet stands). See the tests.
#include "bullet_reference_runs.hpp"

namespace rocking_monitor {
namespace {

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
