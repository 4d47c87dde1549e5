// SPDX-License-Identifier: MIT
// The flow step's guard against non-finite values: each stage of FlowSolver::step (advection, face densities,
// viscosities, viscous step, projection) checks what it produced, so a run stops at the first NaN or infinity
// with the stage, the array, the cell or face (i, j, k) and the time, instead of carrying it into the next
// linear solve (where it showed only as "the pressure solve did not converge (50000 iterations, residual
// -nan)", with no hint of where it came from). One read of each array: all the checks of a step cost about
// one of its ~100 CG iterations (each reads the matrix and several vectors).
#pragma once

#include <string>
#include <vector>

#include "model/flow/advection.h"
#include "model/flow/grid.h"

namespace pastemix::flow {

// Where a check runs: the stage that produced the values, the flow time at the start of the step and the step.
struct CheckPoint {
  const char* stage = "";  // "after advection", ...
  double time = 0.0;  // s
  long step = 0;
};

// RuntimeFailure unless every entry (one per cell) is finite, and also > 0 when `positive`.
void require_finite_cells(const Grid& g, const std::vector<double>& v, const char* what, const CheckPoint& at,
                          bool positive = false);
// The same per face of each component (Grid::face indexing).
void require_finite_faces(const Grid& g, const Faces& u, const char* what, const CheckPoint& at, bool positive = false);

}  // namespace pastemix::flow
