// SPDX-License-Identifier: MIT
// The decision behind `pastemix sweep`: a converged reference from a ladder of runs, each run's error
// against it, and the cheapest setting within tolerance. Pure numbers (no engine), so it is tested on
// synthetic ladders.
//
// Reference: Richardson extrapolation from the three finest points when the ladder is a geometric
// refinement (dt halving, ratio r = 2): observed order p = log(|q3 - q2| / |q2 - q1|) / log r (q1 finest),
// q* = q1 + (q1 - q2) / (r^p - 1). It is used only when the differences converge monotonically (same sign,
// |q3 - q2| > |q2 - q1|), 0.5 <= p <= 8, and, for ensembles, both differences exceed twice their seed
// standard error (otherwise the "order" is noise). In every other case the reference is the finest run.
#pragma once

#include <string>
#include <vector>

namespace pastemix::app::study {

struct LadderPoint {
  double value = 0.0;     // the varied setting (s, m, Pa)
  double qoi = 0.0;       // mean over seeds
  double qoi_sd = 0.0;    // sd over seeds (0 for one seed)
  int seeds = 1;
  double wall_s = 0.0;    // mean wall-clock seconds of one run
  double work = 0.0;      // particle-steps of one run (deterministic cost; 0 = unknown, use wall_s)
};

struct Reference {
  double qoi = 0.0;
  std::string method;     // "Richardson (p = 2.01, r = 2)" or "finest run (why)"
  double order = 0.0;     // observed p; 0 when not extrapolated
};

// `points` ordered coarse -> fine (the last is the finest); `ratio` > 1 is the refinement ratio between
// neighbours, 0 when the ladder is not a geometric refinement (no extrapolation).
Reference reference_of(const std::vector<LadderPoint>& points, double ratio);

struct Choice {
  int index = -1;          // into points; -1 when none is within tolerance
  std::vector<double> rel_error;     // |q - ref| / |ref| per point
  std::vector<bool> significant;     // |q - ref| > 2 x seed standard error (always true for one seed)
};

// The cheapest point whose relative error is <= tol. Cheapest = fewest particle-steps when every point has
// `work` (deterministic: wall-clock on a shared machine jitters by more than the difference between
// neighbouring small runs), else the smallest wall_s.
Choice choose(const std::vector<LadderPoint>& points, const Reference& ref, double tol);

}  // namespace pastemix::app::study
