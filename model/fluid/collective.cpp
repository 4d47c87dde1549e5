// SPDX-License-Identifier: MIT
#include "model/fluid/collective.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <utility>

#if defined(__AVX512F__) || defined(__AVX2__)
#include <immintrin.h>
#endif

#include "model/fluid/asin_poly.h"
#include "model/fluid/buoyancy.h"

namespace pastemix::model::fluid {

double skempton_nc(double breadth, double embedment) {
  if (!(breadth > 0.0)) return 6.0;
  return std::min(9.0, 6.0 * (1.0 + 0.2 * std::max(0.0, embedment) / breadth));
}

namespace {

// The strips of disc_union_area over a set of discs: the lowest y (m), the strips' width (m), their count
// (0: nothing to cover).
struct StripLayout {
  double y_lo = 0.0, step = 0.0;
  long rows = 0;
};

// The strip of height y (m) among strips of width step (m) from y_lo (m), unclamped (strip_lengths and
// CollectiveYield::cut_rows must agree on every disc's strips).
long strip_of(double y, double y_lo, double step) { return static_cast<long>(std::floor((y - y_lo) / step)); }

StripLayout strip_layout(const double* cy, const double* r, std::size_t n, double h) {
  if (n == 0) return {};
  double y_lo = cy[0] - r[0], y_hi = cy[0] + r[0];
  for (std::size_t k = 1; k < n; ++k) y_lo = std::min(y_lo, cy[k] - r[k]), y_hi = std::max(y_hi, cy[k] + r[k]);
  // At most 4000 lines: the rows' cost stays bounded for a wide PSD (a 50 mm rock beside 1 mm fines).
  const double span = y_hi - y_lo;
  if (!(span > 0.0)) return {};
  const long rows = std::max(1L, std::min(4000L, static_cast<long>(std::ceil(span / h))));
  return {y_lo, span / static_cast<double>(rows), rows};
}

constexpr long kRowBlock = 64;  // strips per block of strip_lengths

// The strip boundaries y_lo + (row0 + j) step (m), j < n <= kRowBlock + 1, as offsets from the centre c (m) of a
// disc of radius r (m) clamped to [-r, r]: cl[j]; and the integral of the disc's chord from its centre line to
// there, F(t) = t sqrt(r^2 - t^2) + r^2 asin(t / r) (m^2): prim[j]. The disc's extent in strip [j, j + 1] is
// [max(offset j, -r), min(offset j + 1, r)] (the offsets grow with the row), the same numbers as cl[j], cl[j + 1]
// wherever it is not empty; so the disc's area in that strip is prim[j + 1] - prim[j] where cl[j + 1] > cl[j],
// and it does not reach the strip elsewhere. Eight boundaries per instruction with AVX-512 (asin8), the same
// operations, hence bits, as the scalar loop.
void chord_integrals(double y_lo, double step, long row0, long n, double c, double r, double* cl, double* prim) {
  const double rr = r * r;
  long j = 0;
#if defined(__AVX512F__)
  const __m512d lane = _mm512_setr_pd(0, 1, 2, 3, 4, 5, 6, 7), v_lo = _mm512_set1_pd(y_lo);
  const __m512d v_step = _mm512_set1_pd(step), v_c = _mm512_set1_pd(c), v_r = _mm512_set1_pd(r);
  const __m512d v_mr = _mm512_set1_pd(-r), v_rr = _mm512_set1_pd(rr);
  for (; j < n; j += 8) {  // (lanes past n: further boundaries, finite and unused, inside the arrays)
    const __m512d row = _mm512_add_pd(_mm512_set1_pd(static_cast<double>(row0 + j)), lane);  // exact integers
    const __m512d u = _mm512_sub_pd(_mm512_add_pd(v_lo, _mm512_mul_pd(row, v_step)), v_c);
    const __m512d t = _mm512_maskz_min_pd(0xff, _mm512_maskz_max_pd(0xff, u, v_mr), v_r);
    const __m512d root = _mm512_maskz_sqrt_pd(0xff, _mm512_sub_pd(v_rr, _mm512_mul_pd(t, t)));
    _mm512_store_pd(cl + j, t);
    const __m512d area = _mm512_mul_pd(v_rr, asin8(_mm512_div_pd(t, v_r)));
    _mm512_store_pd(prim + j, _mm512_add_pd(_mm512_mul_pd(t, root), area));
  }
#elif defined(__AVX2__) && defined(__FMA__)
  // Four boundaries per instruction with AVX2 alone (asin4): the same operations.
  const __m256d lane = _mm256_setr_pd(0, 1, 2, 3), v_lo = _mm256_set1_pd(y_lo);
  const __m256d v_step = _mm256_set1_pd(step), v_c = _mm256_set1_pd(c), v_r = _mm256_set1_pd(r);
  const __m256d v_mr = _mm256_set1_pd(-r), v_rr = _mm256_set1_pd(rr);
  for (; j + 4 <= n; j += 4) {
    const __m256d row = _mm256_add_pd(_mm256_set1_pd(static_cast<double>(row0 + j)), lane);
    const __m256d u = _mm256_sub_pd(_mm256_add_pd(v_lo, _mm256_mul_pd(row, v_step)), v_c);
    // std::min(std::max(u, -r), r): max(u, -r) is (u < -r ? -r : u), min(., r) is (r < . ? r : .).
    __m256d t = _mm256_blendv_pd(u, v_mr, _mm256_cmp_pd(u, v_mr, _CMP_LT_OQ));
    t = _mm256_blendv_pd(t, v_r, _mm256_cmp_pd(v_r, t, _CMP_LT_OQ));
    const __m256d root = _mm256_sqrt_pd(_mm256_sub_pd(v_rr, _mm256_mul_pd(t, t)));
    _mm256_storeu_pd(cl + j, t);
    const __m256d area = _mm256_mul_pd(v_rr, asin4(_mm256_div_pd(t, v_r)));
    _mm256_storeu_pd(prim + j, _mm256_add_pd(_mm256_mul_pd(t, root), area));
  }
#endif
  // (|t| <= r, and rounding is monotonic: t t <= r r and |t / r| <= 1, so neither the root's argument nor the
  // asin's needs a clamp of its own.)
  for (; j < n; ++j) {
    const double u = y_lo + static_cast<double>(row0 + j) * step - c;
    const double t = std::min(std::max(u, -r), r);
    cl[j] = t;
    prim[j] = t * std::sqrt(rr - t * t) + rr * asin_poly(t / r);
  }
}

// The covered lengths (m) of strips [row0, row1) of layout s, each strip's merged segments in order, appended
// to `out`: disc_union_area's length is their sum in this order (strips of different callers, taken in
// ascending row order, give the same sum to the bit).
//
// Per strip a disc crosses: the interval centred on the disc whose length is the disc's mean chord over the
// strip (its exact area in the strip / the strip's width). So a disc alone has its exact area; where two discs
// share a strip (overlapping, or one above the other within a strip's width) their intervals are merged, an
// error of order (h / r) of the shared strips' area.
//
// The strips are swept in blocks of kRowBlock (issue 19: one pass that bucketed every interval of a 13k-sphere
// bed, ~0.4 M of them, and sorted each strip with std::sort was a third of the collective rule's run): a block's
// intervals stay in cache, and the discs are visited in ascending x, so each strip's intervals arrive nearly
// sorted by their start and an insertion sort orders them. The intervals, their order and so the segments are
// the same values as any other sort gives: the same bits.
void strip_lengths(const double* cx, const double* cy, const double* r, std::size_t n, const StripLayout& s,
                   long row0, long row1, std::vector<double>& out) {
  if (row1 <= row0) return;
  const double y_lo = s.y_lo, step = s.step;
  // The discs in ascending x, each listed in every block of strips it reaches (counting sort by block).
  std::vector<std::uint32_t> by_x;
  by_x.reserve(n);
  for (std::size_t k = 0; k < n; ++k)
    if (r[k] > 0.0) by_x.push_back(static_cast<std::uint32_t>(k));
  std::sort(by_x.begin(), by_x.end(), [&](std::uint32_t a, std::uint32_t b) { return cx[a] < cx[b]; });
  const long blocks = (row1 - row0 + kRowBlock - 1) / kRowBlock;
  // Each disc's strips within [row0, row1), computed once: [lo[k], hi[k]] (empty where lo > hi).
  std::vector<long> lo(n, 0), hi(n, -1);
  for (std::uint32_t k : by_x) {
    lo[k] = std::max(row0, strip_of(cy[k] - r[k], y_lo, step));
    hi[k] = std::min(row1 - 1, strip_of(cy[k] + r[k], y_lo, step));
  }
  auto for_blocks = [&](std::uint32_t k, auto&& f) {  // f(b) for each block of strips disc k reaches
    if (lo[k] <= hi[k])
      for (long b = (lo[k] - row0) / kRowBlock; b <= (hi[k] - row0) / kRowBlock; ++b) f(static_cast<std::size_t>(b));
  };
  std::vector<std::size_t> first(static_cast<std::size_t>(blocks) + 1, 0);
  for (std::uint32_t k : by_x) for_blocks(k, [&](std::size_t b) { ++first[b + 1]; });
  for (long b = 0; b < blocks; ++b) first[static_cast<std::size_t>(b) + 1] += first[static_cast<std::size_t>(b)];
  std::vector<std::uint32_t> in_block(first.back());
  {
    std::vector<std::size_t> fill(first.begin(), first.end() - 1);
    for (std::uint32_t k : by_x) for_blocks(k, [&](std::size_t b) { in_block[fill[b]++] = k; });
  }
  std::array<std::vector<std::pair<double, double>>, kRowBlock> iv;
  alignas(64) double cl[kRowBlock + 9], prim[kRowBlock + 9];  // a disc's boundaries in a block (<= kRowBlock + 1)
  for (long b = 0; b < blocks; ++b) {
    const long b0 = row0 + b * kRowBlock, b1 = std::min(row1, b0 + kRowBlock);
    for (auto& v : iv) v.clear();
    for (std::size_t e = first[static_cast<std::size_t>(b)]; e < first[static_cast<std::size_t>(b) + 1]; ++e) {
      const std::uint32_t k = in_block[e];
      // Half the mean chord over each strip the disc crosses: the difference of the chord's integral at the
      // strip's two boundaries (each boundary evaluated once per block), over the strip's width.
      const long lo_row = std::max(lo[k], b0), hi_row = std::min(hi[k], b1 - 1);
      if (hi_row < lo_row) continue;
      const long nb = hi_row - lo_row + 2;  // boundaries lo_row .. hi_row + 1
      chord_integrals(y_lo, step, lo_row, nb, cy[k], r[k], cl, prim);
      for (long q = 0; q + 1 < nb; ++q) {
        if (!(cl[q + 1] > cl[q])) continue;  // the disc does not reach into this strip
        const double half = 0.5 * (prim[q + 1] - prim[q]) / step;
        iv[static_cast<std::size_t>(lo_row + q - b0)].emplace_back(cx[k] - half, cx[k] + half);
      }
    }
    for (long row = b0; row < b1; ++row) {
      auto& v = iv[static_cast<std::size_t>(row - b0)];
      if (v.empty()) continue;
      // Insertion sort by the start alone, each interval moved once into the hole its larger predecessors
      // leave. The discs come in ascending x, so the starts are partly sorted, but a pile's layers overlap in
      // projection: in a perf profile of one footprint of case 3's discs at t = 1.5 s this sort was about half
      // of the function. Intervals with equal starts keep their arrival order instead of being ordered by
      // their ends, which changes no segment (an interval starting where the one before it starts never
      // opens a segment), so the lengths are the same bits.
      for (std::size_t i = 1; i < v.size(); ++i) {
        const std::pair<double, double> x = v[i];
        std::size_t j = i;
        for (; j > 0 && x.first < v[j - 1].first; --j) v[j] = v[j - 1];
        v[j] = x;
      }
      // The merged segments' lengths, without a branch on "does this interval start a new segment" (as
      // unpredictable as the spheres' spacing) and without push_back, which kept `e` on the stack: every
      // interval writes the running segment's length e - a at the next free slot and moves that slot on only
      // where a gap ends the segment, so the slot keeps the length the segment had when it ended, the value
      // the branch wrote: the same bits. With the sort above (issue 19; bench/footprint_probe, 12,108 discs,
      // five interleaved runs against the previous form): 11.45-11.96 -> 10.87-11.27 ms per footprint.
      const std::size_t base = out.size();
      out.resize(base + v.size());  // at most one segment per interval
      double* seg = out.data() + base;
      std::size_t k = 0;
      double a = v[0].first, e = v[0].second;
      for (std::size_t i = 1; i < v.size(); ++i) {
        const bool gap = v[i].first > e;
        seg[k] = e - a;
        k += gap;
        a = gap ? v[i].first : a;
        e = std::max(e, v[i].second);
      }
      seg[k++] = e - a;
      out.resize(base + k);
    }
  }
}

}  // namespace

double disc_union_area(const std::vector<double>& cx, const std::vector<double>& cy, const std::vector<double>& r,
                       double h) {
  const StripLayout s = strip_layout(cy.data(), r.data(), cx.size(), h);
  std::vector<double> seg;
  strip_lengths(cx.data(), cy.data(), r.data(), cx.size(), s, 0, s.rows, seg);
  double length = 0.0;
  for (double x : seg) length += x;
  return length * s.step;
}

double lens_area(double r1, double r2, double c) {
  if (c >= r1 + r2) return 0.0;
  if (c <= std::abs(r1 - r2)) return kPi * std::min(r1, r2) * std::min(r1, r2);
  const double a1 = std::acos(std::clamp((c * c + r1 * r1 - r2 * r2) / (2.0 * c * r1), -1.0, 1.0));
  const double a2 = std::acos(std::clamp((c * c + r2 * r2 - r1 * r1) / (2.0 * c * r2), -1.0, 1.0));
  const double k = (-c + r1 + r2) * (c + r1 - r2) * (c - r1 + r2) * (c + r1 + r2);
  return r1 * r1 * a1 + r2 * r2 * a2 - 0.5 * std::sqrt(std::max(0.0, k));
}

long CollectiveYield::find(long k) {
  while (parent_[static_cast<std::size_t>(k)] != k) {
    const long up = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(k)])];
    parent_[static_cast<std::size_t>(k)] = up;  // path halving
    k = up;
  }
  return k;
}

ClusterStats CollectiveYield::factors(const CollectiveInput& in, std::vector<double>& factor) {
  begin(in, 1);
  footprints(0);
  return finish(in, factor);
}

void CollectiveYield::begin(const CollectiveInput& in, int parts) {
  const Particles& p = *in.particles;
  const std::vector<long>& m = *in.members;
  const std::size_t nm = m.size();
  stats_ = ClusterStats{};
  pending_.clear(), cx_.clear(), cy_.clear(), cr_.clear();
  parts_ = std::clamp(parts, 1, kMaxParts);
  for (auto& s : seg_) s.clear();
  seg_start_.assign(static_cast<std::size_t>(parts_), {});
  cut_.clear();
  if (nm < 2 || in.yield_stress <= 0.0) return;

  slot_.assign(p.size(), -1);
  parent_.resize(nm);
  for (std::size_t k = 0; k < nm; ++k) slot_[static_cast<std::size_t>(m[k])] = static_cast<long>(k), parent_[k] = static_cast<long>(k);
  cover_.assign(nm, 0.0);
  const auto& pi = *in.pair_i;
  const auto& pj = *in.pair_j;
  for (std::size_t e = 0; e < pi.size(); ++e) {
    const long sa = slot_[pi[e]], sb = slot_[pj[e]];
    if (sa < 0 || sb < 0) continue;
    const double ra = p.radius[pi[e]], rb = p.radius[pj[e]];
    const double gap = norm(p.x[pi[e]] - p.x[pj[e]]) - ra - rb;
    if (gap >= kTouchGap * std::min(ra, rb)) continue;
    const long a = find(sa), b = find(sb);
    if (a != b) parent_[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    // The upper sphere of the two is shadowed by the lower one where their horizontal projections overlap.
    const Vec3 &xa = p.x[pi[e]], &xb = p.x[pj[e]];
    const double c = std::hypot(xa.x - xb.x, xa.y - xb.y);
    if (xa.z > xb.z) cover_[static_cast<std::size_t>(sa)] += lens_area(ra, rb, c);
    else if (xb.z > xa.z) cover_[static_cast<std::size_t>(sb)] += lens_area(rb, ra, c);
  }
  // Members grouped by root, ascending within each group (a counting sort keeps the order): every sum below
  // runs in ascending particle order, whatever the union order was.
  start_.assign(nm + 1, 0);
  for (std::size_t k = 0; k < nm; ++k) ++start_[static_cast<std::size_t>(find(static_cast<long>(k))) + 1];
  for (std::size_t k = 0; k < nm; ++k) start_[k + 1] += start_[k];
  order_.resize(nm);
  {
    std::vector<long> fill(start_.begin(), start_.end() - 1);
    for (std::size_t k = 0; k < nm; ++k) order_[static_cast<std::size_t>(fill[static_cast<std::size_t>(find(static_cast<long>(k)))]++)] = static_cast<long>(k);
  }
  const std::vector<double>& d0 = *in.rest_drag;
  for (std::size_t root = 0; root < nm; ++root) {
    const long b = start_[root], e = start_[root + 1];
    if (e - b < 2) continue;
    ++stats_.clusters;
    stats_.largest = std::max(stats_.largest, e - b);
    Pending c{b, e};
    c.disc0 = cx_.size();
    for (long q = b; q < e; ++q) {
      const long k = order_[static_cast<std::size_t>(q)];
      const std::size_t a = static_cast<std::size_t>(m[static_cast<std::size_t>(k)]);
      const double exposed = std::max(0.0, 1.0 - cover_[static_cast<std::size_t>(k)] / (kPi * p.radius[a] * p.radius[a]));
      cover_[static_cast<std::size_t>(k)] = exposed;  // from here on: the exposed fraction
      c.sum += exposed * d0[static_cast<std::size_t>(k)];
      c.sum_all += d0[static_cast<std::size_t>(k)];
      c.strongest = std::max(c.strongest, exposed * d0[static_cast<std::size_t>(k)]);
      const double r = p.radius[a], z = p.x[a].z;
      c.lowest = std::min(c.lowest, z - r);
      c.r_min = std::min(c.r_min, r);
      // Horizontal section of the wetted part: the full disc once the centre is submerged, else the cap's base.
      const double above = z - in.surface;
      const double rw = above <= 0.0 ? r : std::sqrt(std::max(0.0, r * r - above * above));
      cx_.push_back(p.x[a].x), cy_.push_back(p.x[a].y), cr_.push_back(rw);
    }
    if (!(c.sum > 0.0)) {
      cx_.resize(c.disc0), cy_.resize(c.disc0), cr_.resize(c.disc0);
      continue;
    }
    c.disc1 = cx_.size();
    // Strips r_min / 16 wide: the footprint's area to ~0.2 % (tested), far below the spread of N_c (5.14-6).
    const StripLayout s = strip_layout(cy_.data() + c.disc0, cr_.data() + c.disc0, c.disc1 - c.disc0, c.r_min / 16.0);
    c.y_lo = s.y_lo, c.step = s.step, c.rows = s.rows;
    cut_rows(c);
    pending_.push_back(c);
  }
}

// Where the parts' strips of cluster c begin and end (appended to cut_, parts_ + 1 rows): at equal shares of
// the disc-strip crossings, strip_lengths' work (one chord and one interval each), not of the rows. Equal
// rows left one thread with most of the work wherever the discs crowd one side of the footprint (chapter-7
// test 1 on 2 threads, perf, session 41: strip_lengths 0.79 % of the samples on thread 0 against 0.30 % on
// thread 1). Any contiguous cut gives the same lengths in the same row order: the same bits.
void CollectiveYield::cut_rows(const Pending& c) {
  const std::size_t base = cut_.size();
  cut_.resize(base + static_cast<std::size_t>(parts_) + 1, c.rows);
  cut_[base] = 0;
  if (parts_ == 1 || c.rows <= 0) return;
  // Crossings per row: a difference array over the rows (rows <= 4000), each disc its [lo, hi] as in
  // strip_lengths.
  std::vector<long>& per_row = row_scratch_;
  per_row.assign(static_cast<std::size_t>(c.rows) + 1, 0);
  long total = 0;
  for (std::size_t k = c.disc0; k < c.disc1; ++k) {
    if (!(cr_[k] > 0.0)) continue;
    const long lo = std::clamp(strip_of(cy_[k] - cr_[k], c.y_lo, c.step), 0L, c.rows - 1);
    const long hi = std::clamp(strip_of(cy_[k] + cr_[k], c.y_lo, c.step), lo, c.rows - 1);
    ++per_row[static_cast<std::size_t>(lo)], --per_row[static_cast<std::size_t>(hi) + 1];
    total += hi - lo + 1;
  }
  long in_row = 0, run = 0;
  int t = 1;
  for (long row = 0; row < c.rows && t < parts_; ++row) {
    in_row += per_row[static_cast<std::size_t>(row)];
    run += in_row;  // crossings of rows 0 .. row
    while (t < parts_ && run * parts_ >= total * t) cut_[base + static_cast<std::size_t>(t++)] = row + 1;
  }
}

void CollectiveYield::footprints(int part) {
  if (part < 0 || part >= parts_) return;  // more threads than parts: nothing left for this one
  const std::size_t t = static_cast<std::size_t>(part);
  auto& seg = seg_[t];
  auto& at = seg_start_[t];
  at.assign(pending_.size() + 1, 0);
  for (std::size_t q = 0; q < pending_.size(); ++q) {
    const Pending& c = pending_[q];
    at[q] = seg.size();
    // This part's strips (cut_rows), in ascending order of the parts.
    const std::size_t cuts = q * static_cast<std::size_t>(parts_ + 1) + t;
    const long row0 = cut_[cuts], row1 = cut_[cuts + 1];
    const StripLayout s{c.y_lo, c.step, c.rows};
    strip_lengths(cx_.data() + c.disc0, cy_.data() + c.disc0, cr_.data() + c.disc0, c.disc1 - c.disc0, s, row0,
                  row1, seg);
  }
  at[pending_.size()] = seg.size();
}

ClusterStats CollectiveYield::finish(const CollectiveInput& in, std::vector<double>& factor) {
  factor.assign(in.members->size(), 1.0);
  ClusterStats stats = stats_;
  for (std::size_t q = 0; q < pending_.size(); ++q) {
    const Pending& c = pending_[q];
    // The covered length over the strips in ascending row order (parts in order): disc_union_area's sum.
    double length = 0.0;
    for (int t = 0; t < parts_; ++t) {
      const auto& at = seg_start_[static_cast<std::size_t>(t)];
      const auto& seg = seg_[static_cast<std::size_t>(t)];
      for (std::size_t x = at[q]; x < at[q + 1]; ++x) length += seg[x];
    }
    const double area = length * c.step;
    const double breadth = std::sqrt(4.0 * area / kPi);
    const double embed = std::max(0.0, in.surface - c.lowest);
    // End bearing: the exposed underside pushing through (sum), at most the footing's; plus the side shear.
    const double end = std::min(c.sum, in.yield_stress * skempton_nc(breadth, embed) * area);
    const double side = in.yield_stress * kPi * breadth * embed;
    // At most what the spheres would resist each on its own (that mechanism is always possible), and at
    // least the most exposed sphere alone.
    const double resist = std::max(c.strongest, std::min(c.sum_all, end + side));
    const double f = resist / c.sum;
    for (long k = c.b; k < c.e; ++k) {
      const std::size_t i = static_cast<std::size_t>(order_[static_cast<std::size_t>(k)]);
      factor[i] = cover_[i] * f;
      stats.min_factor = std::min(stats.min_factor, factor[i]);
    }
  }
  return stats;
}

}  // namespace pastemix::model::fluid
