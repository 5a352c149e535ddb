#pragma once

// A body's contact geometry (issue 40 part 3): the convex hull of its mesh, over which the contact
// moves as the body tilts beyond its base. Every hull face is a base the body may rest or rock on
// (in that face's own floor frame, as a BaseBody); every hull vertex a point it may pivot on.

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "rocking_monitor/physics/base_body.hpp"

namespace rocking_monitor::core {

/// One hull face as a base.
struct HullFace {
  std::shared_ptr<const BaseBody> body;  ///< the body standing on this face, in the face's floor frame
  /// The face's floor frame: a point x of the item frame is at rotation * x + offset (the face on
  /// z = 0, the body above it). Identity and zero for the base (face 0).
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  std::vector<int> hull_vertex;  ///< face vertex k (the face body's vertex k) -> hull vertex
  std::vector<int> across;       ///< face edge k -> the hull face across it (-1: none, no hull)
  /// Face edge k: the rotation about it (theta of the face body's edge k) at which the face across
  /// lies flat on the floor, rad (+inf: no face across).
  std::vector<double> fold;
};

struct ContactHull {
  /// Every hull vertex in the item frame (position, inertia about it, ...); the first n are the
  /// base's n vertices in the base's order.
  std::vector<BaseVertex> vertices;
  /// Per hull vertex, the vertices that can touch the floor first when the body pivots on it: its
  /// hull neighbours (without a hull: every other base vertex).
  std::vector<std::vector<int>> neighbours;
  std::vector<HullFace> faces;  ///< face 0: the base
  bool from_hull = false;       ///< built from BaseBodyParameters::hull
  /// The face the body lies on when the hull's points within `tolerance` of the floor are those of
  /// `rotation` (item -> world); the face whose outward normal points most nearly down.
  int face_down(const Eigen::Matrix3d& rotation) const;
  /// Of the two faces at the hull edge between vertices a and b, the one to rock on in pose
  /// `rotation` (item -> world): the nearer to flat of those the centre of mass lies inside of (edge
  /// alpha > 0; one always does), and that edge's index in it. False if a, b is not a hull edge.
  bool face_with_edge(int a, int b, const Eigen::Matrix3d& rotation, int& face, int& edge) const;
};

}  // namespace rocking_monitor::core
