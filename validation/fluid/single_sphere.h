// SPDX-License-Identifier: MIT
// One sphere in one fluid region, run through the full engine (scene text -> parse_scene -> World): the
// harness of the fluid validations (water settling, terminal velocities, suspension, steel balls) and of
// the viscosity calibration. Building the scene as TOML text exercises the same path as a user's scene.
#pragma once

#include <string>
#include <vector>

#include "base/drag_curves.h"

namespace pastemix::validation {

struct SphereRun {
  double d = 0.0;          // m, sphere diameter
  double rho_p = 0.0;      // kg/m3
  double rho_f = 0.0;      // kg/m3
  double tau_y = 0.0;      // Pa (0: Newtonian, viscosity = eta)
  double eta = 0.0;        // Pa.s, viscosity or Bingham plastic viscosity
  drag::DragCurve curve;   // Cd(Re')
  double depth = 1.0;      // m, fluid depth (bottom at z = 0, surface at z = depth)
  double box_half = 0.0;   // m, half width of the fluid box (0: 10 depths, the surface hardly rises)
  // Release: the sphere's bottom `drop` above the surface (m); negative: its top that far below it.
  double drop = -1e-3;
  double vz0 = 0.0;        // m/s, initial vertical velocity
  double dt = 1e-4;        // s
  bool floor = true;       // a plane wall at the bottom
  double mould_radius = 0.0;  // m, > 0: a cylinder wall on the axis from the bottom to above the release
  double x0 = 0.0;         // m, horizontal offset of the release from the axis (a ball near the mould wall)
  double youngs_modulus = 2e11;  // Pa, of the sphere and wall materials (contacts only)
  bool yield_term = true, partial_submergence = true, buoyancy = true, surface_rise = true;
};

struct SphereTrace {
  std::vector<double> t, z, vz;  // s, m (centre), m/s, one entry per step (t = 0 included)
  double surface0 = 0.0;         // m, initial free surface
  double surface = 0.0;          // m, free surface at the end
  bool stopped = false;          // came to exact rest (v == 0) inside the fluid and stayed
  bool reached_bottom = false;   // came within a radius of the bottom
};

std::string single_sphere_scene(const SphereRun& run, double end_time);

// Runs until end_time, or until the sphere has been at exact rest for `rest_steps` steps (if > 0), or
// comes within one radius + 1 mm of the bottom.
SphereTrace run_single_sphere(const SphereRun& run, double end_time, long rest_steps = 0);

// Settling distance (m): from the initial free surface to the sphere's bottom at rest (trace.stopped).
double settling_distance(const SphereRun& run, const SphereTrace& trace);

}  // namespace pastemix::validation
