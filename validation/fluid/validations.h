// SPDX-License-Identifier: MIT
// Fluid validations through the engine (one sphere per run, validation/fluid/single_sphere.h). The CLI
// (`pastemix validate ...`, `pastemix calibrate viscosity`) prints their tables; the tests run reduced sizes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "validation/fluid/single_sphere.h"

namespace pastemix::validation {

// --- 1. Water settling (Table 4.1): 0.1 mm, 2700 kg/m3 in water (1000 kg/m3, 1e-3 Pa.s), Stokes drag. ---
struct WaterSettling {
  double dt = 0.0;          // s
  double v_terminal = 0.0;  // m/s, (rho_p - rho_f) g d^2 / (18 eta)
  double tau = 0.0;         // s, rho_p d^2 / (18 eta) (no added mass, as the thesis)
  double max_rel_error = 0.0;  // max over steps t in (0, 10 tau] of |v - v_a| / v_a, v_a = v_t (1 - exp(-t/tau))
  long steps = 0;
};
WaterSettling water_settling(double dt);

// --- 2. Terminal velocity of a sphere in a column (the sphere starts at rest just below the surface). ---
struct ColumnSettling {
  double v_final = 0.0;   // m/s, downward speed at the end of the column
  double v_change = 0.0;  // -, relative change of that speed over the last 10 % of the travel (steadiness)
  bool trapped = false;   // stopped (exact rest) before the end of the column
  double time = 0.0;      // s simulated
};
ColumnSettling column_settling(SphereRun run, double column);

// --- 3. Suspension: at rest, released; did it move? ---
struct SuspensionResult {
  double threshold_ratio = 0.0;  // tau_y / (g d (rho_p - rho_f)) used
  double displacement = 0.0;     // m, |z_end - z_0| after the run
  double speed_end = 0.0;        // m/s
};
// The yield number below which a sphere sinks for this curve (the engine's rest drag D(0+) = net weight):
// (pi/6) / (pi^2/4 + k pi/8), k = the curve's Cd Re' as Re' -> 0 (24: Stokes, 4.19, fitted k).
double suspension_threshold(const drag::DragCurve& curve);
SuspensionResult suspension(SphereRun run, double end_time);

// --- 4. Steel balls in paste (Table 4.4). ---
struct SteelBallPaste {
  double rho_ball = 8135.0;  // kg/m3
  double rho_paste = 1843.0; // kg/m3
  double tau_y = 138.0;      // Pa, this repository's slump reduction (Pashias-Boger, H = 152 mm); printed 136
  double mould_diameter = 0.075, mould_height = 0.150;  // m (paste fills the mould)
  bool mould_wall = true;    // the mould's cylinder wall (a steel contact surface); false: no side wall
  double offset = 0.0;       // m, release point's distance from the mould axis
  drag::DragCurve curve{drag::CurveId::published_4_19, {}};
  double dt = 2e-5;          // s
};
struct BallDrop {
  double distance = 0.0;     // m, initial free surface to the ball's bottom at rest
  double time_to_rest = 0.0; // s after release
  bool reached_bottom = false;
};
// The single-sphere run of a ball of diameter d (m) released at rest with its bottom `height` (m) above the
// paste surface, in the mould (the fluid box of the mould's area).
SphereRun steel_ball_run(const SteelBallPaste& paste, double d, double height, double eta_B);
// That ball's settling distance at rest.
BallDrop steel_ball_drop(const SteelBallPaste& paste, double d, double height, double eta_B);

// Plastic viscosity (Pa.s) that gives the settling distance `distance` (m) for the ball and height, by
// bisection in log(eta) on [eta_lo, eta_hi] (the distance decreases with eta). Throws RuntimeFailure if the
// target is outside the distances at the bracket ends.
struct Calibration {
  double eta = 0.0;          // Pa.s
  double distance = 0.0;     // m, at eta
  int runs = 0;
};
Calibration calibrate_viscosity(const SteelBallPaste& paste, double d, double height, double distance,
                                double eta_lo = 0.01, double eta_hi = 100.0, double rel_tol = 1e-4);

}  // namespace pastemix::validation
