#pragma once

namespace rocking_monitor::core {

/// Angular-velocity ratio theta_dot'/theta_dot when the pivot switches so that the corner at
/// horizontal distance nu_s*B from the centre of mass becomes the new pivot (paper eq. 34,
/// conservation of angular momentum about the new pivot). ig2 = i_g^2, all lengths in m.
/// For nu_s = 1/2 and a homogeneous rectangle this is Housner's 1 - 1.5 sin^2(alpha).
double impact_velocity_ratio(double ig2, double h, double width, double nu_s);

/// Kinetic-energy ratio E'/E for the same impact (paper eq. 38).
/// Note: eq. 38 is symmetric in nu_s <-> 1 - nu_s, so the energy lost is the same in both
/// directions even though the velocity ratio (eq. 34) is not.
double impact_energy_ratio(double ig2, double h, double width, double nu_s);

}  // namespace rocking_monitor::core
