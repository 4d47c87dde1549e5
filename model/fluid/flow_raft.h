// SPDX-License-Identifier: MIT
// `raft` (issue 18 acceptance): a square raft of touching spheres loaded on a Bingham paste, through the
// engine (a dynamics = "flow" scene). A footing on a yield-stress material holds below its bearing capacity
// and goes above it; Skempton's range for a footing is q_u = 5 .. 9 tau_y (Skempton 1951: Nc = 5.14 for a
// strip at the surface, ~6.2 for a square at the surface, up to 9 deep).
//
// The raft: one layer of 10 x 10 spheres of 5 mm, touching (5 nm apart: the scene refuses an overlap), 5 cm
// wide (A = 25 cm2), centred in a box of paste 6 cm deep. It starts seated, its tops level with the surface
// (its base D0 = 5 mm deep): the spheres' kernels (half-width c d / 2 = 5 mm) then reach the paste with a paste
// share of ~0.8, the factor of each sphere's drag and yield part. Set on the surface (bottoms on it) the share
// was 0.24, a yield support of 0.24 x 11.9 tau_y d^2 per sphere, and above q ~ 3.5 the raft slid through the
// paste whatever the paste's bearing capacity (model/coupling/VALIDATION.md, raft).
//
// The load q (given as q / tau_y) is the raft's weight over A: the spheres' density is q A / (g V_raft). The
// weight is the one force that enters the engine's half kick, so the paste's drag (implicit) and its yield
// stick see the load as they see any force. (The draft pushed the raft with a velocity kick F h / M after
// each step instead, outside the drag step: a stuck raft then still moved F h / M every step, measured 0.93
// mm/s at q = 3 against F h / M = 0.97 mm/s, and 2.3 mm/s at q = 5, above the hold speed.)
//
// Rigid in shape: after every DEM step the spheres are put back on one vertical translation of their start
// (the mean displacement: no tilt, no spread); their velocities are left as the engine made them (flow_raft.cpp
// says why a velocity reset fails), so each sphere carries its own weight into the paste: a uniform load, as
// on Prandtl's footing.
//
// The paste's weight: 1789 kg/m3 against tau_y = 46 Pa makes gamma B / tau_y = 19, so every millimetre the raft
// sinks adds gamma x 1 mm = 0.38 tau_y of overburden at its base (Skempton's gross capacity is Nc tau_y +
// gamma D). A raft that goes sinks until its net pressure q - gamma D is back at the paste's capacity, and then
// holds there: it does not plunge. The result reports that net pressure.
//
// Goes (`punched`): the settlement exceeds fail_settlement (0.1 B, the usual failure settlement of a footing
// whose load-settlement curve does not plunge), or the mean sinking speed over the last speed_window is above
// hold_speed. Holds otherwise.
#pragma once

#include <vector>

namespace pastemix::model::fluid {

struct RaftSettings {
  double load = 3.0;               // q / tau_y: the raft's weight over (tau_y A)
  double yield_stress = 46.0;      // Pa, the paste's tau_y (the 72.5 % paste of flow_stream_small.toml)
  double viscosity = 0.2;          // Pa s, plastic viscosity
  double paste_density = 1789.4;   // kg/m3
  double regularisation = 1000.0;  // s, Papanastasiou's m: a held raft creeps at ~ B / m (flow_raft.cpp)
  double cell = 0.005;             // m, cubic cells
  double box = 0.1;                // m, the paste box's side (the raft centred in it)
  double time = 1.0;               // s simulated
  double time_step = 1e-4;         // s, the DEM step (no contact acts: the raft keeps its shape by its reset)
  long coupling_interval = 50;     // DEM steps per flow interval
  double flow_time_step = 0.0;     // s, the flow's largest sub-step in a cycle (0: the solver's default, 1e-2)
  bool implicit_stick = false;     // model/coupling/coupled_flow.h
  double hold_speed = 2e-3;        // m/s: a raft slower than this at the end has stopped
  double speed_window = 0.1;       // s, the end speed is the mean over the run's last window
  double fail_settlement = 5e-3;   // m, 0.1 B
  double trace_every = 0.0;        // s, > 0: RaftResult::trace sampled this often
};

// What the paste's drag sees at the spheres (coupling/exchange.h's masked weights W, without the disturbance
// shift), means over the spheres.
struct RaftSample {
  double time = 0.0, penetration = 0.0, speed = 0.0;  // s, m, m/s (sinking: positive)
  double paste_speed = 0.0;  // m/s, the fastest paste (flow::paste_speed)
  double share = 0.0;        // the spheres' paste share (the factor of their drag and yield part)
  double slip = 0.0;         // m/s, (W u - v)_z: > 0, the raft sinks through the paste at its spheres
  double swirl = 0.0;        // m/s, the paste's velocity W u at the spheres about the raft's vertical axis
};

struct RaftResult {
  double penetration = 0.0;  // m, the raft's settlement below its seat at the end
  double slid = 0.0;         // m, of it: the sink through the paste at the spheres (the cycles' slip x T);
                             // the rest is the paste's own sink with the raft
  double net_load = 0.0;     // q / tau_y - gamma (D0 + penetration) / tau_y at the end
  double speed_end = 0.0;    // m/s, the mean sinking speed over the last speed_window
  double max_speed = 0.0;    // m/s, the fastest mean sinking over the run
  double density = 0.0;      // kg/m3, the spheres' (the load as their weight)
  double weight = 0.0;       // N, the load q A
  bool punched = false;      // the raft went (see above)
  long cycles = 0, flow_steps = 0;
  double seconds = 0.0;  // wall time
  std::vector<RaftSample> trace;
};

// std::invalid_argument for a load below the paste's buoyancy (a raft lighter than the paste it displaces).
RaftResult run_raft(const RaftSettings& s);

}  // namespace pastemix::model::fluid
