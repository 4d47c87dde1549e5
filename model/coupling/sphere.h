// SPDX-License-Identifier: MIT
// The `sphere` case of issue 18: one sphere settling through the coupled paste (coupled_flow.h) in a periodic
// box, against the reference for that box.
//
// Newtonian: Stokes's terminal velocity U_s = F / (3 pi mu d) with the periodic array's correction (Hasimoto
// 1959; Sangani & Acrivos 1982, Int. J. Multiphase Flow 8, 343-360, simple cubic array, phi = the sphere's
// volume over the box's):
//   U = U_s (1 - 1.7601 phi^(1/3) + phi - 1.5593 phi^2 + 3.9799 phi^(8/3) - 3.0734 phi^(10/3)),
// U the sphere's velocity relative to the fluid's mean. A periodic box has no hydrostatic pressure, so a mean
// pressure gradient G = M g / V_box (M: fluid + sphere) holds the mixture, as in Hasimoto's problem: the fluid
// feels g - G / rho_f, the sphere m g - V_p G (model A's buoyancy, with the mixture's mean density), so that
// F = V_p (rho_p - M / V_box) g is the drag at the terminal state and the mixture's momentum stays 0.
// Bingham: the paste is the flow's regularised Bingham fluid and the drag law Bingham-Dedegil on the Stokes
// curve; at Y = tau_y / (g d (rho_p - rho_f)) above the law's rest threshold (pi / 6) / (pi^2 / 4 + 3 pi)
// = 0.044 the sphere sticks (it must stay at rest: no creep through the coupling), below it moves.
#pragma once

#include <array>

namespace pastemix::coupling {

struct SphereSettings {
  double cell_over_diameter = 1.0;  // h / d
  double box_over_diameter = 8.0;   // L / d (the box: a whole number of cells)
  double width_factor = 2.0;        // kernel c
  bool disturbance = true;          // drag.h's self-induced velocity correction
  double diameter = 0.01;           // m
  double rho_particle = 2000.0, rho_fluid = 1000.0;  // kg/m3
  double viscosity = 5.0;           // Pa s (Newtonian) or the plastic viscosity (Bingham)
  double yield_number = 0.0;        // Y; > 0: Bingham paste with tau_y = Y g d (rho_p - rho_f)
  double regularisation = 1000.0;   // s, Papanastasiou m of the flow's Bingham law
  // Simulated time: a settling time (0: three times the longer of the sphere's relaxation time and the box's
  // slowest viscous mode, L^2 / (4 pi^2 nu)), then the averaging window: the time to settle by one cell at the
  // reference velocity (the drag varies with the sphere's place in its cell; Bingham: the settling time again).
  double settle_time = 0.0;         // s
  double coupling_interval = 0.005;  // s: one DEM step per flow step
  // The start, in box lengths: off the cell lattice's symmetry points, so that the answer is not a lucky
  // alignment (x and y stay; z is averaged over a cell's travel).
  std::array<double, 3> start{0.37, 0.41, 0.53};
};

struct SphereResult {
  double velocity = 0.0;      // m/s, the sphere's slip against the fluid's mean, averaged over the window
  double slip_min = 0.0, slip_max = 0.0;  // m/s, over the window (the cell-position modulation)
  double reference = 0.0;     // m/s, Hasimoto's (Newtonian)
  double stokes = 0.0;        // m/s, U_s of the same force in an unbounded fluid
  double error = 0.0;         // -, velocity / reference - 1
  double max_speed_late = 0.0;  // m/s, max |v_p| over the window (Bingham: the creep)
  double travel = 0.0;          // m, how far the sphere settled over the window
  double reynolds = 0.0;      // -, rho_f U d / mu
  // -, the resolved pressure's force on the sphere (model A's -V_p grad p beyond the mean gradient) over the
  // window, upward positive, over F: what the sphere's own reaction's pressure adds to its drag.
  double pressure_share = 0.0;
  int cells = 0, cycles = 0;
  double seconds = 0.0;       // wall time
};

SphereResult run_sphere(const SphereSettings& s);

}  // namespace pastemix::coupling
