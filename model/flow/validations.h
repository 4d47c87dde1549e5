// SPDX-License-Identifier: MIT
// The flow solver's validations against published references (`pastemix validate flow NAME`; the tests run
// the cheap ones). Each returns its error against the reference, its cost and its paste-volume drift.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "model/flow/solver.h"
#include "model/flow/validation_run.h"  // Cost, cost_of

namespace pastemix::flow {

struct Profile {
  std::vector<double> position, velocity;  // reference points (cavity sides, lid speeds)
};
struct GhiaReference {
  Profile u_vertical, v_horizontal;
};
// Reads datasets/reference/ghia_ghia_shin_1982_cavity.csv for one Reynolds number (InputError if absent).
GhiaReference read_ghia(const std::filesystem::path& csv, int re);

// --- cavity: lid-driven, n x n in x-z, 2 cells deep periodic in y, U = L = 1, rho = 1, eta = 1/Re. ---
struct CavityResult {
  int n = 0;
  double re = 0.0;
  double time = 0.0;            // s simulated (the lid time L/U is 1 s)
  double steady_change = 0.0;   // max |u(t) - u(t - 1 s)| at the end (lid speeds)
  double max_error_u = 0.0, max_error_v = 0.0;  // max |model - Ghia| over the table's interior points (lid speeds)
  double rms_error_u = 0.0, rms_error_v = 0.0;
  std::vector<double> model_u, model_v;         // at the reference positions
  double volume_drift = 0.0;    // |V - V0| / V0
  double max_divergence = 0.0;  // max over steps of the projection's relative divergence
  Cost cost;
};
// Runs until the centreline profiles change by less than `steady_tol` per lid time, or until max_time.
CavityResult cavity(int n, double re, const GhiaReference& ref, double max_time, double steady_tol = 1e-4);

// --- still: flat paste/air interface at rest. ---
struct StillResult {
  int cells_below = 0;
  double interface_cells = 0.0;  // interface height in cells (10.37)
  double time = 0.0;
  double max_speed = 0.0;        // max over all steps and faces of |u| (m/s)
  double volume_drift = 0.0;
  double max_divergence = 0.0;
  Cost cost;
};
StillResult still(double end_time = 1.0, double ratio = 1800.0, double interface_cells = 10.37);

// --- dam-break: Martin & Moyce (1952), n^2 = 2, a = 2.25 in, 2-D (one cell deep, periodic). ---
struct Series {
  std::vector<double> T, Z;
};
struct DamBreakResult {
  int cells_across = 0;          // cells across the column's width a
  std::vector<double> T, front;  // front Z = z/a at the reference T = t sqrt(2 g / a)
  Series track;                  // (T, Z) after every step: when the model reaches a given Z
  double volume_drift = 0.0;
  double max_divergence = 0.0;
  Cost cost;
};
// Front = where the bottom row of cells crosses alpha = 1/2 (linear between cell centres), over a.
DamBreakResult dam_break(int cells_across, const std::vector<double>& T);
inline constexpr double kDamBreakWidth = 2.25 * 0.0254;  // m, the column's width a (Martin & Moyce's larger column)
inline constexpr double kDamBreakGravity = 9.81;         // m/s2
// The dam break at t = 0: water (1000 kg/m3) in [0, a] x [0, 2a], air (rho_air, kg/m3) around it, the closed
// free-slip box.
FlowSolver dam_break_setup(int cells_across, double rho_air = 1.2);
// The pressure (Pa) in the column just after an instant release, relative to the column's top, at (x, z) in
// [0, a] x [0, 2a]: the potential-flow solution of the first instant (velocity zero, acceleration from
// -grad p / rho + g): Laplace's equation, p = 0 on the free face x = a and on the top z = 2a, dp/dx = 0 on the
// back wall, dp/dz = -rho g on the floor. Series in cos(k_n z), k_n = (2n + 1) pi / (4a), air neglected.
double release_pressure(double x, double z);
// The first T at which the track's front reaches Z (linear between steps); NaN if it never does. The
// difference to the data's T at the same Z is the model's lead in time: a constant lead is what a delay at
// the experiment's release gives.
double time_to_reach(const Series& track, double Z);
Series read_martin_moyce(const std::filesystem::path& csv);

}  // namespace pastemix::flow
