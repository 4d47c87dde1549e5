// SPDX-License-Identifier: MIT
#include "analysis/score/score.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lab/ingest/block_cut.h"

namespace pastemix::analysis {

namespace {

// Mean absolute C error (pp) between one set of per-block C values and the lab's, over blocks where both
// are defined; returns {mae, max, count}.
struct Mae {
  double mae = 0.0, max = 0.0;
  int n = 0;
};
template <class Get>
Mae mae_of(const lab::BlockGrid& lab, Get model_C) {
  Mae m;
  double sum = 0.0;
  for (int b = 0; b < lab::kBlocks; ++b) {
    const double mc = model_C(b), lc = lab.C[static_cast<std::size_t>(b)];
    if (!std::isfinite(mc) || !std::isfinite(lc)) continue;
    const double e = 100.0 * std::abs(mc - lc);
    sum += e;
    m.max = std::max(m.max, e);
    ++m.n;
  }
  m.mae = m.n ? sum / m.n : std::nan("");
  return m;
}

// One BlockScore per block of the grid, in (i, j, k) order: the ensemble's C and S class against the lab's.
void score_blocks(const lab::BlockGrid& g, const Ensemble& e, const BlockLayout& L, Score& s) {
  for (int i = 1; i <= lab::kBlocksI; ++i)
    for (int j = 1; j <= lab::kBlocksJ; ++j)
      for (int k = 1; k <= lab::kLayers; ++k) {
        const auto lb = static_cast<std::size_t>(lab::block_index(i, j, k));
        const std::size_t mb = L.index(i, j, k);
        BlockScore bs;
        bs.i = i;
        bs.j = j;
        bs.k = k;
        bs.id = block_name(i, j, k);
        bs.lab_C = g.C[lb];
        bs.model_C = e.C[mb];
        bs.error_pp = 100.0 * (bs.model_C.mean - bs.lab_C);
        bs.lab_class = s_class(g.flag[lb]);
        bs.model_class = e.s_class[mb];
        bs.model_class_share = e.s_class_share[mb];
        bs.class_compared = bs.lab_class != SClass::unknown && bs.model_class != SClass::unknown;
        bs.class_agrees = bs.class_compared && bs.lab_class == bs.model_class;
        s.classes_compared += bs.class_compared;
        s.classes_agree += bs.class_agrees;
        bs.lab_S = g.S[lb];
        bs.model_S = e.S[mb];
        bs.S_compared = std::isfinite(bs.lab_S) && std::isfinite(bs.model_S.mean);
        if (bs.S_compared) {
          s.S_mae_pp += 100.0 * std::abs(bs.model_S.mean - bs.lab_S);
          ++s.S_compared;
        }
        s.blocks.push_back(bs);
      }
  s.S_mae_pp = s.S_compared ? s.S_mae_pp / s.S_compared : std::nan("");
}

// The two centre blocks (2,2,k) and (3,2,k) of each layer: their mean C, lab against model (pp).
void score_centre(const lab::BlockGrid& g, const std::vector<MixingMap>& maps, const BlockLayout& L, Score& s) {
  double centre_sum = 0.0;
  for (int k = 1; k <= lab::kLayers; ++k) {
    const auto a = static_cast<std::size_t>(lab::block_index(2, 2, k));
    const auto b = static_cast<std::size_t>(lab::block_index(3, 2, k));
    CentreLayer c;
    c.k = k;
    c.lab_C = 0.5 * (g.C[a] + g.C[b]);
    c.model_C = 0.5 * (s.blocks[a].model_C.mean + s.blocks[b].model_C.mean);
    // sd of the two-block mean over realizations: from the per-realization centre values.
    std::vector<double> v;
    for (const auto& mp : maps) v.push_back(0.5 * (mp.C[L.index(2, 2, k)] + mp.C[L.index(3, 2, k)]));
    c.model_sd = summarize(v).sd;
    c.error_pp = 100.0 * (c.model_C - c.lab_C);
    centre_sum += std::abs(c.error_pp);
    s.centre.push_back(c);
  }
  s.centre_mae_pp = centre_sum / lab::kLayers;
}

// The share of the rock below the top layer (0 with no rock).
double deep_share(const std::vector<double>& layer) {
  double all = 0.0;
  for (double x : layer) all += x;
  return all > 0.0 ? (all - layer.front()) / all : 0.0;
}

// Rock per layer (kg) and the deep share, lab and per realization, and the headline: each layer's rock within
// its tolerance.
void score_layers(const lab::BlockGrid& g, const std::vector<MixingMap>& maps, const BlockLayout& L, Score& s) {
  s.lab_layer_rock.assign(lab::kLayers, 0.0);
  for (int i = 1; i <= lab::kBlocksI; ++i)
    for (int j = 1; j <= lab::kBlocksJ; ++j)
      for (int k = 1; k <= lab::kLayers; ++k)
        s.lab_layer_rock[static_cast<std::size_t>(k - 1)] += g.M_wr[static_cast<std::size_t>(lab::block_index(i, j, k))];
  s.lab_deep_share = deep_share(s.lab_layer_rock);
  std::vector<std::vector<double>> per_layer(lab::kLayers);
  std::vector<double> shares;
  for (const auto& mp : maps) {
    std::vector<double> layer(lab::kLayers, 0.0);
    for (int i = 1; i <= lab::kBlocksI; ++i)
      for (int j = 1; j <= lab::kBlocksJ; ++j)
        for (int k = 1; k <= lab::kLayers; ++k) layer[static_cast<std::size_t>(k - 1)] += mp.rock_mass[L.index(i, j, k)];
    for (int k = 0; k < lab::kLayers; ++k) per_layer[static_cast<std::size_t>(k)].push_back(layer[static_cast<std::size_t>(k)]);
    shares.push_back(deep_share(layer));
  }
  for (const auto& v : per_layer) s.model_layer_rock.push_back(summarize(v));
  s.model_deep_share = summarize(shares);
  for (int k = 0; k < lab::kLayers; ++k) {
    LayerHeadline h;
    h.k = k + 1;
    h.lab = s.lab_layer_rock[static_cast<std::size_t>(k)];
    h.model = s.model_layer_rock[static_cast<std::size_t>(k)];
    h.rel_error = h.lab > 0.0 ? (h.model.mean - h.lab) / h.lab : std::nan("");
    h.tolerance = std::max({kLayerRelTolerance * h.lab, 2.0 * h.model.sd, kLayerAbsTolerance});
    h.matched = std::abs(h.model.mean - h.lab) <= h.tolerance;
    s.layers_matched += h.matched;
    s.headline.push_back(h);
  }
}

}  // namespace

Score score_against_lab(const LabCase& lab, const std::vector<MixingMap>& maps, std::vector<Realization> reals,
                        double no_rock_below) {
  if (maps.size() != reals.size()) throw std::invalid_argument("score: one realization record per map");
  const BlockLayout& L = maps.front().layout;
  if (L.count[0] != lab::kBlocksI || L.count[1] != lab::kBlocksJ || L.layers != lab::kLayers)
    throw std::invalid_argument("score: the model grid must have the lab's 4 x 3 blocks and 3 layers");
  const Ensemble e = ensemble(maps, no_rock_below);
  const lab::BlockGrid& g = lab.grid;
  Score s;
  s.case_id = lab.case_id;
  s.K = lab.K;
  s.K_source = lab.K_source;
  s.top_open = L.top_open;
  s.no_rock_below = no_rock_below;
  for (std::size_t r = 0; r < maps.size(); ++r)
    reals[r].mae_pp = mae_of(g, [&](int b) { return maps[r].C[L.index(b / 9 + 1, b / 3 % 3 + 1, b % 3 + 1)]; }).mae;
  std::vector<double> per_real;
  for (const auto& r : reals) per_real.push_back(r.mae_pp);
  s.realization_mae_pp = summarize(per_real);
  s.realizations = std::move(reals);
  score_blocks(g, e, L, s);
  const Mae m = mae_of(g, [&](int b) { return s.blocks[static_cast<std::size_t>(b)].model_C.mean; });
  s.mae_pp = m.mae;
  s.max_abs_error_pp = m.max;
  s.blocks_compared = m.n;
  score_centre(g, maps, L, s);
  s.cone_221 = s.blocks[static_cast<std::size_t>(lab::block_index(2, 2, 1))].model_C.mean;
  s.cone_321 = s.blocks[static_cast<std::size_t>(lab::block_index(3, 2, 1))].model_C.mean;
  s.lab_cone_221 = g.C[static_cast<std::size_t>(lab::block_index(2, 2, 1))];
  s.lab_cone_321 = g.C[static_cast<std::size_t>(lab::block_index(3, 2, 1))];
  s.model_cone = s.cone_221 >= 0.9 && s.cone_321 >= 0.9;
  s.lab_cone = s.lab_cone_221 >= 0.9 && s.lab_cone_321 >= 0.9;
  s.poured = e.poured;
  s.mixed = e.mixed;
  s.unmixed = e.unmixed;
  s.outside_grid = e.outside_grid;
  s.escaped = e.escaped;
  for (double x : g.M_wr) s.lab_recovered_rock += x;
  score_layers(g, maps, L, s);
  return s;
}

}  // namespace pastemix::analysis
