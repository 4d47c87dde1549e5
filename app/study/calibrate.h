// SPDX-License-Identifier: MIT
// `pastemix calibrate rolling-resistance`: the rolling-resistance coefficient mu_r that makes the simulated
// repose angle equal a measured one (thesis ch. 6, Table 6.1), from a smooth surrogate of angle(mu_r).
//
// Design (common random numbers): the same seeds seed0 .. seed0 + N - 1 (the scene's top-level seed) at every
// mu_r, so that the seed-to-seed part of the angle is shared by all points and cancels in the slope. Points:
// `values`, or `points` evenly over [lo, hi]. Every (mu_r, seed) is one task of the studies' runner (tasks.h:
// keyed, kept, never rerun, resumable, spread over --jobs / MPI ranks / a Slurm array). The surrogate
// (surrogate.h: monotone in mu_r, the seed spread as the noise) is fitted over every run, not the point means,
// and inverted at the target: mu_r +- sd from the fit's covariance (and the target's sd if given). Then
// `refine` rounds add mu* -+ max(2 sd, 5 % of the range) and refit. A run that fails (blow-up, unfinished
// pile) is listed and left out of the fit. It is for the rolling law the scene names ([contact] rolling); a
// different law gives a different coefficient. Every [[interaction]]'s rolling_friction is set to mu_r
// (rock/rock and rock/wall alike, as the thesis did).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/study/ledger.h"
#include "app/study/ranks.h"
#include "app/study/surrogate.h"
#include "app/study/tasks.h"
#include "model/scene_doc.h"

namespace pastemix::app::study {

struct RollingOptions {
  double target = 0.0, target_sd = 0.0;  // deg
  double lo = 0.0, hi = 0.0;             // mu_r range of the initial points
  std::vector<double> values;            // explicit initial points (replace the even grid)
  int points = 5, seeds = 3, refine = 1;
  int jobs = 1;
  std::filesystem::path out = "out/calibrate/rolling_resistance";
  bool no_cache = false;                 // keep no run records (the ledger, if given, is still used)
  bool quiet = false;
  Ledger* ledger = nullptr;
  const Ranks* ranks = nullptr;
  std::optional<long> task_index;
  double checkpoint_wall_s = 300.0;      // s of wall clock between checkpoints of a run in progress
  std::string resume_with, engine;
};

struct RollingRun {
  double mu = 0.0;
  long seed = 0;
  bool failed = false;
  std::string failure;
  double angle = 0.0, wall_s = 0.0, work = 0.0;  // deg, s, particle-steps
  From from = From::ran;
};

struct RollingResult {
  std::string law;                 // [contact] rolling
  std::vector<RollingRun> runs;    // sorted by mu, then seed
  MonotoneFit fit;
  Inverse answer;
  TaskCounts counts;
};

// The scene with every [[interaction]] rolling_friction set to mu.
model::SceneDoc with_rolling_resistance(const model::SceneDoc& base, double mu);

RollingResult calibrate_rolling(const model::SceneDoc& base, const RollingOptions& o);
// The printed table: every point (mean +- seed sd, the surrogate there), the fit, the answer or why none.
std::string rolling_table(const RollingResult& r, const RollingOptions& o);
// OUT/points.csv (one row per run) and OUT/table.txt.
void write_rolling_outputs(const RollingResult& r, const RollingOptions& o);

}  // namespace pastemix::app::study
