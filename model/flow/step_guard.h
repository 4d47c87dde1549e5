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
#include <string>
#include <vector>

#include "base/error.h"
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

// The fluid's volume flux eps_f u on the faces (eps_face: the step's new fluid fraction per face) moved more than
// kMaxSweepCfl cells per sweep over the step: the split VOF sweeps would be unbounded. The step was chosen from
// u before the continuity projection made room for the particles' volume change over it; a change too fast for
// the step (a rock of several cells entering the box in one coupling cycle: chapter-7 test 3's 50 mm rock took
// 0.555 of a top cell's fluid fraction in one 1 ms step) drives the fluid faster than that step allows.
// FlowSolver::step throws it with u as it was before the projection, so that a caller can retry the step in
// shorter parts (model/coupling/coupled_flow.cpp does); uncaught, it ends the run with its diagnosis (exit 3).
class FluxStepTooLong : public RuntimeFailure {
 public:
  FluxStepTooLong(const std::string& what, double cfl) : RuntimeFailure(what), cfl_(cfl) {}
  double cfl() const { return cfl_; }  // cells per sweep the flux took (> kMaxSweepCfl)
 private:
  double cfl_;
};

// The largest |eps_f u| dt / h over the faces.
double flux_cfl(const Grid& g, const Faces& u, const Faces& eps_face, double dt);

// The diagnosis of a flux CFL `cfl` above the bound: the time, the fastest face, its paste and fluid fractions
// (eps_f old and new per cell) and the largest fluid-fraction change of a cell over the step dt (s).
std::string flux_cfl_diagnosis(const Grid& g, const Faces& u, const Faces& eps_face, const std::vector<double>& alpha,
                               const std::vector<double>& eps_old, const std::vector<double>& eps_new, double dt,
                               double time, long step);

}  // namespace pastemix::flow
