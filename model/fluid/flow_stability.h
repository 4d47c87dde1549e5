// SPDX-License-Identifier: MIT
// `bed` and `stream` (issue 18's stability acceptance), through the engine with a dynamics = "flow" scene: a
// packed bed (simple cubic, eps_s = pi / 6 = 0.52) at rest in a paste at rest, and a dense stream of spheres
// falling through the air into the paste, at a DEM step of `relaxations` drag relaxation times tau = m / beta
// (beta = 3 pi eta d, the Stokes drag of a Newtonian paste: the paste's viscosity is set to give it) and a
// coupling interval of `interval` steps. The contacts stay resolved (the step is ~20 % of the spheres'
// Rayleigh time: a paste thousands of times more viscous than the real one makes tau that short).
//
// What is checked (reported, and bounded by the tests): no NaN (the World's own checks), and no energy growth:
// gravity is the only source, so the kinetic energy of particles and fluid together, K(t), never exceeds
// K(0) + the particles' potential energy released since t = 0 (the drag, the paste's viscosity and the
// contacts only dissipate; the paste displaced upwards only stores more). growth = max over the samples of
// K(t) - K(0) - dPE_particles(t), J: <= 0 up to round-off for a stable coupling.
#pragma once

#include <string>

namespace pastemix::model::fluid {

struct StabilitySettings {
  std::string name = "bed";   // "bed" or "stream"
  int layers = 4;             // bed: spheres per side (a cube of layers^3); stream: spheres in the stream / 10
  double diameter = 0.005;    // m
  double relaxations = 10.0;  // DEM step / tau
  long interval = 1;          // DEM steps per flow interval
  double time = 0.02;         // s simulated
  double cell = 0.01;         // m
};

struct StabilityResult {
  double dt = 0.0, tau = 0.0, viscosity = 0.0;  // s, s, Pa s
  long spheres = 0, steps = 0, cycles = 0, samples = 0;
  double kinetic_end = 0.0;         // J, particles + fluid at the end
  double released_end = 0.0;        // J, particles' potential energy released by the end
  double growth = 0.0;              // J, max of K(t) - K(0) - dPE(t) (<= 0: no growth)
  double budget = 0.0;              // J, K(0) + the most potential energy released at a sample (growth's scale)
  double max_speed = 0.0;           // m/s, particles, over the samples
  double paste_volume_error = 0.0;  // relative, end against the first sample (the particles in the grid)
  double seconds = 0.0;             // wall time
};

// Throws InputError for an unknown name, RuntimeFailure (the World's) for a NaN or a blow-up.
StabilityResult run_stability(const StabilitySettings& s);

}  // namespace pastemix::model::fluid
