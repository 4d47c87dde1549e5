// SPDX-License-Identifier: MIT
// The table, CSV, PNG and calibration record of `pastemix calibrate rheology` (calibrate_rheology.h).
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "app/study/calibrate_rheology.h"
#include "base/staged_output.h"
#include "lab/run_info.h"

namespace pastemix::app::study {

namespace rh = lab::rheology;

std::string calibration_table(const RheologyCalResult& r, const RheologyCalOptions& o) {
  std::ostringstream t;
  const auto& p = r.prior;
  t << fmt::format("calibrate rheology: family {}, shape {} ({}), prior [{:.6g}, {:.6g}] ({})\n",
                   rh::to_string(r.model.family), p.name, p.unit, p.lo, p.hi, rh::kPriorSource);
  t << fmt::format("case {}: C_w = {:g}; target per-layer rock {:.2f} / {:.2f} / {:.2f} g from {}\n", o.case_id,
                   r.solids_fraction, 1e3 * r.target[0], 1e3 * r.target[1], 1e3 * r.target[2], r.target_source);
  t << fmt::format("objective J = (1/3) sum_k ((M_k - L_k)/L_k)^2 of the seed-mean layers; {} seed(s) per point "
                   "(common random numbers); eta_B x {:g}\n",
                   o.seeds, o.eta_factor);
  if (o.seeds < 3)
    t << fmt::format("WARNING: {} seed(s) per point: the seed spread is not usable (the protocol asks for >= 3)\n",
                     o.seeds);
  t << fmt::format("runs: {} in all, {} computed now, {} read back from {}/runs\n", r.runs_total, r.runs_executed,
                   r.runs_total - r.runs_executed, o.out.string());
  t << fmt::format("  {:>9} | {:>8} | {:>8} | {:>7} | {:>15} | {:>15} | {:>15} | {:>9} | {:>9} | {:>17}\n", p.name,
                   "tau_y Pa", "eta Pa.s", "rho", "layer 1 g (sd)", "layer 2 g (sd)", "layer 3 g (sd)", "J", "J se",
                   "J_s mean (sd)");
  for (const auto& q : r.points) {
    if (!q.failure.empty()) {
      t << fmt::format("  {:>9.5g} | {:>8.4g} | {:>8.4g} | {:>7.1f} | FAILED: {}\n", q.shape, q.tau_y, q.eta_B,
                       q.density, q.failure);
      continue;
    }
    auto layer = [&](int k) {
      return fmt::format("{:.2f} ({:.2f})", 1e3 * q.layers[static_cast<std::size_t>(k)],
                         1e3 * q.layers_sd[static_cast<std::size_t>(k)]);
    };
    t << fmt::format("  {:>9.5g} | {:>8.4g} | {:>8.4g} | {:>7.1f} | {:>15} | {:>15} | {:>15} | {:>9.4g} | {:>9.3g} | "
                     "{:>8.4g} ({:.3g})\n",
                     q.shape, q.tau_y, q.eta_B, q.density, layer(0), layer(1), layer(2), q.J, q.J_se, q.J_seed_mean,
                     q.J_seed_sd);
  }
  const auto& f = r.fit;
  if (f.c2 > 0.0)
    t << fmt::format("surrogate: J = {:.4g} + {:.4g} (p - {:.6g}) + {:.4g} (p - {:.6g})^2 on {} points\n", f.c0, f.c1,
                     f.p_ref, f.c2, f.p_ref, f.used.size());
  if (f.ok) {
    rh::Model m = r.model;
    const rh::Point at = rh::evaluate(m, r.solids_fraction);
    t << fmt::format("result: {} = {:.5g} +- {:.2g} {} (sd: max of fit {:.2g}, spread/curvature {:.2g}); {:.0f} % of "
                     "the prior range from its low end\n",
                     p.name, f.vertex, f.sd, p.unit, f.sd_delta, f.sd_curvature, 100.0 * (f.vertex - p.lo) / (p.hi - p.lo));
    t << fmt::format("  at C_w = {:g}: tau_y = {:.4g} +- {:.2g} Pa, eta_B = {:.4g} +- {:.2g} Pa.s, rho = {:.1f} kg/m3 "
                     "({})\n",
                     r.solids_fraction, at.yield_stress, at.yield_stress_sd, at.plastic_viscosity,
                     at.plastic_viscosity_sd, at.density, "at-rest effective");
  } else {
    t << fmt::format("NO RESULT: {}\n", f.why);
  }
  return t.str();
}

std::string write_calibration_outputs(const RheologyCalResult& r, const RheologyCalOptions& o,
                                      const std::string& command) {
  StagedOutput staged;
  const std::string table = calibration_table(r, o);
  staged.write_text(o.out / "table.txt", table);
  std::ostringstream c;
  c << "shape,tau_y_Pa,eta_B_Pa_s,density_kg_m3,layer1_kg,layer2_kg,layer3_kg,layer1_sd,layer2_sd,layer3_sd,J,J_se,"
       "J_seed_mean,J_seed_sd,seeds,failed\n";
  for (const auto& q : r.points)
    c << fmt::format("{:.10g},{:.8g},{:.8g},{:.8g},{:.8g},{:.8g},{:.8g},{:.6g},{:.6g},{:.6g},{:.8g},{:.6g},{:.8g},{:.6g},{},{}\n",
                     q.shape, q.tau_y, q.eta_B, q.density, q.layers[0], q.layers[1], q.layers[2], q.layers_sd[0],
                     q.layers_sd[1], q.layers_sd[2], q.J, q.J_se, q.J_seed_mean, q.J_seed_sd, q.runs.size(),
                     q.failure.empty() ? 0 : 1);
  staged.write_text(o.out / "points.csv", c.str());
  std::string record;
  if (r.fit.ok) {
    rh::Calibration cal;
    cal.family = r.model.family;
    cal.shape = r.fit.vertex;
    cal.sd = r.fit.sd;
    cal.case_id = o.case_id;
    cal.detail = fmt::format("per-layer rock mass of case {}, {} seeds per point, {} points, J = {:.4g} at the best point; "
                             "{}",
                             o.case_id, o.seeds, r.points.size(), r.fit.c0 - r.fit.c1 * r.fit.c1 / (4.0 * r.fit.c2),
                             o.eta_factor == 1.0 ? "eta_B by the model" : fmt::format("eta_B x {:g}", o.eta_factor));
    record = (o.out / "rheology_calibration.toml").string();
    staged.write_text(record, rh::calibration_toml(cal, command, lab::utc_now()));
  }
  staged.commit();
  const std::string py = std::string(PASTEMIX_SOURCE_DIR) + "/scripts/plot_rheology_calibration.py";
  const auto& f = r.fit;
  const std::string cmd = fmt::format(
      "/usr/bin/python3 '{}' '{}' '{}' --name '{}' --prior {:.10g} {:.10g} --fit {:.10g} {:.10g} {:.10g} {:.10g} "
      "{:.10g} {:.10g} {} >/dev/null 2>&1",
      py, (o.out / "points.csv").string(), (o.out / "objective.png").string(), r.prior.name, r.prior.lo, r.prior.hi,
      f.c0, f.c1, f.c2, f.p_ref, f.vertex, f.sd, f.ok ? 1 : 0);
  if (std::system(cmd.c_str()) != 0) fmt::print(stderr, "warning: no objective.png (python/matplotlib failed)\n");
  return record;
}

}  // namespace pastemix::app::study
