#include "rocking_monitor/physics/impact.hpp"

namespace rocking_monitor::core {

double impact_velocity_ratio(double ig2, double h, double width, double nu_s) {
  const double b2 = width * width;
  return (ig2 + h * h - (1.0 - nu_s) * nu_s * b2) / (ig2 + h * h + nu_s * nu_s * b2);
}

double impact_energy_ratio(double ig2, double h, double width, double nu_s) {
  const double b2 = width * width;
  const double num = ig2 + h * h - (1.0 - nu_s) * nu_s * b2;
  return num * num /
         ((ig2 + h * h + (1.0 - nu_s) * (1.0 - nu_s) * b2) * (ig2 + h * h + nu_s * nu_s * b2));
}

}  // namespace rocking_monitor::core
