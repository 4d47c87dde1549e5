// SPDX-License-Identifier: MIT
// Insertion: place spheres of given radii in a region without overlaps (random sequential addition).
//
// Radii are placed largest first (small spheres then fill the gaps), each at uniformly random positions
// from a seeded Rng until one overlaps neither an already placed sphere (hash grid) nor a wall. This fills
// loosely (up to ~30-35 % solids); a region too small for the mass fails with the number placed, rather
// than overlapping or silently dropping particles.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "model/vec3.h"
#include "model/walls.h"

namespace pastemix::model {

struct FillRegion {
  enum Shape { box, cylinder, frustum } shape = box;
  Vec3 lo, hi;                    // box: corners (m)
  double cx = 0, cy = 0;          // cylinder / frustum: axis (m)
  double z_min = 0, z_max = 0;    // cylinder / frustum: height range (m)
  double r_bottom = 0, r_top = 0; // cylinder: both = radius; frustum: radius at z_min and z_max (m)

  // Whether a sphere of radius r centred at p lies inside the region.
  bool contains(const Vec3& p, double r) const;
  void bounds(Vec3* lo_out, Vec3* hi_out) const;
};

// Positions for `radii` (m) in `region`, avoiding `existing` spheres (positions + radii) and the walls;
// returns nullopt and the count placed if some sphere found no free spot in `max_attempts` tries.
struct FillResult {
  std::vector<Vec3> positions;  // same order as radii
  std::size_t placed = 0;
  bool complete = false;
};
FillResult fill_region(const FillRegion& region, const std::vector<double>& radii,
                       const std::vector<Vec3>& existing_x, const std::vector<double>& existing_r,
                       const std::vector<Wall>& walls, std::uint64_t seed, int max_attempts = 5000);

}  // namespace pastemix::model
