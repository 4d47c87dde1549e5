// SPDX-License-Identifier: MIT
// The band table and CSVs of `pastemix predict rheology` (predict_rheology.h).
#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "app/study/predict_rheology.h"
#include "base/staged_output.h"
#include "base/stats.h"

namespace pastemix::app::study {

namespace rh = lab::rheology;

namespace {

// Seed mean and sd of quantity `k` over a group's successful runs (n = 0 when none has it).
Summary over_seeds(const PredictGroup& g, std::size_t k) {
  std::vector<double> v;
  for (const auto& r : g.runs)
    if (r.failure.empty() && r.q.size() > k) v.push_back(r.q[k]);
  return v.empty() ? Summary{} : summarize(v);
}

int failed(const PredictGroup& g) {
  int n = 0;
  for (const auto& r : g.runs) n += !r.failure.empty();
  return n;
}

std::string label_of(const PredictGroup& g, const PredictResult& r) {
  return g.label == 0 ? r.prior.name : fmt::format("{} {} sd", r.prior.name, g.label < 0 ? "-" : "+");
}

// "mean +- sd" of a quantity, scaled (g for kg, % for a share).
std::string pm(const PredictGroup& g, std::size_t k, double scale, int digits) {
  const Summary s = over_seeds(g, k);
  if (s.n == 0) return "-";
  return fmt::format("{:.{}f} +- {:.{}f}", scale * s.mean, digits, scale * s.sd, digits);
}

}  // namespace

std::string band_table(const PredictResult& r, const PredictOptions& o) {
  std::ostringstream t;
  const auto& p = r.prior;
  t << fmt::format("predict rheology (docs/rheology_protocol.md step 5), engine {}\n", o.engine);
  t << fmt::format("model {}: {} = {:.5g} +- {:.2g} {} from {}; prior [{:.6g}, {:.6g}]; label: {}\n",
                   rh::to_string(r.model.family), p.name, r.model.shape, r.model.shape_sd, p.unit, r.shape_source,
                   p.lo, p.hi, "at-rest effective");
  t << fmt::format("store {}; scenes {}/mixing_case<N>.toml with the model's rheology at each case's solids content\n",
                   o.store.string(), o.scenes.string());
  if (r.overrides_text.empty())
    t << "overrides: none (nothing of the physics edited)\n";
  else
  {
    t << fmt::format("overrides (the only physics edit, every scene): {}\n", o.overrides.string());
    std::istringstream lines(r.overrides_text);
    for (std::string l; std::getline(lines, l);)
      if (l.find_first_not_of(" \t") != std::string::npos) t << "  | " << l << "\n";
  }
  t << fmt::format("{} seed(s) per value, the same at every value (common random numbers); values: mean +- sd over "
                   "the seeds\n", o.seeds);
  if (o.seeds < 3)
    t << fmt::format("WARNING: {} seed(s): the protocol asks for >= 3\n", o.seeds);
  t << fmt::format("runs: {} in all, {} computed now, {} read back from {}/runs\n", r.runs_total, r.computed,
                   r.read_back, o.out.string());
  t << fmt::format("{:>4} | {:>5} | {:>9} | {:>8} | {:>7} | {:>7} | {:>6} | {:>5} | {:>15} | {:>15} | {:>15} | "
                   "{:>13} | {:>15} | {:>15} | {:>11} | {:>13} | {}\n",
                   "case", "C_w", "value", p.name, "tau_y", "eta_B", "rho", "seeds", "layer 1 g", "layer 2 g",
                   "layer 3 g", "deep %", "mixed g", "unmixed g", "score /3", "MAE pp", "ensemble (pastemix score)");
  for (const auto& g : r.groups) {
    std::string ens = g.scored ? "-" : "no lab grid";
    if (g.ensemble_layers_matched)
      ens = fmt::format("{}/3 layers, MAE {:.2f} pp", *g.ensemble_layers_matched, g.ensemble_mae_pp);
    const int nf = failed(g);
    t << fmt::format("{:>4} | {:>5.3g} | {:>9} | {:>8.5g} | {:>7.4g} | {:>7.4g} | {:>6.1f} | {:>5} | {:>15} | {:>15} | "
                     "{:>15} | {:>13} | {:>15} | {:>15} | {:>11} | {:>13} | {}{}\n",
                     g.case_id, 100.0 * g.solids_fraction, label_of(g, r), g.shape, g.tau_y, g.eta_B, g.density,
                     g.runs.size() - static_cast<std::size_t>(nf), pm(g, 0, 1e3, 2), pm(g, 1, 1e3, 2),
                     pm(g, 2, 1e3, 2), pm(g, 3, 100.0, 1), pm(g, 4, 1e3, 2), pm(g, 5, 1e3, 2),
                     g.scored ? pm(g, 6, 1.0, 1) : "-", g.scored ? pm(g, 7, 1.0, 2) : "-", ens,
                     nf ? fmt::format("; {} run(s) FAILED", nf) : "");
  }
  for (const auto& g : r.groups)
    for (const auto& run : g.runs)
      if (!run.failure.empty())
        t << fmt::format("FAILED: case {} {} seed {}: {}\n", g.case_id, label_of(g, r), run.seed, run.failure);
  t << "units: tau_y Pa, eta_B Pa.s, rho kg/m3; deep = rock in layers 2-3 / rock in all blocks; score = layers "
       "whose rock matches the lab's (analysis/score/score.h)\n";
  return t.str();
}

std::string band_csv(const PredictResult& r) {
  std::ostringstream c;
  c << "case,solids_fraction,value,shape,tau_y_Pa,eta_B_Pa_s,density_kg_m3,seeds,failed";
  for (const auto& n : predict_quantity_names()) c << fmt::format(",{0}_mean,{0}_sd", n);
  c << ",ensemble_layers_matched,ensemble_mae_pp\n";
  for (const auto& g : r.groups) {
    c << fmt::format("{},{:.6g},{},{:.10g},{:.8g},{:.8g},{:.8g},{},{}", g.case_id, g.solids_fraction, g.label,
                     g.shape, g.tau_y, g.eta_B, g.density, g.runs.size(), failed(g));
    for (std::size_t k = 0; k < predict_quantity_names().size(); ++k) {
      const Summary s = over_seeds(g, k);
      c << (s.n == 0 ? std::string(",,") : fmt::format(",{:.8g},{:.8g}", s.mean, s.sd));
    }
    c << (g.ensemble_layers_matched ? fmt::format(",{},{:.8g}\n", *g.ensemble_layers_matched, g.ensemble_mae_pp)
                                    : std::string(",,\n"));
  }
  return c.str();
}

std::string runs_csv(const PredictResult& r) {
  std::ostringstream c;
  c << "case,value,shape,seed,key";
  for (const auto& n : predict_quantity_names()) c << "," << n;
  c << ",failure\n";
  for (const auto& g : r.groups)
    for (const auto& run : g.runs) {
      c << fmt::format("{},{},{:.10g},{},{}", g.case_id, g.label, g.shape, run.seed, run.key);
      for (std::size_t k = 0; k < predict_quantity_names().size(); ++k)
        c << (k < run.q.size() ? fmt::format(",{:.8g}", run.q[k]) : std::string(","));
      std::string why = run.failure;
      for (char& ch : why) ch = (ch == ',' || ch == '\n' || ch == '"') ? ' ' : ch;
      c << "," << why << "\n";
    }
  return c.str();
}

void write_band_outputs(const PredictResult& r, const PredictOptions& o) {
  StagedOutput staged;
  staged.write_text(o.out / "band.txt", band_table(r, o));
  staged.write_text(o.out / "band.csv", band_csv(r));
  staged.write_text(o.out / "runs.csv", runs_csv(r));
  staged.commit();
}

}  // namespace pastemix::app::study
