#include "rocking_monitor/physics/support_polygon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rocking_monitor::core {
namespace {

double support_cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

double extent_of(const std::vector<Eigen::Vector2d>& p) {
  double e = 0.0;
  for (const auto& v : p) e = std::max(e, (v - p[0]).norm());
  return e;
}

}  // namespace

std::string polygon_problem(const std::vector<Eigen::Vector2d>& p) {
  const std::size_t n = p.size();
  if (n < 3) return "needs at least 3 vertices, found " + std::to_string(n);
  for (std::size_t i = 0; i < n; ++i)
    if (!p[i].allFinite()) return "vertex " + std::to_string(i + 1) + " is not finite";
  const double extent = extent_of(p);
  if (!(extent > 0.0)) return "all vertices coincide";
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = p[i];
    const Eigen::Vector2d& b = p[(i + 1) % n];
    const Eigen::Vector2d& c = p[(i + 2) % n];
    if ((b - a).norm() <= 1e-9 * extent)
      return "vertices " + std::to_string(i + 1) + " and " + std::to_string((i + 1) % n + 1) + " coincide";
    // Strictly convex and counter-clockwise: every turn to the left (a collinear vertex would make
    // an edge of zero length in the hull's sense: rocking about it is rocking about its neighbours).
    if (support_cross(b - a, c - b) <= 1e-12 * extent * extent)
      return "not strictly convex and counter-clockwise at vertex " + std::to_string((i + 1) % n + 1) +
             " (seen from above)";
  }
  return {};
}

std::vector<Eigen::Vector2d> clip_convex(const std::vector<Eigen::Vector2d>& subject,
                                         const std::vector<Eigen::Vector2d>& clip) {
  std::vector<Eigen::Vector2d> out = subject, in;
  for (std::size_t k = 0; k < clip.size() && !out.empty(); ++k) {
    const Eigen::Vector2d a = clip[k], e = clip[(k + 1) % clip.size()] - a;
    auto side = [&](const Eigen::Vector2d& x) { return support_cross(e, x - a); };  // >= 0: inside (left)
    in.swap(out);
    out.clear();
    for (std::size_t i = 0; i < in.size(); ++i) {
      const Eigen::Vector2d& p = in[i];
      const Eigen::Vector2d& q = in[(i + 1) % in.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0.0) out.push_back(p);
      if ((sp >= 0.0) != (sq >= 0.0)) out.push_back(p + (q - p) * (sp / (sp - sq)));
    }
  }
  // Drop repeated and collinear vertices (a support edge along a base edge leaves both).
  const double tol = 1e-9 * std::max(extent_of(subject), extent_of(clip));
  for (bool changed = true; changed && out.size() >= 3;) {
    changed = false;
    for (std::size_t i = 0; i < out.size() && out.size() >= 3; ++i) {
      const Eigen::Vector2d& a = out[(i + out.size() - 1) % out.size()];
      const Eigen::Vector2d& b = out[i];
      const Eigen::Vector2d& c = out[(i + 1) % out.size()];
      if ((b - a).norm() <= tol || std::abs(support_cross(b - a, c - b)) <= tol * std::max((c - a).norm(), tol)) {
        out.erase(out.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
      }
    }
  }
  if (out.size() < 3) out.clear();
  return out;
}

double inside_margin(const std::vector<Eigen::Vector2d>& p, const Eigen::Vector2d& x) {
  double m = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Eigen::Vector2d e = p[(k + 1) % p.size()] - p[k];
    m = std::min(m, support_cross(e, x - p[k]) / e.norm());
  }
  return m;
}

int first_outside(const std::vector<Eigen::Vector2d>& points, const std::vector<Eigen::Vector2d>& polygon,
                  double tol) {
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!(inside_margin(polygon, points[i]) >= -tol)) return static_cast<int>(i);
  return -1;
}

}  // namespace rocking_monitor::core
