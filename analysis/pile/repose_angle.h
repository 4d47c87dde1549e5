// SPDX-License-Identifier: MIT
// Angle of repose of a pile of spheres, measured from the pile's surface profile.
//
// Lab practice (thesis ch. 5/6) measures the pile height and diameter; a simulation gives every particle,
// so we measure the surface itself:
//  1. The pile axis is the vertical through `axis_xy` (the funnel axis), or the pile's mass centre.
//  2. Space around the axis is divided into `sectors` azimuthal sectors and radial bins of width `bin`.
//     In each (sector, bin) cell the surface height is the highest sphere top (z + r) in the cell.
//  3. In each sector the flank is the part of the profile outward of the sector's highest cell and between
//     `flank_lo` and `flank_hi` of the pile's height above the base; a least-squares line h = a - b rho
//     through those points gives the sector's angle atan(b). Excluding the rounded top and the toe (rolling particles) is what makes the number
//     comparable to a lab protractor/height-diameter reading.
//     The sector's pile ends at its foot, the first two radial bins in a row outward of the peak whose surface
//     sphere lies on the base (or that are empty): a single layer is no pile, and spheres beyond it (an apron,
//     debris that bounced or rolled away) are neither flank nor pile.
//  4. The angle is the mean over sectors with a usable flank; its standard deviation over sectors is the
//     azimuthal spread. The pile diameter is twice the mean over sectors of the largest radius inside the
//     foot at which the surface is still above `toe_height` (m) over the base.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>

#include "base/vec3.h"

namespace pastemix::analysis {

struct ReposeOptions {
  std::optional<std::array<double, 2>> axis_xy;  // m; default: mass centre of the particles
  double base_z = 0.0;                           // m, the floor the pile stands on
  int sectors = 12;
  double bin = 0.0;          // m, radial bin width; 0 = 2 x the mean particle diameter
  double flank_lo = 0.15;    // fraction of the pile height: lower end of the fitted flank
  double flank_hi = 0.75;    // upper end
  double toe_height = 0.0;   // m; 0 = one mean particle diameter
};

struct ReposeAngle {
  double angle_deg = 0.0;     // mean over sectors
  double sd_deg = 0.0;        // spread over sectors
  int sectors_used = 0;
  double height = 0.0;        // m, highest surface point above the base
  double diameter = 0.0;      // m
  std::string method;         // for provenance in outputs
};

// Throws pastemix::RuntimeFailure when the particles do not form a pile with a measurable flank (e.g. they
// all flowed away, or fewer than 3 sectors have 3 flank points): never a silent "0 degrees".
ReposeAngle measure_repose_angle(std::span<const Vec3> position, std::span<const double> radius,
                                 const ReposeOptions& options = {});

}  // namespace pastemix::analysis
