// SPDX-License-Identifier: MIT
// `raft` (issue 18 acceptance): a square raft of touching spheres loaded on a Bingham paste, through the
// engine (a dynamics = "flow" scene). A footing on a yield-stress material holds below its bearing capacity
// and punches in above it; Skempton's range for a square footing is q_u = 5 .. 9 tau_y (Skempton 1951: Nc =
// 5.14 at the surface, ~6.2 for a square, up to 9 deep). The raft is one layer of 10 x 10 spheres of 5 mm
// (5 cm wide, A = 25 cm2), rigid: after every DEM step its spheres are put back on one vertical path (the mean
// vertical velocity of the layer, plus the load's kick F h / M), so it neither tilts nor spreads. The load
// q = (F + raft weight) / A is given in units of tau_y.
//
// Holds: the penetration stays below half the width and the raft's speed at the end is below hold_speed.
// Punches in: the penetration exceeds half the width, or the speed stays above hold_speed.
#pragma once

namespace pastemix::model::fluid {

struct RaftSettings {
  double load = 3.0;            // q / tau_y, (F + raft weight) / (tau_y A)
  double yield_stress = 46.0;   // Pa, the paste's tau_y
  double viscosity = 0.2;       // Pa s, plastic viscosity
  double regularisation = 100.0;  // s, Papanastasiou's m
  double cell = 0.01;           // m, cubic cells
  double time = 1.0;            // s simulated
  double time_step = 1e-4;      // s, the DEM step (no contact acts: the raft is rigid by its driving)
  long coupling_interval = 50;  // DEM steps per flow interval
  double hold_speed = 2e-3;     // m/s: a raft slower than this at the end has stopped
};

struct RaftResult {
  double penetration = 0.0;  // m, the raft's sink below its start at the end
  double speed_end = 0.0;    // m/s, its sinking speed at the end
  double force = 0.0;        // N, the extra load F
  bool punched = false;
  long cycles = 0;
  double seconds = 0.0;  // wall time
};

RaftResult run_raft(const RaftSettings& s);

}  // namespace pastemix::model::fluid
