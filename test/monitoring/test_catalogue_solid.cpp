// The catalogue's 3-D description of an item (base_polygon, centre_of_mass, central_inertia, mass,
// restitution_factor, hull): read as given, and every bad value refused naming the item and the field.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "rocking_monitor/monitoring/catalogue.hpp"

namespace rocking_monitor::core {
namespace {

using nlohmann::json;

json item() {
  return json::parse(R"({"id": "vase", "width": 0.2, "cg_height": 0.3, "mass": 12.0,
    "centre_of_mass": [0.1, 0.05, 0.3],
    "central_inertia": [[0.5, 0.01, 0.0], [0.01, 0.6, 0.02], [0.0, 0.02, 0.2]],
    "base_polygon": [[0, 0], [0.2, 0], [0.15, 0.12], [0.0, 0.1]], "restitution_factor": 0.9})");
}

std::string error_of(const json& entry) {
  try {
    parse_catalogue_items(json::array({entry}));
  } catch (const CatalogueError& e) {
    return e.what();
  }
  return "";
}

TEST(CatalogueSolid, TheThreeDimensionalDescriptionIsReadAsGiven) {
  const auto items = parse_catalogue_items(json::array({item()}));
  ASSERT_TRUE(items[0].spec.solid.has_value());
  const BaseBodyParameters& b = *items[0].spec.solid;
  EXPECT_EQ(b.mass, 12.0);
  EXPECT_EQ(b.centre_of_mass.y(), 0.05);
  EXPECT_EQ(b.central_inertia(1, 2), 0.02);
  ASSERT_EQ(b.base.size(), 4u);
  EXPECT_EQ(b.base[2].x(), 0.15);
  EXPECT_EQ(b.restitution_factor, 0.9);
  json planar = item();
  for (const char* k : {"mass", "centre_of_mass", "central_inertia", "base_polygon", "restitution_factor"}) planar.erase(k);
  EXPECT_FALSE(parse_catalogue_items(json::array({planar}))[0].spec.solid.has_value());
}

// A hull: the base's corners and four points above them (a frustum), read as given and built.
json with_hull() {
  json e = item();
  e["hull"] = json::parse("[[0, 0, 0.5], [0.2, 0, 0.5], [0.15, 0.12, 0.5], [0.0, 0.1, 0.5], [0.2, 0, 0]]");
  return e;
}

TEST(CatalogueSolid, AHullIsReadAndChecked) {
  const auto items = parse_catalogue_items(json::array({with_hull()}));
  const BaseBodyParameters& b = *items[0].spec.solid;
  ASSERT_EQ(b.hull.size(), 5u);
  EXPECT_EQ(b.hull[2].y(), 0.12);
  EXPECT_EQ(BaseBody(b).contact_hull().faces.size(), 6u);  // a prism over the quadrilateral
  json e = with_hull();
  e["hull"][1] = json::array({0.2, 0.0});
  EXPECT_NE(error_of(e).find("'vase': hull: point 2 [x, y, z] (m): must have 3 numbers, found 2"), std::string::npos) << error_of(e);
  e = with_hull();
  e["hull"][0][2] = -0.1;
  EXPECT_NE(error_of(e).find("'vase': hull: point 1 lies below the floor"), std::string::npos) << error_of(e);
  e = with_hull();
  e["hull"].push_back(json::array({0.3, 0.05, 0.0}));
  EXPECT_NE(error_of(e).find("'vase': hull: point 6 lies on the floor outside base_polygon"), std::string::npos) << error_of(e);
  json planar = with_hull();
  for (const char* k : {"mass", "centre_of_mass", "central_inertia", "base_polygon", "restitution_factor"}) planar.erase(k);
  EXPECT_NE(error_of(planar).find("hull: needs the 3-D description"), std::string::npos) << error_of(planar);
}

TEST(CatalogueSolid, BadValuesNameTheItemAndTheField) {
  json e = item();
  e.erase("mass");
  EXPECT_NE(error_of(e).find("'vase': mass: missing"), std::string::npos) << error_of(e);
  e = item();
  e["centre_of_mass"] = json::array({0.1, 0.05});
  EXPECT_NE(error_of(e).find("centre_of_mass: [x, y, z] in m: must have 3 numbers, found 2"), std::string::npos) << error_of(e);
  e = item();
  e["central_inertia"][1][0] = 0.3;  // not symmetric
  EXPECT_NE(error_of(e).find("central_inertia: must be a symmetric matrix"), std::string::npos) << error_of(e);
  e = item();
  e["base_polygon"] = json::parse("[[0, 0], [0, 0.1], [0.2, 0], [0.15, 0.12]]");  // clockwise start
  EXPECT_NE(error_of(e).find("base_polygon: not strictly convex and counter-clockwise"), std::string::npos) << error_of(e);
  e = item();
  e["base_polygon"][1] = "x";
  EXPECT_NE(error_of(e).find("base_polygon: vertex 2 [x, y] (m): must be a list"), std::string::npos) << error_of(e);
  e = item();
  e["centre_of_mass"][0] = 0.5;
  EXPECT_NE(error_of(e).find("centre_of_mass: its plan position lies outside the base polygon"), std::string::npos) << error_of(e);
  e = item();
  e["restitution_factor"] = 1.2;
  EXPECT_NE(error_of(e).find("restitution_factor: must lie in [0, 1]"), std::string::npos) << error_of(e);
  json planar = item();
  for (const char* k : {"mass", "centre_of_mass", "central_inertia", "base_polygon"}) planar.erase(k);
  EXPECT_NE(error_of(planar).find("restitution_factor: needs the 3-D description"), std::string::npos) << error_of(planar);
}

}  // namespace
}  // namespace rocking_monitor::core
