#include "rocking_monitor/study/study_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "study_internal.hpp"

namespace rocking_monitor::core::study {

using detail::format_number;

std::vector<double> geometric_spacing(double lo, double hi, int n) {
  std::vector<double> v;
  if (n < 1) return v;
  if (n == 1) return {lo};
  v.reserve(static_cast<std::size_t>(n));
  const double ratio = std::log(hi / lo) / (n - 1);
  for (int i = 0; i < n; ++i) v.push_back(i == n - 1 ? hi : lo * std::exp(ratio * i));
  return v;
}

double eccentricity_of(const BodyParameters& body) { return std::min(body.nu1, 1.0 - body.nu1); }

std::vector<StudyBody> grid_bodies(const StudyGrid& g) {
  auto fail = [](const std::string& what) { throw StudyError("invalid body grid: " + what); };
  if (g.heights < 1) fail("heights = " + std::to_string(g.heights) + " (must be >= 1)");
  if (g.widths < 1) fail("widths = " + std::to_string(g.widths) + " (must be >= 1)");
  for (double v : {g.min_height, g.max_height, g.min_width, g.max_width, g.min_width_ratio,
                   g.max_width_ratio})
    if (!(v > 0.0) || !std::isfinite(v)) fail("limits must be finite and > 0");
  if (g.min_height > g.max_height) fail("min_height > max_height");
  if (g.eccentricities.empty()) fail("no eccentricities");
  for (double nu : g.eccentricities)
    if (!(nu > 0.0 && nu < 1.0)) fail("eccentricity " + format_number("%g", nu) + " outside (0, 1)");
  std::vector<StudyBody> bodies;
  const std::vector<double> heights = geometric_spacing(g.min_height, g.max_height, g.heights);
  for (double nu : g.eccentricities) {
    for (double h : heights) {
      const double lo = std::max(g.min_width, g.min_width_ratio * h);
      const double hi = std::min(g.max_width, g.max_width_ratio * h);
      if (lo > hi)
        fail("no width for h = " + format_number("%g", h) + " m: range [" + format_number("%g", lo) +
             ", " + format_number("%g", hi) + "] m is empty");
      for (double b : geometric_spacing(lo, hi, g.widths)) {
        StudyBody sb;
        sb.parameters.width = b;
        sb.parameters.cg_height = h;
        sb.parameters.nu1 = nu;
        // The eccentric body keeps the moment of inertia of its symmetric twin (homogeneous B x 2h).
        sb.parameters.radius_of_gyration = Body::homogeneous_radius_of_gyration(b, h);
        char name[96];
        std::snprintf(name, sizeof name, "h%.3f_B%.4f_nu%.2f", h, b, nu);
        sb.name = name;
        bodies.push_back(std::move(sb));
      }
    }
  }
  return bodies;
}

BodyParameters plane_body(const ItemSpec& item, Plane plane) {
  BodyParameters x = item.body;
  if (std::isnan(x.radius_of_gyration)) x.radius_of_gyration = Body::homogeneous_radius_of_gyration(x.width, x.cg_height);
  if (plane == Plane::X) return x;
  try {
    return y_plane_body(x, item.depth);
  } catch (const std::exception& e) {
    throw StudyError("item '" + item.id + "': y plane: " + e.what());
  }
}

std::vector<BodyParameters> member_bodies(const StudyBody& body, int n, std::uint64_t seed) {
  if (!body.uncertain) return std::vector<BodyParameters>(static_cast<std::size_t>(std::max(n, 0)), body.parameters);
  std::vector<BodyParameters> out;
  for (const ItemSpec& m : draw_members(*body.uncertain, n, seed)) out.push_back(plane_body(m, body.plane));
  return out;
}

}  // namespace rocking_monitor::core::study
