// SPDX-License-Identifier: MIT
#include "model/insert/fill.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "base/rng.h"

namespace pastemix::model {

bool FillRegion::contains(const Vec3& p, double r) const {
  switch (shape) {
    case box:
      return p.x - r >= lo.x && p.x + r <= hi.x && p.y - r >= lo.y && p.y + r <= hi.y && p.z - r >= lo.z &&
             p.z + r <= hi.z;
    case cylinder:
    case frustum: {
      if (p.z - r < z_min || p.z + r > z_max) return false;
      const double rho = std::hypot(p.x - cx, p.y - cy);
      // Conservative for a frustum: the smaller radius over the sphere's height range.
      const double s0 = (p.z - r - z_min) / (z_max - z_min), s1 = (p.z + r - z_min) / (z_max - z_min);
      const double R = std::min(r_bottom + s0 * (r_top - r_bottom), r_bottom + s1 * (r_top - r_bottom));
      return rho + r <= R;
    }
  }
  return false;
}

void FillRegion::bounds(Vec3* a, Vec3* b) const {
  if (shape == box) {
    *a = lo;
    *b = hi;
    return;
  }
  const double R = std::max(r_bottom, r_top);
  *a = {cx - R, cy - R, z_min};
  *b = {cx + R, cy + R, z_max};
}

namespace {

struct Grid {
  double cell;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> cells;
  std::int64_t key(long i, long j, long k) const {
    return (static_cast<std::int64_t>(i) * 73856093) ^ (static_cast<std::int64_t>(j) * 19349663) ^
           (static_cast<std::int64_t>(k) * 83492791);
  }
  long idx(double v) const { return static_cast<long>(std::floor(v / cell)); }
};

}  // namespace

FillResult fill_region(const FillRegion& region, const std::vector<double>& radii,
                       const std::vector<Vec3>& existing_x, const std::vector<double>& existing_r,
                       const std::vector<Wall>& walls, std::uint64_t seed, int max_attempts) {
  FillResult out;
  out.positions.assign(radii.size(), Vec3{});
  std::vector<std::size_t> order(radii.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return radii[a] > radii[b]; });

  double rmax = 0.0;
  for (double r : radii) rmax = std::max(rmax, r);
  for (double r : existing_r) rmax = std::max(rmax, r);
  Grid grid{2.0 * std::max(rmax, 1e-9), {}};
  std::vector<Vec3> xs = existing_x;
  std::vector<double> rs = existing_r;
  auto insert = [&](std::uint32_t k) {
    grid.cells[grid.key(grid.idx(xs[k].x), grid.idx(xs[k].y), grid.idx(xs[k].z))].push_back(k);
  };
  for (std::uint32_t k = 0; k < xs.size(); ++k) insert(k);
  auto free_spot = [&](const Vec3& p, double r) {
    const long ci = grid.idx(p.x), cj = grid.idx(p.y), ck = grid.idx(p.z);
    for (long i = ci - 1; i <= ci + 1; ++i)
      for (long j = cj - 1; j <= cj + 1; ++j)
        for (long k = ck - 1; k <= ck + 1; ++k) {
          auto it = grid.cells.find(grid.key(i, j, k));
          if (it == grid.cells.end()) continue;
          for (std::uint32_t q : it->second) {
            const double s = r + rs[q];
            if (norm2(xs[q] - p) < s * s) return false;
          }
        }
    for (const Wall& w : walls) {
      Vec3 n;
      if (wall_distance(w, Vec3{}, p, &n) < r) return false;
    }
    return true;
  };

  Rng rng(seed);
  Vec3 lo, hi;
  region.bounds(&lo, &hi);
  for (std::size_t idx : order) {
    const double r = radii[idx];
    bool ok = false;
    for (int attempt = 0; attempt < max_attempts && !ok; ++attempt) {
      const Vec3 p{rng.uniform(lo.x + r, hi.x - r), rng.uniform(lo.y + r, hi.y - r), rng.uniform(lo.z + r, hi.z - r)};
      if (!region.contains(p, r) || !free_spot(p, r)) continue;
      out.positions[idx] = p;
      xs.push_back(p);
      rs.push_back(r);
      insert(static_cast<std::uint32_t>(xs.size() - 1));
      ok = true;
    }
    if (!ok) return out;
    ++out.placed;
  }
  out.complete = true;
  return out;
}

}  // namespace pastemix::model
