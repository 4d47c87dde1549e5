// SPDX-License-Identifier: MIT
// When to run a loop in parallel. Below a few hundred items an OpenMP fork/join costs more than the loop
// (and on a loaded machine a barrier can wait for a descheduled thread), so small loops stay serial. The
// threshold belongs to the World (WorldConfig::parallel_min_items; tests set 0 to exercise the parallel
// paths on small scenes), which hands each list build its thread count. The result does not depend on it:
// every loop writes outputs indexed by its own variable only.
#pragma once

#include <omp.h>

namespace pastemix::model {

// Loops with fewer items than this run on one thread (the default of WorldConfig::parallel_min_items).
inline constexpr long kParallelMinItems = 512;

// The threads for a loop over n items: one below min_items, else OpenMP's maximum.
inline int threads_for(long n, long min_items) { return n >= min_items ? omp_get_max_threads() : 1; }

}  // namespace pastemix::model
