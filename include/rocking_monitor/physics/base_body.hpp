#pragma once

// A rigid body standing on a convex polygonal base (issue 27): the 3-D generalisation of the
// paper's planar body. Each hull edge is a planar pivot (physics/body.hpp's Pivot: alpha, R, p
// about that edge); each hull vertex is a point pivot for the corner wobble.

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rocking_monitor/physics/body.hpp"

namespace rocking_monitor::core {

/// Hull vertices a base may have (the 3-D model keeps a fixed-size per-vertex state).
inline constexpr int kMaxBaseVertices = 128;

/// What the user (or scripts/rocking_geometry.py) describes. SI units, in the item's floor frame:
/// z up, z = 0 the floor, x the item's x (its first rocking plane), y = z cross x.
struct BaseBodyParameters {
  double mass = 1.0;                    ///< kg (the motion depends on inertia / mass only)
  Eigen::Vector3d centre_of_mass{0.0, 0.0, 0.0};  ///< m; z = height above the floor, > 0
  Eigen::Matrix3d central_inertia = Eigen::Matrix3d::Zero();  ///< kg m^2 about the centre of mass
  /// The base contact's convex hull on the floor, m, counter-clockwise seen from above, >= 3
  /// vertices, no repeated or collinear ones.
  std::vector<Eigen::Vector2d> base;
  /// Static friction coefficient; +inf = not given (sliding not checked).
  double mu_s = std::numeric_limits<double>::infinity();
  /// Kinetic friction coefficient while sliding (issue 51); NaN = mu_s.
  double mu_k = std::numeric_limits<double>::quiet_NaN();
  /// Multiplies the angular velocity after each impact of the 3-D law (angular momentum about the
  /// new contact conserved), in [0, 1]: 1 = the law itself (the 3-D form of eq. 34).
  double restitution_factor = 1.0;
  /// Tilt of the base from the floor at which the body lies on its side and counts OVERTURNED, rad.
  double overturn_angle = 1.5707963267948966;
  /// The body's convex hull (issue 40 part 3), m, item frame: points whose hull, with the base's
  /// vertices, is the contact geometry once the body tilts beyond its base. Empty: the base polygon
  /// alone (the body rocks on its base's edges and corners only). At most kMaxBaseVertices hull
  /// vertices; no point below the floor or on it outside the base.
  std::vector<Eigen::Vector3d> hull;
  /// What the item stands on when not the floor (issue 51): the top of its plinth, shelf or pedestal, m,
  /// item frame, convex, counter-clockwise; empty: the floor, unbounded. The contact polygon is the base
  /// where it lies on the support (BaseBody clips `base` to it), and the item falls off when its centre
  /// of mass passes the support's edge. With a hull only a pedestal within the base: the body rocks
  /// on the pedestal's edges, and no other hull face can come down onto the pedestal.
  std::vector<Eigen::Vector2d> support;
  /// The support's edges with a lip (issue 51), 0-based: edge k runs from support vertex k to k + 1. A
  /// lip is a stop at the support's top along that edge, low beside the item: the base cannot slide
  /// across it; meeting it the item trips (pivots on the base's corner or edge at the lip, the plastic
  /// impact) or slides on along it. The base must lie within every lipped edge.
  std::vector<int> support_lips;
  /// The lips' height above the support's top, m (>= 0). Pivoting on a corner, a lifted base corner
  /// lower than this meets the lip's face (a plastic impact stops its motion into it); 0: the lip is
  /// low beside the item and a corner rocking over it passes over it.
  double support_lip_height = 0.0;
};

/// Empty when valid, else "<field>: <problem>" naming the field as the catalogue does.
std::string validate(const BaseBodyParameters& parameters);

/// Rocking about one hull edge: a planar pivot in the plane normal to the edge.
struct BaseEdge {
  int a = 0, b = 0;           ///< vertex indices (a -> b counter-clockwise)
  Eigen::Vector3d axis;       ///< unit vector a -> b; theta > 0 about it lifts the base
  Eigen::Vector3d normal;     ///< outward horizontal unit normal = axis x z
  double length = 0.0;        ///< m
  Pivot pivot;                ///< alpha, R, I/m, p about this edge (restitution unused)
};

/// Pivoting on one hull vertex (3 rotational degrees of freedom).
struct BaseVertex {
  Eigen::Vector3d position;       ///< on the floor (z = 0), m
  Eigen::Vector3d to_centre;      ///< centre of mass - position at rest, m
  Eigen::Matrix3d inertia;        ///< inertia about the vertex / mass at rest, m^2
  Eigen::Matrix3d inertia_inverse;
  double alpha = 0.0;             ///< angle of to_centre from the vertical, rad
  double radius = 0.0;            ///< |to_centre|, m
};

struct ContactHull;

class BaseBody {
 public:
  /// Throws BodyError with validate()'s message.
  explicit BaseBody(const BaseBodyParameters& parameters);
  /// A face of a hull as a base: the centre of mass may lie beyond its edges (then those edges'
  /// alpha <= 0 and stands() is false); no hull of its own.
  static BaseBody face(const BaseBodyParameters& parameters);
  /// The same body after it slid or turned on its support (issue 51): `placed` is the support's top
  /// as seen in the item frame now, and the contact is the whole base (as given, before any support
  /// cut it) where it lies on it. parameters() keep the support where the item stood. Throws
  /// BodyError when the centre of mass is off `placed` or they do not overlap.
  BaseBody on_support(const std::vector<Eigen::Vector2d>& placed) const;
  /// The base as given, before a support cut it to the contact (the contact is base(): vertices).
  const std::vector<Eigen::Vector2d>& whole_base() const { return whole_base_; }

  const BaseBodyParameters& parameters() const { return params_; }
  int vertex_count() const { return static_cast<int>(vertices_.size()); }
  const BaseVertex& vertex(int i) const { return vertices_[static_cast<std::size_t>(i)]; }
  /// Edge k runs from vertex k to vertex k+1 (mod n).
  const BaseEdge& edge(int k) const { return edges_[static_cast<std::size_t>(k)]; }
  int next(int i) const { return (i + 1) % vertex_count(); }
  int previous(int i) const { return (i + vertex_count() - 1) % vertex_count(); }
  /// Central inertia / mass, m^2.
  const Eigen::Matrix3d& central_inertia_per_mass() const { return central_; }
  const Eigen::Vector3d& centre_of_mass() const { return params_.centre_of_mass; }
  /// Mean of the base vertices (on the floor): a point inside the base.
  const Eigen::Vector3d& centroid() const { return centroid_; }
  double overturn_angle() const { return params_.overturn_angle; }
  double restitution_factor() const { return params_.restitution_factor; }
  /// Smallest edge tipping angle and the largest p of any edge (step-size scales).
  double min_alpha() const { return min_alpha_; }
  double max_p() const { return max_p_; }
  /// The centre of mass lies above the base (every edge's alpha > 0): the body can rest on it.
  bool stands() const { return stands_; }
  /// The contact geometry: the hull's vertices and faces (face 0 the base). Without a hull in the
  /// parameters: the base's vertices and the base as the only face.
  const ContactHull& contact_hull() const { return *hull_; }

 private:
  BaseBody(const BaseBodyParameters& parameters, bool must_stand);
  void build_contact_hull();
  BaseBodyParameters params_;
  std::vector<Eigen::Vector2d> whole_base_;
  bool stands_ = true;
  std::shared_ptr<const ContactHull> hull_;
  Eigen::Matrix3d central_;
  Eigen::Vector3d centroid_ = Eigen::Vector3d::Zero();
  std::vector<BaseVertex> vertices_;
  std::vector<BaseEdge> edges_;
  double min_alpha_ = 0.0, max_p_ = 0.0;
};

/// The box-like item of the planar decomposition as a 3-D body: a rectangular base B x D with the
/// corners (0,0), (B,0), (B,D), (0,D), the centre of mass at (nu1 B, nu_y D, h), central inertia
/// per unit mass diag(i_x^2, i_g^2, (B^2 + D^2) / 12) where i_g is the x plane's radius of gyration
/// (about y) and i_x the y plane's (about x). The x plane of this body is `x` exactly.
BaseBodyParameters box_base_body(const BodyParameters& x, double depth, double nu_y,
                                 double radius_of_gyration_y);

}  // namespace rocking_monitor::core
