// SPDX-License-Identifier: MIT
// Neighbour search: Verlet pair list built with a multi-level cell grid (counting sort per level).
//
// Choice and why: one grid with cells of 2 r_max + skin is the fastest structure when sizes are similar
// (the benchmark pour, 2.5-5 mm), but at the 42:1 ratio of the ch. 7 pours (1.18-50 mm) cells sized by the
// 50 mm rock hold hundreds of fines and every fine scans 27 of them. So particles are split into size
// classes of a factor 2 in radius (level = floor(log2(r / r_min))), each with its own grid of 2 r_max(level)
// + skin. A particle searches its own level with the half stencil (own cell, higher indices; 13 forward
// cells) and every finer level over the cells within its pair cutoff, so each pair is found once, by the
// larger sphere. For ratios below 2 this is exactly the single-grid search. Measured (1 thread, 150 spheres
// of 50 mm among 60,000 of 1.18-2 mm, skin 0.3 mm): 0.03-0.05 s per build against 2.7 s for one grid.
//
// The list holds every pair with centre distance < r_i + r_j + skin, stored as (lower index, higher
// index), so it stays valid until some particle has moved more than skin/2; the World rebuilds it then.
// Built in parallel, the list is the same for any thread count: the finder particles are taken in chunks
// (any thread), each chunk writes its own buffer, and the buffers are concatenated in chunk order.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "model/parallel.h"
#include "model/vec3.h"

namespace pastemix::model {

struct CandidatePairs {
  std::vector<std::uint32_t> i, j;  // dense indices, i < j
};

// The search with its buffers, kept between builds: a rebuild every few steps (a pour: every ~8) then
// allocates nothing.
class NeighborSearch {
 public:
  // Replaces `out` by the pairs of x / radius closer than r_i + r_j + skin.
  // threads: of its loops (model/parallel.h; 1 for a small list); the pairs do not depend on it.
  void build(const std::vector<Vec3>& x, const std::vector<double>& radius, double skin, CandidatePairs& out,
             int threads);
  // The same, run by every thread of a team inside its parallel region (model/parallel.h); `out` is
  // complete after the team's next sync. side: other work shared by the whole team (a Team that must not
  // sync: each thread its range) after the particles are sorted into the grids, before the search; not run
  // by a one-thread team.
  void build(const std::vector<Vec3>& x, const std::vector<double>& radius, double skin, CandidatePairs& out,
             const Team& team, const std::function<void(const Team&)>& side = {});

  // One grid level: the particles whose radius falls in one size class, counting-sorted into cells of
  // 2 r_max(level) + skin.
  struct Level {
    double rmax = 0.0, cell = 0.0, inv = 0.0;
    long dim[3] = {1, 1, 1};
    std::size_t count = 0;
    std::vector<std::uint32_t> start, sorted;
    // Positions (one array per axis) and radii in cell order: the search scans them contiguously (the same
    // pairs in the same order as through `sorted`, fewer cache misses), several candidates per instruction.
    std::vector<double> xs, ys, zs, rs;
    std::size_t first = 0;  // its first cell in the counting sort's arrays of all levels' cells (count_)
    long clamp_cell(double v, int axis) const;
    std::size_t index(long cx, long cy, long cz) const {
      return static_cast<std::size_t>((cz * dim[1] + cy) * dim[0] + cx);
    }
  };
  // The grid levels of the last build (tests: their cell sizes).
  const std::vector<Level>& levels() const { return lev_; }
  // The bounding box (min xyz, max xyz) of the last build's positions (any number of them; std::min and
  // std::max from x[0], as a serial loop over them gives it).
  const std::array<double, 6>& box() const { return boxes_[0]; }

 private:
  struct Chunk {
    std::vector<std::uint32_t> i, j;  // capacity only grows; `n` entries are valid
    std::size_t n = 0;
  };
  std::vector<Level> lev_;
  std::vector<double> radius_;  // the radii level_of_ was computed for
  int nlev_ = 1;
  std::vector<int> level_of_;
  std::vector<std::uint32_t> cell_id_, slot_;  // slot_[k]: k's position in its level's `sorted`
  std::vector<Chunk> chunks_;
  std::vector<std::size_t> offset_;
  std::vector<std::array<double, 6>> boxes_;  // per thread: the bounding box (min xyz, max xyz) of its share
  WorkQueue queue_;                           // the search's chunks among the team

  std::size_t cells_ = 0;                          // all levels' cells
  std::vector<std::vector<std::uint32_t>> count_;  // per thread and cell: its particles, then its cursor
  std::vector<std::uint64_t> range_sums_;          // per thread: the particles counted in its range of cells
  void set_up(const std::vector<Vec3>& x, const std::vector<double>& radius, double skin, int threads);
  void count_cells(const std::vector<Vec3>& x, int me, long k0, long k1);
  std::uint64_t cell_sum(int threads, long g0, long g1) const;
  void place_cells(int threads, long g0, long g1, std::uint64_t base);
  void fill_cells(const std::vector<Vec3>& x, const std::vector<double>& radius, int me, long k0, long k1);
  void search_chunk(std::size_t c, const std::vector<Vec3>& x, const std::vector<double>& radius, double skin,
                    const Vec3& lo);
};

namespace detail {
// Candidates s0 .. s1 of a level (positions xs, ys, zs, radii rs, particle ids `sorted`, in cell order)
// against particle a at xa with radius + skin ra: every pair closer than ra + r_s is written as (min, max)
// to pi[m], pj[m], ... in scan order; returns the new m. pi and pj need room for m + (s1 - s0) + 8
// entries. The test is dx^2 + dy^2 + dz^2 < (ra + r_s)^2, operations in that order, in both versions:
// scan_candidates is eight candidates per instruction where the engine is built for AVX-512, else the
// scalar loop; both give the same pairs in the same order (tests/model/neighbor_test.cpp).
std::size_t scan_candidates(const double* xs, const double* ys, const double* zs, const double* rs,
                            const std::uint32_t* sorted, std::uint32_t s0, std::uint32_t s1, std::uint32_t a,
                            const Vec3& xa, double ra, std::uint32_t* pi, std::uint32_t* pj, std::size_t m);
std::size_t scan_candidates_scalar(const double* xs, const double* ys, const double* zs, const double* rs,
                                   const std::uint32_t* sorted, std::uint32_t s0, std::uint32_t s1,
                                   std::uint32_t a, const Vec3& xa, double ra, std::uint32_t* pi,
                                   std::uint32_t* pj, std::size_t m);
// Whether scan_candidates is the vector version.
bool scan_is_vectorized();
}  // namespace detail

CandidatePairs build_pairs(const std::vector<Vec3>& x, const std::vector<double>& radius, double skin);
// Reference O(N^2) search (tests and PASTEMIX_VALIDATE).
CandidatePairs brute_force_pairs(const std::vector<Vec3>& x, const std::vector<double>& radius, double skin);

}  // namespace pastemix::model
