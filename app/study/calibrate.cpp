// SPDX-License-Identifier: MIT
#include "app/study/calibrate.h"

#include <cmath>

#include <fmt/format.h>

#include "base/error.h"

namespace pastemix::app::study {

BracketResult bracket_root(const std::function<Evaluation(double)>& f, double lo, double hi, double target,
                           double tol_deg, double mu_tol, int max_evaluations) {
  BracketResult r;
  auto eval = [&](double mu) {
    Evaluation e = f(mu);
    e.mu = mu;
    r.history.push_back(e);
    if (r.history.size() == 1 || std::abs(e.angle - target) < std::abs(r.best.angle - target)) r.best = e;
    return e;
  };
  Evaluation a = eval(lo), b = eval(hi);
  if ((a.angle - target) * (b.angle - target) > 0)
    throw RuntimeFailure(fmt::format("target angle {:.2f} deg is not bracketed: mu_r = {:g} gives {:.2f} deg, "
                                     "mu_r = {:g} gives {:.2f} deg; widen the bracket",
                                     target, lo, a.angle, hi, b.angle));
  while (std::abs(r.best.angle - target) > tol_deg && std::abs(b.mu - a.mu) > mu_tol &&
         static_cast<int>(r.history.size()) < max_evaluations) {
    const Evaluation m = eval(0.5 * (a.mu + b.mu));
    ((m.angle - target) * (a.angle - target) > 0 ? a : b) = m;
  }
  r.mu = r.best.mu;
  r.converged = std::abs(r.best.angle - target) <= tol_deg;
  return r;
}

model::SceneDoc with_rolling_resistance(const model::SceneDoc& base, double mu) {
  model::SceneDoc d = base;
  if (base.size("interaction") == 0) throw InputError(base.path(), 0, "interaction", "the scene has no [[interaction]]");
  for (std::size_t i = 0; i < base.size("interaction"); ++i)
    d.set("interaction." + std::to_string(i) + ".rolling_friction", fmt::format("{:.10g}", mu));
  return d;
}

}  // namespace pastemix::app::study
