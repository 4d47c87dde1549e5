// SPDX-License-Identifier: MIT
// `pastemix calibrate rolling-resistance`: the rolling-resistance coefficient mu_r that makes the simulated
// repose angle equal a measured one (thesis ch. 6, Table 6.1), by bracketing.
//
// The angle grows monotonically with mu_r over the useful range (more rolling resistance, steeper pile), so
// a bisection on [lo, hi] that must bracket the target is enough and never extrapolates: if the target is
// outside [angle(lo), angle(hi)] the command fails and says so. Each evaluation is the mean over seeds; the
// search stops when |mean - target| <= tol_deg or the bracket is narrower than mu_tol, and the answer carries
// the seed sd of its angle. It is for the rolling law the scene names ([contact] rolling); a different law
// gives a different coefficient. Every [[interaction]]'s rolling_friction is set to mu_r (rock/rock and
// rock/wall alike, as the thesis did).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "model/scene_doc.h"

namespace pastemix::app::study {

struct Evaluation {
  double mu = 0.0, angle = 0.0, sd = 0.0;
};

struct BracketResult {
  double mu = 0.0;              // the best evaluated mu (closest angle to the target)
  Evaluation best;
  std::vector<Evaluation> history;
  bool converged = false;       // |angle - target| <= tol_deg
};

// f(mu) -> {angle mean, sd}; throws RuntimeFailure when the target is not bracketed by f(lo), f(hi).
BracketResult bracket_root(const std::function<Evaluation(double)>& f, double lo, double hi, double target,
                           double tol_deg, double mu_tol, int max_evaluations);

// The scene with every [[interaction]] rolling_friction set to mu.
model::SceneDoc with_rolling_resistance(const model::SceneDoc& base, double mu);

}  // namespace pastemix::app::study
