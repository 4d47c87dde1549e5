// SPDX-License-Identifier: MIT
// The yield-stress validations of the flow solver (issue 17; `pastemix validate flow poiseuille | incline |
// cliff`). Each runs a flow with a known answer and returns its error, its cost and its paste-volume drift.
// The paste is the measured 75 % paste unless a case says otherwise: tau_y = 138 Pa (paste.yield_stress,
// Pashias-Boger reduction of datasets/thesis/slump_tests.csv: 137.97 Pa), eta_B = 0.7 Pa s (Table 4.4's
// steel-ball calibration), rho = 1843 kg/m3; regularised after Papanastasiou (model/flow/bingham.h) with the
// m each call gives.
#pragma once

#include <functional>
#include <limits>
#include <vector>

#include "model/flow/obstacle.h"
#include "model/flow/validations.h"

namespace pastemix::flow {

struct BinghamPaste {
  double tau_y = 138.0;   // Pa
  double eta_B = 0.7;     // Pa s
  double rho = 1843.0;    // kg/m3
};

// --- poiseuille: plane channel between no-slip walls z = 0 and z = H, periodic along x (one cell) and y,
// driven by a body force G = rho g_x (Pa/m) chosen so that the plug half-width tau_y / G is H / 4. ---
// Analytic (Bird, Armstrong & Hassager 1987): with zeta = |z - H/2| and y0 = tau_y / G,
//   u = G/(2 eta_B) ((H/2)^2 - zeta^2) - tau_y/eta_B (H/2 - zeta)  for zeta >= y0,
//   u = G/(2 eta_B) (H/2 - y0)^2 (the plug)                          for zeta <  y0.
struct PoiseuilleResult {
  int cells = 0;                 // across the channel
  double m = 0.0;                // s
  double H = 0.0;                // m
  double l2_error = 0.0;         // ||u - u_exact|| / ||u_exact|| over the cell centres
  double max_error = 0.0;        // max |u - u_exact| / u_plug
  double plug_width = 0.0;       // m, model: where eta(gd) gd crosses tau_y (edge strain rates, linear between)
  double plug_width_exact = 0.0; // m, 2 tau_y / G
  double plug_speed = 0.0, plug_speed_exact = 0.0;  // m/s, at the centre
  double last_change = 0.0;      // max |u(step) - u(step - 1)| / u_plug at the end (steady)
  double volume_drift = 0.0, max_divergence = 0.0;
  std::vector<double> z, u, u_exact;
  Cost cost;
};
PoiseuilleResult bingham_poiseuille(int cells, double m, const BinghamPaste& p = {});

// --- incline: a paste layer of depth h on a plane tilted by theta (gravity (g sin, 0, -g cos)), periodic
// along x and y, no-slip floor, air above under a no-slip lid. h_c = tau_y / (rho g sin theta). Analytic
// (Bingham film): no flow for h <= h_c; for h > h_c the surface (plug) speed is
//   U = rho g sin theta (h - h_c)^2 / (2 eta_B). ---
struct InclineResult {
  double depth_over_hc = 0.0, m = 0.0, theta_deg = 0.0;
  int cells = 0;                  // across the layer
  double h_c = 0.0, h = 0.0;      // m
  double surface_speed = 0.0;     // m/s: the top paste cell's velocity along the slope
  double surface_speed_exact = 0.0;
  double time = 0.0;              // s simulated
  double last_change = 0.0;       // relative change of the surface speed over the last 0.25 s
  double volume_drift = 0.0, max_divergence = 0.0;
  Cost cost;
};
InclineResult bingham_incline(double depth_over_hc, int cells, double m, double theta_deg = 30.0,
                              const BinghamPaste& p = {});

// --- cliff: plane strain (one periodic cell along y) vertical cut of height H = k tau_y / (rho g), the paste
// 2 H wide behind the face with a symmetry (free-slip) plane at x = 0, no-slip floor, air around, open top.
// Limit analysis puts the critical height near 3.77 tau_y / (rho g) (Pastor et al. 2000: 3.772-3.786). ---
struct CliffResult {
  double height_over_scale = 0.0, m = 0.0;
  int cells = 0;                 // across H
  double H = 0.0, h = 0.0;       // m: the cut's height, the cell
  double time = 0.0;             // s
  double displacement = 0.0;     // m: integral of the max paste speed over time (bounds any paste's movement)
  double front_advance = 0.0;    // m: how far the foot of the cut moved out (floor row, alpha = 1/2)
  double top_drop = 0.0;         // m: how far the paste's top at x = 0 fell
  double volume_drift = 0.0, max_divergence = 0.0;
  Cost cost;
};
CliffResult bingham_cliff(double height_over_scale, int cells, double m, double time = 2.0,
                          const BinghamPaste& p = {});

}  // namespace pastemix::flow

namespace pastemix::flow {

// --- slump: the lab's slump test (152 mm cylinder, H = D, datasets/thesis/slump_tests.csv) on a quarter
// domain (symmetry planes x = 0 and y = 0, no-slip plate, open top), the mould lifted at a finite speed
// (obstacle.h: a staircase shell of radius 76 mm whose lower edge rises at `lift_speed` from t = 0, free slip on
// both its sides; the paste fills the staircase inside it to 152 mm) or at once (lift_speed infinite: the
// exact quarter cylinder and no shell, as before), run to rest
// (model/flow/bingham.h at_rest: the paste's RMS speed below kRestSpeed). References, both quasi-static:
//   Pashias, Boger, Summers & Glenister (1996, J. Rheol. 40:1179), the cylinder: S/H = 1 - 2 tau'(1 - ln 2 tau'),
//     tau' = tau_y / (rho g H) (101.7 mm at 138 Pa, 1843 kg/m3);
//   Roussel & Coussot (2005, J. Rheol. 49:705), the spread (thin-layer) regime: on a no-slip plane the
//     stopped shape obeys rho g h |dh/dr| = tau_y, h = sqrt(2 tau_y (R - r) / (rho g)), whose volume gives
//     R = (225 rho g Omega^2 / (128 pi^2 tau_y))^(1/5) (Omega the sample's volume).
// The slump is measured at the axis (the paste's height in the column of cells at the corner), the spread as
// the diameter of the circle with the area the paste covers on the plate (the bottom row's alpha). ---
struct SlumpResult {
  double cell = 0.0, m = 0.0;            // m, s
  double lift_speed = 0.0;               // m/s; infinity: the instantaneous release
  double released = 0.0;                 // s, when the mould's lower edge passed the paste's highest column
  double tau_y = 0.0, rho = 0.0;         // Pa, kg/m3 (the store's)
  double time = 0.0;                     // s, when at rest (the start of a spell of kSlumpRestHold) or the limit
  double end_time = 0.0;                 // s, the end of the run (time + kSlumpRestHold when at rest)
  bool at_rest = false;
  double final_speed = 0.0;              // m/s, paste_rms_speed at the end (what at_rest judges)
  double final_max_speed = 0.0;          // m/s, paste_speed at the end (the fastest cell with alpha >= 1/2)
  double final_air_speed = 0.0;          // m/s, FlowSolver::max_speed at the end (the fastest face: the air's)
  double slump = 0.0, slump_pashias = 0.0;      // m
  double spread = 0.0, spread_roussel = 0.0;    // m, diameters
  double volume_drift = 0.0, max_divergence = 0.0;
  Cost cost;
};
// The slump (the mould's height minus the corner column's paste height) and the spread (the diameter of the
// circle with the bottom row's paste area), m, of the quarter domain's current state.
struct SlumpShape {
  double slump = 0.0, spread = 0.0;
};
SlumpShape slump_shape(const FlowSolver& s);
// The paste must stay at rest (at_rest) this long before the run stops: a dip of the RMS speed is not rest.
inline constexpr double kSlumpRestHold = 0.1;  // s
// `progress`, when given, is called after every step (the command prints a line per 0.05 s of flow time from it).
using FlowProgress = std::function<void(const FlowSolver&)>;
// At rest counts only once the mould has let go of the paste (its lower edge above the highest column).
SlumpResult bingham_slump(double cell, double m, double tau_y, double rho, double eta_B, double max_time = 4.0,
                          const FlowProgress& progress = {},
                          double lift_speed = std::numeric_limits<double>::infinity());
// The slump's mould (radius 76 mm, height 152 mm, axis on the quarter domain's corner) lifted at `speed` (m/s).
LiftedMould slump_mould(double speed);
double pashias_boger_slump(double tau_y, double rho, double H);  // m
double roussel_coussot_radius(double tau_y, double rho, double volume);  // m

}  // namespace pastemix::flow
