// SPDX-License-Identifier: MIT
#include "analysis/maps/mixing_map.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "lab/ingest/block_cut.h"

namespace pastemix::analysis {

double MixingMap::conservation_error() const {
  if (!(poured > 0.0)) return 0.0;
  const double grid = std::abs(poured - (in_blocks + below_grid + beside_grid + above_uncounted + escaped)) / poured;
  const double surface = std::abs(poured - (submerged + above_surface + escaped)) / poured;
  return std::max(grid, surface);
}

std::string block_name(int i, int j, int k) {
  if (i < 10 && j < 10 && k < 10) return fmt::format("M_{}{}{}", i, j, k);
  return fmt::format("M_{}_{}_{}", i, j, k);
}

MixingMap mixing_map(const MixingInputs& in, const ParticleView& particles) {
  const BlockMasses bm = rock_in_blocks(in.layout, in.surface_z, particles);
  MixingMap m;
  m.layout = in.layout;
  const std::size_t nb = in.layout.block_count();
  m.rock_mass = bm.rock_mass;
  m.rock_volume = bm.rock_volume;
  m.rock_volume_submerged = bm.rock_volume_submerged;
  m.block_volume = bm.block_volume;
  m.paste_volume.assign(nb, 0.0);
  m.paste_dried_mass.assign(nb, 0.0);
  m.C.assign(nb, 0.0);
  m.S.assign(nb, 0.0);
  m.S_raw.assign(nb, 0.0);
  m.flag.assign(nb, 0);
  m.escaped = in.escaped_mass;
  m.poured = bm.total + in.escaped_mass;
  m.in_blocks = bm.in_blocks;
  m.below_grid = bm.below_grid;
  m.beside_grid = bm.beside_grid;
  m.above_surface = bm.above_surface;
  m.above_uncounted = bm.above_uncounted;
  m.submerged = bm.submerged;
  // One scratch lab grid: its block 0 is each of our blocks in turn, so any layout size reuses the lab's
  // C and S formula unchanged.
  lab::BlockGrid scratch;
  scratch.K = in.K;
  scratch.rho_s[0] = in.rho_s;
  scratch.e_f[0] = in.e_f;
  for (std::size_t b = 0; b < nb; ++b) {
    double vp = m.block_volume[b] - m.rock_volume_submerged[b];
    if (vp < 0.0) {  // soft-sphere overlaps can pack a block past full; no paste then, and say so
      ++m.overfull_blocks;
      vp = 0.0;
    }
    m.paste_volume[b] = vp;
    m.paste_dried_mass[b] = vp * in.paste_density * in.solids_fraction;
    scratch.M_wr[0] = m.rock_mass[b];
    scratch.M_paste[0] = m.paste_dried_mass[b];
    lab::compute_block(scratch, 0);
    m.C[b] = scratch.C[0];
    m.S[b] = scratch.S[0];
    m.S_raw[b] = scratch.S_raw[0];
    m.flag[b] = scratch.flag[0];
  }
  return m;
}

}  // namespace pastemix::analysis
