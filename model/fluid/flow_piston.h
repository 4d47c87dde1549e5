// SPDX-License-Identifier: MIT
// `piston` with DEM spheres (issue 18 acceptance): coupling::run_piston's case (a 3 x 3 x 3 block of 10 mm
// spheres, here 0.2 mm apart, pushed at constant speed from the air into a Newtonian paste in a 10 x 10 x 12 cm box with an open
// top) run through the engine: a scene with a dynamics = "flow" region, the block's 27 spheres real World
// particles, coupled both ways by the flow pass (their kernels' solid fraction, the paste's drag and pressure
// force on them, the reaction on the paste). The block is glued and driven: after every DEM step its spheres
// are put back on the prescribed path (x = x0 - U min(t, t_push) e_z, v = -U e_z while pushed, then 0), as a
// clump moved at constant speed; the paste feels their drag and displacement. The spheres are heavy (1e6
// kg/m3) so that the drag impulse a half kick sums, beta h (u - v') with v' = v + (g + F/m) h, is that of the
// driven velocity: for a sphere the drag can relax (beta h / m large), it would also carry the sphere's weight
// over to the paste, which a driven piston's drive holds (measured at 2760 kg/m3 and a 1 ms step: the rise
// +65 % too high). Left: the slip error g h of the half kick, 1 % of U at the default 0.1 ms step.
//
// Reference (as coupling/piston.h): with the paste at rest again its free surface is level at H, A H = V_paste
// + int_{z < H} eps_s dV (the displaced volume over the free area); measured: the mean paste column over the
// columns the block's kernel does not reach.
#pragma once

namespace pastemix::model::fluid {

struct DemPistonSettings {
  double cell = 0.005;           // m, cubic cells
  double speed = 0.05;           // m/s, downwards
  double push_time = 0.6;        // s: the block's bottom from 1 cm above the surface to 2 cm below it
  double settle_time = 1.0;      // s, block held, paste settling
  double time_step = 1e-4;       // s, the DEM step (no contact acts: the spheres are driven)
  long coupling_interval = 50;   // DEM steps per flow interval
  double eta = 5.0;              // Pa s, the paste (Newtonian)
};

struct DemPistonResult {
  double rise_measured = 0.0, rise_expected = 0.0;  // m
  double relative_error = 0.0;                      // |measured - expected| / expected
  double volume_error = 0.0;                        // |V_paste(end) - V_paste(0)| / V_paste(0)
  double surface_spread = 0.0;                      // m, over the free columns
  double max_speed_end = 0.0;                       // m/s, the flow's at the end
  long steps = 0, cycles = 0, flow_steps = 0;
  double seconds = 0.0;  // wall time
};

DemPistonResult run_dem_piston(const DemPistonSettings& s);

}  // namespace pastemix::model::fluid
