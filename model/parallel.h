// SPDX-License-Identifier: MIT
// When to run a loop in parallel. Below a few hundred items an OpenMP fork/join costs more than the loop
// (and on a loaded machine a barrier can wait for a descheduled thread), so small loops stay serial. The
// result does not depend on this: every loop writes outputs indexed by its own variable only.
#pragma once

namespace pastemix::model {

// Loops with fewer items than this run on one thread. Tests set 0 to exercise the parallel paths.
inline long parallel_min_items = 512;

}  // namespace pastemix::model
