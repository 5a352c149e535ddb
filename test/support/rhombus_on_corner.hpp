#pragma once
// The rhombus of testing::rhombus() on its +x vertex in both codes: the 3-D model and the planar
// contact model of its x-z plane, put in the same state (the slide-rock and flight reductions).

#include <Eigen/Geometry>

#include "rocking_monitor/model/contact_model.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"

namespace rocking_monitor::core::testing {

/// The planar contact model's settings for the reductions: 512 RK4 sub-steps a sample.
inline ContactSettings fine_contact() {
  ContactSettings cs;
  cs.substeps = 512;
  return cs;
}

/// Both at time 0 on the +x corner, tilted by theta0 (rad) and turning at omega0 (rad/s) about y.
inline void tilt_on_corner(Rocking3DModel& solid, ContactModel& planar, double theta0, double omega0) {
  solid.reset(0.0);
  solid.set_vertex_state(2, Eigen::Quaterniond(Eigen::AngleAxisd(theta0, Eigen::Vector3d::UnitY())),
                         Eigen::Vector3d(0.0, omega0, 0.0));
  planar.reset(0.0);
  planar.set_state(0.0, 0.0, 0.0, 1, theta0, omega0);
}

}  // namespace rocking_monitor::core::testing
