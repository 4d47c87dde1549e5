// SPDX-License-Identifier: MIT
// The lab's cut-block grid and the rock/paste masses a simulation puts in each block.
//
// The lab cut the hardened box into layers measured from the top of the mixture down (layer 1 = top), each
// layer into blocks; we measure depth from the FINAL free surface of the paste, which has risen by the
// volume of the rock that entered it. Rock mass goes into blocks by the exact volume of each sphere inside
// each block (sphere_box_volume), never by its centre.
//
// Rock above the surface (the unmixed cone). With `top_open` (the default), layer 1 reaches up without limit:
// rock above the surface counts in the layer-1 block under it, as in the lab, which cut the hardened
// specimen from its top and so put the unmixed cone into layer 1: the lab's 36 blocks hold 0.85-1.02 kg of
// the 1 kg poured (case 3: 1.0154 kg, 0.983 kg of it in layer 1, M_221 and M_321 all rock and no paste),
// which is only possible if the cone was cut with layer 1. With `top_open = false` rock above the surface
// is in no block (a strictly "submerged only" map). Either way it is UNMIXED rock (`above_surface`), and a
// block's paste is only what lies below the surface.
//
// Accounting (every rock's volume lands in exactly one of these, so they add up to the poured mass):
//   blocks          the part inside a grid block (inside the grid's footprint and depth; with top_open,
//                   layer 1 includes everything above the surface over its footprint);
//   above_uncounted above the final free surface and in no block (beside the footprint; all of it when the
//                   top is closed);
//   below_grid      below the surface, inside the footprint, deeper than the last layer;
//   beside_grid     below the surface but outside the grid's footprint (e.g. between grid and wall).
// Independently of the grid: above_surface (unmixed) + submerged (mixed) = total.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "base/vec3.h"

namespace pastemix::analysis {

// Named BlockLayout (not BlockGrid) because lab::BlockGrid is a case's measured grid; this is only geometry.
struct BlockLayout {
  std::array<double, 2> origin{0.0, 0.0};  // m, (x, y) of the grid corner with i = 1, j = 1
  std::array<int, 2> count{4, 3};           // blocks along x (i) and y (j)
  std::array<double, 2> size{0.05, 0.055};  // m, block size along x and y
  int layers = 3;                           // k = 1 (top) ... layers
  double layer_thickness = 0.03;            // m
  bool top_open = true;                     // rock above the surface counts in layer 1 (see above)
  std::size_t block_count() const { return static_cast<std::size_t>(count[0] * count[1] * layers); }
  // Flat index of block M_ijk, all 1-based (k = 1 the top layer), row-major [i][j][k]: the same order as
  // lab::block_index, so a model grid and a lab grid of the default layout index identically.
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(((i - 1) * count[1] + (j - 1)) * layers + (k - 1));
  }
};

// Particles as read from a result file: centres (m), radii (m), densities (kg/m3).
struct ParticleView {
  std::span<const Vec3> position;
  std::span<const double> radius;
  std::span<const double> density;
};

struct BlockMasses {
  std::vector<double> rock_mass;    // kg per block
  std::vector<double> rock_volume;  // m3 per block (with top_open, layer 1 includes rock above the surface)
  std::vector<double> rock_volume_submerged;  // m3 per block, the part below the surface (displaces paste)
  std::vector<double> block_volume; // m3 per block below the surface (all of it, the grid is below it)
  double in_blocks = 0.0;           // kg, sum of rock_mass
  double above_uncounted = 0.0;     // kg, above the surface and in no block
  double above_surface = 0.0;       // kg, all rock above the surface (unmixed), whatever its x, y
  double submerged = 0.0;           // kg, all rock below the surface (mixed)
  double below_grid = 0.0;          // kg
  double beside_grid = 0.0;         // kg
  double total = 0.0;               // kg, sum of all particle masses
};

// Distributes rock mass over the grid whose top is at `surface_z` (m, the final free surface).
BlockMasses rock_in_blocks(const BlockLayout& grid, double surface_z, const ParticleView& particles);

}  // namespace pastemix::analysis
