#pragma once
// Small builders shared by the core tests.

#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include <fstream>

#include "rocking_monitor/physics/base_body.hpp"
#include "rocking_monitor/physics/body.hpp"
#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/integrate/solver_settings.hpp"
#include "rocking_monitor/motion/ground_motion.hpp"
#include "rocking_monitor/motion/record_reader.hpp"

namespace rocking_monitor::core::testing {

/// Built with AddressSanitizer (scripts/run_sanitizers.sh, 5-20x slower): the heaviest statistical
/// tests take fewer cases there, with the same assertions; the Release ctest runs them in full.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kUnderSanitizers = true;
#else
inline constexpr bool kUnderSanitizers = false;
#endif

/// A uniform box: base b x d centred on the origin, centre of mass h up (height 2h), friction mu_s, mu_k.
inline BaseBodyParameters uniform_box(double b, double d, double h, double mu_s, double mu_k) {
  BaseBodyParameters p;
  p.centre_of_mass = {0.0, 0.0, h};
  p.base = {{-b / 2, -d / 2}, {b / 2, -d / 2}, {b / 2, d / 2}, {-b / 2, d / 2}};
  p.central_inertia = Eigen::Vector3d((d * d + 4 * h * h) / 12, (b * b + 4 * h * h) / 12, (b * b + d * d) / 12).asDiagonal();
  p.mu_s = mu_s;
  p.mu_k = mu_k;
  return p;
}

/// A rhombus base (a vertex at +x, symmetric about the x-z plane; diagonals 2a along x, 2c along y), the
/// centre of mass h above its centre, radius of gyration ig about y, friction mu. Pivoting on its +x
/// vertex it moves in the x-z plane as planar_rhombus() on its corner (the slide-rock and flight tests).
inline BaseBodyParameters rhombus(double a, double c, double h, double ig, double mu) {
  BaseBodyParameters p;
  p.centre_of_mass = {0.0, 0.0, h};
  p.base = {{-a, 0.0}, {0.0, -c}, {a, 0.0}, {0.0, c}};
  p.central_inertia = Eigen::Vector3d(ig * ig + 0.01, ig * ig, 0.05).asDiagonal();
  p.mu_s = p.mu_k = mu;
  return p;
}

/// The planar body of rhombus(a, c, h, ig, mu) in its x-z plane: width 2a.
inline BodyParameters planar_rhombus(double a, double h, double ig, double mu) {
  BodyParameters x;
  x.width = 2 * a;
  x.cg_height = h;
  x.radius_of_gyration = ig;
  x.mu_s = x.mu_k = mu;
  return x;
}

/// A homogeneous regular hexagonal prism (circumradius a, length along y) lying on a rectangular
/// side: the base is that side, the hull its 12 corners (a body whose hull rolls, issue 40).
inline BaseBodyParameters hexagonal_prism(double a, double length) {
  BaseBodyParameters p;
  const double ap = a * std::sqrt(3.0) / 2.0;
  p.centre_of_mass = {0.0, length / 2.0, ap};
  const double ix = 5.0 * a * a / 24.0 + length * length / 12.0;
  p.central_inertia = Eigen::Vector3d(ix, 5.0 * a * a / 12.0, ix).asDiagonal();
  p.base = {{-a / 2, 0.0}, {a / 2, 0.0}, {a / 2, length}, {-a / 2, length}};
  const double xz[6][2] = {{-a / 2, 0}, {a / 2, 0}, {a, ap}, {a / 2, 2 * ap}, {-a / 2, 2 * ap}, {-a, ap}};
  for (double y : {0.0, length})
    for (const auto& v : xz) p.hull.emplace_back(v[0], y, v[1]);
  return p;
}

/// Homogeneous symmetric rectangle with given p (rad/s) and alpha (rad): for a rectangle
/// I_O = (4/3) m R^2, so p^2 = 3 g / (4 R).
inline BodyParameters rectangle_with(double p, double alpha) {
  const double r = 3.0 * kGravity / (4.0 * p * p);
  BodyParameters b;
  b.width = 2.0 * r * std::sin(alpha);
  b.cg_height = r * std::cos(alpha);
  return b;
}

/// One-sine pulse a_p sin(w t) for 0 <= t <= 2 pi / w, then zeros until t_end; sampled at dt.
inline GroundMotion one_sine_pulse(double a_p, double w, double dt, double t_end) {
  GroundMotion g;
  g.dt = dt;
  const double tp = 2.0 * kPi / w;
  const auto n = static_cast<std::size_t>(std::llround(t_end / dt)) + 1;
  g.horizontal.resize(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    g.horizontal[i] = t <= tp ? a_p * std::sin(w * t) : 0.0;
  }
  return g;
}

inline double deg(double d) { return d * kPi / 180.0; }

/// Default settings at a tolerance tight enough to compare two models' states closely.
inline SolverSettings tight_settings(double tol = 1e-10) {
  SolverSettings s;
  s.tol = tol;
  return s;
}

#ifdef ROCKING_RECORDS_DIR
/// The first horizontal component of a real record under ROCKING_RECORDS_DIR (../shared/records),
/// unscaled; false, with a printed notice, when the file is absent (the caller skips that case).
inline bool first_horizontal(const std::string& relative, GroundMotion& out) {
  const std::string path = std::string(ROCKING_RECORDS_DIR) + "/" + relative;
  if (!std::ifstream(path).good()) {
    std::printf("[ notice ] %s not found: record skipped\n", path.c_str());
    return false;
  }
  for (const Component& c : read_record(path)) {
    if (c.vertical) continue;
    out = make_ground_motion(c, nullptr, 1.0);
    return true;
  }
  return false;
}
#endif

/// Runs a shell command (tests of the command-line tools); `out` is its standard output (append
/// 2>&1 to the command to capture errors too), `status` its exit status (-1 if it did not exit).
struct CommandResult {
  int status = -1;
  std::string out;
};
inline CommandResult run_command(const std::string& cmd) {
  CommandResult r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), pipe) != nullptr) r.out += buf.data();
  const int st = pclose(pipe);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

/// A number as a command-line argument that reads back to the same double (17 significant digits).
inline std::string exact_number(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

}  // namespace rocking_monitor::core::testing
