// SPDX-License-Identifier: MIT
#include "analysis/maps/mixing_map.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "base/error.h"
#include "base/units.h"
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

MixingInputs mixing_inputs(const ResultSnapshot& r, const BlockLayout& layout) {
  MixingInputs in;
  in.layout = layout;
  in.surface_z = r.surface_z.value;
  in.surface_source = r.surface_z.source;
  in.paste_density = r.paste_density.value;
  in.solids_fraction = r.solids_fraction.value;
  in.escaped_mass = r.escaped_mass;
  if (r.paste_field) {
    in.paste_field = &*r.paste_field;
    if (r.surface_z.source.rfind("command line", 0) != 0) {  // an override keeps its flat surface
      const double x0 = layout.origin[0], y0 = layout.origin[1];
      in.surface_z = paste_surface_z(*r.paste_field, x0, x0 + layout.count[0] * layout.size[0], y0,
                                     y0 + layout.count[1] * layout.size[1]);
      in.surface_source = "area-mean paste height over the block grid, " + r.paste_field->source;
    }
  }
  return in;
}

namespace {

// The box of block M_ijk below `surface` (m); layer 1 reaches up to `top` (m).
Box3 block_box(const BlockLayout& L, int i, int j, int k, double surface, double top) {
  Box3 b;
  b.lo = {L.origin[0] + (i - 1) * L.size[0], L.origin[1] + (j - 1) * L.size[1], surface - k * L.layer_thickness};
  b.hi = {b.lo.x + L.size[0], b.lo.y + L.size[1], k == 1 ? top : surface - (k - 1) * L.layer_thickness};
  return b;
}

// A flow result's paste per block and its mixed / unmixed split (the header's field rules).
void paste_from_field(const MixingInputs& in, const ParticleView& particles, MixingMap& m) {
  const PasteField& f = *in.paste_field;
  const BlockLayout& L = in.layout;
  const double top = L.top_open ? std::max(in.surface_z, f.origin[2] + f.n[2] * f.h[2]) : in.surface_z;
  for (int i = 1; i <= L.count[0]; ++i)
    for (int j = 1; j <= L.count[1]; ++j)
      for (int k = 1; k <= L.layers; ++k)
        m.paste_volume[L.index(i, j, k)] = paste_volume_in(f, block_box(L, i, j, k, in.surface_z, top), particles);
  const std::vector<double> share = paste_share_around(f, particles);
  double total = 0.0, wet = 0.0;
  for (std::size_t p = 0; p < share.size(); ++p) {
    const double r = particles.radius[p];
    const double mass = particles.density[p] * 4.0 / 3.0 * units::pi * r * r * r;
    total += mass;
    wet += share[p] * mass;
  }
  m.submerged = wet;
  m.above_surface = total - wet;
  m.from_paste_field = true;
}

}  // namespace

MixingMap mixing_map(const MixingInputs& in, const ParticleView& particles) {
  if (!std::isfinite(in.surface_z))
    throw InputError(in.surface_source, 0, "surface_z", "the final surface height is not finite");
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
  if (in.paste_field) paste_from_field(in, particles, m);
  // One scratch lab grid: its block 0 is each of our blocks in turn, so any layout size reuses the lab's
  // C and S formula unchanged.
  lab::BlockGrid scratch;
  scratch.K = in.K;
  scratch.rho_s[0] = in.rho_s;
  scratch.e_f[0] = in.e_f;
  for (std::size_t b = 0; b < nb; ++b) {
    double vp = m.from_paste_field ? m.paste_volume[b] : m.block_volume[b] - m.rock_volume_submerged[b];
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
