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

CandidatePairs build_pairs(const std::vector<Vec3>& x, const std::vector<double>& radius, double skin) {
  CandidatePairs out;
  const std::size_t n = x.size();
  if (n < 2) return out;
  Vec3 lo = x[0], hi = x[0];
  double rmax = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    lo = {std::min(lo.x, x[k].x), std::min(lo.y, x[k].y), std::min(lo.z, x[k].z)};
    hi = {std::max(hi.x, x[k].x), std::max(hi.y, x[k].y), std::max(hi.z, x[k].z)};
    rmax = std::max(rmax, radius[k]);
  }
  double cell = 2.0 * rmax + skin;
  // A sparse cloud (particles flying apart) must not allocate a huge grid: grow the cells until the grid
  // has at most ~4 cells per particle.
  auto count = [&](double c, long* d) {
    d[0] = static_cast<long>((hi.x - lo.x) / c) + 1;
    d[1] = static_cast<long>((hi.y - lo.y) / c) + 1;
    d[2] = static_cast<long>((hi.z - lo.z) / c) + 1;
    return static_cast<double>(d[0]) * static_cast<double>(d[1]) * static_cast<double>(d[2]);
  };
  long dim[3];
  while (count(cell, dim) > 4.0 * static_cast<double>(n) + 64.0) cell *= 1.5;
  const double inv = 1.0 / cell;
  auto cell_of = [&](const Vec3& p, long* c) {
    c[0] = std::min(static_cast<long>((p.x - lo.x) * inv), dim[0] - 1);
    c[1] = std::min(static_cast<long>((p.y - lo.y) * inv), dim[1] - 1);
    c[2] = std::min(static_cast<long>((p.z - lo.z) * inv), dim[2] - 1);
  };
  const std::size_t ncell = static_cast<std::size_t>(dim[0] * dim[1] * dim[2]);
  // Counting sort of particle indices by cell (stable: ascending index inside a cell).
  std::vector<std::uint32_t> start(ncell + 1, 0), sorted(n), cell_id(n);
  for (std::size_t k = 0; k < n; ++k) {
    long c[3];
    cell_of(x[k], c);
    cell_id[k] = static_cast<std::uint32_t>((c[2] * dim[1] + c[1]) * dim[0] + c[0]);
    ++start[cell_id[k] + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) start[c + 1] += start[c];
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < n; ++k) sorted[fill[cell_id[k]]++] = static_cast<std::uint32_t>(k);
  }

  const int nthreads = static_cast<long>(n) >= parallel_min_items ? omp_get_max_threads() : 1;
  std::vector<CandidatePairs> local(static_cast<std::size_t>(nthreads));
#pragma omp parallel num_threads(nthreads)
  {
    CandidatePairs& mine = local[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(static)
    for (std::size_t a = 0; a < n; ++a) {
      long c[3];
      cell_of(x[a], c);
      const double ra = radius[a] + skin;
      // Half stencil: the own cell (partners of higher index) and the 13 "forward" neighbour cells (all
      // partners); each pair is found once. Pairs are stored as (lower index, higher index).
      for (int o = 0; o < 14; ++o) {
        const long cx = c[0] + kStencil[o][0], cy = c[1] + kStencil[o][1], cz = c[2] + kStencil[o][2];
        if (cx < 0 || cx >= dim[0] || cy < 0 || cy >= dim[1] || cz < 0 || cz >= dim[2]) continue;
        const std::size_t cc = static_cast<std::size_t>((cz * dim[1] + cy) * dim[0] + cx);
        for (std::uint32_t s = start[cc]; s < start[cc + 1]; ++s) {
          const std::uint32_t b = sorted[s];
          if (o == 0 && b <= a) continue;
          const double cut = ra + radius[b];
          if (norm2(x[b] - x[a]) < cut * cut) {
            mine.i.push_back(static_cast<std::uint32_t>(std::min<std::size_t>(a, b)));
            mine.j.push_back(static_cast<std::uint32_t>(std::max<std::size_t>(a, b)));
          }
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
