// SPDX-License-Identifier: MIT
// `pastemix sweep SCENE.toml --vary dt|psd_cut|youngs_modulus --qoi NAME [--values ...] [--levels N]
//  [--tol REL] [--seeds N] [--material NAME] [--set key=value ...] [--out DIR]`: speed against error
// (app/study/sweep.h); `pastemix calibrate rolling-resistance SCENE.toml --target DEG --bracket LO HI ...`
// (app/study/calibrate.h); `pastemix calibrate rheology --case 2 ...` (app/study/calibrate_rheology.h).
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "app/commands.h"
#include "base/stats.h"
#include "app/study/calibrate.h"
#include "app/study/calibrate_rheology.h"
#include "base/error.h"
#include "base/params.h"
#include "lab/reduce.h"
#include "lab/reduce_outputs.h"
#include "lab/run_info.h"
#include "app/study/qoi.h"
#include "app/study/sweep.h"

namespace pastemix::app {
namespace {

// Rewrites the parameter store (parameters.toml, lab.h5 beside it) with the calibration record: `lab reduce`
// of the store's own dataset with --rheology-calibration, so the store is never edited by hand.
void write_store(const std::string& store, std::string dataset, const std::string& record) {
  if (dataset.empty()) {
    const Params root = Params::parse_file(store);
    dataset = root.table("reduce").string("dataset");  // not finish()ed: only this key is read
  }
  std::string out = std::filesystem::path(store).parent_path().string();
  if (out.empty()) out = ".";
  lab::ReduceOptions ro;
  ro.rheology_calibration = record;
  const lab::ReduceResult r = lab::reduce(dataset, ro);
  const std::string cmd = fmt::format("pastemix lab reduce {} --out {} --rheology-calibration {}", dataset, out, record);
  lab::write_reduce_outputs(r, out, {lab::software_version(), cmd, lab::utc_now()});
  fmt::print("store updated ({}):\n", cmd);
  for (const auto& p : r.parameters)
    if (p.key.rfind("paste_rheology.cw_", 0) == 0 &&
        (p.key.find(".yield_stress") != std::string::npos || p.key.find(".plastic_viscosity") != std::string::npos))
      fmt::print("  {} = {:.4g} +- {:.2g} {} ({})\n", p.key, p.value, p.sd, p.unit, p.method);
}

void register_rheology(CLI::App* cal) {
  struct Opts {
    study::RheologyCalOptions o;
    std::string scene, overrides, dataset, out;
    std::vector<std::string> sets;
    std::vector<double> target;
    double layer_thickness = 0.03;
    bool no_store = false;
  };
  auto c = std::make_shared<Opts>();
  CLI::App* r = cal->add_subcommand("rheology", "the paste-rheology model's shape parameter from a mixing case's "
                                                "per-layer rock mass (docs/rheology_protocol.md)");
  r->add_option("--case", c->o.case_id, "mixing case (the protocol: 2)")->required();
  r->add_option("--family", c->o.family, "exponential | packing (default: the store's)");
  r->add_option("--seeds", c->o.seeds, "seeds per point, the same at every point (default 3)");
  r->add_option("--jobs", c->o.jobs, "runs at once, one thread each (default 1)");
  r->add_option("--points", c->o.points, "initial points across the prior range (default 5)");
  r->add_option("--refine", c->o.refine, "refinement rounds around the surrogate's minimum (default 1)");
  r->add_option("--values", c->o.values, "initial points (replace the grid)");
  r->add_option("--scene", c->scene, "scene (default datasets/scenes/mixing_case<N>.toml)");
  r->add_option("--overrides", c->overrides, "file of key.path = value lines, applied before --set");
  r->add_option("--set", c->sets, "scene override key.path=value");
  r->add_option("--params", c->o.store, "the parameter store (default out/lab/parameters.toml)");
  r->add_option("--lab-h5", c->o.lab_h5, "lab.h5 with the case's grid (default out/lab/lab.h5)");
  r->add_option("--out", c->out, "output folder (default out/calibrate/rheology_case<N>); runs/ keeps every run");
  r->add_option("--target-layers", c->target, "per-layer rock target in kg, 3 values (synthetic tests; default the lab's)")
      ->expected(3)->delimiter(',');
  r->add_option("--layer-thickness", c->layer_thickness, "grid layer thickness, m (default 0.03, the lab's)");
  r->add_option("--eta-factor", c->o.eta_factor, "eta_B x this at every point (sensitivity, default 1)");
  r->add_flag("--no-store", c->no_store, "write the record but leave the store as it is");
  r->add_option("--dataset", c->dataset, "dataset for the store rewrite (default: the store's [reduce] dataset)");
  r->add_flag("--quiet", c->o.quiet, "no per-run lines");
  r->add_option("--checkpoint-every", c->o.checkpoint_wall_s,
                "wall-clock s between checkpoints of a run in progress; a rerun continues it (default 300, 0: none)")
      ->check(CLI::NonNegativeNumber);
  r->callback([c] {
    auto& o = c->o;
    const std::string scene = c->scene.empty() ? fmt::format("datasets/scenes/mixing_case{}.toml", o.case_id) : c->scene;
    o.out = c->out.empty() ? fmt::format("out/calibrate/rheology_case{}", o.case_id) : c->out;
    o.resume_with = fmt::format("the same `pastemix calibrate rheology --case {} --out {}` command", o.case_id,
                                o.out.string());
    if (!c->target.empty()) o.target_layers = std::array<double, 3>{c->target[0], c->target[1], c->target[2]};
    if (!(c->layer_thickness > 0.0)) throw InputError("--layer-thickness", 0, "", "must be positive (m)");
    o.layout.layer_thickness = c->layer_thickness;
    const model::SceneDoc base = model::scene_with_overrides(scene, c->overrides, c->sets);
    const auto res = study::calibrate_rheology(base, o);
    std::string command = fmt::format("pastemix calibrate rheology --case {} --family {} --seeds {} --scene {} --out {}",
                                      o.case_id, lab::rheology::to_string(res.model.family), o.seeds, scene,
                                      o.out.string());
    if (o.eta_factor != 1.0) command += fmt::format(" --eta-factor {:g}", o.eta_factor);
    const std::string record = study::write_calibration_outputs(res, o, command);
    fmt::print("{}", study::calibration_table(res, o));
    fmt::print("wrote {0}/table.txt, {0}/points.csv, {0}/objective.png{1}\n", o.out.string(),
               record.empty() ? "" : ", " + record);
    if (!res.fit.ok) throw RuntimeFailure("calibrate rheology: no result: " + res.fit.why);
    if (!c->no_store) write_store(o.store.string(), c->dataset, record);
  });
}

struct SweepCli {
  std::string scene;
  study::SweepOptions o;
  std::vector<std::string> sets;
  std::string overrides;
  bool no_cache = false;
};

void run_sweep(SweepCli& c) {
  if (c.o.runs.empty() && !c.no_cache) c.o.runs = c.o.out / "runs";
  if (c.no_cache) c.o.runs.clear();
  c.o.engine = lab::software_version();
  const model::SceneDoc base = model::scene_with_overrides(c.scene, c.overrides, c.sets);
  const study::SweepResult r = study::sweep(base, c.o);
  fmt::print("{}", r.table);
  if (!c.o.runs.empty())
    fmt::print("runs: {} done now, {} read back from {}\n", r.executed, r.read_back, c.o.runs.string());
  study::write_outputs(r, c.o);
  fmt::print("wrote {0}/sweep.csv, {0}/sweep.png{1}\n", c.o.out.string(),
             r.override_text.empty() ? "" : fmt::format(", {}/chosen_overrides.toml", c.o.out.string()));
}

void register_sweep(CLI::App& app) {
  auto opts = std::make_shared<SweepCli>();
  std::string qoi_help = "quantity of interest:";
  for (const auto& q : study::qoi_registry()) qoi_help += " " + q.name + " (" + q.unit + ")";
  CLI::App* s = app.add_subcommand("sweep", "speed against error: run a scene over a ladder of one setting");
  s->add_option("scene", opts->scene, "scene file (TOML)")->required();
  s->add_option("--vary", opts->o.vary, "dt | youngs_modulus | psd_cut")->required()->check(
      CLI::IsMember({"dt", "youngs_modulus", "psd_cut"}));
  s->add_option("--qoi", opts->o.qoi, qoi_help)->required();
  s->add_option("--values", opts->o.values, "ladder values, coarse -> fine (default: see app/study/sweep.h)");
  s->add_option("--levels", opts->o.levels, "default-ladder length (default 4)");
  s->add_option("--tol", opts->o.tol, "relative tolerance on the QoI (default 0.01)");
  s->add_option("--seeds", opts->o.seeds, "runs per point with seeds seed, seed+1, ... (default 1)");
  s->add_option("--material", opts->o.material, "youngs_modulus: the material varied (default: the first)");
  s->add_option("--overrides", opts->overrides, "file of key.path = value lines, applied before --set");
  s->add_option("--set", opts->sets, "scene override key.path=value applied before the ladder");
  s->add_option("--out", opts->o.out, "output folder (default sweep_out)");
  s->add_flag("--quiet", opts->o.quiet, "no per-run lines");
  s->add_flag("--fixed-dt", opts->o.fixed_dt, "psd_cut: keep the scene's time step (default: dt follows the smallest d_min)");
  s->add_option("--save", opts->o.save, "folder for each run's final state (<vary>_<value>_seed<S>.h5 + .xmf)");
  s->add_option("--jobs", opts->o.jobs, "runs at once, one thread each (default 1: one run with the OpenMP threads)");
  s->add_option("--runs", opts->o.runs, "folder of finished-run records, read back by a rerun (default <out>/runs)");
  s->add_flag("--no-cache", opts->no_cache, "keep no run records and read none: every run is done");
  s->callback([opts] { run_sweep(*opts); });
}

struct RollingCli {
  std::string scene;
  double target = 0.0, tol_deg = 0.5, mu_tol = 0.005;
  std::vector<double> bracket;
  int seeds = 1, max_evaluations = 8;
  std::vector<std::string> sets;
  std::string overrides;
  std::string out = "out/calibrate/rolling_resistance";
  bool no_cache = false;
};

void run_rolling_resistance(const RollingCli& c) {
  const model::SceneDoc base = model::scene_with_overrides(c.scene, c.overrides, c.sets);
  const long seed0 = base.has("seed") ? std::stol(base.get("seed")) : 1;
  const study::RunCache cache(c.no_cache ? std::filesystem::path{} : std::filesystem::path(c.out) / "runs");
  const std::string engine = lab::software_version();
  // The repose angle at mu_r (deg): mean and sd over the seeds, each pile read back from the cache if kept.
  auto f = [&](double mu) {
    std::vector<double> angles;
    for (int k = 0; k < c.seeds; ++k) {
      model::SceneDoc d = study::with_rolling_resistance(base, mu);
      if (c.seeds > 1) d.set("seed", std::to_string(seed0 + k));
      bool on_disk = false;
      const auto r = study::cached_run_once(d, "repose_angle", cache,
                                            fmt::format("rolling-resistance mu_r = {:.10g} seed {}", mu, seed0 + k),
                                            engine, on_disk);
      angles.push_back(r.qoi);
      fmt::print(stderr, "  mu_r = {:.4f} seed {}: {:.2f} deg ({:.1f} s){}\n", mu, seed0 + k, r.qoi, r.wall_s,
                 on_disk ? " (on disk)" : "");
    }
    const auto st = summarize(angles);
    return study::Evaluation{mu, st.mean, c.seeds > 1 ? st.sd : 0.0};
  };
  const auto r = study::bracket_root(f, c.bracket[0], c.bracket[1], c.target, c.tol_deg, c.mu_tol,
                                     c.max_evaluations);
  fmt::print("rolling law: {}; target {:.2f} deg\n", base.get("contact.rolling"), c.target);
  fmt::print("  {:>8} | {:>10} | {:>6}\n", "mu_r", "angle deg", "sd");
  for (const auto& e : r.history) fmt::print("  {:>8.4f} | {:>10.2f} | {:>6.2f}\n", e.mu, e.angle, e.sd);
  fmt::print("mu_r = {:.4f}: angle {:.2f} +- {:.2f} deg (seed sd, {} seed(s)), objective |angle - target| = "
             "{:.2f} deg{}\n", r.mu, r.best.angle, r.best.sd, c.seeds, std::abs(r.best.angle - c.target),
             r.converged ? "" : " (NOT within --tol-deg: more evaluations or seeds needed)");
}

void register_rolling_resistance(CLI::App* cal) {
  auto c = std::make_shared<RollingCli>();
  CLI::App* rr = cal->add_subcommand("rolling-resistance",
                                     "mu_r (all [[interaction]]s) so that the simulated repose angle = the measured");
  rr->add_option("scene", c->scene, "repose scene (e.g. datasets/scenes/repose_ch5.toml)")->required();
  rr->add_option("--target", c->target, "measured repose angle, deg (Table 6.1)")->required();
  rr->add_option("--bracket", c->bracket, "mu_r lo hi; the target must lie between their angles")->expected(2)->required();
  rr->add_option("--tol-deg", c->tol_deg, "stop when |angle - target| <= this (deg, default 0.5)");
  rr->add_option("--mu-tol", c->mu_tol, "stop when the bracket is narrower (default 0.005)");
  rr->add_option("--seeds", c->seeds, "runs per mu_r (default 1)");
  rr->add_option("--max-evaluations", c->max_evaluations, "default 8");
  rr->add_option("--overrides", c->overrides, "file of key.path = value lines, applied before --set");
  rr->add_option("--set", c->sets, "scene override key.path=value");
  rr->add_option("--out", c->out, "folder whose runs/ keeps every finished pile, read back by a rerun "
                                  "(default out/calibrate/rolling_resistance)");
  rr->add_flag("--no-cache", c->no_cache, "keep no run records and read none: every pile is run");
  rr->callback([c] { run_rolling_resistance(*c); });
}

}  // namespace

void register_study_commands(CLI::App& app) {
  register_sweep(app);
  CLI::App* cal = group_subcommand(app, "calibrate", "calibrate an unmeasurable parameter against lab tests");
  register_rolling_resistance(cal);
  register_rheology(cal);
}

}  // namespace pastemix::app
