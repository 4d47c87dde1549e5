// SPDX-License-Identifier: MIT
// What every flow validation (validations.cpp, validations_bingham.cpp) measures the same way: the solver's
// cost, the paste-volume drift, the leftover divergence of a step, and the step loop up to a time.
#pragma once

#include "model/flow/solver.h"

namespace pastemix::flow {

struct Cost {
  long cells = 0, steps = 0;
  double seconds = 0.0;                  // wall s in the solver's steps
  double cell_steps_per_second = 0.0;    // cells x steps / s
  double pressure_iterations = 0.0;      // mean CG iterations per pressure solve
  double viscous_iterations = 0.0;       // mean CG iterations per viscous solve
};
Cost cost_of(const FlowSolver& s);

// |v - v0| / v0 (0 when v0 = 0): the paste volume's drift over a run.
double relative_drift(double v, double v0);
// What a validation's result ends its run with: the paste volume's drift from v0 (m3) and the solver's cost.
template <class Result>
Result finished(Result r, const FlowSolver& s, double v0) {
  r.volume_drift = relative_drift(s.paste_volume(), v0);
  r.cost = cost_of(s);
  return r;
}
// ||div u|| after the projection over ||div u*|| before it (0 when there was none): the step's leftover.
double relative_divergence(const StepStats& st);

// Steps the solver up to t_end (s): each step the solver's own, the last one cut to land on t_end (to 1e-14
// relative); `max_divergence` keeps the largest relative_divergence of those steps.
void advance_to(FlowSolver& s, double t_end, double& max_divergence);

}  // namespace pastemix::flow
