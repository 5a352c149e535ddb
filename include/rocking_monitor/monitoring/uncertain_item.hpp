#pragma once

// An item whose parameters are uncertain (issue 13, part 1): the nominal ItemSpec, one Distribution per
// uncertain field, and the ensemble members drawn from them by a reproducible Latin hypercube.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "rocking_monitor/monitoring/item_spec.hpp"
#include "rocking_monitor/physics/parameter_distribution.hpp"

namespace rocking_monitor::core {

/// The numeric item keys that may carry a distribution (catalogue names in to_string()).
enum class UncertainField : std::uint8_t {
  MuS,
  Restitution,
  Eccentricity,
  EccentricityY,
  CgHeight,
  Width,
  Depth,
  RadiusOfGyration,
  RadiusOfGyrationY,
  InputGain,
};
inline constexpr int kUncertainFieldCount = 10;
/// "mu_s", "restitution", "eccentricity", "eccentricity_y", "cg_height", "width", "depth",
/// "radius_of_gyration", "radius_of_gyration_y", "input_gain".
const char* to_string(UncertainField field);
/// The field's valid values, the range every law is restricted to: mu_s [0, inf), restitution [0, 1],
/// eccentricities (0, 1), lengths and input_gain (0, inf).
ValueRange valid_range(UncertainField field);
/// The field's value in an item (body, depth).
double value_of(const ItemSpec& item, UncertainField field);
void set_value(ItemSpec& item, UncertainField field, double value);

/// Central radius of gyration of a solid cylinder of diameter d and height 2h about a horizontal
/// diameter through its centre of mass: sqrt(d^2 / 16 + h^2 / 3), m (the catalogue's shape: cylinder).
double cylinder_radius_of_gyration(double diameter, double cg_height);

struct UncertainItemSpec {
  /// The nominal item: every uncertain field at its law's nominal() (mean or given `nominal:`).
  ItemSpec nominal;
  /// One law per field, indexed by UncertainField; Fixed (the default): every member keeps the nominal
  /// item's value.
  std::array<Distribution, kUncertainFieldCount> laws{};
  /// The catalogue's shape: cylinder with no radius_of_gyration (_y) given: the nominal's radius was
  /// derived from its width (depth) and cg_height, and each member re-derives its own from the member's
  /// width (depth) and cg_height. (A box without a given radius keeps NaN: Body derives it.)
  bool cylinder_radius_x = false;
  bool cylinder_radius_y = false;

  Distribution& law(UncertainField f) { return laws[static_cast<int>(f)]; }
  const Distribution& law(UncertainField f) const { return laws[static_cast<int>(f)]; }
  /// Any field given as a distribution (even of zero spread): the item is to run an ensemble.
  bool uncertain() const;
};

/// Empty if valid, else "item '<id>': <field>: <law>: <problem>" (the laws, each in its field's range,
/// the nominal fields equal to the laws' nominals, then validate(nominal)).
std::string validate(const UncertainItemSpec& spec);

/// The seed of one item's members: FNV-1a (64 bit) of the id, combined with the global seed through
/// splitmix64. Depends only on (global seed, id): adding, removing or reordering other items does not
/// change an item's members.
std::uint64_t item_seed(std::uint64_t global_seed, const std::string& id);

/// n ensemble members of the item (n >= 0; throws std::invalid_argument for n < 0), reproducible to
/// the bit on every machine and run for the same (spec, n, global_seed):
///
/// Latin hypercube over the uncertain fields. Field f (each with its own std::mt19937_64, seeded from
/// item_seed(global_seed, id) and the field's name, so a field's draws do not depend on which other
/// fields are uncertain) gets a permutation pi_f of the n strata (Fisher-Yates with an unbiased
/// bounded integer by rejection) and member m the probability
///   u = (pi_f(m) + (2 r + 1) 2^-53) / n,  r = engine() >> 12 (52 bits: the position is exact),
/// i.e. exactly one member in each stratum [k/n, (k+1)/n) of the field's CDF, and the value
/// law.quantile(u). The engine's output is fixed by the standard; std::uniform_real_distribution and
/// std::shuffle (implementation-defined) are not used. Fixed fields keep the nominal value. Member 0 is
/// not the nominal item (that one is separate). The members keep the nominal's id, sensor and frame.
///
/// Every drawn value lies in its field's valid range (the laws are restricted to it). A member can
/// still be invalid as a whole through a constraint between fields: the y plane's radius of gyration
/// derived from the x plane's (i_x^2 + (D^2 - B^2) / 12 > 0), or an overturn_angle below a tipping angle.
/// Such a member is never dropped: its uncertain fields are pulled toward the nominal item on the
/// straight line nominal + t (draw - nominal), t the largest valid value found by bisection (60 halvings)
/// in [0, 1) (t = 0 is the nominal, valid). Its index is appended to *pulled when pulled != nullptr.
/// The spec must be valid (validate(spec) empty, as parse_catalogue guarantees). Cost: about 1 us per
/// member (100 items x 32 members with four uncertain fields: 2.6 ms on this machine).
std::vector<ItemSpec> draw_members(const UncertainItemSpec& spec, int n, std::uint64_t global_seed,
                                   std::vector<int>* pulled = nullptr);

}  // namespace rocking_monitor::core
