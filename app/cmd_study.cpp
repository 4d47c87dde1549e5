// SPDX-License-Identifier: MIT
// `pastemix sweep SCENE.toml --vary dt|psd_cut|youngs_modulus --qoi NAME [--values ...] [--levels N]
//  [--tol REL] [--seeds N] [--material NAME] [--set key=value ...] [--out DIR]`: speed against error
// (app/study/sweep.h); `pastemix calibrate rolling-resistance SCENE.toml --target DEG --bracket LO HI ...`
// (app/study/calibrate.h); `pastemix calibrate rheology --case 2 ...` (app/study/calibrate_rheology.h);
// `pastemix predict rheology --calibration REC --cases 1,4,5,6,7 ...` (app/study/predict_rheology.h).
#include <filesystem>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "app/commands.h"
#include "base/stats.h"
#include "app/study/calibrate.h"
#include "app/study/calibrate_rheology.h"
#include "app/study/predict_rheology.h"
#include "app/study/ledger.h"
#include "app/study/ranks.h"
#include "app/study/tasks.h"
#include "base/error.h"
#include "base/params.h"
#include "lab/reduce.h"
#include "lab/reduce_outputs.h"
#include "lab/run_info.h"
#include "app/study/qoi.h"
#include "app/study/sweep.h"

namespace pastemix::app {
namespace {

// The options every study shares: its ledger, MPI, one task of a Slurm array, checkpoints.
struct StudyCli {
  std::string ledger;
  bool mpi = false;
  std::optional<long> task_index;
};

void add_study_options(CLI::App* c, StudyCli& s) {
  c->add_option("--ledger", s.ledger, "CSV of finished tasks (keys and QoIs), read at start and appended as tasks "
                                      "finish (commit it: docs/studies/<name>.csv)");
  c->add_flag("--mpi", s.mpi, "spread the tasks over the MPI ranks (mpirun -np K pastemix ...; implied under mpirun)");
  c->add_option("--task-index", s.task_index, "run task N of the list alone and record it (a Slurm array index; "
                                              "the same command without it gathers)");
}

// The ranks and (on rank 0) the ledger of a study.
struct StudySetup {
  const study::Ranks* ranks = nullptr;
  std::unique_ptr<study::Ledger> ledger;
};

StudySetup setup_study(const StudyCli& s) {
  StudySetup st;
  st.ranks = &study::Ranks::start(s.mpi);
  if (!s.ledger.empty() && st.ranks->root()) {
    try {
      st.ledger = std::make_unique<study::Ledger>(s.ledger);
    } catch (const InputError& e) {
      if (st.ranks->size() > 1) {
        fmt::print(stderr, "error: {}\n", e.what());
        st.ranks->abort(2);
      }
      throw;
    }
    const std::size_t other = st.ledger->other_engine(lab::software_version());
    fmt::print(stderr, "ledger {}: {} finished task(s){}\n", s.ledger, st.ledger->size(),
               other ? fmt::format(", {} of them by another engine than {}", other, lab::software_version()) : "");
  }
  return st;
}

// Runs a study's body: a --task-index run ends with its message (exit 0); an input error on one rank of
// several ends them all.
template <class F>
void guarded(const study::Ranks& ranks, F&& body) {
  try {
    body();
  } catch (const study::TaskIndexDone& d) {
    fmt::print("{}\n", d.message);
  } catch (const InputError& e) {
    if (ranks.size() > 1) {
      fmt::print(stderr, "error (rank {}): {}\n", ranks.rank(), e.what());
      ranks.abort(2);
    }
    throw;
  }
}

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
    StudyCli study;
  };
  auto c = std::make_shared<Opts>();
  CLI::App* r = cal->add_subcommand("rheology", "the paste-rheology model's shape parameter from a mixing case's "
                                                "per-layer rock mass (docs/rheology_protocol.md)");
  r->add_option("--case", c->o.case_id, "mixing case (the protocol: 2)")->required();
  r->add_option("--family", c->o.family, "exponential | packing (default: the store's)");
  r->add_option("--seeds", c->o.seeds, "seeds per point, the same at every point (default 3)");
  r->add_option("--jobs", c->o.jobs, "runs at once, one thread each when more than 1 (default 1: one run with the OpenMP threads; OMP_NUM_THREADS=1 for one thread)");
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
  add_study_options(r, c->study);
  r->callback([c] {
    auto& o = c->o;
    StudySetup st = setup_study(c->study);
    o.ranks = st.ranks;
    o.ledger = st.ledger.get();
    o.task_index = c->study.task_index;
    o.engine = lab::software_version();
    const std::string scene = c->scene.empty() ? fmt::format("datasets/scenes/mixing_case{}.toml", o.case_id) : c->scene;
    o.out = c->out.empty() ? fmt::format("out/calibrate/rheology_case{}", o.case_id) : c->out;
    o.resume_with = fmt::format("the same `pastemix calibrate rheology --case {} --out {}` command", o.case_id,
                                o.out.string());
    if (!c->target.empty()) o.target_layers = std::array<double, 3>{c->target[0], c->target[1], c->target[2]};
    if (!(c->layer_thickness > 0.0)) throw InputError("--layer-thickness", 0, "", "must be positive (m)");
    o.layout.layer_thickness = c->layer_thickness;
    const model::SceneDoc base = model::scene_with_overrides(scene, c->overrides, c->sets);
    study::RheologyCalResult res;
    bool index_run = true;
    guarded(*st.ranks, [&] {
      res = study::calibrate_rheology(base, o);
      index_run = false;
    });
    if (!index_run && o.task_index) fmt::print("task {}: every task of the study is finished; the gathering run (the same command without --task-index) "
                 "writes the ledger and the outputs\n", *o.task_index);
    if (index_run || o.task_index || !st.ranks->root()) {
      if (!res.fit.ok && !index_run && !o.task_index) throw RuntimeFailure("calibrate rheology: no result: " + res.fit.why);
      return;
    }
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
  StudyCli study;
};

void run_sweep(SweepCli& c) {
  if (c.o.runs.empty() && !c.no_cache) c.o.runs = c.o.out / "runs";
  if (c.no_cache) c.o.runs.clear();
  c.o.engine = lab::software_version();
  StudySetup st = setup_study(c.study);
  c.o.ranks = st.ranks;
  c.o.ledger = st.ledger.get();
  c.o.task_index = c.study.task_index;
  const model::SceneDoc base = model::scene_with_overrides(c.scene, c.overrides, c.sets);
  c.o.resume_with = "the same `pastemix sweep` command";
  study::SweepResult r;
  bool index_run = true;
  guarded(*st.ranks, [&] {
    r = study::sweep(base, c.o);
    index_run = false;
  });
  if (!index_run && c.o.task_index) fmt::print("task {}: every task of the study is finished; the gathering run (the same command without --task-index) "
                 "writes the ledger and the outputs\n", *c.o.task_index);
  if (index_run || c.o.task_index || !st.ranks->root()) return;
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
  s->add_option("--vary", opts->o.vary, "dt | youngs_modulus | psd_cut | lift_speed")->required()->check(
      CLI::IsMember({"dt", "youngs_modulus", "psd_cut", "lift_speed"}));
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
  s->add_option("--settle", opts->o.settle_s, "lift_speed: s of settling after the lift, kept at every speed (default 1)");
  s->add_option("--save", opts->o.save, "folder for each run's final state (<vary>_<value>_seed<S>.h5 + .xmf)");
  s->add_option("--jobs", opts->o.jobs, "runs at once, one thread each (default 1: one run with the OpenMP threads)");
  s->add_option("--runs", opts->o.runs, "folder of finished-run records, read back by a rerun (default <out>/runs)");
  s->add_flag("--no-cache", opts->no_cache, "keep no run records and read none: every run is done");
  s->add_option("--checkpoint-every", opts->o.checkpoint_wall_s,
                "wall-clock s between checkpoints of a run in progress (final-state QoIs); a rerun continues it "
                "(default 300, 0: none)")->check(CLI::NonNegativeNumber);
  add_study_options(s, opts->study);
  s->callback([opts] { run_sweep(*opts); });
}

struct RollingCli {
  std::string scene;
  study::RollingOptions o;
  std::vector<double> bracket;
  std::vector<std::string> sets;
  std::string overrides;
  StudyCli study;
};

void run_rolling_resistance(RollingCli& c) {
  auto& o = c.o;
  if (o.values.empty() && c.bracket.size() != 2)
    throw InputError("", 0, "--bracket", "give --bracket LO HI (or --values)");
  if (c.bracket.size() == 2) o.lo = c.bracket[0], o.hi = c.bracket[1];
  o.engine = lab::software_version();
  o.resume_with = "the same `pastemix calibrate rolling-resistance` command";
  StudySetup st = setup_study(c.study);
  o.ranks = st.ranks;
  o.ledger = st.ledger.get();
  o.task_index = c.study.task_index;
  const model::SceneDoc base = model::scene_with_overrides(c.scene, c.overrides, c.sets);
  study::RollingResult r;
  bool index_run = true;
  guarded(*st.ranks, [&] {
    r = study::calibrate_rolling(base, o);
    index_run = false;
  });
  if (!index_run && o.task_index) fmt::print("task {}: every task of the study is finished; the gathering run (the same command without --task-index) "
                 "writes the ledger and the outputs\n", *o.task_index);
  if (index_run || o.task_index) return;
  if (st.ranks->root()) {
    study::write_rolling_outputs(r, o);
    fmt::print("{}", study::rolling_table(r, o));
    fmt::print("wrote {0}/points.csv, {0}/table.txt\n", o.out.string());
  }
  if (!r.answer.ok) throw RuntimeFailure("calibrate rolling-resistance: no result: " + r.answer.why);
}

void register_rolling_resistance(CLI::App* cal) {
  auto c = std::make_shared<RollingCli>();
  CLI::App* rr = cal->add_subcommand("rolling-resistance",
                                     "mu_r (all [[interaction]]s) so that the simulated repose angle = the measured, "
                                     "from a monotone surrogate of angle(mu_r) over every run");
  rr->add_option("scene", c->scene, "repose scene (e.g. datasets/scenes/repose_ch5.toml)")->required();
  rr->add_option("--target", c->o.target, "measured repose angle, deg (Table 6.1)")->required();
  rr->add_option("--target-sd", c->o.target_sd, "the measured angle's sd, deg (added to mu_r's sd; default 0)");
  rr->add_option("--bracket", c->bracket, "mu_r lo hi: the range of the initial points")->expected(2);
  rr->add_option("--points", c->o.points, "initial points evenly over the bracket (default 5)");
  rr->add_option("--values", c->o.values, "initial mu_r points (replace the even grid)");
  rr->add_option("--seeds", c->o.seeds, "runs per mu_r, the same seeds at every mu_r (default 3)");
  rr->add_option("--refine", c->o.refine, "rounds adding mu* -+ max(2 sd, 5 % of the range) (default 1)");
  rr->add_option("--jobs", c->o.jobs, "runs at once, one thread each when more than 1 (default 1: one run with the OpenMP threads; OMP_NUM_THREADS=1 for one thread)");
  rr->add_option("--overrides", c->overrides, "file of key.path = value lines, applied before --set");
  rr->add_option("--set", c->sets, "scene override key.path=value");
  rr->add_option("--out", c->o.out, "folder whose runs/ keeps every finished pile, read back by a rerun "
                                    "(default out/calibrate/rolling_resistance)");
  rr->add_flag("--no-cache", c->o.no_cache, "keep no run records and read none (the ledger is still used)");
  rr->add_flag("--quiet", c->o.quiet, "no per-run lines");
  rr->add_option("--checkpoint-every", c->o.checkpoint_wall_s,
                 "wall-clock s between checkpoints of a pile in progress; a rerun continues it (default 300, 0: none)")
      ->check(CLI::NonNegativeNumber);
  add_study_options(rr, c->study);
  rr->callback([c] { run_rolling_resistance(*c); });
}


// `pastemix predict rheology`: the protocol's prediction band. No option edits physics but --overrides.
void register_predict(CLI::App& app) {
  struct Opts {
    study::PredictOptions o;
    std::string calibration;
    std::optional<double> shape, shape_sd;
    std::optional<long> seed0;
    StudyCli study;
  };
  auto c = std::make_shared<Opts>();
  CLI::App* grp = group_subcommand(app, "predict", "blind predictions with a calibrated model");
  CLI::App* r = grp->add_subcommand("rheology", "the band {s - sd, s, s + sd} of the paste-rheology shape over "
                                                "mixing cases, N seeds each (docs/rheology_protocol.md step 5)");
  r->add_option("--calibration", c->calibration, "the record of `pastemix calibrate rheology` (rheology_calibration.toml)");
  r->add_option("--shape", c->shape, "the band's centre instead of a record (family: the store's)");
  r->add_option("--shape-sd", c->shape_sd, "the band's half-width (1 sd), with --shape");
  r->add_option("--cases", c->o.cases, "mixing cases (default 1,4,5,6,7)")->delimiter(',');
  r->add_option("--seeds", c->o.seeds, "seeds per value, the same at every value and case (default 3)");
  r->add_option("--seed0", c->seed0, "first seed (default: each scene's own seed)");
  r->add_option("--jobs", c->o.jobs, "runs at once, one thread each when more than 1 (default 1: one run with the OpenMP threads; OMP_NUM_THREADS=1 for one thread)");
  r->add_option("--scenes", c->o.scenes, "folder of mixing_case<N>.toml (default datasets/scenes)");
  r->add_option("--overrides", c->o.overrides, "file of key.path = value lines for every scene (the only physics "
                                               "edit; stated in band.txt)");
  r->add_option("--params", c->o.store, "the parameter store: the model's anchor (default out/lab/parameters.toml)");
  r->add_option("--lab-h5", c->o.lab_h5, "lab.h5: the cases with a block grid are scored (default out/lab/lab.h5)");
  r->add_option("--out", c->o.out, "output folder (default out/predict/rheology); runs/ keeps every run");
  r->add_flag("--quiet", c->o.quiet, "no per-run lines");
  r->add_option("--checkpoint-every", c->o.checkpoint_wall_s,
                "wall-clock s between checkpoints of a run in progress; a rerun continues it (default 300, 0: none)")
      ->check(CLI::NonNegativeNumber);
  add_study_options(r, c->study);
  r->callback([c] {
    auto& o = c->o;
    o.calibration = c->calibration;
    o.shape = c->shape, o.shape_sd = c->shape_sd, o.seed0 = c->seed0;
    if (!o.lab_h5.empty() && !std::filesystem::exists(o.lab_h5))
      throw InputError(o.lab_h5.string(), 0, "--lab-h5", "no such file (run `pastemix lab reduce`)");
    StudySetup st = setup_study(c->study);
    o.ranks = st.ranks;
    o.ledger = st.ledger.get();
    o.task_index = c->study.task_index;
    o.engine = lab::software_version();
    o.resume_with = fmt::format("the same `pastemix predict rheology --out {}` command", o.out.string());
    study::PredictResult res;
    bool index_run = true;
    guarded(*st.ranks, [&] {
      res = study::predict_rheology(o);
      index_run = false;
    });
    if (!index_run && o.task_index) fmt::print("task {}: every task of the study is finished; the gathering run (the same command without --task-index) "
                 "writes the ledger and the outputs\n", *o.task_index);
    if (index_run || o.task_index || !st.ranks->root()) return;
    study::write_band_outputs(res, o);
    fmt::print("{}", study::band_table(res, o));
    fmt::print("wrote {0}/band.txt, {0}/band.csv, {0}/runs.csv\n", o.out.string());
  });
}

}  // namespace

void register_study_commands(CLI::App& app) {
  register_sweep(app);
  CLI::App* cal = group_subcommand(app, "calibrate", "calibrate an unmeasurable parameter against lab tests");
  register_rolling_resistance(cal);
  register_rheology(cal);
  register_predict(app);
}

}  // namespace pastemix::app
