// SPDX-License-Identifier: MIT
#include "model/run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>
#include <omp.h>

#include "base/error.h"
#include "base/staged_output.h"
#include "model/checkpoint.h"
#include "model/output.h"

namespace pastemix::model {

std::string format_profile(const Profile& p, long steps, double wall_seconds, std::size_t particles) {
  double total = 0.0;
  for (double s : p.seconds) total += s;
  const std::string sorts = p.sorts > 0 ? fmt::format(", {} spatial sorts", p.sorts) : "";
  std::string out = fmt::format("stage profile ({} steps, {} particles, {} neighbour rebuilds{}):\n", steps,
                                particles, p.rebuilds, sorts);
  for (int k = 0; k < Profile::count; ++k)
    out += fmt::format("  {:<15} {:9.3f} s  {:5.1f} %\n", Profile::names[k], p.seconds[k],
                       total > 0 ? 100.0 * p.seconds[k] / total : 0.0);
  const double sps = wall_seconds > 0 ? static_cast<double>(steps) / wall_seconds : 0.0;
  out += fmt::format("  {:<15} {:9.3f} s  ({:.0f} steps/s, {:.3g} particle-steps/s)\n", "total wall", wall_seconds,
                     sps, sps * static_cast<double>(particles));
  return out;
}

std::string RunSummary::escaped_line() const {
  if (!outflow) return "";
  return fmt::format("outflow: {} particle(s) left the domain and were removed, {:.6g} kg = {:.4g} % of the {:.6g} kg "
                     "of particles (listed in /escaped)\n",
                     escaped_count, escaped_mass, total_mass > 0 ? 100.0 * escaped_mass / total_mass : 0.0,
                     total_mass);
}

namespace {

RunSummary run_checked(const Scene& scene, const std::filesystem::path& out_dir, const RunOptions& opt) {
  using Clock = std::chrono::steady_clock;
  RunSummary r;
  r.threads = omp_get_max_threads();
  const std::string stem =
      opt.stem.empty() ? std::filesystem::path(scene.path).stem().string() : opt.stem;
  r.h5 = out_dir / (stem + ".h5");
  r.xmf = out_dir / (stem + ".xmf");
  StagedOutput staged;
  const auto h5_tmp = staged.path(r.h5);
  World world = make_world(scene);
  RunOutput out(h5_tmp, r.h5.filename().string(), scene);

  const double dt = scene.config.dt;
  const long total_steps = std::lround(scene.end_time / dt);
  const long snap_every = std::max(1L, std::lround(scene.output_interval / dt));
  const long sample_every = std::max(1L, std::lround(scene.energy_interval / dt));
  const auto t0 = Clock::now();
  auto last_progress = t0;
  // [stop] rule = "at_rest": a census every check_interval from `start` on; the run ends after `hold`
  // consecutive passing checks (the last state is written as a snapshot and a sample).
  const StopRule& rule = scene.stop;
  RestMonitor rest(rule, dt, total_steps);
  const long stop_every = rest.every();
  bool fired = false;
  // Checkpoints: taken only where the loop stops anyway (below), so they change no batch of steps.
  const std::filesystem::path ckpt = checkpoint_path(out_dir, stem);
  const long ckpt_every = scene.checkpoint_interval > 0 ? std::max(1L, std::lround(scene.checkpoint_interval / dt)) : 0;
  remove_stale_siblings(ckpt);  // a checkpoint being written when an earlier run was killed
  double wall_before = 0.0;  // s, of the run before its checkpoint
  long s0 = 0;
  auto emit = [&](long s, bool last) {
    auto timer0 = Clock::now();
    if (s % snap_every == 0 || last) out.snapshot(world);
    if (s % sample_every == 0 || last) out.sample(world);
    world.profile().seconds[Profile::output] += std::chrono::duration<double>(Clock::now() - timer0).count();
  };
  if (opt.resume) {
    const CheckpointInfo info = resume_from_checkpoint(ckpt, scene, world, rest, out, h5_tmp);
    s0 = info.step;
    wall_before = info.wall_seconds;
    r.resumed_at_step = s0;
  } else {
    world.check();
    emit(0, total_steps == 0);
  }
  long ckpt_step = s0;
  auto ckpt_wall = Clock::now();
  // Steps run in batches up to the next step that checks, writes or reports: World::advance fuses the end
  // of one step with the start of the next inside a batch (the same trajectory as single steps).
  auto next_multiple = [](long s, long every) { return (s / every + 1) * every; };
  for (long s = s0; s < total_steps;) {
    long next = std::min({total_steps, next_multiple(s, opt.check_every), next_multiple(s, snap_every),
                          next_multiple(s, sample_every), next_multiple(s, stop_every)});
    if (opt.progress) next = std::min(next, next_multiple(s, 100));
    world.advance(next - s);
    s = next;
    if (s % opt.check_every == 0) world.check();
    fired = rest.check(world, s);
    emit(s, fired || s == total_steps);
    if (fired) break;
    if (s < total_steps && ((ckpt_every > 0 && s - ckpt_step >= ckpt_every) ||
                            (opt.checkpoint_wall_s > 0 &&
                             std::chrono::duration<double>(Clock::now() - ckpt_wall).count() >= opt.checkpoint_wall_s))) {
      const auto c0 = Clock::now();
      write_checkpoint(ckpt, out, world, rest, wall_before + std::chrono::duration<double>(c0 - t0).count(),
                       opt.resume_with);
      world.profile().seconds[Profile::output] += std::chrono::duration<double>(Clock::now() - c0).count();
      ckpt_step = s;
      ckpt_wall = Clock::now();
      ++r.checkpoints;
    }
    if (opt.progress && s % 100 == 0) {
      const auto now = Clock::now();
      if (std::chrono::duration<double>(now - last_progress).count() >= opt.progress_every_s) {
        last_progress = now;
        const double el = std::chrono::duration<double>(now - t0).count();
        const double sps = static_cast<double>(s - s0) / el;
        std::fprintf(stderr, "\rt = %.4g / %.4g s  %.0f steps/s  ETA %.0f s   ", world.time(), scene.end_time, sps,
                     static_cast<double>(total_steps - s) / sps);
        std::fflush(stderr);
      }
    }
  }
  world.check();
  if (opt.progress) std::fprintf(stderr, "\n");
  if (opt.at_end) opt.at_end(world);
  r.stop.rule_at_rest = rule.at_rest;
  r.stop.fired = fired;
  r.stop.start = rule.start;
  r.stop.time = world.time();
  // The displacement measure's last census is of mean speeds; they go into the last snapshot for the maps.
  const std::vector<double>* mean = rest.mean_speeds(world, world.steps());
  r.stop.last = census(world, rule, mean);
  if (mean) out.mean_speed(world, *mean);
  out.stop_outcome(r.stop, rule);
  r.wall_seconds = wall_before + std::chrono::duration<double>(Clock::now() - t0).count();
  r.steps = world.steps();
  r.steps_per_second = r.wall_seconds > 0 ? static_cast<double>(r.steps) / r.wall_seconds : 0.0;
  const std::string xmf = out.finish(world, r.wall_seconds, r.threads);
  staged.write_text(r.xmf, xmf);
  staged.commit();
  // The result is out: its checkpoint is of no more use (a kill before this line resumes and publishes again).
  std::error_code ec;
  std::filesystem::remove(ckpt, ec);
  r.outflow = scene.config.on_exit == ExitRule::remove;
  r.escaped_count = world.escaped().size();
  r.escaped_mass = world.escaped_mass();
  r.total_mass = world.escaped_mass();
  for (double m : world.particles().mass) r.total_mass += m;
  r.profile = world.profile();
  r.profile_table = format_profile(r.profile, r.steps, r.wall_seconds, world.particles().size());
  // The load balance at the end: each thread's share of the partition's cost (World::update_shares).
  if (world.thread_shares().size() > 1) {
    r.profile_table += "  thread shares  ";
    for (double s : world.thread_shares()) r.profile_table += fmt::format(" {:.3f}", s);
    r.profile_table += "  (of the pair and particle work, by measured speed)\n";
  }
  return r;
}

}  // namespace

RunSummary run_scene(const Scene& scene, const std::filesystem::path& out_dir, const RunOptions& opt) {
  try {
    return run_checked(scene, out_dir, opt);
  } catch (const RuntimeFailure& e) {
    // A blow-up is deterministic: resuming the same scene would meet it again, so under its own name the
    // checkpoint would only stop the next fresh run. It is kept under another (failed_checkpoint_path), where
    // nothing resumes it by itself: the state shortly before the failure, for a diagnosis (chapter-7 test 3's
    // overfilled cell took 17 minutes of rerun to see again, docs/mixing_scenes.md).
    const std::string stem = opt.stem.empty() ? std::filesystem::path(scene.path).stem().string() : opt.stem;
    const std::filesystem::path ckpt = checkpoint_path(out_dir, stem), kept = failed_checkpoint_path(out_dir, stem);
    std::error_code ec;
    std::filesystem::remove(kept, ec);
    if (!std::filesystem::exists(ckpt, ec)) throw;
    std::filesystem::rename(ckpt, kept, ec);
    if (ec) {
      std::filesystem::remove(ckpt, ec);
      throw;
    }
    throw RuntimeFailure(fmt::format("{}\nthe last checkpoint is kept as {} for a diagnosis (to continue from it, "
                                     "e.g. with a build that logs more, rename it to {} and run with --resume)",
                                     e.what(), kept.string(), ckpt.filename().string()));
  }
}

}  // namespace pastemix::model
