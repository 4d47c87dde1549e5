// SPDX-License-Identifier: MIT
// The lower real branch of the Lambert W function, W_-1(x) for x in [-1/e, 0).
//
// Needed by the closed-form inverse of the Pashias-Boger slump relation (lab/ingest/slump.*). We implement it
// ourselves (no Boost) with Halley's iteration from a start that is already close: the branch-point series
// near x = -1/e and the logarithmic asymptote near x = 0, so 2-4 iterations reach full double precision.
#pragma once

namespace pastemix::lab {

// W_-1(x): the solution w <= -1 of w e^w = x. Throws std::domain_error outside [-1/e, 0).
double lambert_w_minus1(double x);

}  // namespace pastemix::lab
