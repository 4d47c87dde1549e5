// SPDX-License-Identifier: MIT
// Neighbour search: Verlet pair list built with a uniform cell grid (counting sort, half of the 27-cell
// stencil via j > i).
//
// Choice and why: the scenes the engine must run today (the LIGGGHTS benchmark pour, 2.5-5 mm; repose-angle
// funnels, <= 8 mm) have size ratios of 2-7, for which one grid with cells of (2 r_max + skin) is the
// fastest and simplest structure: cost per particle ~ 27 cells x (cell volume / particle volume), small.
// At the 42:1 ratio of the ch. 7 pour scenes, one grid sized by the largest particle puts ~(42)^3 / packing
// of the small spheres in a cell, and the search degrades to near O(N^2) around the fines; the planned
// answer is a multi-level grid (one level per size class, each particle inserted in its own level and
// querying the levels at or below its size with the cutoff of the pair), which reuses this counting-sort
// grid per level. It is not built yet (see model/README.md).
//
// The list holds every pair with centre distance < r_i + r_j + skin, so it stays valid until some particle
// has moved more than skin/2; the World rebuilds it then. Built in parallel, the list is the same for any
// thread count (each thread handles a contiguous block of particles; blocks are concatenated in order).
#pragma once

#include <cstdint>
#include <vector>

#include "model/vec3.h"

namespace pastemix::model {

struct CandidatePairs {
  std::vector<std::uint32_t> i, j;  // dense indices, i < j
};

CandidatePairs build_pairs(const std::vector<Vec3>& x, const std::vector<double>& radius, double skin);
// Reference O(N^2) search (tests and PASTEMIX_VALIDATE).
CandidatePairs brute_force_pairs(const std::vector<Vec3>& x, const std::vector<double>& radius, double skin);

}  // namespace pastemix::model
