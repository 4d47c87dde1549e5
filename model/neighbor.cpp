// SPDX-License-Identifier: MIT
#include "model/neighbor.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>

#include <omp.h>
#if defined(__AVX512F__) && defined(__AVX512VL__)
#include <immintrin.h>
#endif

#include "model/parallel.h"

namespace pastemix::model {

namespace {

constexpr std::size_t kFinders = 256;  // finder particles per chunk of the search
constexpr std::size_t kSlack = 8;       // entries a scan may write past its last pair (a whole vector store)

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
  return std::clamp(static_cast<long>(std::floor(v * inv)), 0L, dim[axis] - 1);
}

void NeighborSearch::build(const std::vector<Vec3>& x, const std::vector<double>& radius, double skin,
                           CandidatePairs& out, int threads) {
  const std::size_t n = x.size();
  out.i.clear();
  out.j.clear();
  if (n < 2) return;
  const long nn = static_cast<long>(n);
  const int nthreads = threads;
  level_of_.resize(n);
  cell_id_.resize(n);
  slot_.resize(n);
  const std::size_t nchunks = (n + kFinders - 1) / kFinders;
  if (chunks_.size() < nchunks) chunks_.resize(nchunks);
  offset_.assign(nchunks + 1, 0);
  double lox = x[0].x, loy = x[0].y, loz = x[0].z, hix = lox, hiy = loy, hiz = loz;
  Vec3 lo;
  // One parallel region with three barriers (on this 2-core VM a sleeping thread takes tens of us to wake,
  // and a pour rebuilds every ~8 steps): the bounding box in parallel, the set-up in one thread (size
  // levels, grids, counting sort: linear, a fraction of the search), the search in parallel, then the
  // concatenation in one thread.
#pragma omp parallel num_threads(nthreads)
  {
#pragma omp for reduction(min : lox, loy, loz) reduction(max : hix, hiy, hiz)
    for (long k = 0; k < nn; ++k) {
      lox = std::min(lox, x[k].x), loy = std::min(loy, x[k].y), loz = std::min(loz, x[k].z);
      hix = std::max(hix, x[k].x), hiy = std::max(hiy, x[k].y), hiz = std::max(hiz, x[k].z);
    }
#pragma omp single
    {
      lo = {lox, loy, loz};
      const Vec3 hi{hix, hiy, hiz};
      // Size classes of a factor 2 in radius: level = floor(log2(r / r_min)); one level for ratios < 2.
      // Radii do not change during a run: recomputed only when they differ from the last build's.
      if (radius_ != radius) {
        radius_ = radius;
        double rmin = radius[0];
        for (double r : radius) rmin = std::min(rmin, r);
        nlev_ = 1;
        for (std::size_t k = 0; k < n; ++k) {
          level_of_[k] = std::min(30, static_cast<int>(std::floor(std::log2(radius[k] / rmin))));
          nlev_ = std::max(nlev_, level_of_[k] + 1);
        }
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
      for (Level& L : lev_) {
        L.sorted.resize(L.count);
        L.xs.resize(L.count);
        L.ys.resize(L.count);
        L.zs.resize(L.count);
        L.rs.resize(L.count);
        if (L.count == 0) {
          L.start.assign(2, 0);
          continue;
        }
        L.cell = 2.0 * L.rmax + skin;
        // A sparse cloud must not allocate a huge grid: grow the cells until there are at most ~4 per particle.
        auto cells = [&](double c) {
          L.dim[0] = static_cast<long>((hi.x - lo.x) / c) + 1;
          L.dim[1] = static_cast<long>((hi.y - lo.y) / c) + 1;
          L.dim[2] = static_cast<long>((hi.z - lo.z) / c) + 1;
          return static_cast<double>(L.dim[0]) * static_cast<double>(L.dim[1]) * static_cast<double>(L.dim[2]);
        };
        while (cells(L.cell) > 4.0 * static_cast<double>(L.count) + 64.0) L.cell *= 1.5;
        L.inv = 1.0 / L.cell;
        L.start.assign(static_cast<std::size_t>(L.dim[0] * L.dim[1] * L.dim[2]) + 1, 0);
      }
      // Counting sort per level, stable (ascending index inside a cell): count into start[c + 1], prefix
      // sums, fill with start[c] as the cursor, then shift start back by one cell.
      for (std::size_t k = 0; k < n; ++k) {
        Level& L = lev_[static_cast<std::size_t>(level_of_[k])];
        cell_id_[k] = static_cast<std::uint32_t>(L.index(L.clamp_cell(x[k].x - lo.x, 0), L.clamp_cell(x[k].y - lo.y, 1),
                                                         L.clamp_cell(x[k].z - lo.z, 2)));
        ++L.start[cell_id_[k] + 1];
      }
      for (Level& L : lev_)
        for (std::size_t c = 0; c + 1 < L.start.size(); ++c) L.start[c + 1] += L.start[c];
      for (std::size_t k = 0; k < n; ++k) {
        Level& L = lev_[static_cast<std::size_t>(level_of_[k])];
        const std::uint32_t s = L.start[cell_id_[k]]++;
        L.sorted[s] = static_cast<std::uint32_t>(k);
        L.xs[s] = x[k].x;
        L.ys[s] = x[k].y;
        L.zs[s] = x[k].z;
        L.rs[s] = radius[k];
        slot_[k] = s;
      }
      for (Level& L : lev_) {
        for (std::size_t c = L.start.size() - 1; c >= 1; --c) L.start[c] = L.start[c - 1];
        L.start[0] = 0;
      }
    }

#pragma omp for schedule(dynamic, 1)
    for (std::size_t c = 0; c < nchunks; ++c) {
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
#pragma omp single nowait
    {
      for (std::size_t c = 0; c < nchunks; ++c) offset_[c + 1] = offset_[c] + chunks_[c].n;
      out.i.resize(offset_[nchunks]);
      out.j.resize(offset_[nchunks]);
      for (std::size_t c = 0; c < nchunks; ++c) {
        std::copy_n(chunks_[c].i.data(), chunks_[c].n, out.i.data() + offset_[c]);
        std::copy_n(chunks_[c].j.data(), chunks_[c].n, out.j.data() + offset_[c]);
      }
    }
  }
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
