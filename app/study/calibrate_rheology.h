// SPDX-License-Identifier: MIT
// `pastemix calibrate rheology --case 2`: the one shape parameter of the paste-rheology model
// (lab/rheology/paste_rheology.h) that makes the simulated per-layer rock mass of a mixing case match the
// lab's (protocol: docs/rheology_protocol.md, written before any run).
//
// Objective (fixed by the protocol): the rock mass per layer k = 1..3 of the case's block grid, model M_k
// (ensemble mean over the seeds, as `pastemix score` uses the ensemble mean) against the lab's L_k (sum of
// M_wr over the layer's 12 blocks, lab.h5), combined as the mean squared relative error
//     J = (1/3) sum_k ((M_k - L_k) / L_k)^2,
// computed by the analysis layer's maps code (analysis/maps) on each run's result file. Its seed spread: the
// per-seed J_s (each seed's own M_sk) with their sd, and the jackknife standard error of J over the seeds.
// Common random numbers: seeds seed0 .. seed0 + N - 1 at every point (the scene's top-level seed).
//
// Search (deterministic, so a rerun asks for the same points): a grid of `points` values across the prior
// range, then `refine` rounds that add the vertex of a weighted quadratic fitted to the (up to 5) points
// nearest the best one, and the vertex +- a step. The result is the final fit's vertex; its sd is the larger of
// (a) the delta-method sd of the vertex from the fit's covariance (weights 1/se^2, scaled by chi2/dof when
// that exceeds 1) and (b) the half-width at which the surrogate rises by the se of J at the minimum (spread
// over curvature). A vertex outside the prior range, or no positive curvature, is a RuntimeFailure (exit 3)
// after the table and PNG are written: the record and the store are then not written.
//
// Runs: each (point, seed) is one scene run (`model::run_scene`, one thread each with `jobs` > 1) whose result
// file is kept under OUT/runs/<scene hash>.h5, the hash of the resolved scene text (every override, the
// rheology values and the seed are in it); a file already there is read, never recomputed. A run whose final
// state is not at rest (the maps' test, analysis/maps/motion.h: more than 1 g faster than 0.01 m/s; a scene
// with [stop] rule = "at_rest" ends there) fails its point, which is then left out of the fit and reported.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "analysis/maps/block_grid.h"
#include "app/study/ledger.h"
#include "app/study/ranks.h"
#include "app/study/tasks.h"
#include "lab/rheology/paste_rheology.h"
#include "model/scene_doc.h"

namespace pastemix::app::study {

struct RheologyCalOptions {
  int case_id = 2;
  std::string family;                        // empty: the store's family
  int seeds = 3;
  int jobs = 1;
  int points = 5;                            // initial grid across the prior range
  int refine = 1;                            // refinement rounds
  std::vector<double> values;                // explicit initial points (replace the grid)
  std::filesystem::path store = "out/lab/parameters.toml";
  std::filesystem::path lab_h5 = "out/lab/lab.h5";
  std::filesystem::path out = "out/calibrate/rheology_case2";
  std::optional<std::array<double, 3>> target_layers;  // kg: replaces the lab's per-layer rock (synthetic tests)
  analysis::BlockLayout layout;              // default: the chapter-3 grid
  double eta_factor = 1.0;                   // sensitivity: eta_B x this at every point
  bool quiet = false;
  // A run in progress writes runs/<hash>.checkpoint.h5 every this many wall-clock seconds (0: never), and
  // a rerun after a kill continues it from there (bit-identical to an unbroken run: model/checkpoint.h).
  double checkpoint_wall_s = 300.0;
  std::string resume_with;                   // the command that resumes the calibration (stored in each checkpoint)
  std::string engine;                        // software version (ledger rows)
  Ledger* ledger = nullptr;                  // the study's ledger (ledger.h: layers per task); null: none
  const Ranks* ranks = nullptr;              // MPI ranks; null: one process
  std::optional<long> task_index;            // run this task of the current round alone (Slurm; tasks.h)
};

// One (point, seed) run.
struct SeedRun {
  long seed = 0;
  std::string hash;
  std::array<double, 3> layers{};  // kg
  double J = 0.0;
  bool cached = false;
  bool resumed = false;            // continued from its checkpoint
};

struct CalPoint {
  double shape = 0.0;
  double tau_y = 0.0, eta_B = 0.0, density = 0.0;  // at the case's solids content
  std::vector<SeedRun> runs;
  std::array<double, 3> layers{}, layers_sd{};      // kg, mean and sd over seeds
  double J = 0.0;            // of the seed-mean layers
  double J_se = 0.0;         // jackknife standard error over the seeds
  double J_seed_mean = 0.0, J_seed_sd = 0.0;  // the per-seed J_s
  std::string failure;       // non-empty: a run failed (the point is left out of the fit)
};

struct QuadFit {
  double c0 = 0.0, c1 = 0.0, c2 = 0.0;  // J ~ c0 + c1 (p - p_ref) + c2 (p - p_ref)^2
  double p_ref = 0.0;
  double vertex = 0.0, sd_delta = 0.0, sd_curvature = 0.0, sd = 0.0;
  std::vector<double> used;             // the shapes it was fitted on
  bool ok = false;
  std::string why;                      // when not ok
};

struct RheologyCalResult {
  lab::rheology::Model model;          // family and anchor; shape/sd = the result when ok
  lab::rheology::Prior prior;
  double solids_fraction = 0.0;
  std::array<double, 3> target{};      // kg
  std::string target_source;
  std::vector<CalPoint> points;        // sorted by shape
  QuadFit fit;
  int runs_total = 0, runs_executed = 0;
  std::string table;
};

// Runs `doc` into RUNS/<hash>.h5 (model::run_scene, checkpoints every `checkpoint_wall_s` of wall clock)
// unless that file is already there (from = From::disk, nothing run); continues RUNS/<hash>.checkpoint.h5
// when a kill left one (from = From::resumed). The record has the cost, no QoI.
RunRecord run_kept(const model::SceneDoc& doc, const std::filesystem::path& runs, const std::string& hash,
                   double checkpoint_wall_s, const std::string& resume_with, From& from);
// The scene's top-level seed (InputError naming the scene when absent: common random numbers need it).
long scene_seed(const model::SceneDoc& d);
// C_w of the [[fluid]] that reads its rheology from the store (InputError when none does).
double scene_solids(const model::SceneDoc& d);
// The scene with every [[fluid]] that reads `rheology_from` given explicit values instead.
model::SceneDoc with_rheology(const model::SceneDoc& base, double tau_y, double eta_B, double density);
// J and the per-layer relative errors.
double layer_objective(const std::array<double, 3>& model, const std::array<double, 3>& target);
// Weighted quadratic through (p, J) with standard errors se, and the vertex's sd (see the header).
QuadFit fit_quadratic(const std::vector<double>& p, const std::vector<double>& J, const std::vector<double>& se);

RheologyCalResult calibrate_rheology(const model::SceneDoc& base, const RheologyCalOptions& o);
// The printed table: every point with its seed spread, the surrogate, the result (or why there is none).
std::string calibration_table(const RheologyCalResult& r, const RheologyCalOptions& o);
// OUT/table.txt, OUT/points.csv, OUT/objective.png (python; a warning without it), and, when the fit is ok,
// OUT/rheology_calibration.toml (the record for `lab reduce --rheology-calibration`). Returns the record path
// ("" when not written).
std::string write_calibration_outputs(const RheologyCalResult& r, const RheologyCalOptions& o,
                                      const std::string& command);

}  // namespace pastemix::app::study
