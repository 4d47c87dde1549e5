// SPDX-License-Identifier: MIT
// `pastemix predict rheology`: the prediction band of the rheology protocol (docs/rheology_protocol.md,
// step 5). For each mixing case and each shape value of the band {s - sd, s, s + sd} (s, sd: the calibration
// record of `pastemix calibrate rheology`, or given), the case's scene with the paste rheology of the store's
// model at the case's solids content (with_rheology), run for N seeds seed0 .. seed0 + N - 1 (common random
// numbers: the same seeds at every value and case).
//
// "Reported without changing anything afterwards": nothing here edits physics but the overrides file (applied
// to every scene, stated in the output). Every run is a Task of the studies' one runner (tasks.h), kept as
// OUT/runs/<key>.h5 (key: run_key of the resolved scene text and "predict rheology"): a finished run is read
// back, never recomputed; one killed part-way continues from its checkpoint.
//
// Per run, by the analysis layer's code on the result file (a state not at rest fails the run, as `pastemix
// maps` refuses it): the rock per layer k = 1..3 (kg, rock above the surface in layer 1), the deep share
// (layers 2..3 / all blocks), the mixed (submerged) and unmixed (above the surface) rock, kg; for a case whose
// block grid is in lab.h5, also `pastemix score`'s headline (layers matched, of 3) and MAE (pp) of that run
// alone (analysis::score_against_lab), and, per value, the score of the seeds' ensemble as `pastemix score`
// prints it for those files.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "analysis/maps/block_grid.h"
#include "app/study/ledger.h"
#include "app/study/ranks.h"
#include "lab/rheology/paste_rheology.h"
#include "model/scene_doc.h"

namespace pastemix::app::study {

struct PredictOptions {
  std::vector<int> cases{1, 4, 5, 6, 7};
  std::filesystem::path calibration;        // the record; empty: shape / shape_sd below
  std::optional<double> shape, shape_sd;    // instead of a record (family: the store's)
  int seeds = 3;
  std::optional<long> seed0;                // default: each scene's own top-level seed
  int jobs = 1;
  std::filesystem::path scenes = "datasets/scenes";  // mixing_case<N>.toml
  std::filesystem::path overrides;          // the only physics edit (stated in the output); empty: none
  std::filesystem::path store = "out/lab/parameters.toml";
  std::filesystem::path lab_h5 = "out/lab/lab.h5";  // empty: no case is scored
  std::filesystem::path out = "out/predict/rheology";
  analysis::BlockLayout layout;             // default: the chapter-3 grid (scoring needs it)
  bool quiet = false;
  double checkpoint_wall_s = 300.0;
  std::string resume_with;
  std::string engine;                       // software version (table, ledger)
  Ledger* ledger = nullptr;
  const Ranks* ranks = nullptr;
  std::optional<long> task_index;
};

// The per-run quantities, in this order in RunRecord::qoi (6 values, 8 when scored).
inline constexpr int kPredictMaps = 6, kPredictScored = 8;
const std::vector<std::string>& predict_quantity_names();  // "layer1_kg", ..., "score_layers", "mae_pp"

struct PredictRun {
  long seed = 0;
  std::string key;
  std::vector<double> q;  // the quantities (empty when failed)
  std::string failure;
  bool computed = false;  // run now (or continued), not read back
};

struct PredictGroup {  // one case at one shape value
  int case_id = 0;
  double solids_fraction = 0.0;
  int label = 0;  // -1, 0, +1: s - sd, s, s + sd
  double shape = 0.0, tau_y = 0.0, eta_B = 0.0, density = 0.0;
  bool scored = false;  // the case's lab grid is in lab.h5
  std::vector<PredictRun> runs;
  // The ensemble of the seeds, scored as `pastemix score` does (scored groups with every run at rest).
  std::optional<int> ensemble_layers_matched;
  double ensemble_mae_pp = 0.0;
};

struct PredictResult {
  lab::rheology::Model model;  // family and anchor; shape/sd = the band's centre
  lab::rheology::Prior prior;
  std::string shape_source;    // the record's path and case, or "--shape"
  std::vector<PredictGroup> groups;  // case order, then -sd, 0, +sd
  std::string overrides_text;  // the overrides file's lines ("" when none)
  int runs_total = 0, computed = 0, read_back = 0;
};

PredictResult predict_rheology(const PredictOptions& o);

std::string band_table(const PredictResult& r, const PredictOptions& o);  // OUT/band.txt
std::string band_csv(const PredictResult& r);                              // OUT/band.csv: one row per group
std::string runs_csv(const PredictResult& r);                              // OUT/runs.csv: one row per run
// Writes OUT/band.txt, OUT/band.csv, OUT/runs.csv together (StagedOutput: all or none).
void write_band_outputs(const PredictResult& r, const PredictOptions& o);

}  // namespace pastemix::app::study
