// SPDX-License-Identifier: MIT
#include "model/flow/validation_run.h"

#include <algorithm>
#include <cmath>

namespace pastemix::flow {

Cost cost_of(const FlowSolver& s) {
  Cost c;
  const CostTotals& t = s.totals();
  c.cells = s.grid().cell_count();
  c.steps = t.steps;
  c.seconds = t.seconds;
  c.cell_steps_per_second = t.seconds > 0 ? static_cast<double>(c.cells) * static_cast<double>(c.steps) / t.seconds : 0.0;
  c.pressure_iterations = t.steps ? static_cast<double>(t.pressure_iterations) / static_cast<double>(t.steps) : 0.0;
  c.viscous_iterations = t.steps ? static_cast<double>(t.viscous_iterations) / static_cast<double>(t.steps) : 0.0;
  return c;
}

double relative_drift(double v, double v0) { return v0 > 0 ? std::abs(v - v0) / v0 : 0.0; }

double relative_divergence(const StepStats& st) {
  const auto& p = st.projection;
  return p.divergence_before > 0 ? p.divergence_after / p.divergence_before : 0.0;
}

void advance_to(FlowSolver& s, double t_end, double& max_divergence) {
  while (s.time() < t_end * (1 - 1e-14)) {
    s.step(std::min(s.next_time_step(), t_end - s.time()));
    max_divergence = std::max(max_divergence, relative_divergence(s.last()));
  }
}

}  // namespace pastemix::flow
