// The convex hull of a point set (physics/convex_polyhedron.hpp) and a body's contact hull
// (physics/contact_hull.hpp): counts and normals against shapes whose hull is known, Euler's formula
// and containment on random clouds, the folds between faces, and clear errors for a bad hull.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <string>

#include <Eigen/Geometry>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/physics/contact_hull.hpp"
#include "rocking_monitor/physics/convex_polyhedron.hpp"
#include "test_helpers.hpp"

namespace rocking_monitor::core {
namespace {

std::vector<Eigen::Vector3d> cube_with_inner_points() {
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i < 8; ++i) p.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  p.emplace_back(0.5, 0.5, 0.5);  // inside
  p.emplace_back(0.5, 0.5, 1.0);  // the middle of the top face: on it, not a corner
  p.emplace_back(1.0, 0.5, 0.0);  // the middle of an edge
  return p;
}

TEST(ConvexPolyhedron, ACubeHasEightCornersSixSquareFacesAndThreeNeighboursPerCorner) {
  const ConvexPolyhedron h = convex_polyhedron(cube_with_inner_points(), 1e-9);
  ASSERT_EQ(h.points.size(), 8u);
  ASSERT_EQ(h.faces.size(), 6u);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(h.source[i], static_cast<int>(i));  // the input's order
  for (const auto& f : h.faces) {
    EXPECT_EQ(f.vertices.size(), 4u);
    EXPECT_NEAR(f.normal.cwiseAbs().maxCoeff(), 1.0, 1e-15);  // axis-aligned
    EXPECT_NEAR(f.offset, f.normal.sum() > 0 ? 1.0 : 0.0, 1e-15);
  }
  for (const auto& nb : h.neighbours) EXPECT_EQ(nb.size(), 3u);
}

// Euler's formula V - E + F = 2, every point inside every face's plane, every face convex and
// counter-clockwise seen from outside, the face across every edge found.
TEST(ConvexPolyhedron, RandomCloudsObeyEulerAndContainEveryPoint) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n01;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Eigen::Vector3d> p;
    for (int i = 0; i < 60; ++i) p.emplace_back(n01(rng), 0.5 * n01(rng), 2.0 * n01(rng));
    const ConvexPolyhedron h = convex_polyhedron(p, 1e-12);
    std::size_t edges = 0;
    for (std::size_t f = 0; f < h.faces.size(); ++f) {
      const auto& v = h.faces[f].vertices;
      edges += v.size();
      for (std::size_t k = 0; k < v.size(); ++k) {
        const Eigen::Vector3d& a = h.points[v[k]];
        const Eigen::Vector3d& b = h.points[v[(k + 1) % v.size()]];
        const Eigen::Vector3d& c = h.points[v[(k + 2) % v.size()]];
        EXPECT_GT((b - a).cross(c - b).dot(h.faces[f].normal), 0.0);
        EXPECT_GE(h.face_across(static_cast<int>(f), v[k], v[(k + 1) % v.size()]), 0);
      }
      for (const auto& q : p) EXPECT_LE(h.faces[f].normal.dot(q) - h.faces[f].offset, 1e-12);
    }
    EXPECT_EQ(edges % 2, 0u);
    EXPECT_EQ(static_cast<long>(h.points.size()) - static_cast<long>(edges / 2) + static_cast<long>(h.faces.size()), 2)
        << "trial " << trial;
  }
}

TEST(ConvexPolyhedron, PointsThatSpanNoVolumeAreRefused) {
  EXPECT_THROW(convex_polyhedron({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, 1e-9), std::invalid_argument);
  EXPECT_THROW(convex_polyhedron({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 1e-9), std::invalid_argument);
}

using testing::hexagonal_prism;

TEST(ContactHull, APrismLyingOnASideHasItsFacesAsBasesWithSixtyDegreeFolds) {
  const BaseBody body(hexagonal_prism(0.1, 0.5));
  const ContactHull& h = body.contact_hull();
  ASSERT_TRUE(h.from_hull);
  EXPECT_EQ(h.vertices.size(), 12u);  // the base's corners are hull points listed once
  ASSERT_EQ(h.faces.size(), 8u);
  for (int k = 0; k < 4; ++k)  // face 0 is the base, in its own order
    EXPECT_EQ((h.vertices[k].position - Eigen::Vector3d(body.vertex(k).position)).norm(), 0.0);
  // the long edges fold onto the next side at 60 degrees, the ends onto the hexagons at 90
  EXPECT_NEAR(h.faces[0].fold[1], kPi / 3.0, 1e-12);
  EXPECT_NEAR(h.faces[0].fold[3], kPi / 3.0, 1e-12);
  EXPECT_NEAR(h.faces[0].fold[0], kPi / 2.0, 1e-12);
  int sides = 0;
  for (const auto& f : h.faces) {
    // every face's body sees the same inertia about the same centre: the prism's axis is horizontal
    // on a rectangular side, vertical on a hexagon
    EXPECT_NEAR(f.body->parameters().central_inertia.trace(), body.parameters().central_inertia.trace(), 1e-12);
    if (f.body->vertex_count() == 4) {
      ++sides;
      EXPECT_TRUE(f.body->stands());
      EXPECT_NEAR(f.body->centre_of_mass().z(), 0.1 * std::sqrt(3.0) / 2.0, 1e-12);  // the apothem
    }
  }
  EXPECT_EQ(sides, 6);
}

TEST(ContactHull, ABadHullNamesTheFieldAndThePoint) {
  auto message = [](const BaseBodyParameters& p) {
    try {
      BaseBody b(p);
    } catch (const BodyError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  BaseBodyParameters p = hexagonal_prism(0.1, 0.5);
  p.hull[3].z() = -0.01;
  EXPECT_NE(message(p).find("hull: point 4 lies below the floor"), std::string::npos) << message(p);
  p = hexagonal_prism(0.1, 0.5);
  p.hull.emplace_back(0.0, 0.25, -0.0);
  p.hull.back().x() = 0.08;  // on the floor, beyond the base's edge x = a/2
  EXPECT_NE(message(p).find("on the floor outside base_polygon"), std::string::npos) << message(p);
  p = hexagonal_prism(0.1, 0.5);
  p.centre_of_mass.z() = 0.5;  // above the prism
  EXPECT_NE(message(p).find("the centre of mass is not inside the hull"), std::string::npos) << message(p);
  p = hexagonal_prism(0.1, 0.5);
  p.hull.resize(3);
  p.hull = {Eigen::Vector3d(0, 0, 0.1)};  // with the base: a pyramid below the centre of mass
  EXPECT_NE(message(p).find("hull:"), std::string::npos) << message(p);
}

}  // namespace
}  // namespace rocking_monitor::core
