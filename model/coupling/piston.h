// SPDX-License-Identifier: MIT
// `piston`: the displacement test of the volume-averaged flow (issue 18), in its simplest honest form. A block
// of 3 x 3 x 3 glued spheres (10 mm, simple cubic, touching) is pushed down at constant speed from the air into
// a Newtonian paste in a box with an open top; its solid fraction comes from the kernel (kernel.h) at every
// step, and nothing else couples it to the fluid (no drag yet), so the paste can only feel it through eps_f.
//
// Reference: with the paste at rest again, its free surface is level at the height H where the box's volume
// below H holds the paste and the solid below H, A H = V_paste + int_{z < H} eps_s dV (the displaced volume over
// the free area; the solid integral is taken over the deposited eps_s, cell by cell, with the cut cell's share
// below H). The measured H is the paste column height sum_k eps_f alpha h_z, averaged over the columns that
// the kernel does not reach. A coupling without d eps_f/dt in the projection (with_rate = false) displaces
// nothing: the block's cells overfill instead and the surface stays put.
#pragma once

#include <vector>

#include "model/flow/grid.h"

namespace pastemix::coupling {

struct PistonSettings {
  double cell = 0.005;          // m, cubic cells over a 0.1 x 0.1 x 0.12 m box
  double speed = 0.05;          // m/s, downwards
  double push_time = 0.6;       // s: from the block's bottom 1 cm above the surface to 2 cm below it
  double settle_time = 1.0;     // s, block at rest, paste settling
  double width_factor = 2.0;    // kernel c
  double eta = 5.0;             // Pa s, the paste (Newtonian; damps the surface waves in ~0.1 s)
  double max_time_step = 5e-3;  // s
  bool with_rate = true;        // false: the toy coupling (no d eps_f/dt in the projection)
};

struct PistonResult {
  double rise_measured = 0.0, rise_expected = 0.0;  // m, the surface's rise
  double relative_error = 0.0;                      // |measured - expected| / expected
  double volume_error = 0.0;                        // |V_paste(end) - V_paste(0)| / V_paste(0)
  double surface_spread = 0.0;                      // m, max - min column height over the free columns
  double alpha_min = 0.0, alpha_max = 0.0;          // over the run
  double max_speed_end = 0.0;                       // m/s, at the end
  double max_relative_divergence = 0.0;             // of the projections' continuity residual
  long steps = 0;
  double seconds = 0.0;  // wall time
};

PistonResult run_piston(const PistonSettings& s);

// The two sides of the test, for the same case run with DEM spheres through the engine
// (model/fluid/flow_piston.h). The level H of a box of paste volume `paste_volume` (m3) holding the solid
// eps_s (per cell): A H = V_paste + int_{z < H} eps_s dV, by bisection up to `height` (m).
double piston_level(const flow::Grid& g, const std::vector<double>& eps_s, double paste_volume, double height);
// The measured surface: the paste column height sum_k eps_f alpha h_z over the columns with no solid, their
// mean and their spread (max - min), m.
struct FreeColumns {
  double mean = 0.0, spread = 0.0;
  int count = 0;
};
FreeColumns free_columns(const flow::Grid& g, const std::vector<double>& eps_s, const std::vector<double>& eps_f,
                         const std::vector<double>& alpha);

}  // namespace pastemix::coupling
