#pragma once

// The convex hull of a point set in 3-D (issue 40 part 3: a body's contact geometry is the hull of its
// mesh, not only the patch it stands on). Small sets (a catalogue's hull has at most a few hundred
// points): every plane through three points that has all points on one side is a face plane; the
// points on it, as a convex polygon, are the face. Coplanar triangles come out as one polygonal face,
// which is what the rocking model needs (a face is a flat rest, its edges are rocking axes).

#include <stdexcept>
#include <vector>

#include <Eigen/Core>

namespace rocking_monitor::core {

struct PolyhedronFace {
  std::vector<int> vertices;  ///< indices into ConvexPolyhedron::points, counter-clockwise seen from outside
  Eigen::Vector3d normal;     ///< outward unit normal
  double offset = 0.0;        ///< normal . x = offset for points on the face, m
};

struct ConvexPolyhedron {
  std::vector<Eigen::Vector3d> points;     ///< the hull's vertices (only those), m
  std::vector<int> source;                 ///< each vertex's index in the input
  std::vector<PolyhedronFace> faces;
  std::vector<std::vector<int>> neighbours;  ///< per vertex: the vertices joined to it by a hull edge
  /// The face across the edge from vertex a to vertex b of face f (a -> b as listed in f), or -1.
  int face_across(int f, int a, int b) const;
};

/// Throws std::invalid_argument when the points do not span a volume (fewer than 4 points off one
/// plane). Points within `tolerance` (m) of a face's plane lie on it; vertices keep the input's order.
ConvexPolyhedron convex_polyhedron(const std::vector<Eigen::Vector3d>& points, double tolerance);

}  // namespace rocking_monitor::core
