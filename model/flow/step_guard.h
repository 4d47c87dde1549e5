// SPDX-License-Identifier: MIT
// The flow's step-collapse guard. The CFL bound shrinks the step as the fastest face speeds up; a spurious
// velocity runaway (the air above a paste at rest at 10 mm cells and a 100 mm/s mould lift: 0.4 -> 64 m/s in 3 s,
// dt 7.6 ms -> 47 us, VALIDATION.md) then runs on ever more slowly and never ends. The guard stops such a run at
// the step the CFL bound asks for, with a diagnosis: the time, the fastest face (where it is, its speed, the paste
// fraction on its two sides), the fastest paste face and the cause it reads from them.
//
// The floor is 1/100 of the reference step: the smallest of the step cap, the gravity bound sqrt(cfl h / g) (the
// time gravity alone takes to bring a face at rest to the CFL bound) and cfl h / U of each moving wall. Below it
// a face moves faster than cfl h / floor: with the defaults (cfl 0.3, a 10 ms cap, g = 9.81) 30 m/s at 10 mm
// cells, 15 m/s at 5 mm (the cap is the reference down to 3.3 mm), 100 sqrt(cfl g h) below (5.4 m/s at 1 mm),
// where the flows of this project move at < 2 m/s (the slump 0.7 m/s, the dam break's surge 1.5 m/s). The guard
// only reads: a run it does not stop is the same bit for bit.
#pragma once

#include <array>
#include <vector>

#include "model/flow/advection.h"
#include "model/flow/grid.h"

namespace pastemix::flow {

// What the time-step control knows (FlowSettings' fields of the same names).
struct StepControl {
  double cfl = 0.3;
  double max_time_step = 1e-2;              // s
  std::array<double, 3> gravity{};          // m/s2
};

inline constexpr double kStepCollapse = 100.0;  // reference step / floor

// The reference step (s) and what it is ("gravity bound sqrt(cfl h / g)", ...).
struct ReferenceStep {
  double dt = 0.0;
  const char* what = "";
};
ReferenceStep reference_step(const Grid& g, const StepControl& c);
inline double time_step_floor(const Grid& g, const StepControl& c) { return reference_step(g, c).dt / kStepCollapse; }

// RuntimeFailure (exit 3) with the diagnosis when the CFL step dt (s) is below time_step_floor; `alpha` is the
// paste fraction per cell, `time` and `step` where the run stands; `eps_f`, with particles in the cells, the
// fluid fraction per cell (named on the fastest face's two sides too: a runaway in a packed pile shows there).
void require_time_step_above_floor(const Grid& g, const StepControl& c, const Faces& u, const std::vector<double>& alpha,
                                   double dt, double time, long step, const std::vector<double>* eps_f = nullptr);

}  // namespace pastemix::flow
