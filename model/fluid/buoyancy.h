// SPDX-License-Identifier: MIT
// Buoyancy with partial submergence: the submerged volume of a sphere below a horizontal free surface.
//
// The thesis's f-EDEM applied full buoyancy as soon as a particle's centre entered the paste. For a 50 mm
// rock falling into a 150 mm paste layer that is a large error for the first rock diameters of travel, so
// we use the spherical cap below the surface: V = pi h^2 (3 r - h) / 3 with h the submerged depth of the
// sphere, clamped to [0, 2 r].
#pragma once

#include <algorithm>

#include "base/units.h"

namespace pastemix::model::fluid {

inline constexpr double kPi = units::pi;  // base/units.h, the project's one pi

// Submerged volume (m^3) of a sphere of radius r (m) with centre height z (m) below a surface at z_s (m).
inline double submerged_volume(double z, double r, double z_s) {
  const double h = std::clamp(z_s - (z - r), 0.0, 2.0 * r);
  return kPi * h * h * (3.0 * r - h) / 3.0;
}

// Height of a cap's centroid is not needed: buoyancy is applied at the particle centre (no torque), which
// is exact for a fully submerged sphere and a small error for a partly submerged one (no rotation drive).

}  // namespace pastemix::model::fluid
