// SPDX-License-Identifier: MIT
#include "model/neighbor.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>

#include <omp.h>
#if defined(__AVX512F__) && defined(__AVX512VL__)
#include <immintrin.h>
#endif
#include "model/simd_avx2.h"

#include "model/parallel.h"

namespace pastemix::model {

namespace {

constexpr std::size_t kFinders = 256;  // finder particles per chunk of the search
constexpr std::size_t kSlack = 8;       // entries a scan may write past its last pair (a whole vector store)
// Most cells a level's grid may have per particle before its cells grow (a sparse cloud must not allocate
// a huge grid). A pour from a funnel spreads its spheres over a tall, mostly empty box: chapter-7 test 1's
// 65k spheres span up to 18 cells of 2 r_max + skin each, and at the former 4 per particle the cells grew
// 2.25x (11x the volume a finder scans; the search was 16 % of test 2's run). A grid costs ~1 ns a cell per
// rebuild (its count array zeroed and summed), a scanned candidate about half that.
constexpr double kCellsPerParticle = 32.0;

}  // namespace

namespace detail {

std::size_t scan_candidates_scalar(const double* xs, const double* ys, const double* zs, const double* rs,
                                   const std::uint32_t* sorted, std::uint32_t s0, std::uint32_t s1,
                                   std::uint32_t a, const Vec3& xa, double ra, std::uint32_t* pi,
                                   std::uint32_t* pj, std::size_t m) {
  // Branch-free: every candidate is written, the count advances on a hit.
  for (std::uint32_t s = s0; s < s1; ++s) {
    const std::uint32_t b = sorted[s];
    const double cut = ra + rs[s];
    const double dx = xs[s] - xa.x, dy = ys[s] - xa.y, dz = zs[s] - xa.z;
    const bool hit = dx * dx + dy * dy + dz * dz < cut * cut;
    pi[m] = std::min(a, b);
    pj[m] = std::max(a, b);
    m += hit;
  }
  return m;
}

#if defined(__AVX512F__) && defined(__AVX512VL__)
// Eight candidates per instruction, the hits packed by a compress (a pour's finder scans ~5 rows of ~10
// candidates, a third of them hits; the scalar loop's per-candidate work was ~60 % of the search).
std::size_t scan_candidates(const double* xs, const double* ys, const double* zs, const double* rs,
                            const std::uint32_t* sorted, std::uint32_t s0, std::uint32_t s1, std::uint32_t a,
                            const Vec3& xa, double ra, std::uint32_t* pi, std::uint32_t* pj, std::size_t m) {
  const __m512d ax = _mm512_set1_pd(xa.x), ay = _mm512_set1_pd(xa.y), az = _mm512_set1_pd(xa.z);
  const __m512d rav = _mm512_set1_pd(ra);
  const __m256i av = _mm256_set1_epi32(static_cast<int>(a));
  for (std::uint32_t s = s0; s < s1; s += 8) {
    const __mmask8 live = s1 - s >= 8 ? __mmask8(0xff) : static_cast<__mmask8>((1u << (s1 - s)) - 1u);
    const __m512d dx = _mm512_sub_pd(_mm512_maskz_loadu_pd(live, xs + s), ax);
    const __m512d dy = _mm512_sub_pd(_mm512_maskz_loadu_pd(live, ys + s), ay);
    const __m512d dz = _mm512_sub_pd(_mm512_maskz_loadu_pd(live, zs + s), az);
    const __m512d cut = _mm512_add_pd(rav, _mm512_maskz_loadu_pd(live, rs + s));
    const __m512d d2 =
        _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)), _mm512_mul_pd(dz, dz));
    const __mmask8 hit = _mm512_mask_cmp_pd_mask(live, d2, _mm512_mul_pd(cut, cut), _CMP_LT_OQ);
    const __m256i b = _mm256_maskz_loadu_epi32(live, sorted + s);
    // Compressed in a register and stored whole (a compress straight to memory is microcoded and slow on
    // some CPUs); the caller's buffers have kSlack entries of slack.
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(pi + m),
                        _mm256_maskz_compress_epi32(hit, _mm256_min_epu32(av, b)));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(pj + m),
                        _mm256_maskz_compress_epi32(hit, _mm256_max_epu32(av, b)));
    m += static_cast<std::size_t>(__builtin_popcount(hit));
  }
  return m;
}
bool scan_is_vectorized() { return true; }
#elif defined(PASTEMIX_AVX2_LANES)
// Four candidates per instruction (AVX2 alone, model/simd_avx2.h): the AVX-512 scan's operations, the tail
// by masked loads, the hits packed by a table's permute.
std::size_t scan_candidates(const double* xs, const double* ys, const double* zs, const double* rs,
                            const std::uint32_t* sorted, std::uint32_t s0, std::uint32_t s1, std::uint32_t a,
                            const Vec3& xa, double ra, std::uint32_t* pi, std::uint32_t* pj, std::size_t m) {
  const __m256d ax = _mm256_set1_pd(xa.x), ay = _mm256_set1_pd(xa.y), az = _mm256_set1_pd(xa.z);
  const __m256d rav = _mm256_set1_pd(ra);
  const __m128i av = _mm_set1_epi32(static_cast<int>(a));
  const __m128i lane = _mm_setr_epi32(0, 1, 2, 3);
  for (std::uint32_t s = s0; s < s1; s += 4) {
    const std::uint32_t left = s1 - s;
    const __m128i live32 = _mm_cmpgt_epi32(_mm_set1_epi32(static_cast<int>(std::min(left, 4u))), lane);
    const __m256i live = _mm256_cvtepi32_epi64(live32);  // all ones in the live lanes
    const __m256d dx = _mm256_sub_pd(_mm256_maskload_pd(xs + s, live), ax);
    const __m256d dy = _mm256_sub_pd(_mm256_maskload_pd(ys + s, live), ay);
    const __m256d dz = _mm256_sub_pd(_mm256_maskload_pd(zs + s, live), az);
    const __m256d cut = _mm256_add_pd(rav, _mm256_maskload_pd(rs + s, live));
    const __m256d d2 = avx2::norm2(dx, dy, dz);
    const unsigned hit = static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(d2, _mm256_mul_pd(cut, cut), _CMP_LT_OQ))) &
                         static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(live32)));
    const __m128i b = _mm_maskload_epi32(reinterpret_cast<const int*>(sorted + s), live32);
    // Stored whole: the caller's buffers have kSlack entries of slack.
    _mm_storeu_si128(reinterpret_cast<__m128i*>(pi + m), avx2::compress_epi32(hit, _mm_min_epu32(av, b)));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(pj + m), avx2::compress_epi32(hit, _mm_max_epu32(av, b)));
    m += static_cast<std::size_t>(__builtin_popcount(hit));
  }
  return m;
}
bool scan_is_vectorized() { return true; }
#else
std::size_t scan_candidates(const double* xs, const double* ys, const double* zs, const double* rs,
                            const std::uint32_t* sorted, std::uint32_t s0, std::uint32_t s1, std::uint32_t a,
                            const Vec3& xa, double ra, std::uint32_t* pi, std::uint32_t* pj, std::size_t m) {
  return scan_candidates_scalar(xs, ys, zs, rs, sorted, s0, s1, a, xa, ra, pi, pj, m);
}
bool scan_is_vectorized() { return false; }
#endif

}  // namespace detail

long NeighborSearch::Level::clamp_cell(double v, int axis) const {
  // Clamped in double, then converted: a cell for any v (NaN: 0), and a form the compiler vectorises in
  // count_cells's loop over the particles (a clamp of the converted long it did not vectorise).
  return static_cast<long>(std::min(std::max(0.0, std::floor(v * inv)), static_cast<double>(dim[axis] - 1)));
}

void NeighborSearch::build(const std::vector<Vec3>& x, const std::vector<double>& radius, double skin,
                           CandidatePairs& out, int threads) {
  YieldBarrier barrier;
  run_team(threads, barrier, [&](const Team& t) { build(x, radius, skin, out, t); });
}

void NeighborSearch::build(const std::vector<Vec3>& x, const std::vector<double>& radius, double skin,
                           CandidatePairs& out, const Team& t, const std::function<void(const Team&)>& side) {
  const std::size_t n = x.size();
  if (n < 2) {
    if (t.me == 0) out.i.clear(), out.j.clear();
    if (side && t.size > 1) side(Team{t.me, t.size, nullptr});
    return;
  }
  // Ten phases, nine syncs of the team (no libgomp region or barrier: on this 2-core VM a sleeping thread
  // takes tens of us to wake, and a pour rebuilds every ~8 steps): thread 0 sizes the buffers; each thread's
  // bounding box of its share; their union, the size levels and the grids in thread 0; the counting sort's
  // four phases (count_cells, cell_sum, place_cells, fill_cells); the search of the finder chunks (a
  // WorkQueue); the chunks' offsets in thread 0; then each thread copies its chunks into `out` (the caller
  // syncs before reading it).
  long k0 = 0, k1 = 0;
  t.range(static_cast<long>(n), k0, k1);
  std::array<double, 6> box{x[0].x, x[0].y, x[0].z, x[0].x, x[0].y, x[0].z};
  for (long k = k0; k < k1; ++k) {
    box[0] = std::min(box[0], x[k].x), box[1] = std::min(box[1], x[k].y), box[2] = std::min(box[2], x[k].z);
    box[3] = std::max(box[3], x[k].x), box[4] = std::max(box[4], x[k].y), box[5] = std::max(box[5], x[k].z);
  }
  const std::size_t nchunks = (n + kFinders - 1) / kFinders;
  if (t.me == 0) {
    boxes_.resize(static_cast<std::size_t>(t.size));
    level_of_.resize(n);
    cell_id_.resize(n);
    slot_.resize(n);
    if (chunks_.size() < nchunks) chunks_.resize(nchunks);
    offset_.assign(nchunks + 1, 0);
    queue_.reset(static_cast<long>(nchunks), t.size);
  }
  t.sync();
  boxes_[static_cast<std::size_t>(t.me)] = box;
  t.sync();
  if (t.me == 0) set_up(x, radius, skin, t.size);
  t.sync();
  count_cells(x, t.me, k0, k1);
  t.sync();
  // The cells' starts and the threads' cursors: a prefix sum over all levels' cells, each thread its range of
  // them (a serial pass over a chapter-7 pour's ~2 M mostly empty cells was ~4 % of thread 0's time at 2
  // threads, the other waiting).
  long g0 = 0, g1 = 0;
  t.range(static_cast<long>(cells_), g0, g1);
  range_sums_[static_cast<std::size_t>(t.me)] = cell_sum(t.size, g0, g1);
  t.sync();
  std::uint64_t base = 0;
  for (int u = 0; u < t.me; ++u) base += range_sums_[static_cast<std::size_t>(u)];
  place_cells(t.size, g0, g1, base);
  t.sync();
  fill_cells(x, radius, t.me, k0, k1);
  if (side && t.size > 1) side(Team{t.me, t.size, nullptr});
  t.sync();
  const Vec3 lo{boxes_[0][0], boxes_[0][1], boxes_[0][2]};
  // Each thread its own run of chunks first (model/parallel.h: WorkQueue); the pairs do not depend on which
  // thread searched a chunk.
  for (long c = queue_.next(t.me); c >= 0; c = queue_.next(t.me))
    search_chunk(static_cast<std::size_t>(c), x, radius, skin, lo);
  t.sync();
  if (t.me == 0) {
    for (std::size_t c = 0; c < nchunks; ++c) offset_[c + 1] = offset_[c] + chunks_[c].n;
    out.i.resize(offset_[nchunks]);
    out.j.resize(offset_[nchunks]);
  }
  // The chunks copied into place by the threads that found them (copied by thread 0 alone, this was ~1.4 % of
  // chapter-7 test 2's run on 2 threads).
  t.sync();
  for (std::size_t c = static_cast<std::size_t>(t.me); c < nchunks; c += static_cast<std::size_t>(t.size)) {
    std::copy_n(chunks_[c].i.data(), chunks_[c].n, out.i.data() + offset_[c]);
    std::copy_n(chunks_[c].j.data(), chunks_[c].n, out.j.data() + offset_[c]);
  }
}

// The union of the threads' boxes (into boxes_[0]), the size levels and their grids (one thread): the
// counting sort of the particles into them follows in count_cells, place_cells and fill_cells.
void NeighborSearch::set_up(const std::vector<Vec3>& x, const std::vector<double>& radius, double skin, int threads) {
  const std::size_t n = x.size();
  std::array<double, 6>& u = boxes_[0];
  for (const auto& b : boxes_) {
    for (int k = 0; k < 3; ++k) u[k] = std::min(u[k], b[k]);
    for (int k = 3; k < 6; ++k) u[k] = std::max(u[k], b[k]);
  }
  const Vec3 lo{u[0], u[1], u[2]}, hi{u[3], u[4], u[5]};
  // Size classes of a factor 2 in radius: level = floor(log2(r / r_min)); one level for ratios < 2.
  // Radii do not change during a run: the levels, their counts and largest radii are recomputed only when
  // the radii differ from the last build's.
  if (radius_ != radius) {
    radius_ = radius;
    double rmin = radius[0];
    for (double r : radius) rmin = std::min(rmin, r);
    nlev_ = 1;
    for (std::size_t k = 0; k < n; ++k) {
      level_of_[k] = std::min(30, static_cast<int>(std::floor(std::log2(radius[k] / rmin))));
      nlev_ = std::max(nlev_, level_of_[k] + 1);
    }
    lev_.resize(static_cast<std::size_t>(nlev_));
    for (Level& L : lev_) {
      L.rmax = 0.0;
      L.count = 0;
    }
    for (std::size_t k = 0; k < n; ++k) {
      Level& L = lev_[static_cast<std::size_t>(level_of_[k])];
      L.rmax = std::max(L.rmax, radius[k]);
      ++L.count;
    }
  }
  cells_ = 0;
  for (Level& L : lev_) {
    L.sorted.resize(L.count);
    L.xs.resize(L.count);
    L.ys.resize(L.count);
    L.zs.resize(L.count);
    L.rs.resize(L.count);
    L.first = cells_;
    if (L.count == 0) {
      L.start.assign(2, 0);
      continue;
    }
    L.cell = 2.0 * L.rmax + skin;
    // A sparse cloud must not allocate a huge grid: grow the cells until there are at most kCellsPerParticle.
    auto cells = [&](double c) {
      L.dim[0] = static_cast<long>((hi.x - lo.x) / c) + 1;
      L.dim[1] = static_cast<long>((hi.y - lo.y) / c) + 1;
      L.dim[2] = static_cast<long>((hi.z - lo.z) / c) + 1;
      return static_cast<double>(L.dim[0]) * static_cast<double>(L.dim[1]) * static_cast<double>(L.dim[2]);
    };
    while (cells(L.cell) > kCellsPerParticle * static_cast<double>(L.count) + 64.0) L.cell *= 1.5;
    L.inv = 1.0 / L.cell;
    L.start.resize(static_cast<std::size_t>(L.dim[0] * L.dim[1] * L.dim[2]) + 1);
    L.start.back() = static_cast<std::uint32_t>(L.count);  // (place_cells fills the others)
    cells_ += L.start.size() - 1;
  }
  count_.resize(static_cast<std::size_t>(threads));
  range_sums_.resize(static_cast<std::size_t>(threads));
}

// The counting sort of particles k0 .. k1 (a thread's share) into the levels' cells, in phases with a team
// sync between them: each thread counts its share's particles per cell into its own count_ (and keeps each
// particle's cell), the threads turn the counts into every cell's start and each thread's cursor in it (each
// a range of the cells: cell_sum, place_cells), then each thread places its share. A cell holds the
// particles in ascending index (thread 0's share first, each share ascending): the same order as the
// one-thread sort, so the same pairs in the same order. (One thread sorted all of them while the other
// waited: at 2 threads this serial phase was ~21 % of the 52k bench pour's rebuild, and it read the other
// thread's positions from its cache.)
void NeighborSearch::count_cells(const std::vector<Vec3>& x, int me, long k0, long k1) {
  std::vector<std::uint32_t>& count = count_[static_cast<std::size_t>(me)];
  count.assign(cells_, 0);
  const Vec3 lo{boxes_[0][0], boxes_[0][1], boxes_[0][2]};
  if (nlev_ == 1) {
    // One level (sizes within a factor 2: most scenes): the cells without the per-particle level, in a loop of
    // their own that the compiler vectorises, then the counts.
    const Level& L = lev_[0];
    const double* X = &x[0].x;  // x, y, z of particle k at 3 k .. 3 k + 2
    std::uint32_t* cell = cell_id_.data();
    for (long k = k0; k < k1; ++k) {
      const long cx = L.clamp_cell(X[3 * k] - lo.x, 0), cy = L.clamp_cell(X[3 * k + 1] - lo.y, 1);
      cell[k] = static_cast<std::uint32_t>(L.index(cx, cy, L.clamp_cell(X[3 * k + 2] - lo.z, 2)));
    }
    for (long k = k0; k < k1; ++k) ++count[cell[k]];
  } else {
    for (long k = k0; k < k1; ++k) {
      const Level& L = lev_[static_cast<std::size_t>(level_of_[static_cast<std::size_t>(k)])];
      const auto c = static_cast<std::uint32_t>(
          L.index(L.clamp_cell(x[k].x - lo.x, 0), L.clamp_cell(x[k].y - lo.y, 1), L.clamp_cell(x[k].z - lo.z, 2)));
      cell_id_[static_cast<std::size_t>(k)] = c;
      ++count[L.first + c];
    }
  }
}

// The particles counted in cells [g0, g1) of all levels' cells (count_: the threads' counts).
std::uint64_t NeighborSearch::cell_sum(int threads, long g0, long g1) const {
  std::uint64_t sum = 0;
  for (int t = 0; t < threads; ++t) {
    const std::uint32_t* count = count_[static_cast<std::size_t>(t)].data();
    for (long g = g0; g < g1; ++g) sum += count[g];
  }
  return sum;
}

// Cells [g0, g1) of all levels' cells, `base` particles counted before g0 (in the cells of lower index):
// each cell's start in its level's `sorted` and each thread's cursor in it (its count until then). The
// global running count less the particles of the lower levels is a level's own running count, so the
// ranges give the numbers a serial pass over every cell gives.
void NeighborSearch::place_cells(int threads, long g0, long g1, std::uint64_t base) {
  std::uint64_t below = 0;  // the particles of the levels before L
  for (Level& L : lev_) {
    const long first = static_cast<long>(L.first), last = first + static_cast<long>(L.start.size()) - 1;
    const long c0 = std::max(g0, first), c1 = std::min(g1, last);
    if (L.count > 0 && c0 < c1) {
      auto run = static_cast<std::uint32_t>(base - below);
      for (long g = c0; g < c1; ++g) {
        L.start[static_cast<std::size_t>(g - first)] = run;
        for (int t = 0; t < threads; ++t) {
          std::uint32_t& slot = count_[static_cast<std::size_t>(t)][static_cast<std::size_t>(g)];
          const std::uint32_t here = slot;
          slot = run;  // thread t's cursor in cell g
          run += here;
        }
      }
      base = below + run;
    }
    below += L.count;
  }
}

void NeighborSearch::fill_cells(const std::vector<Vec3>& x, const std::vector<double>& radius, int me, long k0,
                                long k1) {
  std::vector<std::uint32_t>& cursor = count_[static_cast<std::size_t>(me)];
  const auto fill = [&](Level& L, std::size_t k) {
    const std::uint32_t s = cursor[L.first + cell_id_[k]]++;
    L.sorted[s] = static_cast<std::uint32_t>(k);
    L.xs[s] = x[k].x;
    L.ys[s] = x[k].y;
    L.zs[s] = x[k].z;
    L.rs[s] = radius[k];
    slot_[k] = s;
  };
  if (nlev_ == 1)
    for (long k = k0; k < k1; ++k) fill(lev_[0], static_cast<std::size_t>(k));
  else
    for (long k = k0; k < k1; ++k)
      fill(lev_[static_cast<std::size_t>(level_of_[static_cast<std::size_t>(k)])], static_cast<std::size_t>(k));
}

// The pairs found by the finders of chunk c (particles c kFinders .. (c + 1) kFinders), in scan order.
void NeighborSearch::search_chunk(std::size_t c, const std::vector<Vec3>& x, const std::vector<double>& radius,
                                  double skin, const Vec3& lo) {
  const std::size_t n = x.size();
  Chunk& ch = chunks_[c];
  std::size_t m = 0;
  // Candidates s0 .. s1 of level L against particle a, the pairs in scan order.
  auto scan = [&](const Level& L, std::uint32_t s0, std::uint32_t s1, std::uint32_t a, const Vec3& xa, double ra) {
    if (s1 <= s0) return;
    if (m + (s1 - s0) + kSlack > ch.i.size()) {
      ch.i.resize(2 * (m + (s1 - s0)) + 64);
      ch.j.resize(ch.i.size());
    }
    m = detail::scan_candidates(L.xs.data(), L.ys.data(), L.zs.data(), L.rs.data(), L.sorted.data(), s0, s1, a,
                                xa, ra, ch.i.data(), ch.j.data(), m);
  };
  const std::size_t a_end = std::min(n, (c + 1) * kFinders);
  for (std::size_t a = c * kFinders; a < a_end; ++a) {
    const auto a32 = static_cast<std::uint32_t>(a);
    const int la = level_of_[a];
    const double ra = radius[a] + skin;
    const Vec3 xa = x[a];
    const Vec3 rel = xa - lo;
    // Own level: half stencil, each pair of the level found once: the rest of the own cell (higher
    // indices: the cell is sorted by index) and the next cell in x, then the 3-cell rows (y + 1, z),
    // (y - 1 .. y + 1, z + 1); a row of cells is one contiguous range of the sorted particles.
    {
      const Level& L = lev_[static_cast<std::size_t>(la)];
      const long c0 = L.clamp_cell(rel.x, 0), c1 = L.clamp_cell(rel.y, 1), c2 = L.clamp_cell(rel.z, 2);
      const long xl = std::max(c0 - 1, 0L), xh = std::min(c0 + 1, L.dim[0] - 1);
      auto row = [&](long first_x, long cy, long cz, std::uint32_t from) {
        if (cy < 0 || cy >= L.dim[1] || cz >= L.dim[2]) return;
        const std::uint32_t s0 = from != UINT32_MAX ? from : L.start[L.index(first_x, cy, cz)];
        scan(L, s0, L.start[L.index(xh, cy, cz) + 1], a32, xa, ra);
      };
      row(c0, c1, c2, slot_[a] + 1);
      row(xl, c1 + 1, c2, UINT32_MAX);
      for (long cy = c1 - 1; cy <= c1 + 1; ++cy) row(xl, cy, c2 + 1, UINT32_MAX);
    }
    // Finer levels: every cell within the pair cutoff (a larger sphere finds each smaller partner once).
    for (int lb = 0; lb < la; ++lb) {
      const Level& L = lev_[static_cast<std::size_t>(lb)];
      if (L.count == 0) continue;
      const double reach = ra + L.rmax;
      const long x0 = L.clamp_cell(rel.x - reach, 0), x1 = L.clamp_cell(rel.x + reach, 0);
      const long y0 = L.clamp_cell(rel.y - reach, 1), y1 = L.clamp_cell(rel.y + reach, 1);
      const long z0 = L.clamp_cell(rel.z - reach, 2), z1 = L.clamp_cell(rel.z + reach, 2);
      for (long cz = z0; cz <= z1; ++cz)
        for (long cy = y0; cy <= y1; ++cy)
          scan(L, L.start[L.index(x0, cy, cz)], L.start[L.index(x1, cy, cz) + 1], a32, xa, ra);
    }
  }
  ch.n = m;
}

CandidatePairs build_pairs(const std::vector<Vec3>& x, const std::vector<double>& radius, double skin) {
  NeighborSearch search;
  CandidatePairs out;
  search.build(x, radius, skin, out, threads_for(static_cast<long>(x.size()), kParallelMinItems));
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
