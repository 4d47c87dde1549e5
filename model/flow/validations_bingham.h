// SPDX-License-Identifier: MIT
// The yield-stress validations of the flow solver (issue 17; `pastemix validate flow poiseuille | incline |
// cliff`). Each runs a flow with a known answer and returns its error, its cost and its paste-volume drift.
// The paste is the measured 75 % paste unless a case says otherwise: tau_y = 138 Pa (paste.yield_stress,
// Pashias-Boger reduction of datasets/thesis/slump_tests.csv: 137.97 Pa), eta_B = 0.7 Pa s (Table 4.4's
// steel-ball calibration), rho = 1843 kg/m3; regularised after Papanastasiou (model/flow/bingham.h) with the
// m each call gives.
#pragma once

#include <vector>

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
