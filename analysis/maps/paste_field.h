// SPDX-License-Identifier: MIT
// The paste field of a `dynamics = "flow"` result, as the mixing maps read it (issue 22).
//
// With a paste that flows, the final surface is no longer flat and paste can be pushed aside or left out of a
// pile's voids, so the maps stop assuming "everything below the flat surface is paste" and read the flow's
// paste fraction alpha (the paste's share of the FLUID volume of a cell, model/flow) instead:
//   surface   the area-mean over the block grid's footprint of each column's paste height, the VOF height
//             function z0 + sum_k alpha_k hz (a column full of paste below and air above gives its interface
//             exactly; rock does not enter, because alpha is a share of the fluid, not of the cell)
//   paste     per block, sum over cells c of alpha_c x (|c n block| - rock volume in c n block): the exact
//             fluid volume of each cell-block piece (sphere_box_volume), never the kernel's smoothed 1 - eps_s,
//             which leaks across 3 cm layers
//   mixed     each rock counts as mixed by the paste share of the fluid around it: the volume-weighted mean
//             of alpha over the cells its sphere overlaps, sum_c alpha_c V(sphere n c) / V(sphere); no
//             threshold, so a rock half in the paste is half mixed
// Read from the result file's /flow group (model/output.h; the flow solver's own files, model/flow/flow_output.h,
// have the same layout with the times in /flow/snapshots/time instead of each group's time_s): the grid
// attributes nx.. origin_z and the snapshot whose time is nearest the particles' snapshot (it must be within half a flow output interval, or
// 1e-9 s when the file has one snapshot).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "analysis/geometry/sphere_box.h"
#include "analysis/maps/block_grid.h"

namespace pastemix {
class H5Reader;
}

namespace pastemix::analysis {

struct PasteField {
  std::array<int, 3> n{};         // cells along x, y, z
  std::array<double, 3> h{};      // m, cell size
  std::array<double, 3> origin{}; // m, the grid's low corner
  std::vector<double> alpha;      // -, paste share of the fluid, [k][j][i] (z slowest), in [0, 1]
  double time_s = 0.0;            // the snapshot's time
  std::string source;             // "file:/flow/snapshots/NNNNNN"
  std::size_t cell(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * n[1] + j) * n[0] + i;
  }
  Box3 cell_box(int i, int j, int k) const;
};

// True when the file has a /flow group with at least one snapshot group.
bool has_paste_field(const H5Reader& h5);

// Reads the field nearest `time_s` (see above). Any defect (a missing attribute, dims that are not the grid's,
// alpha outside [-1e-4, 1 + 1e-4] or not finite, no snapshot near time_s) is an InputError naming `file` and
// the dataset or attribute. Values within 1e-4 of [0, 1] are clamped (the flow's advection overshoots by ~5e-6).
PasteField read_paste_field(const H5Reader& h5, const std::string& file, double time_s);

// The area-mean paste height (m) over the rectangle [x0, x1] x [y0, y1]: each column's height function
// weighted by its area inside the rectangle. InputError (naming the field's source) if the rectangle does
// not overlap the grid.
double paste_surface_z(const PasteField& f, double x0, double x1, double y0, double y1);

// Paste volume (m3) inside the box: sum over cells of alpha_c x (|c n box| - the particles' volume in c n box).
double paste_volume_in(const PasteField& f, const Box3& box, const ParticleView& particles);

// Per particle, the paste share of the fluid around it (see above), in [0, 1]. A particle outside the grid
// (above the field's top, say) has alpha 0 there: it is unmixed.
std::vector<double> paste_share_around(const PasteField& f, const ParticleView& particles);

}  // namespace pastemix::analysis
