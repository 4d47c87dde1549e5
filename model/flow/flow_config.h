// SPDX-License-Identifier: MIT
// A flow case from a TOML [flow] table, read through base/params.h so every bad value names file:line.
//
//   [flow]
//   name = "box_still"                 # output file stem
//   box = [0.20, 0.165, 0.25]          # m, the box's extent along x, y, z (z up)
//   origin = [0.0, 0.0, 0.0]           # m, its low corner (default 0)
//   cell = 0.005                       # m, cubic cells; it must divide every side of the box
//   cells = [20, 16, 25]               # or: the number of cells per axis (h_d = box_d / n_d; not with cell)
//   cfl = 0.3                          # max |u_d| dt / h_d per sweep, in (0, 0.5] (VOF boundedness)
//   max_time_step = 0.01               # s
//   end_time = 2.0                     # s
//   output_interval = 0.5              # s between snapshots (and one at t = 0)
//   gravity = [0.0, 0.0, -9.81]        # m/s2 (default)
//   pressure_tolerance = 1e-10         # relative divergence left by the projection, <= 1e-10
//   viscous_tolerance = 1e-10
//   [flow.boundary]                    # no_slip | free_slip | open | periodic, per side or per axis
//   x = "no_slip"                      # both x sides (or x_lo / x_hi); y, z likewise; default no_slip
//   z_hi = "open"
//   z_hi_velocity = [0.0, 0.0, 0.0]    # m/s, a moving wall's velocity (tangential part used), optional
//   [flow.paste]
//   density = 1850.0                   # kg/m3
//   law = "newtonian"                  # newtonian | bingham | herschel_bulkley (model/flow/bingham.h)
//   viscosity = 1.0                    # Pa s (newtonian only)
//   # law = "bingham": yield_stress (Pa), plastic_viscosity (Pa s), density, or instead of those three
//   #   rheology_from = "../../out/lab/parameters.toml" and solids_fraction = 0.75 (the engine's store keys);
//   #   regularisation = 1000.0        # s, Papanastasiou's m (required: its effect is part of every result)
//   # law = "herschel_bulkley": yield_stress (Pa), consistency (Pa s^n), flow_index (-), regularisation (s)
//   [flow.air]
//   density = 1.2                      # kg/m3
//   viscosity = 1.8e-5                 # Pa s
//   [flow.initial]
//   paste_below = 0.10                 # m: paste fills the box up to this height (optional)
//   [[flow.initial.paste_box]]         # and/or boxes of paste (optional, any number)
//   lo = [0.0, 0.0, 0.0]
//   hi = [0.05, 0.165, 0.10]
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "base/params.h"
#include "model/flow/solver.h"

namespace pastemix::flow {

struct PasteBox {
  std::array<double, 3> lo{}, hi{};  // m
};

struct FlowCase {
  std::string name = "flow";
  Grid grid;
  Phases phases;
  FlowSettings settings;
  double end_time = 1.0;         // s
  double output_interval = 0.0;  // s; 0: only the first and last states
  std::vector<PasteBox> paste;
  std::string source;            // the file it came from
};

// Reads the [flow] table (keys as above). Unknown keys are left for the caller's finish().
FlowCase read_flow_case(const Params& flow);
// Parses a file holding a [flow] table; every key must be known (InputError naming file:line otherwise).
FlowCase load_flow_case(const std::filesystem::path& path);

// A solver set up with the case's grid, phases, settings and initial paste.
FlowSolver make_solver(const FlowCase& c);

}  // namespace pastemix::flow
