// SPDX-License-Identifier: MIT
#include "model/neighbor.h"

#include <algorithm>
#include <cmath>

#include <omp.h>

#include "model/parallel.h"

namespace pastemix::model {

namespace {

// Own cell first, then the 13 neighbour cells "after" it in (z, y, x) order.
constexpr long kStencil[14][3] = {{0, 0, 0},   {1, 0, 0},   {-1, 1, 0}, {0, 1, 0},  {1, 1, 0},
                                  {-1, -1, 1}, {0, -1, 1},  {1, -1, 1}, {-1, 0, 1}, {0, 0, 1},
                                  {1, 0, 1},   {-1, 1, 1},  {0, 1, 1},  {1, 1, 1}};

}  // namespace

namespace {

// One grid level: the particles whose radius falls in one size class, counting-sorted into cells of
// 2 r_max(level) + skin.
struct Level {
  double rmax = 0.0, cell = 0.0, inv = 0.0;
  long dim[3] = {1, 1, 1};
  std::vector<std::uint32_t> start, sorted;
  // Positions and radii in cell order: the search scans them contiguously (the same pairs in the same order
  // as through `sorted`, fewer cache misses).
  std::vector<Vec3> xs;
  std::vector<double> rs;

  long clamp_cell(double v, int axis) const {
    return std::clamp(static_cast<long>(std::floor(v * inv)), 0L, dim[axis] - 1);
  }
  std::size_t index(long cx, long cy, long cz) const {
    return static_cast<std::size_t>((cz * dim[1] + cy) * dim[0] + cx);
  }
};

}  // namespace

CandidatePairs build_pairs(const std::vector<Vec3>& x, const std::vector<double>& radius, double skin) {
  CandidatePairs out;
  const std::size_t n = x.size();
  if (n < 2) return out;
  Vec3 lo = x[0], hi = x[0];
  double rmin = radius[0];
  for (std::size_t k = 0; k < n; ++k) {
    lo = {std::min(lo.x, x[k].x), std::min(lo.y, x[k].y), std::min(lo.z, x[k].z)};
    hi = {std::max(hi.x, x[k].x), std::max(hi.y, x[k].y), std::max(hi.z, x[k].z)};
    rmin = std::min(rmin, radius[k]);
  }
  // Size classes of a factor 2 in radius: level = floor(log2(r / r_min)). One level for ratios < 2.
  std::vector<int> level_of(n);
  int nlev = 1;
  for (std::size_t k = 0; k < n; ++k) {
    level_of[k] = std::min(30, static_cast<int>(std::floor(std::log2(radius[k] / rmin))));
    nlev = std::max(nlev, level_of[k] + 1);
  }
  std::vector<Level> lev(static_cast<std::size_t>(nlev));
  std::vector<std::size_t> count(static_cast<std::size_t>(nlev), 0);
  for (std::size_t k = 0; k < n; ++k) {
    Level& L = lev[static_cast<std::size_t>(level_of[k])];
    L.rmax = std::max(L.rmax, radius[k]);
    ++count[static_cast<std::size_t>(level_of[k])];
  }
  std::vector<std::uint32_t> cell_id(n);
  for (int l = 0; l < nlev; ++l) {
    Level& L = lev[static_cast<std::size_t>(l)];
    if (count[static_cast<std::size_t>(l)] == 0) continue;
    L.cell = 2.0 * L.rmax + skin;
    // A sparse cloud must not allocate a huge grid: grow the cells until there are at most ~4 per particle.
    auto cells = [&](double c) {
      L.dim[0] = static_cast<long>((hi.x - lo.x) / c) + 1;
      L.dim[1] = static_cast<long>((hi.y - lo.y) / c) + 1;
      L.dim[2] = static_cast<long>((hi.z - lo.z) / c) + 1;
      return static_cast<double>(L.dim[0]) * static_cast<double>(L.dim[1]) * static_cast<double>(L.dim[2]);
    };
    while (cells(L.cell) > 4.0 * static_cast<double>(count[static_cast<std::size_t>(l)]) + 64.0) L.cell *= 1.5;
    L.inv = 1.0 / L.cell;
    L.start.assign(static_cast<std::size_t>(L.dim[0] * L.dim[1] * L.dim[2]) + 1, 0);
  }
  // Counting sort per level (stable: ascending index inside a cell).
  for (std::size_t k = 0; k < n; ++k) {
    Level& L = lev[static_cast<std::size_t>(level_of[k])];
    cell_id[k] = static_cast<std::uint32_t>(L.index(L.clamp_cell(x[k].x - lo.x, 0), L.clamp_cell(x[k].y - lo.y, 1),
                                                    L.clamp_cell(x[k].z - lo.z, 2)));
    ++L.start[cell_id[k] + 1];
  }
  for (int l = 0; l < nlev; ++l) {
    Level& L = lev[static_cast<std::size_t>(l)];
    if (count[static_cast<std::size_t>(l)] == 0) continue;
    for (std::size_t c = 0; c + 1 < L.start.size(); ++c) L.start[c + 1] += L.start[c];
    L.sorted.resize(count[static_cast<std::size_t>(l)]);
  }
  {
    std::vector<std::vector<std::uint32_t>> fill(static_cast<std::size_t>(nlev));
    for (int l = 0; l < nlev; ++l)
      if (!lev[static_cast<std::size_t>(l)].start.empty())
        fill[static_cast<std::size_t>(l)].assign(lev[static_cast<std::size_t>(l)].start.begin(),
                                                 lev[static_cast<std::size_t>(l)].start.end() - 1);
    for (std::size_t k = 0; k < n; ++k) {
      const auto l = static_cast<std::size_t>(level_of[k]);
      lev[l].sorted[fill[l][cell_id[k]]++] = static_cast<std::uint32_t>(k);
    }
    for (Level& L : lev) {
      L.xs.resize(L.sorted.size());
      L.rs.resize(L.sorted.size());
      for (std::size_t s = 0; s < L.sorted.size(); ++s) {
        L.xs[s] = x[L.sorted[s]];
        L.rs[s] = radius[L.sorted[s]];
      }
    }
  }

  const int nthreads = static_cast<long>(n) >= parallel_min_items ? omp_get_max_threads() : 1;
  std::vector<CandidatePairs> local(static_cast<std::size_t>(nthreads));
#pragma omp parallel num_threads(nthreads)
  {
    CandidatePairs& mine = local[static_cast<std::size_t>(omp_get_thread_num())];
    auto test = [&](std::size_t a, const Vec3& xa, const Level& L, std::uint32_t s, double ra) {
      const std::uint32_t b = L.sorted[s];
      const double cut = ra + L.rs[s];
      if (norm2(L.xs[s] - xa) < cut * cut) {
        mine.i.push_back(static_cast<std::uint32_t>(std::min<std::size_t>(a, b)));
        mine.j.push_back(static_cast<std::uint32_t>(std::max<std::size_t>(a, b)));
      }
    };
#pragma omp for schedule(static)
    for (std::size_t a = 0; a < n; ++a) {
      const int la = level_of[a];
      const double ra = radius[a] + skin;
      const Vec3 xa = x[a];
      const Vec3 rel = xa - lo;
      // Own level: half stencil (own cell with higher indices, then the 13 "forward" cells); each pair
      // of the level is found once.
      {
        const Level& L = lev[static_cast<std::size_t>(la)];
        const long c0 = L.clamp_cell(rel.x, 0), c1 = L.clamp_cell(rel.y, 1), c2 = L.clamp_cell(rel.z, 2);
        for (int o = 0; o < 14; ++o) {
          const long cx = c0 + kStencil[o][0], cy = c1 + kStencil[o][1], cz = c2 + kStencil[o][2];
          if (cx < 0 || cx >= L.dim[0] || cy < 0 || cy >= L.dim[1] || cz < 0 || cz >= L.dim[2]) continue;
          const std::size_t cc = L.index(cx, cy, cz);
          for (std::uint32_t s = L.start[cc]; s < L.start[cc + 1]; ++s) {
            if (o == 0 && L.sorted[s] <= a) continue;
            test(a, xa, L, s, ra);
          }
        }
      }
      // Finer levels: every cell within the pair cutoff (a larger sphere finds each smaller partner once).
      for (int lb = 0; lb < la; ++lb) {
        const Level& L = lev[static_cast<std::size_t>(lb)];
        if (L.sorted.empty()) continue;
        const double reach = ra + L.rmax;
        const long x0 = L.clamp_cell(rel.x - reach, 0), x1 = L.clamp_cell(rel.x + reach, 0);
        const long y0 = L.clamp_cell(rel.y - reach, 1), y1 = L.clamp_cell(rel.y + reach, 1);
        const long z0 = L.clamp_cell(rel.z - reach, 2), z1 = L.clamp_cell(rel.z + reach, 2);
        for (long cz = z0; cz <= z1; ++cz)
          for (long cy = y0; cy <= y1; ++cy)
            for (long cx = x0; cx <= x1; ++cx) {
              const std::size_t cc = L.index(cx, cy, cz);
              for (std::uint32_t s = L.start[cc]; s < L.start[cc + 1]; ++s) test(a, xa, L, s, ra);
            }
      }
    }
  }
  for (const auto& l : local) {
    out.i.insert(out.i.end(), l.i.begin(), l.i.end());
    out.j.insert(out.j.end(), l.j.begin(), l.j.end());
  }
  return out;
}

CandidatePairs brute_force_pairs(const std::vector<Vec3>& x, const std::vector<double>& radius, double skin) {
  CandidatePairs out;
  for (std::size_t a = 0; a < x.size(); ++a)
    for (std::size_t b = a + 1; b < x.size(); ++b) {
      const double cut = radius[a] + radius[b] + skin;
      if (norm2(x[b] - x[a]) < cut * cut) {
        out.i.push_back(static_cast<std::uint32_t>(a));
        out.j.push_back(static_cast<std::uint32_t>(b));
      }
    }
  return out;
}

}  // namespace pastemix::model
