// SPDX-License-Identifier: MIT
// `pastemix run SCENE.toml [--out DIR] [--threads N] [--quiet] [--realizations N [--seed S]]
//  [--checkpoint-every WALL_S] [--resume DIR]`: runs an f-DEM scene, writes HDF5 + XDMF, prints the per-stage
// profile. Checkpoints and --resume: model/checkpoint.h; a run whose checkpoint is there must be resumed
// (or the file deleted): a fresh run would silently throw its progress away. With --realizations N: N seeded realizations, the
// scene's `seed` set to S, S+1, ... (S default: the scene's seed), run one after another with all threads,
// written as NAME_r0 ... NAME_r{N-1}; every factory takes its seed from the scene seed, so the rock sizes and
// positions change (a factory with its own `seed` would not: rejected).
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app/commands.h"
#include "base/error.h"
#include "model/checkpoint.h"
#include "model/run.h"
#include "model/scene.h"
#include "model/scene_doc.h"

namespace pastemix::app {

namespace {

struct Resume {
  double wall_every = 0.0;  // s, --checkpoint-every
  bool resume = false;      // --resume given
  std::string command;      // the command line that resumes this run
};

// With --resume: "finished" (the result is there and no checkpoint: skipped), else resumes; without: a
// checkpoint left by a killed run stops a fresh start (exit 2) rather than being overwritten.
bool should_run(const std::string& out_dir, const std::string& stem, const Resume& rs) {
  const auto ck = model::checkpoint_path(out_dir, stem);
  const bool has_ck = std::filesystem::exists(ck);
  if (rs.resume && !has_ck && std::filesystem::exists(std::filesystem::path(out_dir) / (stem + ".h5"))) {
    fmt::print("{}: finished earlier (no checkpoint), not run again\n", (std::filesystem::path(out_dir) / (stem + ".h5")).string());
    return false;
  }
  if (!rs.resume && has_ck) {
    const model::CheckpointInfo info = model::read_checkpoint_info(ck);
    throw InputError(ck.string(), 0, "",
                     fmt::format("an interrupted run of this scene stopped at t = {:.6g} s (step {}): continue it "
                                 "with `{}`, or delete the file to start again",
                                 info.time, info.step, rs.command));
  }
  return true;
}

void run_one(const model::Scene& scene, const std::string& out_dir, bool quiet, const std::string& stem,
             const Resume& rs) {
  // The time step against the Rayleigh time of the smallest sphere (../shared/DESIGN.md section 3):
  // informative, the right step is found by a convergence study, not by habit.
  const double tr = model::smallest_rayleigh_time(scene);
  fmt::print(stderr, "time step {:.3g} s = {:.1f} % of the Rayleigh time of the smallest sphere ({:.3g} s)\n",
             scene.config.dt, 100.0 * scene.config.dt / tr, tr);
  for (const auto& w : scene.warnings) fmt::print(stderr, "warning: {}\n", w);
  model::RunOptions ro;
  ro.progress = !quiet;
  ro.stem = stem;
  ro.checkpoint_wall_s = rs.wall_every;
  ro.resume = rs.resume && std::filesystem::exists(model::checkpoint_path(
                               out_dir, stem.empty() ? std::filesystem::path(scene.path).stem().string() : stem));
  if (rs.resume && !ro.resume) fmt::print(stderr, "no checkpoint of this run in {}: starting from t = 0\n", out_dir);
  ro.resume_with = rs.command;
  const model::RunSummary r = model::run_scene(scene, out_dir, ro);
  if (r.resumed_at_step >= 0) fmt::print("resumed at step {} of the checkpoint\n", r.resumed_at_step);
  fmt::print("{} particles, {} steps of {:.3g} s, {} thread(s)\n", scene.particles.size(), r.steps, scene.config.dt,
             r.threads);
  fmt::print("{}", r.profile_table);
  fmt::print("{}", r.escaped_line());
  fmt::print(r.failed_to_rest() ? stderr : stdout, "{}", r.stop.line());
  fmt::print("wrote {} and {}\n", r.h5.string(), r.xmf.string());
}

// A factory with its own `seed` would place the same rock in every realization.
void reject_factory_seeds(const model::SceneDoc& doc) {
  for (std::size_t k = 0; k < doc.size("factory"); ++k)
    if (const std::string key = fmt::format("factory.{}.seed", k); doc.has(key))
      throw InputError(doc.path(), doc.line_of(key), "factory.seed",
                       "--realizations sets the scene seed; a factory with its own seed would not change "
                       "between realizations (remove it)");
}

struct RunCli {
  std::string scene;
  std::string out = ".";
  int threads = 0;
  bool quiet = false;
  std::vector<std::string> sets;
  std::string overrides;
  int realizations = 0;
  long seed = -1;
  double checkpoint_every = 0.0;
  std::string resume;
  long sort_every = -1;  // --sort-every; -1: the scene's [neighbor] sort_every
};

// --sort-every: a run-time setting like --threads, so not an edit of the scene (its text and hash stay the
// scene's).
model::Scene with_sort(const RunCli& o, model::Scene s) {
  if (o.sort_every >= 0) s.config.sort_every = o.sort_every;
  return s;
}

// The checkpoint settings and the command that continues this run (stored in its checkpoints, quoted in
// messages).
Resume resume_of(const RunCli& o) {
  Resume rs;
  rs.wall_every = o.checkpoint_every;
  rs.resume = !o.resume.empty();
  rs.command = fmt::format("pastemix run {} --resume {}", o.scene, o.out);
  if (!o.overrides.empty()) rs.command += " --overrides " + o.overrides;
  for (const auto& s : o.sets) rs.command += " --set " + s;
  if (o.realizations > 0) rs.command += fmt::format(" --realizations {}", o.realizations);
  if (o.seed >= 0) rs.command += fmt::format(" --seed {}", o.seed);
  if (o.sort_every >= 0) rs.command += fmt::format(" --sort-every {}", o.sort_every);
  return rs;
}

// --realizations N: every realization set up (and checked) before anything is written, then run in turn.
void run_realizations(const RunCli& o, const model::SceneDoc& doc, const Resume& rs) {
  reject_factory_seeds(doc);
  const long first = o.seed >= 0 ? o.seed : static_cast<long>(doc.load().seed);
  std::vector<model::Scene> scenes;
  for (int k = 0; k < o.realizations; ++k) {
    model::SceneDoc dk = doc;
    dk.apply(fmt::format("seed={}", first + k));
    scenes.push_back(with_sort(o, dk.load()));
  }
  const std::string stem = std::filesystem::path(o.scene).stem().string();
  std::vector<char> todo;
  for (int k = 0; k < o.realizations; ++k) todo.push_back(should_run(o.out, fmt::format("{}_r{}", stem, k), rs));
  for (int k = 0; k < o.realizations; ++k) {
    const std::string sk = fmt::format("{}_r{}", stem, k);
    if (!todo[static_cast<std::size_t>(k)]) continue;
    fmt::print("realization {} of {}: seed {}\n", k + 1, o.realizations, first + k);
    run_one(scenes[static_cast<std::size_t>(k)], o.out, o.quiet, sk, rs);
  }
}

void run_command(RunCli& o, const CLI::App& run) {
  // 0 or a negative count used to mean "all cores" silently.
  if (run.count("--threads") && o.threads < 1)
    throw InputError("--threads", 0, "", fmt::format("expected a thread count >= 1, got {}", o.threads));
  if (o.threads > 0) omp_set_num_threads(o.threads);
  if (!o.resume.empty()) {
    if (run.count("--out") && std::filesystem::path(o.out) != std::filesystem::path(o.resume))
      throw InputError("--resume", 0, "", fmt::format("resumes into its own folder {}; --out {} differs", o.resume, o.out));
    o.out = o.resume;
  }
  const Resume rs = resume_of(o);
  model::SceneDoc doc = model::scene_with_overrides(o.scene, o.overrides, o.sets);
  if (o.realizations > 0) return run_realizations(o, doc, rs);
  if (o.seed >= 0) doc.apply(fmt::format("seed={}", o.seed));
  const model::Scene scene = with_sort(o, doc.load());
  if (should_run(o.out, std::filesystem::path(scene.path).stem().string(), rs)) run_one(scene, o.out, o.quiet, "", rs);
}

}  // namespace

void register_model_commands(CLI::App& app) {
  auto opts = std::make_shared<RunCli>();
  CLI::App* run = app.add_subcommand("run", "run an f-DEM scene (TOML) and write <stem>.h5 + <stem>.xmf");
  run->add_option("scene", opts->scene, "scene file (TOML, format in model/scene.h)")->required();
  run->add_option("--out", opts->out, "output folder (default: current)");
  run->add_option("--threads", opts->threads, "OpenMP threads (default: OMP_NUM_THREADS or all cores)");
  run->add_flag("--quiet", opts->quiet, "no progress line");
  run->add_option("--set", opts->sets, "override a scene value: key.path=value (model/scene_override.h)");
  run->add_option("--overrides", opts->overrides, "file of key.path = value lines (as pastemix sweep writes), applied before --set");
  run->add_option("--realizations", opts->realizations, "run N seeded realizations, written as NAME_rK.h5/.xmf")
      ->check(CLI::Range(1, 10000));
  run->add_option("--seed", opts->seed, "first seed of the realizations (default: the scene's seed)")
      ->check(CLI::Range(0L, 1L << 62));
  run->add_option("--checkpoint-every", opts->checkpoint_every,
                  "also write a checkpoint every this many seconds of wall-clock time (model/checkpoint.h)")
      ->check(CLI::PositiveNumber);
  run->add_option("--sort-every", opts->sort_every,
                  "neighbour rebuilds between spatial sorts of the particle store, 0: none (default: the scene's "
                  "[neighbor] sort_every; changes the order of force sums, not the physics)")
      ->check(CLI::Range(0L, 1000000L));
  run->add_option("--resume", opts->resume,
                  "continue the interrupted run whose checkpoint is in DIR (its output folder; same scene and --set)");
  run->callback([opts, run] { run_command(*opts, *run); });
}

}  // namespace pastemix::app
