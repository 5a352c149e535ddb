#pragma once

#include <optional>
#include <string>

#include "rocking_monitor/physics/base_body.hpp"
#include "rocking_monitor/physics/body.hpp"
#include "rocking_monitor/physics/principal_planes.hpp"

namespace rocking_monitor::core {

/// One catalogue entry: a free-standing item, the sensor that feeds it and its frame.
struct ItemSpec {
  std::string id;           ///< unique name
  std::string description;  ///< free text for people
  std::string sensor;       ///< name of the sensor whose acceleration drives it
  std::string frame;        ///< tf frame: x across the base width, y across the depth, z up
  BodyParameters body;      ///< the x-z plane: width, eccentricity, radius of gyration, friction
  DepthParameters depth;    ///< the y-z plane; depth not given: the item rocks in its x plane only
  /// The 3-D description (base polygon, centre of mass, inertia tensor): the 3-D rocking model
  /// can run this item (model/rocking_3d_model.hpp). Not given: planar only.
  std::optional<BaseBodyParameters> solid;
  /// Dimensionless, > 0: multiplies the ground acceleration the item feels (all three components,
  /// gravity excluded), e.g. a fragility calibrated as a lognormal spread of the input's scale
  /// (docs/validation.md section 0, issue 41). Applied where the input is fed: the node, ItemEnsemble,
  /// rocking_experiments; 1 = the record as measured.
  double input_gain = 1.0;

  bool two_planes() const { return depth.given(); }
};

/// Empty if valid, else "item '<id>': <field>: <problem>" (for start-up errors).
std::string validate(const ItemSpec& spec);

}  // namespace rocking_monitor::core
