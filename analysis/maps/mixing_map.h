// SPDX-License-Identifier: MIT
// Mixing map: a model result on the lab's block grid, with C and S computed exactly as the lab layer does.
//
// Per block (layer 1 = top, depth measured down from the final free surface of the paste):
//   rock mass    M_wr   exact sphere-block intersection volumes x rock density (rock_in_blocks)
//   paste volume V_p  = block volume - submerged rock volume in the block (the block lies below the surface)
//   dried paste  M_p  = V_p x paste density x solids fraction    (what oven-drying a cut block leaves)
//   C, S, S_raw, flag from lab::compute_block with the case's K, rho_s and e_f (eqs 3.1 and 3.8).
// Rock above the final surface is UNMIXED (`above_surface`); with the layout's `top_open` (default) it still
// counts in the layer-1 block under it, as the lab cut it (block_grid.h says why), else in no block. Rock
// below the surface is MIXED (`submerged`): in a block, below the grid or beside it.
//
// Rock that left the simulation's domain (an outflow boundary, `escaped_mass`, read from the result's
// /escaped) was poured but is in no block, neither mixed nor unmixed: it is a term of both balances.
//
// With a paste field (a `dynamics = "flow"` result, paste_field.h) the surface is the field's area-mean paste
// height over the grid's footprint, a block's paste is the field's paste in it (not "all fluid below the
// surface"), and each rock is mixed by the paste share of the fluid around it; rock above the surface still
// counts in layer 1 with `top_open`, and layer 1's paste then includes any paste above the mean surface.
//
// Assumes the grid's blocks lie inside the container, full of paste below the surface (the default grid
// covers the chapter-3 box exactly; a box corner at the origin).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "analysis/maps/block_grid.h"
#include "analysis/maps/paste_field.h"
#include "analysis/maps/result_file.h"

namespace pastemix::analysis {

struct MixingInputs {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  BlockLayout layout;            // default: the chapter-3 grid (4 x 3 blocks of 5 x 5.5 cm, 3 layers of 3 cm)
  double surface_z = 0.0;        // m, final free surface
  double paste_density = 0.0;    // kg/m3, wet paste
  double solids_fraction = 0.0;  // -, solids mass / paste mass
  double K = nan;                // kg/m3, rho_wr / n_wr of eq. 3.8; NaN: S not computed (flag no_K)
  double rho_s = 2710.0;         // kg/m3, tailings particle density (thesis ch. 3)
  double e_f = 0.6;              // -, final void ratio of the dried paste (thesis ch. 3)
  double escaped_mass = 0.0;     // kg, rock removed at the domain boundary before the snapshot (ResultSnapshot)
  const PasteField* paste_field = nullptr;  // a flow result's paste (not owned); null: the flat-surface rule
  std::string surface_source;    // where surface_z came from (reported)
};

// The inputs of one result on `layout`: its paste properties, escaped rock and surface; with a paste field the
// surface is the field's area-mean paste height over the layout's footprint, unless --surface-z overrode it.
// K, rho_s and e_f stay at their defaults (the caller's).
MixingInputs mixing_inputs(const ResultSnapshot& r, const BlockLayout& layout);

struct MixingMap {
  BlockLayout layout;
  // Per block, flat index layout.index(i, j, k) (row-major [i][j][k], as the lab's grids).
  std::vector<double> rock_mass, rock_volume, block_volume, paste_volume, paste_dried_mass;  // kg, m3
  std::vector<double> rock_volume_submerged;  // m3, the part of rock_volume below the surface
  std::vector<double> C, S, S_raw;     // fractions; S capped at 1, NaN where undefined
  std::vector<std::int32_t> flag;      // lab::SFlag
  // Accounting, kg: poured = (rock in the snapshot) + escaped; poured = in_blocks + below_grid +
  // beside_grid + above_uncounted + escaped, and, independently of the grid, poured = submerged (mixed) +
  // above_surface (unmixed) + escaped (left the domain).
  double poured = 0.0, in_blocks = 0.0, below_grid = 0.0, beside_grid = 0.0, above_uncounted = 0.0;
  double above_surface = 0.0, submerged = 0.0, escaped = 0.0;
  double mixed() const { return submerged; }
  double unmixed() const { return above_surface; }
  double outside_grid() const { return below_grid + beside_grid + above_uncounted; }
  double conservation_error() const;  // max of both balances' |poured - sum of the parts| / poured
  int overfull_blocks = 0;            // blocks whose rock volume exceeded the block volume (DEM overlaps)
  bool from_paste_field = false;      // the paste and the mixed split came from a flow field
};

MixingMap mixing_map(const MixingInputs& in, const ParticleView& particles);

// "M_ijk" for 1-based indices (several digits joined with '_' when a count exceeds 9).
std::string block_name(int i, int j, int k);

}  // namespace pastemix::analysis
