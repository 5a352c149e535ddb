#include "rocking_monitor/monitoring/uncertain_item.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <utility>

namespace rocking_monitor::core {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a, 64 bit (as shard_of in src/ros/catalogue.cpp)
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

// Steele, Lea, Flood (2014), SplittableRandom's finaliser: a bijection that spreads every input bit.
std::uint64_t splitmix64(std::uint64_t x) {
  std::uint64_t z = x + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Uniform integer in [0, n), n >= 1, unbiased: the 2^64 mod n lowest outputs are rejected so that the
// accepted ones are a whole number of copies of [0, n).
std::uint64_t bounded(std::mt19937_64& engine, std::uint64_t n) {
  const std::uint64_t threshold = (0 - n) % n;  // 2^64 mod n
  for (;;) {
    const std::uint64_t r = engine();
    if (r >= threshold) return r % n;
  }
}

std::string num(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.12g", x);
  return text;
}

bool needs_depth(UncertainField f) {
  return f == UncertainField::Depth || f == UncertainField::EccentricityY || f == UncertainField::RadiusOfGyrationY;
}

}  // namespace

const char* to_string(UncertainField field) {
  switch (field) {
    case UncertainField::MuS: return "mu_s";
    case UncertainField::Restitution: return "restitution";
    case UncertainField::Eccentricity: return "eccentricity";
    case UncertainField::EccentricityY: return "eccentricity_y";
    case UncertainField::CgHeight: return "cg_height";
    case UncertainField::Width: return "width";
    case UncertainField::Depth: return "depth";
    case UncertainField::RadiusOfGyration: return "radius_of_gyration";
    case UncertainField::RadiusOfGyrationY: return "radius_of_gyration_y";
    case UncertainField::InputGain: return "input_gain";
  }
  return "?";
}

ValueRange valid_range(UncertainField field) {
  switch (field) {
    case UncertainField::MuS: return {0.0, kInf, false, true};
    case UncertainField::Restitution: return {0.0, 1.0, false, false};
    case UncertainField::Eccentricity:
    case UncertainField::EccentricityY: return {0.0, 1.0, true, true};
    default: return {0.0, kInf, true, true};
  }
}

double value_of(const ItemSpec& item, UncertainField field) {
  switch (field) {
    case UncertainField::MuS: return item.body.mu_s;
    case UncertainField::Restitution: return item.body.restitution;
    case UncertainField::Eccentricity: return item.body.nu1;
    case UncertainField::EccentricityY: return item.depth.eccentricity_y;
    case UncertainField::CgHeight: return item.body.cg_height;
    case UncertainField::Width: return item.body.width;
    case UncertainField::Depth: return item.depth.depth;
    case UncertainField::RadiusOfGyration: return item.body.radius_of_gyration;
    case UncertainField::RadiusOfGyrationY: return item.depth.radius_of_gyration_y;
    case UncertainField::InputGain: return item.input_gain;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

void set_value(ItemSpec& item, UncertainField field, double value) {
  switch (field) {
    case UncertainField::MuS: item.body.mu_s = value; break;
    case UncertainField::Restitution: item.body.restitution = value; break;
    case UncertainField::Eccentricity: item.body.nu1 = value; break;
    case UncertainField::EccentricityY: item.depth.eccentricity_y = value; break;
    case UncertainField::CgHeight: item.body.cg_height = value; break;
    case UncertainField::Width: item.body.width = value; break;
    case UncertainField::Depth: item.depth.depth = value; break;
    case UncertainField::RadiusOfGyration: item.body.radius_of_gyration = value; break;
    case UncertainField::RadiusOfGyrationY: item.depth.radius_of_gyration_y = value; break;
    case UncertainField::InputGain: item.input_gain = value; break;
  }
}

double cylinder_radius_of_gyration(double diameter, double cg_height) {
  return std::sqrt(diameter * diameter / 16.0 + cg_height * cg_height / 3.0);
}

bool UncertainItemSpec::uncertain() const {
  for (const Distribution& d : laws)
    if (!d.is_fixed()) return true;
  return false;
}

std::string validate(const UncertainItemSpec& spec) {
  const std::string who = "item '" + spec.nominal.id + "': ";
  for (int i = 0; i < kUncertainFieldCount; ++i) {
    const auto f = static_cast<UncertainField>(i);
    const Distribution& d = spec.laws[i];
    if (d.is_fixed()) continue;
    const std::string name = to_string(f);
    if (const std::string e = validate(d, name); !e.empty()) return who + e;
    const ValueRange r = valid_range(f), dr = d.range();
    if (dr.lo != r.lo || dr.hi != r.hi || dr.lo_open != r.lo_open || dr.hi_open != r.hi_open)
      return who + name + ": " + d.name() + ": restricted to " + dr.text() + ", not to the field's range " + r.text();
    if (needs_depth(f) && !spec.nominal.depth.given() && f != UncertainField::Depth)
      return who + name + ": needs depth (the base along the item's y)";
    if (!(value_of(spec.nominal, f) == d.nominal()))
      return who + name + ": the nominal item's " + num(value_of(spec.nominal, f)) + " is not the law's nominal " +
             num(d.nominal());
    if ((f == UncertainField::RadiusOfGyration && spec.cylinder_radius_x) ||
        (f == UncertainField::RadiusOfGyrationY && spec.cylinder_radius_y))
      return who + name + ": both drawn and derived from the cylinder's shape";
  }
  return validate(spec.nominal);
}

std::uint64_t item_seed(std::uint64_t global_seed, const std::string& id) {
  return splitmix64(fnv1a(id) ^ splitmix64(global_seed));
}

std::vector<ItemSpec> draw_members(const UncertainItemSpec& spec, int n, std::uint64_t global_seed,
                                   std::vector<int>* pulled) {
  if (n < 0) throw std::invalid_argument("draw_members: n = " + std::to_string(n) + " (must be >= 0)");
  std::vector<ItemSpec> members(static_cast<std::size_t>(n), spec.nominal);
  if (n == 0) return members;
  const std::uint64_t seed = item_seed(global_seed, spec.nominal.id);

  // draws[f][m]: the value of field f in member m (uncertain fields only).
  std::vector<std::pair<UncertainField, std::vector<double>>> draws;
  for (int i = 0; i < kUncertainFieldCount; ++i) {
    const auto f = static_cast<UncertainField>(i);
    const Distribution& law = spec.laws[i];
    if (law.is_fixed()) continue;
    std::mt19937_64 engine(splitmix64(seed ^ fnv1a(to_string(f))));
    std::vector<std::uint64_t> stratum(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) stratum[k] = static_cast<std::uint64_t>(k);
    for (int k = n - 1; k > 0; --k) std::swap(stratum[k], stratum[bounded(engine, static_cast<std::uint64_t>(k) + 1)]);
    std::vector<double> values(static_cast<std::size_t>(n));
    for (int m = 0; m < n; ++m) {
      const std::uint64_t r = engine() >> 12;  // 52 bits: 2r + 1 < 2^53 is exact
      const double position = static_cast<double>(2 * r + 1) * 0x1.0p-53;  // in (0, 1)
      values[m] = law.quantile((static_cast<double>(stratum[m]) + position) / n);
    }
    draws.emplace_back(f, std::move(values));
  }

  auto build = [&](int m, double t) {
    ItemSpec item = spec.nominal;
    for (const auto& [f, values] : draws) {
      const double nominal = value_of(spec.nominal, f), drawn = values[m];
      set_value(item, f, t == 1.0 ? drawn : nominal + t * (drawn - nominal));
    }
    if (spec.cylinder_radius_x)
      item.body.radius_of_gyration = cylinder_radius_of_gyration(item.body.width, item.body.cg_height);
    if (spec.cylinder_radius_y && item.depth.given())
      item.depth.radius_of_gyration_y = cylinder_radius_of_gyration(item.depth.depth, item.body.cg_height);
    return item;
  };
  for (int m = 0; m < n; ++m) {
    members[m] = build(m, 1.0);
    if (validate(members[m]).empty()) continue;
    double lo = 0.0, hi = 1.0;  // valid at lo (the nominal), invalid at hi
    for (int k = 0; k < 60; ++k) {
      const double mid = 0.5 * (lo + hi);
      (validate(build(m, mid)).empty() ? lo : hi) = mid;
    }
    members[m] = build(m, lo);
    if (pulled) pulled->push_back(m);
  }
  return members;
}

}  // namespace rocking_monitor::core
