#pragma once

// What an item stands on when it is not the floor (issue 51): the top of a plinth, shelf or pedestal,
// a convex polygon in the item's frame. The contact is the base where it lies on the support (their
// intersection), and the item falls off when its centre of mass passes the support's edge.

#include <string>
#include <vector>

#include <Eigen/Core>

namespace rocking_monitor::core {

/// Empty when `polygon` is a valid contact polygon (>= 3 finite vertices, no two coinciding, strictly
/// convex and counter-clockwise), else "<problem>" (the caller names the field).
std::string polygon_problem(const std::vector<Eigen::Vector2d>& polygon);

/// The intersection of two convex counter-clockwise polygons (Sutherland-Hodgman), counter-clockwise,
/// without repeated or collinear vertices (within 1e-9 of the polygons' size); empty when they do not
/// overlap in an area.
std::vector<Eigen::Vector2d> clip_convex(const std::vector<Eigen::Vector2d>& subject,
                                         const std::vector<Eigen::Vector2d>& clip);

/// Signed distance of x from the polygon's boundary, m: > 0 inside (the nearest edge's distance),
/// < 0 outside (beyond the edge it is furthest beyond).
double inside_margin(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& x);

/// The first of `points` that lies more than `tol` (m) outside `polygon` (or whose margin is not a
/// number), -1 when all lie within it.
int first_outside(const std::vector<Eigen::Vector2d>& points, const std::vector<Eigen::Vector2d>& polygon,
                  double tol);

}  // namespace rocking_monitor::core
