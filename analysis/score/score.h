// SPDX-License-Identifier: MIT
// Scoring a model ensemble against a lab case's measured block grid (thesis ch. 3, Table 3.2).
//
// The HEADLINE (printed first, first in score.toml): did the rock go where the lab found it? The rock mass per
// layer, model against lab, with relative errors and a verdict within the lab's noise floor (below); the deep
// share; the centre-column profile; the cone check. Then the block-by-block details:
// The score uses the ensemble MEAN C per block and shows the spread (sd over realizations) beside it:
//   mean absolute C error over the 36 blocks, in percentage points (pp);
//   the centre-column profile: blocks M_22k and M_32k (the two centre columns under the funnel), per layer
//     k = 1..3, model vs lab (the mean of the two blocks) and its error;
//   S class agreement per block: no rock / S < 100 % / capped at 100 % (blocks where either class is unknown,
//     e.g. case 1 without K, are not compared), and the S values themselves: the mean absolute error of the
//     ensemble-mean S (capped) over the blocks where both have one, in pp;
//   the unmixed-cone check: C >= 90 % in M_221 and M_321 (the crater of unmixed rock under the funnel), for the
//     model and for the lab (cases 2-3 have one, case 1 does not): reproduced when both have it;
//   mixed (submerged) and unmixed (above the surface) rock masses, with the lab's recovered rock mass;
//   rock mass per layer (sum of its 12 blocks) and the deep share = rock in layers 2..3 / rock in all blocks,
//     for lab and model: the penetration measure the trends across cases are compared on.
#pragma once

#include <string>
#include <vector>

#include "analysis/maps/motion.h"
#include "analysis/score/ensemble.h"
#include "analysis/score/lab_case.h"

namespace pastemix::analysis {

struct Realization {
  std::string path;
  std::int64_t seed = -1;
  std::string scene_hash;
  int snapshot = 0;
  double time_s = 0.0;
  double mae_pp = 0.0;  // this realization's own mean absolute C error
  StateMark state;      // at rest, or an unfinished state mapped with --allow-moving
};

// The headline's per-layer tolerance, from the lab's own noise floor (datasets/thesis, Table 3.2): one specimen
// per case, whose 36 blocks recovered 0.85-1.02 kg of the 1 kg poured, i.e. the lab's rock balance is known to
// ~15 %. A layer's model rock mass matches the lab's within max(15 % of the lab's layer mass, 2 model sd over
// the realizations, 10 g); the 10 g floor (1 % of the pour) keeps a near-empty lab layer from demanding an
// exact zero.
inline constexpr double kLayerRelTolerance = 0.15;
inline constexpr double kLayerAbsTolerance = 0.010;  // kg

struct LayerHeadline {
  int k = 0;
  double lab = 0.0;           // kg
  Summary model;              // kg over realizations
  double rel_error = 0.0;     // (model mean - lab) / lab (NaN when the lab layer is empty)
  double tolerance = 0.0;     // kg
  bool matched = false;
};

struct BlockScore {
  int i = 0, j = 0, k = 0;  // 1-based
  std::string id;           // M_ijk
  double lab_C = 0.0;       // fraction
  Summary model_C;          // fraction, over realizations
  double error_pp = 0.0;    // 100 (model mean - lab)
  SClass lab_class = SClass::unknown, model_class = SClass::unknown;
  double model_class_share = 0.0;
  bool class_compared = false, class_agrees = false;
  double lab_S = 0.0;        // fraction, capped; NaN where the lab has no S (no rock, or no K)
  Summary model_S;           // over the realizations where S is defined (Ensemble::S)
  bool S_compared = false;   // both defined
};

struct CentreLayer {
  int k = 0;
  double lab_C = 0.0, model_C = 0.0, model_sd = 0.0;  // fractions, mean of M_22k and M_32k
  double error_pp = 0.0;
};

struct Score {
  int case_id = 0;
  double K = 0.0;
  std::string K_source;
  bool top_open = true;  // the maps' rule: rock above the surface counted in layer 1 (BlockLayout::top_open)
  std::vector<Realization> realizations;
  std::vector<BlockScore> blocks;  // lab order (lab::block_index)
  int blocks_compared = 0;
  double mae_pp = 0.0, max_abs_error_pp = 0.0;
  Summary realization_mae_pp;  // spread of the per-realization errors
  std::vector<CentreLayer> centre;
  double centre_mae_pp = 0.0;
  int classes_compared = 0, classes_agree = 0;
  int S_compared = 0;             // blocks where lab and model both have an S value
  double S_mae_pp = 0.0;          // mean |model mean S - lab S| over them (pp); NaN when none
  double no_rock_below = 0.0;  // kg: model blocks with less rock count as 'no rock' in the S classes
  double cone_221 = 0.0, cone_321 = 0.0, lab_cone_221 = 0.0, lab_cone_321 = 0.0;  // fractions
  bool model_cone = false, lab_cone = false;  // C >= 90 % in both M_221 and M_321
  Summary poured, mixed, unmixed, outside_grid, escaped;  // kg (escaped: left the simulation's domain)
  double lab_recovered_rock = 0.0;               // kg, sum of the lab's M_wr over the 36 blocks
  std::vector<double> lab_layer_rock;            // kg per layer k = 1..3
  std::vector<Summary> model_layer_rock;         // kg per layer, over realizations
  double lab_deep_share = 0.0;                   // rock in layers 2..3 / rock in the 36 blocks
  Summary model_deep_share;                      // the same per realization
  std::vector<LayerHeadline> headline;           // per layer: the headline's rock masses and verdicts
  int layers_matched = 0;
  bool all_at_rest() const {
    for (const auto& r : realizations)
      if (!r.state.at_rest) return false;
    return true;
  }
};

// `maps[r]` belongs to `realizations[r]`. The maps must be on a 4 x 3 x 3 layout (std::invalid_argument).
Score score_against_lab(const LabCase& lab, const std::vector<MixingMap>& maps, std::vector<Realization> realizations,
                        double no_rock_below = kLabMassResolution);

std::string headline_table(const Score& s);  // the headline (printed first by score_table)
std::string score_table(const Score& s);  // the printed table
std::string score_csv(const Score& s);    // one row per block
std::string score_toml(const Score& s, const std::string& software, const std::string& command,
                       const std::string& created, const std::string& lab_h5);

}  // namespace pastemix::analysis
