// SPDX-License-Identifier: MIT
// `pastemix sweep`: one scene run over a ladder of one setting, a QoI and the wall-clock cost per run,
// the reference and choice of ladder.h, and the outputs (table, CSV, PNG, override file).
//
// Ladders (coarse -> fine; the finest is the reference unless Richardson applies):
//   dt             time_step halved `levels - 1` times from the scene's value (r = 2, Richardson allowed)
//   youngs_modulus E of `material` from E0 / 10^(levels-1) up to the scene's E0; the time step is scaled by
//                  sqrt(E0 / E) so every run sits at the same fraction of its Rayleigh time (the reason to
//                  reduce E at all is the larger step)
//   psd_cut        d_cut (m): every [[factory]]'s intervals with d_max <= d_cut are dropped and the rest
//                  renormalised (base/psd.h cut_below); default values: the scene's interval lower sieves,
//                  largest first, down to no cut (0). The time step follows the smallest sphere kept,
//                  dt = dt0 x d_min(cut) / d_min(scene), so every cut runs at the same fraction of its own
//                  Rayleigh time (T_R is proportional to r), as the thesis's per-cut "optimal" steps did;
//                  `fixed_dt` keeps dt0 instead
//   lift_speed     every [[wall]] lifted (velocity z > 0) at this speed (m/s); end_time stretched so that the
//                  lift covers the same height and the settling after it (`settle_s`) keeps its length,
//                  end = move_start + (end0 - move_start - settle) v0 / v + settle; default values
//                  v0 2^(levels-1) .. v0 (fast -> the scene's speed, the reference); the time step is kept
// --values replaces the default ladder (given coarse -> fine).
//
// A run that fails (pastemix::RuntimeFailure: a blow-up, a jammed funnel, a pile that cannot be measured)
// does not end the sweep: its point is reported as failed, with the reason, and left out of the reference
// and the choice. `jobs` > 1 runs that many runs at once, one thread each (the ladder x seeds is a queue);
// the cost column stays the deterministic particle-steps, the wall seconds are then those of shared cores.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/study/ladder.h"
#include "app/study/ledger.h"
#include "app/study/ranks.h"
#include "app/study/run_cache.h"
#include "app/study/tasks.h"
#include "model/scene_doc.h"

namespace pastemix::app::study {

struct SweepOptions {
  std::string vary;               // dt | youngs_modulus | psd_cut | lift_speed
  std::string qoi;
  std::vector<double> values;     // empty: default ladder
  int levels = 4;
  double tol = 0.01;              // relative
  int seeds = 1;
  std::string material;           // youngs_modulus: which material (default: the first)
  std::filesystem::path out = "sweep_out";
  bool quiet = false;
  bool fixed_dt = false;          // psd_cut: keep the scene's time step at every cut
  double settle_s = 1.0;          // lift_speed: s of the run after the lift, kept at every speed
  std::filesystem::path save;     // non-empty: each run's final state as <save>/<vary>_<value>_seed<S>.h5/.xmf
  int jobs = 1;                   // runs at once (each one thread when > 1)
  // Finished runs are kept here (app/study/run_cache.h) and read back by a rerun: a killed or repeated
  // sweep recomputes no finished (value, seed). Empty: nothing kept (the command's default is <out>/runs).
  std::filesystem::path runs;
  std::string engine;             // software version, written into each run record (provenance)
  Ledger* ledger = nullptr;       // the study's ledger (ledger.h); null: none
  const Ranks* ranks = nullptr;   // MPI ranks (ranks.h); null: one process
  std::optional<long> task_index; // run this task alone (a Slurm array index; tasks.h)
  // A run in progress writes <runs>/<key>.checkpoint.h5 every this many wall-clock seconds (0: never) and a
  // rerun after a kill continues it (final-state QoIs; a QoI over every step is run in-process, whole).
  double checkpoint_wall_s = 300.0;
  std::string resume_with;        // the command that resumes the study (stored in each checkpoint)
};

// A ladder point at which at least one run failed (left out of the reference and the choice).
struct FailedPoint {
  double value = 0.0;
  long seed = 0;
  std::string reason;
};

struct SweepResult {
  std::vector<LadderPoint> points;
  std::vector<std::vector<double>> per_seed;  // QoI per point per seed
  std::vector<double> time_step;              // s, per point (the ladder may change it)
  std::vector<FailedPoint> failed;
  Reference ref;
  Choice choice;
  std::string override_text;      // the chosen setting as override lines
  std::string table;              // the printed speed-vs-error table
  int executed = 0, read_back = 0;  // runs done now / read back from the run records
};

// Applies the ladder value to a copy of the scene (all the TOML edits live here).
model::SceneDoc at_value(const model::SceneDoc& base, const SweepOptions& o, double value);
std::vector<double> default_ladder(const model::SceneDoc& base, const SweepOptions& o);

struct RunCost {
  double qoi = 0.0;
  double wall_s = 0.0;   // wall-clock seconds of the step loop (scene set-up and insertion excluded)
  double work = 0.0;     // particles x steps
  std::size_t particles = 0;
};
// One run in-process. With `save_h5` the final state is written there (an ordinary result file with one
// snapshot, plus its .xmf) before the QoI is evaluated, so a run whose QoI fails leaves its state to look at.
RunCost run_once(const model::SceneDoc& doc, const std::string& qoi, const std::filesystem::path& save_h5 = {});

SweepResult sweep(const model::SceneDoc& base, const SweepOptions& o);
// Writes <out>/sweep.csv, <out>/chosen_overrides.toml, <out>/sweep.png (PNG only if python works).
void write_outputs(const SweepResult& r, const SweepOptions& o);

// Where a study's run keeps its files: result and checkpoint as <dir>/<stem>.h5 / .checkpoint.h5 (deleted
// once the QoI is taken), or, with `save_h5`, the result kept there (its checkpoint beside it).
struct TaskFiles {
  std::filesystem::path dir;     // empty: run in-process, no files, no checkpoint
  std::string stem;              // the task's key
  double checkpoint_wall_s = 0.0;
  std::string resume_with;
  std::filesystem::path save_h5;
};
// One run of a QoI study (sweep, rolling resistance): a final-state QoI runs through model::run_scene with
// checkpoints, continuing a checkpoint left by a kill (`from` = resumed); a QoI over every step runs
// in-process (run_once). Throws RuntimeFailure as run_once does.
RunCost run_qoi_task(const model::SceneDoc& doc, const std::string& qoi, const TaskFiles& files, From& from);
RunRecord record_of(const RunCost& c);

}  // namespace pastemix::app::study
