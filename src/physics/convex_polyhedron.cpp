#include "rocking_monitor/physics/convex_polyhedron.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <Eigen/Geometry>

namespace rocking_monitor::core {
namespace {

double cross2(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// The points of `on` as a strictly convex polygon, counter-clockwise about `normal` (Andrew's chain).
std::vector<int> face_polygon(const std::vector<Eigen::Vector3d>& pts, const std::vector<int>& on,
                              const Eigen::Vector3d& normal, double tolerance) {
  const Eigen::Vector3d u = normal.unitOrthogonal(), w = normal.cross(u);
  std::vector<std::pair<Eigen::Vector2d, int>> p;
  for (int i : on) p.push_back({Eigen::Vector2d(pts[i].dot(u), pts[i].dot(w)), i});
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) {
    return a.first.x() < b.first.x() || (a.first.x() == b.first.x() && a.first.y() < b.first.y());
  });
  std::vector<std::pair<Eigen::Vector2d, int>> h(2 * p.size());
  std::size_t k = 0;
  // A turn counts as left only beyond the tolerance times the chord: collinear points are dropped.
  auto left = [&](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return cross2(o, a, b) > tolerance * (b - o).norm();
  };
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && !left(h[k - 2].first, h[k - 1].first, p[i].first)) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && !left(h[k - 2].first, h[k - 1].first, p[i].first)) --k;
    h[k++] = p[i];
  }
  std::vector<int> out;
  for (std::size_t i = 0; i + 1 < k; ++i) out.push_back(h[i].second);
  return out;
}

}  // namespace

int ConvexPolyhedron::face_across(int f, int a, int b) const {
  for (int g = 0; g < static_cast<int>(faces.size()); ++g) {
    if (g == f) continue;
    const std::vector<int>& v = faces[static_cast<std::size_t>(g)].vertices;
    const int n = static_cast<int>(v.size());
    for (int i = 0; i < n; ++i)
      if (v[static_cast<std::size_t>(i)] == b && v[static_cast<std::size_t>((i + 1) % n)] == a) return g;
  }
  return -1;
}

ConvexPolyhedron convex_polyhedron(const std::vector<Eigen::Vector3d>& points, double tolerance) {
  const int n = static_cast<int>(points.size());
  double extent = 0.0;
  for (const auto& p : points) extent = std::max(extent, (p - points.front()).norm());
  if (n < 4 || !(extent > 0.0)) throw std::invalid_argument("the hull needs at least 4 points that span a volume");
  // Faces by the set of input points on them (each plane is found once per triple on it).
  std::map<std::vector<int>, PolyhedronFace> found;
  std::vector<int> on;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k) {
        Eigen::Vector3d nrm = (points[j] - points[i]).cross(points[k] - points[i]);
        const double len = nrm.norm();
        if (!(len > 1e-9 * extent * extent)) continue;
        nrm /= len;
        bool above = false, below = false;
        for (int m = 0; m < n && !(above && below); ++m) {
          const double d = nrm.dot(points[m] - points[i]);
          above |= d > tolerance;
          below |= d < -tolerance;
        }
        if (above && below) continue;  // an inner plane (most triples end here after a few points)
        if (above) nrm = -nrm;         // outward: every point on the inner side
        on.clear();
        for (int m = 0; m < n; ++m)
          if (std::abs(nrm.dot(points[m] - points[i])) <= tolerance) on.push_back(m);
        if (found.count(on)) continue;
        PolyhedronFace f;
        f.normal = nrm;
        f.vertices = face_polygon(points, on, nrm, tolerance);
        if (f.vertices.size() < 3) continue;
        double off = 0.0;
        for (int v : f.vertices) off += nrm.dot(points[v]);
        f.offset = off / static_cast<double>(f.vertices.size());
        found.emplace(on, f);
      }
  if (found.size() < 4) throw std::invalid_argument("the hull needs at least 4 points that span a volume");
  // Vertices: the input points that are a corner of some face, in input order.
  std::vector<int> index(static_cast<std::size_t>(n), -1);
  for (const auto& kv : found)
    for (int v : kv.second.vertices) index[static_cast<std::size_t>(v)] = 0;
  ConvexPolyhedron out;
  for (int i = 0; i < n; ++i)
    if (index[static_cast<std::size_t>(i)] == 0) {
      index[static_cast<std::size_t>(i)] = static_cast<int>(out.points.size());
      out.points.push_back(points[static_cast<std::size_t>(i)]);
      out.source.push_back(i);
    }
  out.neighbours.resize(out.points.size());
  for (auto& kv : found) {
    PolyhedronFace f = kv.second;
    for (int& v : f.vertices) v = index[static_cast<std::size_t>(v)];
    const std::size_t m = f.vertices.size();
    for (std::size_t i = 0; i < m; ++i) {
      const int a = f.vertices[i], b = f.vertices[(i + 1) % m];
      auto& na = out.neighbours[static_cast<std::size_t>(a)];
      if (std::find(na.begin(), na.end(), b) == na.end()) na.push_back(b);
      auto& nb = out.neighbours[static_cast<std::size_t>(b)];
      if (std::find(nb.begin(), nb.end(), a) == nb.end()) nb.push_back(a);
    }
    out.faces.push_back(std::move(f));
  }
  for (auto& nb : out.neighbours) std::sort(nb.begin(), nb.end());
  return out;
}

}  // namespace rocking_monitor::core
