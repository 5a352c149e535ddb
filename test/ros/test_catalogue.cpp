// Catalogue parsing: every bad field gives one line naming the entry and the field (no ROS master).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <initializer_list>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "rocking_monitor/monitoring/catalogue_file.hpp"
#include "rocking_monitor/ros/catalogue.hpp"

namespace rocking_monitor::live {
namespace {

using XmlRpc::XmlRpcValue;

XmlRpcValue sensors() {
  XmlRpcValue s;
  s[0]["name"] = "floor";
  s[0]["topic"] = "/floor/imu";
  return s;
}

XmlRpcValue one_item() {
  XmlRpcValue i;
  i[0]["id"] = "cabinet";
  i[0]["sensor"] = "floor";
  i[0]["width"] = 0.5;
  i[0]["cg_height"] = 0.9;
  return i;
}

std::string error_of(const XmlRpcValue& s, const XmlRpcValue& i) {
  try {
    parse_catalogue(s, i);
  } catch (const CatalogueError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(Catalogue, ValidEntryWithDefaults) {
  const Catalogue c = parse_catalogue(sensors(), one_item());
  ASSERT_EQ(c.items.size(), 1u);
  const core::ItemSpec& s = c.items[0].spec;
  EXPECT_EQ(s.frame, "cabinet");  // defaults to the id
  EXPECT_DOUBLE_EQ(s.body.nu1, 0.5);
  EXPECT_TRUE(std::isnan(s.body.radius_of_gyration));  // homogeneous box
  EXPECT_EQ(c.sensors[0].type, SensorSpec::Type::Imu);
  EXPECT_DOUBLE_EQ(c.sensors[0].rate, 200.0);
}

TEST(Catalogue, CylinderShapeSetsItsRadiusOfGyration) {
  XmlRpcValue i = one_item();
  i[0]["shape"] = "cylinder";
  const Catalogue c = parse_catalogue(sensors(), i);
  // Solid cylinder, diameter B, length 2h, about a transverse axis: i^2 = B^2/16 + h^2/3.
  EXPECT_NEAR(c.items[0].spec.body.radius_of_gyration, std::sqrt(0.25 / 16 + 0.81 / 3), 1e-15);
}

TEST(Catalogue, DepthAddsTheYPlane) {
  const Catalogue single = parse_catalogue(sensors(), one_item());
  EXPECT_FALSE(single.items[0].spec.two_planes());
  XmlRpcValue i = one_item();
  i[0]["depth"] = 0.4;
  const Catalogue c = parse_catalogue(sensors(), i);
  const core::ItemSpec& s = c.items[0].spec;
  ASSERT_TRUE(s.two_planes());
  EXPECT_DOUBLE_EQ(s.depth.depth, 0.4);
  EXPECT_DOUBLE_EQ(s.depth.eccentricity_y, 0.5);
  EXPECT_TRUE(std::isnan(s.depth.radius_of_gyration_y));  // homogeneous block in both planes
  // A cylinder with a depth (an elliptic base): each plane with its own diameter.
  i[0]["shape"] = "cylinder";
  i[0]["eccentricity_y"] = 0.45;
  const Catalogue cyl = parse_catalogue(sensors(), i);
  EXPECT_NEAR(cyl.items[0].spec.depth.radius_of_gyration_y, std::sqrt(0.16 / 16 + 0.81 / 3), 1e-15);
  EXPECT_DOUBLE_EQ(cyl.items[0].spec.depth.eccentricity_y, 0.45);
}

TEST(Catalogue, BadDepthFieldsAreNamed) {
  auto with = [](std::initializer_list<std::pair<const char*, XmlRpcValue>> kv) {
    XmlRpcValue i = one_item();
    for (const auto& [k, v] : kv) i[0][k] = v;
    return error_of(sensors(), i);
  };
  EXPECT_EQ(with({{"depth", -0.4}}), "items[0] 'cabinet': depth = -0.4 (must be a finite length > 0 m)");
  EXPECT_EQ(with({{"depth", 0.0}}), "items[0] 'cabinet': depth = 0 (must be a finite length > 0 m)");
  EXPECT_EQ(with({{"depth", std::nan("")}}), "items[0] 'cabinet': depth: must be finite");
  EXPECT_NE(with({{"depth", "deep"}}).find("items[0] 'cabinet': depth: must be a number"), std::string::npos);
  EXPECT_EQ(with({{"depth", 0.4}, {"eccentricity_y", 1.0}}),
            "items[0] 'cabinet': eccentricity_y = 1 (must lie strictly between 0 and 1)");
  EXPECT_EQ(with({{"depth", 0.4}, {"eccentricity_y", 0.0}}),
            "items[0] 'cabinet': eccentricity_y = 0 (must lie strictly between 0 and 1)");
  EXPECT_EQ(with({{"depth", 0.4}, {"eccentricity_y", -std::nan("")}}), "items[0] 'cabinet': eccentricity_y: must be finite");
  EXPECT_EQ(with({{"depth", 0.4}, {"radius_of_gyration_y", -0.1}}),
            "items[0] 'cabinet': radius_of_gyration_y = -0.1 (must be a finite length > 0 m)");
  EXPECT_NE(with({{"eccentricity_y", 0.4}}).find("items[0] 'cabinet': eccentricity_y: needs depth"), std::string::npos);
}

TEST(Catalogue, ShardsByAStableHashOfTheId) {
  // FNV-1a 64-bit test vectors (Fowler, Noll, Vo): "a" -> 0xaf63dc4c8601ec8c, "foobar" -> 0x85944171f73967e8.
  EXPECT_EQ(shard_of("a", 1000), static_cast<int>(0xaf63dc4c8601ec8cull % 1000) + 1);
  EXPECT_EQ(shard_of("foobar", 7), static_cast<int>(0x85944171f73967e8ull % 7) + 1);
  // 10,000 ids in 4 shards: each in exactly one, the shards within 10 % of n/4.
  XmlRpcValue items;
  for (int i = 0; i < 10000; ++i) {
    items[i]["id"] = "item" + std::to_string(i);
    items[i]["sensor"] = "floor";
    items[i]["width"] = 0.5;
    items[i]["cg_height"] = 0.9;
  }
  const Catalogue all = parse_catalogue(sensors(), items);
  std::size_t total = 0;
  for (int k = 1; k <= 4; ++k) {
    const Catalogue part = select_shard(all, k, 4);
    EXPECT_NEAR(static_cast<double>(part.items.size()), 2500.0, 250.0) << "shard " << k;
    for (const CatalogueItem& it : part.items) EXPECT_EQ(shard_of(it.spec.id, 4), k);
    total += part.items.size();
  }
  EXPECT_EQ(total, all.items.size());
  EXPECT_EQ(parse_shard("2/3"), std::make_pair(2, 3));
  for (const char* bad : {"0/2", "3/2", "2", "1/0", "a/b", "1/2x", "-1/2"}) {
    try {
      parse_shard(bad);
      ADD_FAILURE() << bad << " accepted";
    } catch (const CatalogueError& e) {
      EXPECT_EQ(std::string(e.what()), std::string("shard: '") + bad + "' is not k/n with 1 <= k <= n (e.g. 2/3)");
    }
  }
}

TEST(Catalogue, BadFieldsAreNamed) {
  auto with = [](const char* key, XmlRpcValue v) {
    XmlRpcValue i = one_item();
    i[0][key] = v;
    return error_of(sensors(), i);
  };
  EXPECT_EQ(with("width", -0.5), "items[0] 'cabinet': width = -0.5 (must be a finite length > 0 m)");
  EXPECT_NE(with("width", "wide").find("items[0] 'cabinet': width: must be a number"), std::string::npos);
  EXPECT_NE(with("eccentricity", 1.3).find("items[0] 'cabinet': eccentricity nu1 = 1.3"), std::string::npos);
  EXPECT_NE(with("mu_s", -1).find("items[0] 'cabinet': mu_s = -1"), std::string::npos);
  EXPECT_NE(with("sensor", "attic").find("items[0] 'cabinet': sensor: 'attic' is not a sensor"), std::string::npos);
  EXPECT_NE(with("shape", "sphere").find("items[0] 'cabinet': shape: 'sphere'"), std::string::npos);
  EXPECT_NE(with("widht", 0.3).find("items[0] 'cabinet': widht: unknown key"), std::string::npos);
  EXPECT_NE(with("restitution", 2.0).find("restitution = 2"), std::string::npos);

  XmlRpcValue missing = one_item();
  missing[0] = XmlRpcValue();
  missing[0]["id"] = "vase";
  missing[0]["sensor"] = "floor";
  missing[0]["width"] = 0.2;
  EXPECT_EQ(error_of(sensors(), missing), "items[0] 'vase': cg_height: missing (height h of the centre of mass, m)");

  XmlRpcValue dup = one_item();
  const XmlRpcValue first = dup[0];
  dup[1] = first;
  EXPECT_EQ(error_of(sensors(), dup), "items[1] 'cabinet': id: duplicate id");

  XmlRpcValue bad_sensor = sensors();
  bad_sensor[0]["type"] = "gyro";
  EXPECT_EQ(error_of(bad_sensor, one_item()), "sensors[0] 'floor': type: 'gyro' is not one of: imu, accel");
  EXPECT_EQ(error_of(XmlRpcValue(), one_item()), "sensors: must be a non-empty list of sensor entries");

  XmlRpcValue pose = one_item();
  pose[0]["pose"]["x"] = 1.0;
  EXPECT_EQ(error_of(sensors(), pose), "items[0] 'cabinet': pose: parent_frame: missing");
}

XmlRpcValue pair(XmlRpcValue a, XmlRpcValue b) {
  XmlRpcValue v;
  v[0] = a;
  v[1] = b;
  return v;
}

XmlRpcValue law(const char* name, XmlRpcValue params) {
  XmlRpcValue v;
  v[name] = params;
  return v;
}

// A YAML node as rosparam loads it: integers, numbers, strings, lists, maps.
XmlRpcValue to_xmlrpc(const YAML::Node& n) {
  XmlRpcValue v;
  if (n.IsMap()) {
    for (const auto& kv : n) v[kv.first.as<std::string>()] = to_xmlrpc(kv.second);
  } else if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i) v[static_cast<int>(i)] = to_xmlrpc(n[i]);
  } else if (n.IsScalar()) {
    const std::string text = n.Scalar();
    int i;
    double d;
    if (n.Tag() != "!" && YAML::convert<int>::decode(n, i) && text.find_first_of(".eE") == std::string::npos) v = i;
    else if (n.Tag() != "!" && YAML::convert<double>::decode(n, d)) v = d;
    else v = text;
  }
  return v;
}

Catalogue load_example(const std::string& file) {
  const YAML::Node root = YAML::LoadFile(std::string(ROCKING_SOURCE_DIR) + "/config/" + file);
  return parse_catalogue(to_xmlrpc(root["sensors"]), to_xmlrpc(root["items"]));
}

TEST(Catalogue, ExampleCataloguesParse) {
  // The demo's catalogue keeps plain numbers: nothing uncertain, the nominal item is the item.
  const Catalogue plain = load_example("catalogue_example.yaml");
  ASSERT_EQ(plain.items.size(), 6u);
  for (const CatalogueItem& item : plain.items) EXPECT_FALSE(item.uncertain.uncertain()) << item.spec.id;
  EXPECT_EQ(plain.items[1].spec.id, "monitor_cart");
  EXPECT_EQ(plain.items[1].spec.body.mu_s, 0.3);
  // The uncertain example: every item uncertain, its members valid.
  const Catalogue uncertain = load_example("catalogue_uncertain_example.yaml");
  ASSERT_EQ(uncertain.items.size(), 4u);
  const CatalogueItem& cart = uncertain.items[0];
  EXPECT_EQ(cart.spec.body.mu_s, 0.3);  // nominal: 0.3
  EXPECT_EQ(cart.uncertain.law(core::UncertainField::MuS).a(), 0.25);
  EXPECT_EQ(cart.spec.body.cg_height, 0.75);
  EXPECT_EQ(uncertain.items[1].spec.body.cg_height, 0.9 * std::exp(0.5 * 0.1 * 0.1));
  for (const CatalogueItem& item : uncertain.items) {
    EXPECT_TRUE(item.uncertain.uncertain()) << item.spec.id;
    std::vector<int> pulled;
    for (const core::ItemSpec& m : core::draw_members(item.uncertain, 32, 13, &pulled))
      EXPECT_EQ(core::validate(m), "") << item.spec.id;
    EXPECT_TRUE(pulled.empty()) << item.spec.id;
  }
}

TEST(Catalogue, DistributionsGiveTheUncertainSpec) {
  XmlRpcValue i = one_item();
  XmlRpcValue mu = law("uniform", pair(0.25, 0.4));
  mu["nominal"] = 0.3;
  i[0]["mu_s"] = mu;
  i[0]["cg_height"] = law("lognormal", pair(0.9, 0.1));
  i[0]["depth"] = law("normal", pair(0.4, 0));  // an integer sd: accepted as a number
  i[0]["restitution"] = law("normal", pair(0.9, 0.05));
  const Catalogue c = parse_catalogue(sensors(), i);
  const CatalogueItem& item = c.items[0];
  using F = core::UncertainField;
  ASSERT_TRUE(item.uncertain.uncertain());
  EXPECT_EQ(item.spec.body.mu_s, 0.3);                                    // the given nominal
  EXPECT_EQ(item.spec.body.cg_height, 0.9 * std::exp(0.5 * 0.1 * 0.1));  // the lognormal's mean
  EXPECT_EQ(item.spec.depth.depth, 0.4);
  EXPECT_EQ(item.spec.body.restitution, 0.9);
  EXPECT_EQ(item.spec.body.width, 0.5);  // a plain number: fixed
  EXPECT_TRUE(item.uncertain.law(F::Width).is_fixed());
  EXPECT_EQ(item.uncertain.law(F::MuS).kind(), core::Distribution::Kind::Uniform);
  EXPECT_EQ(item.uncertain.law(F::MuS).b(), 0.4);
  EXPECT_EQ(item.uncertain.law(F::Restitution).range().text(), "[0, 1]");  // truncated to the valid range
  EXPECT_EQ(item.uncertain.nominal.body.mu_s, item.spec.body.mu_s);
  EXPECT_EQ(core::validate(item.uncertain), "");
  // Without distributions: not uncertain, and the nominal is the item.
  const Catalogue plain = parse_catalogue(sensors(), one_item());
  EXPECT_FALSE(plain.items[0].uncertain.uncertain());
  EXPECT_EQ(plain.items[0].uncertain.nominal.body.width, 0.5);
  // A cylinder whose width is uncertain: the members re-derive their radius of gyration.
  XmlRpcValue cyl = one_item();
  cyl[0]["shape"] = "cylinder";
  cyl[0]["width"] = law("uniform", pair(0.4, 0.6));
  const Catalogue cc = parse_catalogue(sensors(), cyl);
  EXPECT_TRUE(cc.items[0].uncertain.cylinder_radius_x);
  EXPECT_NEAR(cc.items[0].spec.body.radius_of_gyration, std::sqrt(0.25 / 16 + 0.81 / 3), 1e-15);
  for (const core::ItemSpec& m : core::draw_members(cc.items[0].uncertain, 8, 1))
    EXPECT_EQ(m.body.radius_of_gyration, core::cylinder_radius_of_gyration(m.body.width, 0.9));
}

TEST(Catalogue, BadDistributionsNameItemAndField) {
  auto with = [](const char* key, XmlRpcValue v) {
    XmlRpcValue i = one_item();
    i[0]["depth"] = 0.4;
    i[0][key] = v;
    return error_of(sensors(), i);
  };
  EXPECT_EQ(with("mu_s", law("uniform", pair(0.6, 0.3))), "items[0] 'cabinet': mu_s: uniform: lo 0.6 > hi 0.3");
  EXPECT_EQ(with("width", law("normal", pair(0.5, -0.1))), "items[0] 'cabinet': width: normal: sd -0.1 < 0");
  EXPECT_EQ(with("cg_height", law("lognormal", pair(0, 0.3))), "items[0] 'cabinet': cg_height: lognormal: median 0 <= 0");
  EXPECT_EQ(with("cg_height", law("lognormal", pair(0.9, -0.3))), "items[0] 'cabinet': cg_height: lognormal: beta -0.3 < 0");
  EXPECT_EQ(with("eccentricity", law("uniform", pair(0.0, 0.5))),
            "items[0] 'cabinet': eccentricity: uniform: lo 0 outside (0, 1)");
  EXPECT_EQ(with("restitution", law("uniform", pair(0.8, 1.2))),
            "items[0] 'cabinet': restitution: uniform: hi 1.2 outside [0, 1]");
  EXPECT_EQ(with("mu_s", law("beta", pair(2, 3))),
            "items[0] 'cabinet': mu_s: 'beta' is not a distribution (uniform, normal, lognormal) nor nominal");
  XmlRpcValue three;
  three[0] = 0.1;
  three[1] = 0.2;
  three[2] = 0.3;
  EXPECT_EQ(with("mu_s", law("uniform", three)),
            "items[0] 'cabinet': mu_s: uniform: must be a list [lo, hi] of 2 numbers, found 3 entries");
  EXPECT_EQ(with("mu_s", law("normal", 0.3)),
            "items[0] 'cabinet': mu_s: normal: must be a list [mean, sd] of 2 numbers, found a number");
  EXPECT_EQ(with("mu_s", law("lognormal", pair("low", 0.1))),
            "items[0] 'cabinet': mu_s: lognormal: median: must be a number, found a string");
  XmlRpcValue two = law("uniform", pair(0.2, 0.3));
  two["normal"] = pair(0.25, 0.01);
  EXPECT_EQ(with("mu_s", two), "items[0] 'cabinet': mu_s: two distributions (normal, uniform): give one");
  XmlRpcValue only_nominal;
  only_nominal["nominal"] = 0.3;
  EXPECT_NE(with("mu_s", only_nominal).find("items[0] 'cabinet': mu_s: a map must give a distribution"), std::string::npos);
  XmlRpcValue bad_nominal = law("uniform", pair(0.25, 0.4));
  bad_nominal["nominal"] = 0.5;
  EXPECT_EQ(with("mu_s", bad_nominal), "items[0] 'cabinet': mu_s: uniform: nominal 0.5 outside [0.25, 0.4]");
  bad_nominal["nominal"] = "high";
  EXPECT_EQ(with("mu_s", bad_nominal), "items[0] 'cabinet': mu_s: nominal: must be a number, found a string");
  EXPECT_EQ(with("mu_s", law("normal", pair(std::nan(""), 0.1))),
            "items[0] 'cabinet': mu_s: normal: mean nan is not a finite number");
  // Keys that take no distribution.
  EXPECT_NE(with("overturn_angle", law("uniform", pair(1.0, 1.2))).find("items[0] 'cabinet': overturn_angle: must be a number"),
            std::string::npos);
  // The nominal item is validated as before.
  EXPECT_EQ(with("width", law("uniform", pair(0.5, 0.5))), "accepted");
  XmlRpcValue far = law("normal", pair(5.0, 0.1));
  far["nominal"] = 5.0;
  EXPECT_EQ(with("eccentricity", far), "items[0] 'cabinet': eccentricity: normal: nominal 5 outside (0, 1)");
}

}  // namespace
}  // namespace rocking_monitor::live

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

namespace rocking_monitor::live {
namespace {

TEST(Catalogue, FileReaderEqualsTheParameterServerPath) {
  // The tools and the study read the YAML file directly; the node reads what rosparam loaded. Same
  // items, same laws, same derived radii.
  for (const char* file : {"catalogue_example.yaml", "catalogue_uncertain_example.yaml"}) {
    const Catalogue live = load_example(file);
    const Catalogue offline = core::load_catalogue_file(std::string(ROCKING_SOURCE_DIR) + "/config/" + file);
    ASSERT_EQ(live.items.size(), offline.items.size()) << file;
    ASSERT_EQ(live.sensors.size(), offline.sensors.size()) << file;
    for (std::size_t k = 0; k < live.items.size(); ++k) {
      const CatalogueItem &a = live.items[k], &b = offline.items[k];
      EXPECT_EQ(a.spec.id, b.spec.id);
      EXPECT_EQ(a.spec.sensor, b.spec.sensor);
      for (int f = 0; f < core::kUncertainFieldCount; ++f) {
        const auto field = static_cast<core::UncertainField>(f);
        const double va = core::value_of(a.spec, field), vb = core::value_of(b.spec, field);
        if (std::isnan(va)) EXPECT_TRUE(std::isnan(vb)) << a.spec.id << " " << core::to_string(field);
        else EXPECT_EQ(va, vb) << a.spec.id << " " << core::to_string(field);
        EXPECT_EQ(a.uncertain.law(field).kind(), b.uncertain.law(field).kind()) << a.spec.id;
        if (!a.uncertain.law(field).is_fixed())
          EXPECT_EQ(a.uncertain.law(field).nominal(), b.uncertain.law(field).nominal()) << a.spec.id;
      }
      EXPECT_EQ(a.pose.x, b.pose.x);
      EXPECT_EQ(a.pose.yaw, b.pose.yaw);
      EXPECT_EQ(a.ensemble_size, b.ensemble_size);
    }
  }
}

}  // namespace
}  // namespace rocking_monitor::live
