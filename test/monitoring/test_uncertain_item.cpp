// UncertainItemSpec and draw_members (issue 13, part 1). Oracles: zero spread gives the nominal item
// bit for bit; the Latin hypercube puts exactly one member in each stratum of every field's CDF; the
// members follow each law (Kolmogorov-Smirnov); same seed, same bits; a member made invalid by a
// constraint between fields is pulled back toward the nominal, never dropped.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "rocking_monitor/monitoring/uncertain_item.hpp"

namespace rocking_monitor::core {
namespace {

using F = UncertainField;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every field of two items equal to the bit (NaN defaults included).
void expect_identical(const ItemSpec& a, const ItemSpec& b) {
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.sensor, b.sensor);
  EXPECT_EQ(a.frame, b.frame);
  EXPECT_EQ(a.description, b.description);
  const BodyParameters &x = a.body, &y = b.body;
  for (auto [p, q] : std::initializer_list<std::pair<double, double>>{{x.width, y.width}, {x.cg_height, y.cg_height}, {x.nu1, y.nu1},
                      {x.radius_of_gyration, y.radius_of_gyration}, {x.mu_s, y.mu_s}, {x.mu_k, y.mu_k},
                      {x.restitution, y.restitution}, {x.overturn_angle, y.overturn_angle},
                      {a.depth.depth, b.depth.depth}, {a.depth.eccentricity_y, b.depth.eccentricity_y},
                      {a.depth.radius_of_gyration_y, b.depth.radius_of_gyration_y}})
    EXPECT_TRUE(same_bits(p, q)) << p << " vs " << q;
}

ItemSpec cabinet(const std::string& id = "cabinet") {
  ItemSpec s;
  s.id = id;
  s.sensor = "floor";
  s.frame = id;
  s.body.width = 0.9;
  s.body.cg_height = 0.9;
  s.body.nu1 = 0.4;
  s.body.mu_s = 0.6;
  s.depth.depth = 0.4;
  return s;
}

// The law of field f, restricted to its range, with the nominal item's field set to its nominal.
void give(UncertainItemSpec& u, F f, Distribution d) {
  u.law(f) = d;
  set_value(u.nominal, f, d.nominal());
}

Distribution uniform(F f, double lo, double hi) { return Distribution::uniform(lo, hi, valid_range(f)); }
Distribution normal(F f, double m, double s) { return Distribution::normal(m, s, valid_range(f)); }
Distribution lognormal(F f, double m, double b) { return Distribution::lognormal(m, b, valid_range(f)); }

// Every field uncertain, none able to make a member invalid (no radius of gyration given).
UncertainItemSpec all_laws(const std::string& id = "cabinet") {
  UncertainItemSpec u;
  u.nominal = cabinet(id);
  give(u, F::MuS, uniform(F::MuS, 0.25, 0.4).with_nominal(0.3));
  give(u, F::Restitution, normal(F::Restitution, 0.9, 0.08));  // truncated at 1
  give(u, F::Eccentricity, normal(F::Eccentricity, 0.45, 0.05));
  give(u, F::EccentricityY, uniform(F::EccentricityY, 0.4, 0.6));
  give(u, F::CgHeight, lognormal(F::CgHeight, 0.9, 0.1));
  give(u, F::Width, normal(F::Width, 0.9, 0.01));
  give(u, F::Depth, uniform(F::Depth, 0.38, 0.42));
  return u;
}

TEST(UncertainItem, FixedFieldsAreNotUncertain) {
  UncertainItemSpec u;
  u.nominal = cabinet();
  EXPECT_FALSE(u.uncertain());
  EXPECT_EQ(validate(u), "");
  for (const ItemSpec& m : draw_members(u, 5, 1)) expect_identical(m, u.nominal);
  give(u, F::MuS, uniform(F::MuS, 0.6, 0.6));
  EXPECT_TRUE(u.uncertain());  // a distribution, even of zero spread
}

TEST(UncertainItem, ZeroSpreadGivesTheNominalItemBitForBit) {
  UncertainItemSpec u;
  u.nominal = cabinet();
  u.nominal.body.radius_of_gyration = 0.5;
  give(u, F::MuS, normal(F::MuS, 0.6, 0.0));
  give(u, F::Restitution, uniform(F::Restitution, 0.85, 0.85));
  give(u, F::Eccentricity, normal(F::Eccentricity, 0.4, 0.0));
  give(u, F::EccentricityY, lognormal(F::EccentricityY, 0.55, 0.0));
  give(u, F::CgHeight, lognormal(F::CgHeight, 0.9, 0.0));
  give(u, F::Width, uniform(F::Width, 0.9, 0.9));
  give(u, F::Depth, normal(F::Depth, 0.4, 0.0));
  give(u, F::RadiusOfGyration, uniform(F::RadiusOfGyration, 0.5, 0.5));
  give(u, F::RadiusOfGyrationY, lognormal(F::RadiusOfGyrationY, 0.45, 0.0));
  ASSERT_EQ(validate(u), "");
  std::vector<int> pulled;
  const std::vector<ItemSpec> members = draw_members(u, 64, 2024, &pulled);
  ASSERT_EQ(members.size(), 64u);
  EXPECT_TRUE(pulled.empty());
  for (const ItemSpec& m : members) expect_identical(m, u.nominal);
}

TEST(UncertainItem, LatinHypercubeOneMemberPerStratum) {
  const UncertainItemSpec u = all_laws();
  ASSERT_EQ(validate(u), "");
  for (int n : {1, 7, 100, 1000}) {
    std::vector<int> pulled;
    const std::vector<ItemSpec> members = draw_members(u, n, 42, &pulled);
    ASSERT_TRUE(pulled.empty());
    for (int i = 0; i < kUncertainFieldCount; ++i) {
      const auto f = static_cast<F>(i);
      if (u.law(f).is_fixed()) continue;
      std::vector<int> count(n, 0);
      for (const ItemSpec& m : members) {
        const double p = u.law(f).cdf(value_of(m, f));
        ++count[std::min(n - 1, static_cast<int>(std::floor(p * n)))];
      }
      EXPECT_EQ(std::count(count.begin(), count.end(), 1), n) << to_string(f) << ", n = " << n;
    }
  }
}

TEST(UncertainItem, MembersFollowTheirLaws) {
  // Kolmogorov-Smirnov: D = sup |F_n - F| of 4096 members against each field's CDF, below the 1 %
  // critical value 1.63 / sqrt(n) (a Latin hypercube is in fact within 1/n of F).
  const UncertainItemSpec u = all_laws();
  const int n = 4096;
  const std::vector<ItemSpec> members = draw_members(u, n, 7);
  for (int i = 0; i < kUncertainFieldCount; ++i) {
    const auto f = static_cast<F>(i);
    if (u.law(f).is_fixed()) continue;
    std::vector<double> x;
    for (const ItemSpec& m : members) x.push_back(value_of(m, f));
    std::sort(x.begin(), x.end());
    double d = 0.0;
    for (int k = 0; k < n; ++k) {
      const double c = u.law(f).cdf(x[k]);
      d = std::max({d, std::abs(c - static_cast<double>(k) / n), std::abs(c - static_cast<double>(k + 1) / n)});
    }
    EXPECT_LT(d, 1.63 / std::sqrt(n)) << to_string(f);
    EXPECT_LE(d, 1.0 / n + 1e-12) << to_string(f);  // the stratification's own bound
    RecordProperty(std::string("ks_") + to_string(f), std::to_string(d));
  }
}

TEST(UncertainItem, ReproducibleAndSeededPerItem) {
  const UncertainItemSpec u = all_laws("cabinet");
  const std::vector<ItemSpec> a = draw_members(u, 32, 1), b = draw_members(u, 32, 1);
  for (int m = 0; m < 32; ++m) expect_identical(a[m], b[m]);
  // Another id, another seed: other members (every uncertain field differs in every member).
  const std::vector<ItemSpec> other = draw_members(all_laws("rack"), 32, 1), reseeded = draw_members(u, 32, 2);
  for (int m = 0; m < 32; ++m) {
    EXPECT_NE(a[m].body.mu_s, other[m].body.mu_s);
    EXPECT_NE(a[m].body.cg_height, other[m].body.cg_height);
    EXPECT_NE(a[m].body.mu_s, reseeded[m].body.mu_s);
  }
  EXPECT_NE(item_seed(1, "cabinet"), item_seed(1, "rack"));
  EXPECT_NE(item_seed(1, "cabinet"), item_seed(2, "cabinet"));
  // A field's draws do not depend on which other fields are uncertain.
  UncertainItemSpec only_mu;
  only_mu.nominal = cabinet();
  give(only_mu, F::MuS, u.law(F::MuS));
  const std::vector<ItemSpec> c = draw_members(only_mu, 32, 1);
  for (int m = 0; m < 32; ++m) EXPECT_TRUE(same_bits(c[m].body.mu_s, a[m].body.mu_s));
  // Pinned: a uniform's quantile is plain arithmetic, so these are the same bits on every machine
  // (std::mt19937_64's output is fixed by the standard; no implementation-defined distribution used).
  const std::vector<ItemSpec> pinned = draw_members(only_mu, 4, 20261123);
  const double expected[] = {0x1.0d0e0d2d18ffp-2, 0x1.2ea3ec9e34b86p-2, 0x1.511fcb88a0596p-2, 0x1.7e773ccb22b08p-2};
  for (int m = 0; m < 4; ++m) EXPECT_TRUE(same_bits(pinned[m].body.mu_s, expected[m])) << m << ": " << pinned[m].body.mu_s;
  // The strata are shuffled (member m is not in stratum m): 32 members in stratum order has odds 1/32!.
  int in_order = 0;
  for (int m = 0; m < 32; ++m) in_order += static_cast<int>(std::floor(u.law(F::MuS).cdf(a[m].body.mu_s) * 32)) == m;
  EXPECT_LT(in_order, 32);
  RecordProperty("members_in_their_own_stratum_of_32", in_order);
}

TEST(UncertainItem, InvalidCombinationIsPulledTowardTheNominal) {
  // x plane 0.6 wide, y plane 0.3 deep, i_x drawn in [0.1, 0.4]: the y plane's derived radius,
  // i_y^2 = i_x^2 + (0.3^2 - 0.6^2) / 12 = i_x^2 - 0.0225, is invalid for i_x <= 0.15 (1/6 of the draws).
  UncertainItemSpec u;
  u.nominal = cabinet();
  u.nominal.body.width = 0.6;
  u.nominal.depth.depth = 0.3;
  give(u, F::RadiusOfGyration, uniform(F::RadiusOfGyration, 0.1, 0.4).with_nominal(0.25));
  ASSERT_EQ(validate(u), "");
  const int n = 600;
  std::vector<int> pulled;
  const std::vector<ItemSpec> members = draw_members(u, n, 3, &pulled);
  ASSERT_EQ(members.size(), static_cast<std::size_t>(n));  // none dropped
  EXPECT_EQ(pulled.size(), 100u);                          // exactly the strata below 0.15
  for (const ItemSpec& m : members) EXPECT_EQ(validate(m), "");
  for (int k : pulled) {
    const double i = members[k].body.radius_of_gyration;
    EXPECT_NEAR(i, 0.15, 1e-12);  // on the boundary of the valid set (60 halvings)
  }
  int kept = 0;
  for (const ItemSpec& m : members) kept += m.body.radius_of_gyration > 0.15 + 1e-9;
  EXPECT_EQ(kept, n - 100);
}

TEST(UncertainItem, CylinderMembersDeriveTheirOwnRadius) {
  UncertainItemSpec u;
  u.nominal = cabinet("vase");
  u.nominal.body.width = 0.15;
  u.nominal.depth.depth = 0.15;
  u.nominal.body.cg_height = 0.35;
  give(u, F::Width, uniform(F::Width, 0.14, 0.16));
  u.nominal.body.radius_of_gyration = cylinder_radius_of_gyration(0.15, 0.35);
  u.nominal.depth.radius_of_gyration_y = cylinder_radius_of_gyration(0.15, 0.35);
  u.cylinder_radius_x = u.cylinder_radius_y = true;
  ASSERT_EQ(validate(u), "");
  for (const ItemSpec& m : draw_members(u, 16, 5)) {
    EXPECT_EQ(m.body.radius_of_gyration, cylinder_radius_of_gyration(m.body.width, 0.35));
    EXPECT_EQ(m.depth.radius_of_gyration_y, u.nominal.depth.radius_of_gyration_y);  // depth fixed
  }
}

TEST(UncertainItem, ValidationNamesItemAndField) {
  UncertainItemSpec u;
  u.nominal = cabinet();
  u.law(F::MuS) = uniform(F::MuS, 0.6, 0.3);
  EXPECT_EQ(validate(u), "item 'cabinet': mu_s: uniform: lo 0.6 > hi 0.3");
  u.law(F::MuS) = uniform(F::MuS, 0.3, 0.6);
  EXPECT_EQ(validate(u), "item 'cabinet': mu_s: the nominal item's 0.6 is not the law's nominal 0.45");
  u.law(F::MuS) = Distribution::uniform(0.3, 0.6);  // not restricted to the field's range
  set_value(u.nominal, F::MuS, 0.45);
  EXPECT_EQ(validate(u), "item 'cabinet': mu_s: uniform: restricted to (-inf, inf), not to the field's range [0, inf)");
  u.law(F::MuS) = Distribution();
  u.nominal.depth = DepthParameters{};
  u.law(F::EccentricityY) = uniform(F::EccentricityY, 0.4, 0.6);
  EXPECT_EQ(validate(u), "item 'cabinet': eccentricity_y: needs depth (the base along the item's y)");
  EXPECT_THROW(draw_members(all_laws(), -1, 0), std::invalid_argument);
  EXPECT_TRUE(draw_members(all_laws(), 0, 0).empty());
}

}  // namespace
}  // namespace rocking_monitor::core
