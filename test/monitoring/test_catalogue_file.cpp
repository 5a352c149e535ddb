// The catalogue read from a YAML file (the offline tools' and the study's path): YAML typing, the
// per-item ensemble_size, and errors that name the file, the item and the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "rocking_monitor/monitoring/catalogue_file.hpp"
#include "temp_root.hpp"

namespace rc = rocking_monitor::core;

namespace {

const rc::testing::TempRoot& dir = rc::testing::TempRoot::registered("catalogue_file_");

std::string write(const std::string& text) {
  std::filesystem::create_directories(dir.path());
  const std::string path = (dir.path() / "catalogue.yaml").string();
  std::ofstream(path) << text;
  return path;
}

std::string error_of(const std::string& path) {
  try {
    rc::load_catalogue_items_file(path);
  } catch (const rc::CatalogueError& e) {
    return e.what();
  }
  return "";
}

const char* kItem = "items:\n  - id: cart\n    width: 0.5\n    cg_height: 0.8\n";

}  // namespace

TEST(CatalogueFile, YamlScalarsAreTypedAsRosparamDoes) {
  const std::string path = write("a: 3\nb: 0.25\nc: -1.5e-3\nd: '0.25'\ne: true\nf: .nan\ng: -.inf\nh: ~\ni: text\nj: [1, 2.5]\n");
  const nlohmann::json j = rc::load_yaml_as_json(path);
  EXPECT_TRUE(j["a"].is_number_integer());
  EXPECT_EQ(j["a"].get<int>(), 3);
  EXPECT_EQ(j["b"].get<double>(), 0.25);
  EXPECT_EQ(j["c"].get<double>(), -1.5e-3);
  EXPECT_TRUE(j["d"].is_string());  // quoted stays a string
  EXPECT_TRUE(j["e"].is_boolean());
  EXPECT_TRUE(std::isnan(j["f"].get<double>()));
  EXPECT_EQ(j["g"].get<double>(), -INFINITY);
  EXPECT_TRUE(j["h"].is_null());
  EXPECT_EQ(j["i"].get<std::string>(), "text");
  EXPECT_EQ(j["j"][1].get<double>(), 2.5);
}

TEST(CatalogueFile, ItemsWithoutSensorsAndThePerItemEnsembleSize) {
  const std::string path = write(std::string(kItem) + "    mu_s: {uniform: [0.3, 0.5]}\n    ensemble_size: 128\n"
                                      "  - id: vase\n    width: 0.2\n    cg_height: 0.3\n    sensor: lobby\n");
  const auto items = rc::load_catalogue_items_file(path);
  ASSERT_EQ(items.size(), 2u);
  EXPECT_EQ(items[0].ensemble_size, 128);
  EXPECT_EQ(items[0].spec.body.mu_s, 0.4);  // the uniform's mean
  EXPECT_TRUE(items[0].uncertain.uncertain());
  EXPECT_EQ(items[1].ensemble_size, 0);     // deterministic: no ensemble
  EXPECT_EQ(items[1].spec.sensor, "lobby");  // kept, not checked offline
  // The full catalogue needs its sensors.
  try {
    rc::load_catalogue_file(path);
    FAIL() << "no sensors";
  } catch (const rc::CatalogueError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": sensors: must be a non-empty list of sensor entries");
  }
}

TEST(CatalogueFile, ErrorsNameFileItemAndField) {
  EXPECT_EQ(error_of(write(std::string(kItem) + "    ensemble_size: 64\n")),
            dir.path().string() + "/catalogue.yaml: items[0] 'cart': ensemble_size: only for an item with a "
            "distribution (this item is deterministic: one run)");
  EXPECT_EQ(error_of(write(std::string(kItem) + "    mu_s: {normal: [0.4, 0.1]}\n    ensemble_size: 2.5\n")),
            dir.path().string() + "/catalogue.yaml: items[0] 'cart': ensemble_size: must be an integer in [1, 100000]");
  EXPECT_EQ(error_of(write(std::string(kItem) + "    mu_s: {uniform: [0.6, 0.3]}\n")).find(
                dir.path().string() + "/catalogue.yaml: items[0] 'cart': mu_s: uniform"),
            0u);
  EXPECT_EQ(error_of(write(std::string(kItem) + "    mu_s: lots\n")),
            dir.path().string() + "/catalogue.yaml: items[0] 'cart': mu_s: must be a number (static friction "
            "coefficient), found a string");
  const std::string bad_yaml = error_of(write("items: [\n  - id: cart\n"));
  EXPECT_EQ(bad_yaml.rfind(dir.path().string() + "/catalogue.yaml:", 0), 0u) << bad_yaml;
  EXPECT_NE(bad_yaml.find(":3:"), std::string::npos) << bad_yaml;  // line of the unclosed list's end
  EXPECT_EQ(error_of((dir.path() / "missing.yaml").string()), (dir.path() / "missing.yaml").string() + ": cannot read");
}

// The standard normal's quantile by bisection on std::erfc (independent of the laws' own code).
double normal_quantile(double u) {
  double lo = -10.0, hi = 10.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < u ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(CatalogueFile, InputGainIsANumberOrALawAboveZero) {
  // issue 41: a calibrated fragility is a lognormal scale of the input; a plain number scales it too.
  const auto plain = rc::load_catalogue_items_file(write(std::string(kItem) + "    input_gain: 1.25\n"));
  EXPECT_EQ(plain[0].spec.input_gain, 1.25);
  EXPECT_FALSE(plain[0].uncertain.uncertain());
  EXPECT_EQ(rc::load_catalogue_items_file(write(kItem))[0].spec.input_gain, 1.0);
  const auto law = rc::load_catalogue_items_file(
      write(std::string(kItem) + "    input_gain: {lognormal: [1.2, 0.2], nominal: 1.2}\n    ensemble_size: 40\n"));
  EXPECT_TRUE(law[0].uncertain.uncertain());
  EXPECT_EQ(law[0].spec.input_gain, 1.2);
  EXPECT_EQ(law[0].ensemble_size, 40);
  const auto members = rc::draw_members(law[0].uncertain, 40, 1);
  // Latin hypercube: one member per stratum of the lognormal, so the k-th smallest gain lies between
  // the law's k/40 and (k+1)/40 quantiles: exp(ln 1.2 + 0.2 z).
  std::vector<double> g;
  for (const auto& m : members) g.push_back(m.input_gain);
  std::sort(g.begin(), g.end());
  for (int k = 0; k < 40; ++k) {
    const double zlo = k == 0 ? -INFINITY : normal_quantile(k / 40.0);
    const double zhi = k == 39 ? INFINITY : normal_quantile((k + 1) / 40.0);
    EXPECT_GE(g[k], 1.2 * std::exp(0.2 * zlo) * (1 - 1e-12)) << k;
    EXPECT_LE(g[k], 1.2 * std::exp(0.2 * zhi) * (1 + 1e-12)) << k;
  }
  EXPECT_EQ(error_of(write(std::string(kItem) + "    input_gain: 0\n")),
            dir.path().string() + "/catalogue.yaml: items[0] 'cart': input_gain: 0.000000 must be finite and > 0 "
            "(dimensionless scale of the ground acceleration)");
  EXPECT_EQ(error_of(write(std::string(kItem) + "    input_gain: strong\n")),
            dir.path().string() + "/catalogue.yaml: items[0] 'cart': input_gain: must be a number (dimensionless "
            "scale of the ground acceleration), found a string");
  EXPECT_EQ(error_of(write(std::string(kItem) + "    input_gain: {lognormal: [0, 0.2]}\n")).find(
                dir.path().string() + "/catalogue.yaml: items[0] 'cart': input_gain: lognormal"),
            0u);
}

// Issue 54: ids are names. An item id or sensor name outside letters, digits, '_', '-', '.' is
// refused when the catalogue loads, the error naming item and field; offline catalogues may name
// ensemble members "<id>#<k>" (rocking_geometry.py --ensemble), the live one may not.
namespace {
std::string live_error_of(const std::string& sensor, const std::string& item) {
  const nlohmann::json sensors = {{{"name", sensor}, {"topic", "/imu"}}};
  const nlohmann::json items = {{{"id", item}, {"sensor", sensor}, {"width", 0.5}, {"cg_height", 0.8}}};
  try {
    rc::parse_catalogue(sensors, items);
  } catch (const rc::CatalogueError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(CatalogueFile, IdsAreNamesOfLettersDigitsUnderscoreDashDot) {
  EXPECT_EQ(live_error_of("table_1", "Vase-3.b_2"), "");
  const std::string rule = ": an id is a name of letters, digits, '_', '-' and '.' (it becomes an MQTT topic "
                           "level, a file name and part of an e-mail subject)";
  EXPECT_EQ(live_error_of("table", "vase 1"), "items[0] 'vase 1': id: 'vase 1' holds ' ' at character 5" + rule);
  EXPECT_EQ(live_error_of("table", "vase/1"), "items[0] 'vase/1': id: 'vase/1' holds '/' at character 5" + rule);
  EXPECT_EQ(live_error_of("table", "vase#1"), "items[0] 'vase#1': id: 'vase#1' holds '#' at character 5" + rule);
  // A header injection and invalid UTF-8: refused, and the error itself is printable.
  EXPECT_EQ(live_error_of("table", "v\r\nBcc: x"),
            "items[0] 'v\\x0D\\x0ABcc: x': id: 'v\\x0D\\x0ABcc: x' holds '\\x0D' at character 2" + rule);
  EXPECT_EQ(live_error_of("table", "vase\xFF"),
            "items[0] 'vase\xEF\xBF\xBD': id: 'vase\xEF\xBF\xBD' holds a non-ASCII byte at character 5" + rule);
  EXPECT_EQ(live_error_of("table+1", "vase"), "sensors[0] 'table+1': name: 'table+1' holds '+' at character 6" + rule);
  EXPECT_EQ(live_error_of("table", std::string(129, 'a')).find("items[0] '"), 0u);
  EXPECT_NE(live_error_of("table", std::string(129, 'a')).find("is 129 bytes long: at most 128"), std::string::npos);
  // Offline: members "SP1#0" pass; anything else after '#' does not.
  EXPECT_EQ(error_of(write("items:\n  - id: SP1#12\n    width: 0.5\n    cg_height: 0.8\n")), "");
  EXPECT_EQ(error_of(write("items:\n  - id: SP1#x\n    width: 0.5\n    cg_height: 0.8\n")),
            dir.path().string() + "/catalogue.yaml: items[0] 'SP1#x': id: 'SP1#x' holds '#' at character 4" + rule +
                ", optionally followed by '#<member number>'");
}
