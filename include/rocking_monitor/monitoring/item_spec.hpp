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

  bool two_planes() const { return depth.given(); }
};

/// Empty if valid, else "item '<id>': <field>: <problem>" (for start-up errors).
std::string validate(const ItemSpec& spec);

}  // namespace rocking_monitor::core
