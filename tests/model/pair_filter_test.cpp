// SPDX-License-Identifier: MIT
// The pair pass's filter and staging (model/pair_filter.h): eight candidates at a time (AVX-512 builds; four
// with AVX2 alone) give
// the entries, separations, touching flags and zeroed springs that one candidate at a time gives, bit for bit,
// for a single thread's list and for a thread's part with cross pairs; stage8 fills each lane with its pair's
// state, a cross pair's from the ghost copies and the cross springs.
#include "model/pair_filter.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "model/laws/hertz_mindlin.h"

using namespace pastemix;
using namespace pastemix::model;

namespace {

constexpr long kN = 256;

// n spheres of 1-2 mm in a 2 cm box (a few at NaN), np pairs among them with random springs and flags,
// owners 0/1 and ghost copies (moved a little: a cross pair must read them, not the particles).
struct Setup {
  Particles p;
  PairList L;
  std::vector<std::uint32_t> ks[2];  // each thread's part: ascending, kCrossBit on cross pairs
};

Setup make(std::uint64_t seed, int n, long np) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Setup s;
  Particles& p = s.p;
  p.enable_rotation();
  for (int a = 0; a < n; ++a) {
    p.add(0, 1e-3 * (1.0 + u(rng)), 2650.0, {0.02 * u(rng), 0.02 * u(rng), 0.02 * u(rng)},
          {u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5}, {10 * u(rng), -10 * u(rng), u(rng)});
    if (a % 97 == 5) p.x[a].y = std::numeric_limits<double>::quiet_NaN();
  }
  PairList& L = s.L;
  L.width = 3;
  // Pairs by first particle, partners mostly near (the list's shape after a spatial sort), some far.
  for (long k = 0; k < np; ++k) {
    const auto a = static_cast<std::uint32_t>(k * n / np);
    auto b = static_cast<std::uint32_t>((a + 1 + static_cast<int>(u(rng) * (k % 5 == 0 ? n - 1 : 12))) % n);
    if (b == a) b = (a + 1) % static_cast<std::uint32_t>(n);
    L.i.push_back(a), L.j.push_back(b);
    // A sum a little above the distance or below it: about half touch.
    const double d = norm(p.x[b] - p.x[a]);
    L.rsum.push_back(std::isnan(d) ? 3e-3 : d * (0.9 + 0.2 * u(rng)));
    L.r_star.push_back(u(rng) * 1e-3), L.m_star.push_back(u(rng) * 1e-5);
    L.law_index.push_back(0);
    L.touching.push_back(u(rng) < 0.6 ? 1u : 0u);
    for (int c = 0; c < 3; ++c) L.history.push_back(1e-6 * (u(rng) + 0.1));
  }
  L.owner.resize(static_cast<std::size_t>(n));
  for (int a = 0; a < n; ++a) L.owner[static_cast<std::size_t>(a)] = static_cast<std::uint8_t>(a < n / 2 ? 0 : (a % 7 == 0 ? 0 : 1));
  L.cross.assign(static_cast<std::size_t>(np), PairList::kNone);
  for (long k = 0; k < np; ++k) {
    const int oi = L.owner[L.i[k]], oj = L.owner[L.j[k]];
    const auto entry_k = static_cast<std::uint32_t>(k) | (oi != oj ? PairList::kCrossBit : 0u);
    s.ks[oi].push_back(entry_k);
    if (oi != oj) {
      s.ks[oj].push_back(entry_k);
      L.cross[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(L.cross_pairs.size());
      L.cross_pairs.push_back(static_cast<std::uint32_t>(k));
    }
  }
  for (int c = 0; c < 2; ++c) L.cross_hist[c].assign(L.cross_pairs.size() * 3, 2e-6);
  L.ghost_of.resize(static_cast<std::size_t>(n));
  for (int c = 0; c < 2; ++c) L.ghost[c].resize(static_cast<std::size_t>(n));
  // Ghost slots in another order than the particles (a slot is not a particle index).
  for (int a = 0; a < n; ++a) {
    const auto slot = static_cast<std::size_t>(n - 1 - a);
    L.ghost_of[static_cast<std::size_t>(a)] = static_cast<std::uint32_t>(slot);
    for (int c = 0; c < 2; ++c)
      L.ghost[c][slot] = {p.x[a] + Vec3{1e-5 * c, 0.0, -2e-5}, p.v[a] * (0.5 + c), p.omega[a] * (2.0 + c)};
  }
  for (int c = 0; c < 2; ++c)
    for (std::size_t x = 0; x < L.cross_hist[c].size(); ++x) L.cross_hist[c][x] = 1e-6 * static_cast<double>(x + 7 * c);
  return s;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// One chunk of candidates q0 .. q1 through run() and through scalar() on copies of the list.
template <bool Part>
void check_chunk(const Setup& s, const std::uint32_t* ks, long q0, long q1, int me, int cur) {
  PairList La = s.L, Lb = s.L;
  FilterOut<kN> oa, ob;
  PairFilter<Part>{s.p, La, ks, me, cur}.run(q0, q1, oa);
  PairFilter<Part>{s.p, Lb, ks, me, cur}.scalar(q0, q1, ob);
  REQUIRE(oa.m == ob.m);
  for (long q = 0; q < oa.m; ++q) {
    CHECK(oa.idx[q] == ob.idx[q]);
    const std::uint32_t k = ob.idx[q] & ~PairList::kCrossBit;
    CHECK(oa.ia[q] == s.L.i[k]);
    CHECK(oa.ib[q] == s.L.j[k]);
    CHECK(ob.ia[q] == s.L.i[k]);
    CHECK(ob.ib[q] == s.L.j[k]);
    CHECK(same_bits(oa.sep.x[q], ob.sep.x[q]));
    CHECK(same_bits(oa.sep.y[q], ob.sep.y[q]));
    CHECK(same_bits(oa.sep.z[q], ob.sep.z[q]));
    CHECK(same_bits(oa.sep2[q], ob.sep2[q]));
    CHECK(same_bits(oa.rsums[q], ob.rsums[q]));
  }
  CHECK(La.touching == Lb.touching);
  CHECK(La.history == Lb.history);
  CHECK(La.cross_hist[0] == Lb.cross_hist[0]);
  CHECK(La.cross_hist[1] == Lb.cross_hist[1]);
}

}  // namespace

TEST_CASE("pair filter: eight candidates at a time give what one at a time gives, bit for bit") {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const Setup s = make(seed, 400, 1500);
    int touching = 0, opened = 0;
    {
      PairList L = s.L;
      FilterOut<kN> o;
      PairFilter<false>{s.p, L, nullptr, 0, 0}.scalar(0, kN, o);
      touching = static_cast<int>(o.m);
      for (long k = 0; k < kN; ++k) opened += s.L.touching[k] && !L.touching[k];
    }
    // The case is a real one: some touch, some do not, some contacts open.
    CHECK(touching > kN / 5);
    CHECK(touching < kN * 4 / 5);
    CHECK(opened > 5);
    // A single thread's list, whole chunks and a chunk whose end is not a multiple of eight.
    for (long q0 = 0; q0 < 1500; q0 += kN) check_chunk<false>(s, nullptr, q0, std::min<long>(1500, q0 + kN), 0, 0);
    check_chunk<false>(s, nullptr, 3, 3 + 61, 0, 0);
    // Each thread's part (cross pairs, runs of consecutive pairs and gaps), both buffers.
    for (int t = 0; t < 2; ++t) {
      const auto& ks = s.ks[t];
      CHECK(std::count_if(ks.begin(), ks.end(), [](std::uint32_t e) { return (e & PairList::kCrossBit) != 0; }) > 10);
      const long n = static_cast<long>(ks.size());
      for (long q0 = 0; q0 < n; q0 += kN)
        for (int cur = 0; cur < 2; ++cur) check_chunk<true>(s, ks.data(), q0, std::min(n, q0 + kN), t, cur);
    }
  }
}

TEST_CASE("pair filter: stage8 puts each pair's state in its lane, a cross pair's from the ghosts") {
  const Setup s = make(5, 300, 900);
  HertzMindlin::Batch B{};
  FilterOut<kN> o;
  PairList L = s.L;
  PairFilter<false>{s.p, L, nullptr, 0, 0}.scalar(0, kN, o);
  REQUIRE(o.m >= 16);
  const bool staged = stage8(B, 8, o.idx + 3, o.ia + 3, o.ib + 3, o.sep, o.sep2, o.rsums, 3, s.p, L, 0);
#if (defined(__AVX512F__) && defined(__AVX512VL__)) || defined(PASTEMIX_AVX2_LANES)
  REQUIRE(staged);
#else
  REQUIRE_FALSE(staged);  // neither AVX-512 nor AVX2: the pair pass stages one at a time
  return;
#endif
  for (int l = 0; l < 8; ++l) {
    const long q = 3 + l;
    const std::uint32_t k = o.idx[q], a = L.i[k], b = L.j[k];
    const int e = 8 + l;
    CHECK(same_bits(B.dx[e], o.sep.x[q]));
    CHECK(same_bits(B.dy[e], o.sep.y[q]));
    CHECK(same_bits(B.dz[e], o.sep.z[q]));
    CHECK(same_bits(B.dist2[e], o.sep2[q]));
    CHECK(same_bits(B.rsum[e], o.rsums[q]));
    CHECK(B.ra[e] == s.p.radius[a]);
    CHECK(B.rb[e] == s.p.radius[b]);
    CHECK(B.r_star[e] == L.r_star[k]);
    CHECK(B.m_star[e] == L.m_star[k]);
    CHECK(B.vax[e] == s.p.v[a].x);
    CHECK(B.vay[e] == s.p.v[a].y);
    CHECK(B.vaz[e] == s.p.v[a].z);
    CHECK(B.vbx[e] == s.p.v[b].x);
    CHECK(B.vby[e] == s.p.v[b].y);
    CHECK(B.vbz[e] == s.p.v[b].z);
    CHECK(B.wax[e] == s.p.omega[a].x);
    CHECK(B.way[e] == s.p.omega[a].y);
    CHECK(B.waz[e] == s.p.omega[a].z);
    CHECK(B.wbx[e] == s.p.omega[b].x);
    CHECK(B.wby[e] == s.p.omega[b].y);
    CHECK(B.wbz[e] == s.p.omega[b].z);
    CHECK(B.hx[e] == L.history[k * 3]);
    CHECK(B.hy[e] == L.history[k * 3 + 1]);
    CHECK(B.hz[e] == L.history[k * 3 + 2]);
  }
  // Lanes outside 8 .. 15 untouched.
  CHECK(B.ra[7] == 0.0);
  CHECK(B.ra[16] == 0.0);
  // A group with cross pairs (a thread's part, both buffers): those lanes read the ghost copies of both
  // particles and the spring in cross_hist[cur]; the others the store, as above.
  for (int cur = 0; cur < 2; ++cur) {
    std::vector<std::uint32_t> e8;
    for (std::uint32_t e : s.ks[1])
      if (e8.size() < 8 && ((e & PairList::kCrossBit) != 0 || e8.size() % 3 == 0)) e8.push_back(e);
    REQUIRE(e8.size() == 8);
    REQUIRE(std::count_if(e8.begin(), e8.end(), [](std::uint32_t e) { return (e & PairList::kCrossBit) != 0; }) >= 2);
    HertzMindlin::Batch C{};
    std::vector<std::uint32_t> a8, b8;
    for (std::uint32_t e : e8) a8.push_back(L.i[e & ~PairList::kCrossBit]), b8.push_back(L.j[e & ~PairList::kCrossBit]);
    REQUIRE(stage8(C, 0, e8.data(), a8.data(), b8.data(), o.sep, o.sep2, o.rsums, 0, s.p, L, cur));
    for (int l = 0; l < 8; ++l) {
      const bool cross_pair = (e8[l] & PairList::kCrossBit) != 0;
      const std::uint32_t k = e8[l] & ~PairList::kCrossBit, a = L.i[k], b = L.j[k];
      const Vec3 va = cross_pair ? L.state(a, cur).v : s.p.v[a], vb = cross_pair ? L.state(b, cur).v : s.p.v[b];
      const Vec3 wa = cross_pair ? L.state(a, cur).w : s.p.omega[a], wb = cross_pair ? L.state(b, cur).w : s.p.omega[b];
      const double* h = cross_pair ? &L.cross_hist[cur][L.cross[k] * 3] : &L.history[k * 3];
      CHECK(C.ra[l] == s.p.radius[a]);
      CHECK(C.rb[l] == s.p.radius[b]);
      CHECK(C.r_star[l] == L.r_star[k]);
      CHECK(C.vax[l] == va.x);
      CHECK(C.vby[l] == vb.y);
      CHECK(C.vbz[l] == vb.z);
      CHECK(C.way[l] == wa.y);
      CHECK(C.wbx[l] == wb.x);
      CHECK(C.waz[l] == wa.z);
      CHECK(C.hx[l] == h[0]);
      CHECK(C.hy[l] == h[1]);
      CHECK(C.hz[l] == h[2]);
      if (cross_pair) CHECK(C.vax[l] != s.p.v[a].x);  // the ghost, not the particle
    }
  }
}

#if defined(__AVX512F__) && defined(__AVX512VL__)
TEST_CASE("pair filter: rows8 and load8_pd load what the rows hold, the array's last row included") {
  // An array of exactly n rows (a vector sized to them, nothing after): the masked loads must not need a
  // fourth double past the last row, and each lane must get its own row's x, y, z.
  const std::size_t n = 37;
  std::vector<double> rows(3 * n), one(n);
  for (std::size_t r = 0; r < 3 * n; ++r) rows[r] = 0.5 + static_cast<double>(r) * 1.25;
  for (std::size_t r = 0; r < n; ++r) one[r] = -1.0 - static_cast<double>(r);
  const std::uint32_t id[8] = {36, 0, 17, 36, 5, 35, 1, 20};
  __m512d x, y, z;
  load_rows8(rows.data(), id, x, y, z);
  alignas(64) double gx[8], gy[8], gz[8], g1[8];
  _mm512_store_pd(gx, x), _mm512_store_pd(gy, y), _mm512_store_pd(gz, z);
  _mm512_store_pd(g1, load8_pd(one.data(), id));
  for (int l = 0; l < 8; ++l) {
    CAPTURE(l);
    CHECK(gx[l] == rows[3 * id[l]]);
    CHECK(gy[l] == rows[3 * id[l] + 1]);
    CHECK(gz[l] == rows[3 * id[l] + 2]);
    CHECK(g1[l] == one[id[l]]);
  }
}
#endif

#if defined(PASTEMIX_AVX2_LANES)
TEST_CASE("pair filter: rows4, load4_pd and the compress tables move what they should, the last row included") {
  const std::size_t n = 37;
  std::vector<double> rows(3 * n), one(n);
  for (std::size_t r = 0; r < 3 * n; ++r) rows[r] = 0.5 + static_cast<double>(r) * 1.25;
  for (std::size_t r = 0; r < n; ++r) one[r] = -1.0 - static_cast<double>(r);
  const std::uint32_t id[4] = {36, 0, 17, 35};
  __m256d x, y, z;
  avx2::load_rows4(rows.data(), id, x, y, z);
  alignas(32) double gx[4], gy[4], gz[4], g1[4];
  _mm256_store_pd(gx, x), _mm256_store_pd(gy, y), _mm256_store_pd(gz, z);
  _mm256_store_pd(g1, avx2::load4_pd(one.data(), id));
  for (int l = 0; l < 4; ++l) {
    CAPTURE(l);
    CHECK(gx[l] == rows[3 * id[l]]);
    CHECK(gy[l] == rows[3 * id[l] + 1]);
    CHECK(gz[l] == rows[3 * id[l] + 2]);
    CHECK(g1[l] == one[id[l]]);
  }
  // Every mask: its lanes, in order, at the front.
  for (unsigned mask = 0; mask < 16; ++mask) {
    alignas(32) double d[4];
    alignas(16) std::uint32_t u[4];
    _mm256_store_pd(d, avx2::compress_pd(mask, _mm256_setr_pd(10.5, 11.5, 12.5, 13.5)));
    _mm_store_si128(reinterpret_cast<__m128i*>(u), avx2::compress_epi32(mask, _mm_setr_epi32(20, 21, 22, 23)));
    int k = 0;
    for (int l = 0; l < 4; ++l)
      if ((mask >> l) & 1u) {
        CHECK(d[k] == 10.5 + l);
        CHECK(u[k] == static_cast<std::uint32_t>(20 + l));
        ++k;
      }
  }
}
#endif
