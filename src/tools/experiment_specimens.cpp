// rocking_experiments' specimens: catalogue items -> the members the model runs, with the checks
// that name the item at fault, and the pivot lines printed for each specimen.
#include "experiment_specimens.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>

#include "rocking_monitor/monitoring/uncertain_item.hpp"

namespace rocking_monitor::tools::experiments {

namespace {

/// The item's members as the node draws them (ItemEnsemble: each member's input_gain scales its
/// input); a deterministic item is its one member. For --margins the nominal item alone: the margin
/// is the geometry's, the fragility's spread is what the script fits.
std::vector<rm::ItemSpec> member_specs(const Options& o, const rm::CatalogueItem& item) {
  if (item.uncertain.uncertain() && o.margins.empty())
    return rm::draw_members(item.uncertain, item.ensemble_size > 0 ? item.ensemble_size : o.samples,
                            static_cast<std::uint64_t>(o.seed));
  return {item.spec};
}

/// A member's table azimuth (rad): --table-azimuth minus the item's own yaw on the table (its
/// catalogue pose), the same rotation the node applies to a sensor's input through tf.
double member_azimuth(const Options& o, const rm::CatalogueItem& item, bool solid) {
  double azimuth = o.azimuth_deg * M_PI / 180.0;
  if (item.pose.given) {
    if (item.pose.roll != 0.0 || item.pose.pitch != 0.0)
      throw std::runtime_error(o.catalogue + ": item '" + item.spec.id + "': pose: a specimen stands on the "
                               "table: only its yaw is used, roll and pitch must be 0");
    if (item.pose.yaw != 0.0 && !solid)
      throw std::runtime_error(o.catalogue + ": item '" + item.spec.id + "': pose.yaw needs the 3-D model "
                               "(--model 3d): a planar plane has one axis");
    azimuth -= item.pose.yaw;
  }
  return azimuth;
}

/// One member with the command line's overrides, checked in the order the tool always checked them:
/// the planar body, the pose, the 3-D body.
Member make_member(const Options& o, const rm::CatalogueItem& item, const rm::ItemSpec& spec, bool solid) {
  rm::BodyParameters b = spec.body;
  if (!std::isnan(o.restitution)) b.restitution = o.restitution;
  if (!std::isnan(o.mu_s)) b.mu_s = o.mu_s;
  const std::string problem = rm::validate(b);
  if (!problem.empty()) throw std::runtime_error("item '" + item.spec.id + "': " + problem);
  Member member{b, {}, 0.0, spec.input_gain};
  member.azimuth = member_azimuth(o, item, solid);
  if (solid) {
    if (!spec.solid)
      throw std::runtime_error(o.catalogue + ": item '" + item.spec.id + "': --model 3d needs its 3-D "
                               "description (base_polygon, centre_of_mass, central_inertia, mass: "
                               "scripts/rocking_geometry.py writes them)");
    member.solid = *spec.solid;
    if (!std::isnan(o.restitution_factor)) member.solid.restitution_factor = o.restitution_factor;
    if (!std::isnan(o.mu_s)) member.solid.mu_s = o.mu_s;
    const std::string p3 = rm::validate(member.solid);
    if (!p3.empty()) throw std::runtime_error("item '" + item.spec.id + "': " + p3);
  }
  return member;
}

/// The specimen's first member's pivots (and, for an ensemble, its members' input_gain range).
void print_specimen(const Options& o, const rm::CatalogueItem& item, const std::vector<rm::ItemSpec>& specs,
                    const Member& member, bool solid) {
  if (item.uncertain.uncertain() && o.margins.empty()) {
    const auto by_gain = [](const auto& x, const auto& y) { return x.input_gain < y.input_gain; };
    std::printf("%s: %zu members (seed %ld; input_gain %.4f..%.4f)\n", item.spec.id.c_str(), specs.size(), o.seed,
                std::min_element(specs.begin(), specs.end(), by_gain)->input_gain,
                std::max_element(specs.begin(), specs.end(), by_gain)->input_gain);
  }
  const rm::Body body(member.planar);
  for (int side : {1, -1}) {
    const auto& p = body.pivot(side);
    std::printf("%s pivot %d: alpha %.3f deg, R %.4f m, p %.3f rad/s, uplift at %.3f g, "
                "restitution %.4f\n", item.spec.id.c_str(), side > 0 ? 1 : 2,
                p.alpha * 180.0 / M_PI, p.radius, p.p, p.tan_alpha, p.restitution);
  }
  if (!solid) return;
  const rm::BaseBody body3(member.solid);
  for (int k = 0; k < body3.vertex_count(); ++k) {
    const auto& e = body3.edge(k);
    // only the edges the table (along x) can tip it over
    if (std::abs(e.normal.x()) < 0.2) continue;
    std::printf("%s edge %d (normal %+.2f, %+.2f): alpha %.3f deg, R %.4f m, uplift at %.3f g "
                "along the normal\n", item.spec.id.c_str(), k + 1, e.normal.x(), e.normal.y(),
                e.pivot.alpha * 180.0 / M_PI, e.pivot.radius, e.pivot.tan_alpha);
  }
}

}  // namespace

bool uses_solid_model(const Options& o, const std::vector<rm::CatalogueItem>& items) {
  if (o.model_name != "auto") return o.model_name == "3d";
  return !items.empty() &&
         std::all_of(items.begin(), items.end(), [](const auto& i) { return i.spec.solid.has_value(); });
}

std::vector<Specimen> load_specimens(const Options& o, const rm::MeasuredOutcomes& outcomes,
                                     const std::vector<rm::CatalogueItem>& items, bool solid) {
  std::vector<Specimen> specimens;
  for (const auto& item : items) {
    // Items "SP1#3" are members of SP1's ensemble (rocking_geometry.py --ensemble): P(overturn) is
    // the fraction of members that overturn, the prediction P >= 0.5.
    const std::string name = item.spec.id.substr(0, item.spec.id.find('#'));
    const auto column = std::find(outcomes.specimens.begin(), outcomes.specimens.end(), name);
    if (column == outcomes.specimens.end())
      throw std::runtime_error(o.catalogue + ": item '" + item.spec.id + "': no column " + name +
                               "_overturned in outcomes.csv");
    const std::vector<rm::ItemSpec> specs = member_specs(o, item);
    for (const rm::ItemSpec& spec : specs) {
      const Member member = make_member(o, item, spec, solid);
      auto group = std::find_if(specimens.begin(), specimens.end(), [&](const Specimen& sp) { return sp.id == name; });
      if (group != specimens.end()) {
        group->members.push_back(member);
        continue;
      }
      print_specimen(o, item, specs, member, solid);
      specimens.push_back({name, {member}, static_cast<int>(column - outcomes.specimens.begin())});
    }
  }
  return specimens;
}

}  // namespace rocking_monitor::tools::experiments
