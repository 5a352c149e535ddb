#pragma once

// The bodies of the study: the paper's grid of rectangles (or a list read by study_io.hpp).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rocking_monitor/monitoring/uncertain_item.hpp"
#include "rocking_monitor/physics/body.hpp"
#include "rocking_monitor/physics/base_body.hpp"
#include "rocking_monitor/physics/principal_planes.hpp"
#include "rocking_monitor/study/study_error.hpp"

namespace rocking_monitor::core::study {

struct StudyBody {
  std::string name;           ///< unique label, e.g. "h0.630_B0.252_nu0.30"
  BodyParameters parameters;  ///< radius_of_gyration always set explicitly (finite); the nominal body
  /// A catalogue item given with distributions (issue 13): its laws, and which of its planes this body
  /// is. The fragility runs members drawn from them (member_bodies()); the study runs the nominal.
  std::shared_ptr<const UncertainItemSpec> uncertain;
  Plane plane = Plane::X;
  int ensemble_size = 0;  ///< the item's own member count (0: the run's --members)
};

/// A two-plane item (a body with a depth, issue 11): it rocks in its x-z plane as `x` and in its
/// y-z plane as `y` = y_plane_body(x, depth), without coupling (study_items.hpp runs it).
struct StudyItem {
  std::string name;
  std::shared_ptr<const UncertainItemSpec> uncertain;  ///< as StudyBody's (null: exact)
  int ensemble_size = 0;
  BodyParameters x;        ///< width, eccentricity (nu1), ...; radius_of_gyration set explicitly
  DepthParameters depth;   ///< depth, eccentricity_y, radius_of_gyration_y as given
  BodyParameters y;        ///< the y plane's planar body (radius_of_gyration set explicitly)
  /// The 3-D description (a catalogue item's base polygon, or the box B x D of the planes with
  /// --solid-model 3d): the item also runs the 3-D model (model/rocking_3d_model.hpp) on both
  /// horizontals at once. Empty: the planes only.
  std::optional<BaseBodyParameters> solid;
};

/// The planar body of one plane of a catalogue item, radius of gyration made explicit (a box
/// without one: homogeneous; the y plane: y_plane_body()). Throws StudyError naming the item.
BodyParameters plane_body(const ItemSpec& item, Plane plane);

/// n members of an uncertain body (draw_members() of its item with `seed`, the same Latin hypercube as
/// the live node's ensemble), each as the planar body of the body's plane. A body without
/// distributions gives n copies of its parameters.
std::vector<BodyParameters> member_bodies(const StudyBody& body, int n, std::uint64_t seed);

/// The paper's grid (section "Overturning criteria validation for symmetric bodies"): `heights`
/// centre-of-mass heights log-spaced over [min_height, max_height]; for each, `widths` base widths
/// geometrically spaced over [max(min_width, min_width_ratio h), min(max_width, max_width_ratio h)];
/// homogeneous rectangles B x 2h; each eccentricity nu (CoM at nu B from corner 1) keeps the radius
/// of gyration of its symmetric twin (the paper: "the same moment of inertia").
struct StudyGrid {
  int heights = 4;
  double min_height = 0.25, max_height = 4.0;  ///< m
  int widths = 12;
  double min_width = 0.08, max_width = 3.5;    ///< m
  double min_width_ratio = 0.16, max_width_ratio = 1.2;  ///< B / h limits
  std::vector<double> eccentricities{0.5, 0.4, 0.3, 0.2};
};

/// Bodies of the grid, ordered eccentricity-major, then height, then width. Throws StudyError for an
/// empty or inconsistent grid (counts < 1, limits not positive, empty width range, nu outside (0, 1)).
std::vector<StudyBody> grid_bodies(const StudyGrid& grid = {});

/// n values from lo to hi inclusive with constant ratio (n == 1 gives {lo}).
std::vector<double> geometric_spacing(double lo, double hi, int n);

/// Eccentricity class of a body: min(nu1, 1 - nu1) (a body with nu1 = 0.7 is the mirror image of
/// nu1 = 0.3; both polarities of every record are run, so the two give the same set of cases).
double eccentricity_of(const BodyParameters& body);

}  // namespace rocking_monitor::core::study
