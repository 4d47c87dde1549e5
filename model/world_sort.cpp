// SPDX-License-Identifier: MIT
// The spatial sort of the particle store ([neighbor] sort_every, issue 19): World::cell_order and
// World::sort_particles, apart from the step (model/world.cpp).
#include "model/world.h"

#include <algorithm>
#include <array>

namespace pastemix::model {

// The cell order of the particles: a grid over their bounding box with the cells of the finest neighbour
// level (2 r_max + skin, r_max < 2 r_min: 4 r_min + skin), coarsened while it has more than ~4 cells per
// particle (a sparse cloud), cells numbered with the shortest side of the box fastest and the longest
// slowest, particles in a cell by their current index (a counting sort: stable, linear). Why this order:
// the pair pass then sweeps the box along its longest side, and its working set is a few layers of cells
// across the two shorter sides (a 207k-sphere pour: ~4,000 spheres, ~1 MB, inside the L2 cache), where the
// insertion order put a sphere's partners of the next lattice layer 17,280 entries away; and the threads'
// slabs (PairList::partition, cut across the longest side) become contiguous index ranges.
std::vector<std::uint32_t> World::cell_order() const {
  const std::size_t n = p_.size();
  std::vector<std::uint32_t> map(n);
  if (n == 0) return map;
  Vec3 lo = p_.x[0], hi = p_.x[0];
  double rmin = p_.radius[0];
  for (std::size_t a = 0; a < n; ++a) {
    const Vec3& q = p_.x[a];
    lo = {std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z)};
    hi = {std::max(hi.x, q.x), std::max(hi.y, q.y), std::max(hi.z, q.z)};
    rmin = std::min(rmin, p_.radius[a]);
  }
  const std::array<double, 3> ext{hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
  std::array<int, 3> axis{0, 1, 2};  // fastest .. slowest
  std::stable_sort(axis.begin(), axis.end(), [&](int u, int w) { return ext[u] < ext[w]; });
  double cell = 4.0 * rmin + cfg_.skin;
  std::array<long, 3> dim{};
  auto cells = [&] {
    for (int k = 0; k < 3; ++k) dim[k] = static_cast<long>(ext[axis[k]] / cell) + 1;
    return static_cast<double>(dim[0]) * static_cast<double>(dim[1]) * static_cast<double>(dim[2]);
  };
  while (cells() > 4.0 * static_cast<double>(n) + 64.0) cell *= 1.5;
  const double inv = 1.0 / cell;
  auto coord = [](const Vec3& q, int k) { return k == 0 ? q.x : k == 1 ? q.y : q.z; };
  std::vector<std::uint32_t> key(n), start(static_cast<std::size_t>(dim[0] * dim[1] * dim[2]) + 1, 0);
  for (std::size_t a = 0; a < n; ++a) {
    long c[3];
    for (int k = 0; k < 3; ++k)
      c[k] = std::clamp(static_cast<long>((coord(p_.x[a], axis[k]) - coord(lo, axis[k])) * inv), 0L, dim[k] - 1);
    key[a] = static_cast<std::uint32_t>((c[2] * dim[1] + c[1]) * dim[0] + c[0]);
    ++start[key[a] + 1];
  }
  for (std::size_t c = 0; c + 1 < start.size(); ++c) start[c + 1] += start[c];
  for (std::size_t a = 0; a < n; ++a) map[a] = start[key[a]]++;
  return map;
}

void World::sort_particles() {
  const std::vector<std::uint32_t> map = cell_order();
  bool same = true;
  for (std::size_t a = 0; a < map.size() && same; ++a) same = map[a] == a;
  if (same) return;
  const std::size_t n = p_.size();
  p_.apply_map(map, n);
  pairs_.rename(map, n);
  wall_contacts_.rename(map, n);
  for_each_pass(forces_, [&](auto& pass) {
    if constexpr (requires { pass.particles_moved(map); })
      if (pass.active()) pass.particles_moved(map);
  });
  ++profile_.sorts;
}

}  // namespace pastemix::model
