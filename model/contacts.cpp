// SPDX-License-Identifier: MIT
#include "model/contacts.h"

#include "model/pair_filter.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <variant>

#include <omp.h>

namespace pastemix::model {

namespace {

// Candidates are taken in chunks: a branch-free filter pass finds the touching pairs of the chunk (keeping
// their separation vectors), then a dense pass computes their forces. About 40 % of the candidates of a
// settled bed are not touching; a mixed loop mispredicted the "touching?" branch. What a chunk costs beside
// its pairs (the switch from the filter's sequential sweep of the pair arrays to the staging's scattered
// loads and back, a part batch, a scalar tail) came every 33 touching pairs in a chapter-7 pour with chunks
// of 256 candidates (7.7 candidates per touching pair). Chunks of 2,048 (the filter's output ~106 kB of
// stack, its used part in L1 or L2): the same pairs in the same order, so the same bits; contact stage in
// interleaved runs against 256 (issue 19, session 36): chapter-7 segment, 1 thread, 7.3 / 10.7 -> 5.6 /
// 8.0 s; bench bed 0.783 -> 0.726 s (1 thread), 0.521 -> 0.485 s (2), pour 0.182 -> 0.166 s, 0.133 ->
// 0.123 s (min of 4); case-3 segment, 2 threads, 4.5 / 4.6 -> 4.2 / 4.3 s. The tail alone is not the cause:
// padding the last group to eight lanes (staged and computed whole) changed neither 256's nor 2,048's
// times beyond the noise.
constexpr long kChunk = 2048;

using Separations = model::Separations<kChunk>;

// The force sums' accumulators of a thread's particles (f, and with rotation torque and rolling capacity; each
// particle's sum starts at +0) set to zero just ahead of the pair pass's sweep instead of all at its start: a
// chunk's touching pairs zero every owned particle up to their highest index (model/contacts.h: a pair is
// (lower, higher)) before their forces are added, so the lines of the partners' sums are written shortly
// before the pair pass adds to them. Zeroed all at the start, a chapter-7 pour's partners' f and torque had
// left the caches by then: perf put ~20 % of the pair pass's samples on their two loads (1 thread, t = 0.5 s,
// 65k spheres); zeroed ahead, that segment's contact stage took 10-20 % less on 1 thread and the 207k pour's ~10 %
// less, while 2 threads (each half of the pile in its core's caches) and 13k spheres did not change (issue 19,
// session 40). The same +0 before the same sums in the same order: the same bits.
class LazyZero {
 public:
  // own: the thread's particles, ascending; null: all of p's particles.
  LazyZero(Particles& p, const std::vector<std::uint32_t>* own)
      : p_(p), own_(own), n_(own ? own->size() : p.size()), rot_(p.has_rotation) {}
  // Zeroes every owned particle with an index <= last not zeroed yet.
  void upto(std::size_t last) {
    if (!own_) {
      const std::size_t e = std::min(n_, last + 1);
      if (s_ < e) zero(s_, e - s_), s_ = e;
      return;
    }
    const std::vector<std::uint32_t>& own = *own_;
    while (s_ < n_ && own[s_] <= last) {
      std::size_t e = s_ + 1;  // a run of consecutive indices, zeroed as a block
      while (e < n_ && own[e] == own[e - 1] + 1 && own[e] <= last) ++e;
      zero(own[s_], e - s_);
      s_ = e;
    }
  }
  // The particles m touching pairs (second particles ib) may add to.
  void ahead_of(const std::uint32_t* ib, long m) {
    std::uint32_t last = 0;
    for (long q = 0; q < m; ++q) last = std::max(last, ib[q]);
    if (m > 0) upto(last);
  }
  // Every owned particle not zeroed yet (upto's last + 1 must not wrap).
  void rest() { upto(std::numeric_limits<std::size_t>::max() - 1); }

 private:
  void zero(std::size_t a0, std::size_t len) {
    const auto at = static_cast<std::ptrdiff_t>(a0), n = static_cast<std::ptrdiff_t>(len);
    std::fill_n(p_.f.begin() + at, n, Vec3{});
    if (rot_) {
      std::fill_n(p_.torque.begin() + at, n, Vec3{});
      std::fill_n(p_.rolling_capacity.begin() + at, n, 0.0);
    }
  }
  Particles& p_;
  const std::vector<std::uint32_t>* own_;
  std::size_t n_, s_ = 0;  // s_: the next owned entry (own_) or index (all) to zero
  bool rot_;
};

// Pairs ks[q0 .. q1) (Part = true: pair indices of this thread's list; false: ks = null, pairs q0 .. q1
// of the whole list, one thread owning every particle). Forces are added to the owned particles
// ([lo, hi)) in ascending pair order. Part: a cross pair (both threads compute it) reads its history from
// cross_hist[cur]; the owner of i writes the new one into cross_hist[1 - cur] and its touching flag, the
// other thread works on a private copy.
// The dense part of pair_chunk for a law with a batch kernel (with its tangential spring, rotation, no
// rolling spring): the touching pairs idx[0 .. m) staged kBatch at a time into lanes, computed
// by Law::force_batch (the same bits as Law::force, several contacts per instruction), then added to the
// owned particles in ascending pair order, as the scalar loop does.
template <class Law, class Roll, bool Part>
void batch_chunk(const std::vector<typename Law::Params>& table, const std::vector<typename Roll::Params>& rolling,
                 const StepContext& ctx, Particles& p, PairList& L, const std::uint32_t* idx, const std::uint32_t* ia,
                 const std::uint32_t* ib, const Separations& sep, const double* sep2, const double* rsums, long m,
                 int me, int cur) {
  typename Law::Batch B;
  // One law for every pair (one material, the common case): its parameters in every lane, once.
  const std::uint32_t law0 = L.uniform_law;
  if (law0 != PairList::kNone)
    for (int e = 0; e < Law::kBatch; ++e) Law::load_params(B, e, table[law0]);
  for (long q0 = 0; q0 < m; q0 += Law::kBatch) {
    const int nb = static_cast<int>(std::min<long>(Law::kBatch, m - q0));
    // Lane e: pair idx[q0 + e]'s state (a cross pair's from the ghost copies and its history buffer).
    const auto stage = [&](int e) {
      const long q = q0 + e;
      const std::uint32_t k = idx[q] & ~PairList::kCrossBit;
      const std::uint32_t a = ia[q], b = ib[q];
      B.dx[e] = sep.x[q], B.dy[e] = sep.y[q], B.dz[e] = sep.z[q];
      B.dist2[e] = sep2[q];
      B.rsum[e] = rsums[q];
      B.ra[e] = p.radius[a], B.rb[e] = p.radius[b];
      B.r_star[e] = L.r_star[k], B.m_star[e] = L.m_star[k];
      const bool cross_pair = Part && (idx[q] & PairList::kCrossBit) != 0;
      Vec3 va, vb, wa, wb;
      const double* h;
      if (cross_pair) {
        const PairList::Ghost &ga = L.state(a, cur), &gb = L.state(b, cur);
        va = ga.v, vb = gb.v, wa = ga.w, wb = gb.w;
        h = &L.cross_hist[cur][L.cross[k] * 3];
      } else {
        va = p.v[a], vb = p.v[b], wa = p.omega[a], wb = p.omega[b];
        h = &L.history[k * 3];
      }
      B.vax[e] = va.x, B.vay[e] = va.y, B.vaz[e] = va.z, B.vbx[e] = vb.x, B.vby[e] = vb.y, B.vbz[e] = vb.z;
      B.wax[e] = wa.x, B.way[e] = wa.y, B.waz[e] = wa.z, B.wbx[e] = wb.x, B.wby[e] = wb.y, B.wbz[e] = wb.z;
      B.hx[e] = h[0], B.hy[e] = h[1], B.hz[e] = h[2];
    };
    int l0 = 0;
    // Eight lanes at a time by gathers where the build has AVX-512 (model/pair_filter.h: stage8).
    for (; l0 + 8 <= nb; l0 += 8)
      if (!stage8(B, l0, idx + q0 + l0, ia + q0 + l0, ib + q0 + l0, sep, sep2, rsums, q0 + l0, p, L, cur))
        for (int l = l0; l < l0 + 8; ++l) stage(l);
    for (; l0 < nb; ++l0) stage(l0);
    if (law0 == PairList::kNone)
      for (int l = 0; l < nb; ++l) Law::load_params(B, l, table[L.law_index[idx[q0 + l] & ~PairList::kCrossBit]]);
    Law::force_batch(B, nb, ctx.dt);
    for (int e = 0; e < nb; ++e) {
      const std::uint32_t k = idx[q0 + e] & ~PairList::kCrossBit;
      const std::uint32_t a = ia[q0 + e], b = ib[q0 + e];
      // A pair of this thread's list that does not cross has both particles here.
      const bool cross_pair = Part && (idx[q0 + e] & PairList::kCrossBit) != 0;
      const bool own_a = !cross_pair || L.owner[a] == me;
      const bool own_b = !cross_pair || L.owner[b] == me;
      // The new spring: in place, or (a cross pair) into the next buffer by the owner of i only.
      double* h = cross_pair ? (own_a ? &L.cross_hist[cur ^ 1][L.cross[k] * 3] : nullptr) : &L.history[k * 3];
      if (h) h[0] = B.hx[e], h[1] = B.hy[e], h[2] = B.hz[e];
      const Vec3 force{B.fx[e], B.fy[e], B.fz[e]}, nxt{B.tx[e], B.ty[e], B.tz[e]};
      const double arm_a = B.arm_a[e], arm_b = B.arm_b[e];
      const auto& rp = rolling[law0 != PairList::kNone ? law0 : L.law_index[k]];
      if (own_a) {
        p.f[a] += force;
        p.torque[a] += nxt * arm_a;
        if constexpr (Roll::kick_friction) p.rolling_capacity[a] += Roll::capacity(rp, B.fn[e], arm_a, B.r_star[e]);
      }
      if (own_b) {
        p.f[b] -= force;
        p.torque[b] += nxt * arm_b;
        if constexpr (Roll::kick_friction) p.rolling_capacity[b] += Roll::capacity(rp, B.fn[e], arm_b, B.r_star[e]);
      }
    }
  }
}

template <class Law, class Roll, bool Part>
void pair_chunk(const std::vector<typename Law::Params>& table, const std::vector<typename Roll::Params>& rolling,
                const StepContext& ctx, Particles& p, PairList& L, const std::uint32_t* ks, long q0, long q1, int me,
                int cur, LazyZero& zero) {
  const bool rot = p.has_rotation;
  constexpr bool constant_roll = Roll::kick_friction;
  // Only a rolling law with a contact moment (a spring) reads the relative rotation. Without one the
  // torque terms skip "+ 0": x + (+0) differs from x only for x = -0, and a torque sum that starts at +0
  // never becomes -0 (round to nearest), so adding -0 or +0 to it gives the same bits.
  constexpr bool spring_roll = Roll::history_size > 0;
  const int w = L.width;
  const std::size_t ws = static_cast<std::size_t>(w);
  // The filter (model/pair_filter.h): the chunk's touching pairs, their separations and springs' state.
  FilterOut<kChunk> out;
  PairFilter<Part>{p, L, ks, me, cur}.run(q0, q1, out);
  const std::uint32_t *idx = out.idx, *ia = out.ia, *ib = out.ib;
  const Separations& sep = out.sep;
  const double *sep2 = out.sep2, *rsums = out.rsums;
  const long m = out.m;
  zero.ahead_of(ib, m);
  if constexpr (requires { Law::force_batch; }) {
    if (w == Law::history_size && rot && !spring_roll) {
      batch_chunk<Law, Roll, Part>(table, rolling, ctx, p, L, idx, ia, ib, sep, sep2, rsums, m, me, cur);
      return;
    }
  }
  double scratch[kMaxHistory];
  for (long q = 0; q < m; ++q) {
    const std::uint32_t k = idx[q] & ~PairList::kCrossBit;
    const std::uint32_t a = ia[q], b = ib[q];
    const bool cross_pair = Part && (idx[q] & PairList::kCrossBit) != 0;
    const bool own_a = !cross_pair || L.owner[a] == me;
    const bool own_b = !cross_pair || L.owner[b] == me;
    const Vec3 d{sep.x[q], sep.y[q], sep.z[q]};
    const double rsum = rsums[q];
    double* hist = w ? &L.history[k * ws] : nullptr;
    if (cross_pair && w) {
      const double* old = &L.cross_hist[cur][L.cross[k] * ws];
      hist = own_a ? &L.cross_hist[cur ^ 1][L.cross[k] * ws] : scratch;
      std::copy_n(old, w, hist);
    }
    const double dist = std::sqrt(sep2[q]);
    typename Law::Geometry g;
    g.n = d * (1.0 / dist);
    g.overlap = rsum - dist;
    const double arm_a = p.radius[a] - 0.5 * g.overlap, arm_b = p.radius[b] - 0.5 * g.overlap;
    g.R_star = L.r_star[k];
    g.m_star = L.m_star[k];
    Vec3 va, vb, wa, wb;
    if (cross_pair) {
      const PairList::Ghost &ga = L.state(a, cur), &gb = L.state(b, cur);
      va = ga.v, vb = gb.v, wa = ga.w, wb = gb.w;
    } else {
      va = p.v[a], vb = p.v[b];
      if (rot) wa = p.omega[a], wb = p.omega[b];
    }
    g.v_rel = vb - va;
    if (rot) {
      // omega_b x (-arm_b n) - omega_a x (arm_a n) = -(arm_a omega_a + arm_b omega_b) x n: one cross.
      g.v_rel -= cross(wa * arm_a + wb * arm_b, g.n);
      if (spring_roll) g.w_rel = wa - wb;
    }
    g.arm_i = arm_a;
    g.dt = ctx.dt;
    const auto& prm = table[L.law_index[k]];
    const auto r = Law::force(prm, g, hist, w);
    const auto& rp = rolling[L.law_index[k]];
    Vec3 moment;  // N.m on a, the opposite on b
    if constexpr (spring_roll)
      moment = Roll::moment(rp, {g.w_rel, r.normal_stiffness, r.normal_force, g.R_star, g.m_star, g.dt},
                            hist + Law::history_size);
    const Vec3 nxt = rot ? cross(g.n, r.tangential_i) : Vec3{};  // (arm n) x F_t = arm (n x F_t)
    if (own_a) {
      p.f[a] += r.force_i;
      if (rot) {
        p.torque[a] += spring_roll ? nxt * arm_a + moment : nxt * arm_a;
        if constexpr (constant_roll) p.rolling_capacity[a] += Roll::capacity(rp, r.normal_force, arm_a, g.R_star);
      }
    }
    if (own_b) {
      p.f[b] -= r.force_i;
      if (rot) {
        p.torque[b] += spring_roll ? nxt * arm_b - moment : nxt * arm_b;
        if constexpr (constant_roll) p.rolling_capacity[b] += Roll::capacity(rp, r.normal_force, arm_b, g.R_star);
      }
    }
  }
}

template <class Law, class Roll>
void pair_pass(const std::vector<typename Law::Params>& table, const std::vector<typename Roll::Params>& rolling,
               const StepContext& ctx, Particles& p, PairList& L, int thread, int parity) {
  const bool part = L.threads > 1;
  LazyZero zero(p, part ? &L.own[static_cast<std::size_t>(thread)] : nullptr);
  if (part) {
    // Segment by segment, in list order (each particle's sum still runs in ascending pair order): a run's
    // pairs as one thread's list, by pair index; the rest through the entries.
    const auto& ks = L.mine[thread];
    for (const PairList::Segment& seg : L.segments[thread]) {
      if (seg.run) {
        const long k0 = ks[seg.q0], k1 = k0 + (seg.q1 - seg.q0);
        for (long k = k0; k < k1; k += kChunk)
          pair_chunk<Law, Roll, false>(table, rolling, ctx, p, L, nullptr, k, std::min(k1, k + kChunk), 0, 0, zero);
        continue;
      }
      for (long q = seg.q0; q < seg.q1; q += kChunk)
        pair_chunk<Law, Roll, true>(table, rolling, ctx, p, L, ks.data(), q, std::min<long>(seg.q1, q + kChunk),
                                    thread, parity, zero);
    }
  } else {
    const long n = static_cast<long>(L.size());
    for (long q = 0; q < n; q += kChunk)
      pair_chunk<Law, Roll, false>(table, rolling, ctx, p, L, nullptr, q, std::min(n, q + kChunk), 0, 0, zero);
  }
  zero.rest();  // the owned particles no touching pair reaches
}

}  // namespace

void PairList::rebuild(CandidatePairs& c, const Particles& p, int n_materials, int loop_threads) {
  YieldBarrier barrier;
  run_team(loop_threads, barrier, [&](const Team& t) { rebuild(c, p, n_materials, t); });
  index_by_first(p.size());
}

void PairList::rebuild(CandidatePairs& c, const Particles& p, int n_materials, const Team& t) {
  const std::size_t n = c.i.size();
  // The new history and flags go into the spare buffers (their capacity kept between rebuilds).
  std::vector<double>& new_hist = spare_hist;
  std::vector<std::uint32_t>& new_touch = spare_touch;
  // Sized here, filled (a carried spring or zeros) by the threads' loops: a serial zero-fill of the whole
  // history (~1 MB for a 13k pour) was then written again by both threads.
  if (t.me == 0) {
    new_hist.resize(n * static_cast<std::size_t>(width));
    new_touch.resize(n);
    r_star.resize(n);
    m_star.resize(n);
    rsum.resize(n);
    law_index.resize(n);
    law_range.assign(static_cast<std::size_t>(t.size), {kNone, 0});
  }
  t.sync();
  // History carry-over: a new pair (a, b) looks for (a, b) among the old pairs of a (its old CSR row, a
  // few entries). Only touching pairs carry a spring (a pair stops touching -> its history is zeroed).
  // Dense indices are the same in both lists (a removal or a spatial sort renames the old list first:
  // rename()), so (a, b) names the same two particles in both, and a < b in both (build_pairs; rename()
  // keeps its pairs (lower, higher), negating the springs of a swapped pair).
  const bool carry = !start.empty() && width > 0;
  std::uint32_t law_lo = kNone, law_hi = 0;
  long k0 = 0, k1 = 0;
  t.range(static_cast<long>(n), k0, k1);
  // The pairs' constants in a loop of their own, without the carry-over's search: it vectorises (gathers,
  // eight divisions per instruction; one loop, stalled on the loads and divisions of one pair at a time, was
  // 5.8 % of chapter-7 test 2's run).
  {
    const std::uint32_t *ci = c.i.data(), *cj = c.j.data();
    const double *rad = p.radius.data(), *mass = p.mass.data();
    const int* mat = p.material.data();
    double *rs = r_star.data(), *ms = m_star.data(), *sum = rsum.data();
    std::uint32_t* law = law_index.data();
#pragma omp simd
    for (long k = k0; k < k1; ++k) {
      const std::uint32_t a = ci[k], b = cj[k];
      rs[k] = rad[a] * rad[b] / (rad[a] + rad[b]);
      ms[k] = mass[a] * mass[b] / (mass[a] + mass[b]);
      sum[k] = rad[a] + rad[b];
      law[k] = static_cast<std::uint32_t>(mat[a] * n_materials + mat[b]);
    }
  }
  // The new list comes from the same search of spheres that moved less than the skin, so most of it is the
  // old list in the same order: the old pair after the last one found is tried first (one comparison), the
  // old row of a only where the lists part (a pair that came or went, a scan whose order changed). The old
  // pair found is the same either way (pairs are unique), so the springs carried are too. (The row search for
  // every pair was ~55 % of this function's samples, the bench pour at 1 thread.)
  const std::uint32_t n_old = static_cast<std::uint32_t>(i.size());
  std::uint32_t next = n_old;  // the old pair after the last one found
  for (long k = k0; k < k1; ++k) {
    const std::uint32_t a = c.i[k], b = c.j[k];
    law_lo = std::min(law_lo, law_index[k]);
    law_hi = std::max(law_hi, law_index[k]);
    std::uint32_t from = kNone;  // the old pair whose spring (a, b) carries, if any
    if (carry) {
      std::uint32_t same = kNone;  // the old pair (a, b), if any
      if (next < n_old && i[next] == a && j[next] == b) {
        same = next;
      } else {
        for (std::uint32_t e = start[a]; e < start[a + 1]; ++e)
          if (j[entry[e]] == b) {
            same = entry[e];
            break;
          }
      }
      if (same != kNone) {
        next = same + 1;
        if (touching[same]) from = same;
      }
    }
    new_touch[k] = from != kNone;
    double* h = new_hist.data() + static_cast<std::size_t>(k) * width;
    if (from != kNone)
      std::copy_n(&history[static_cast<std::size_t>(from) * width], width, h);
    else
      std::fill_n(h, width, 0.0);
  }
  law_range[static_cast<std::size_t>(t.me)] = {law_lo, law_hi};
  t.sync();
  if (t.me != 0) return;  // the rest in thread 0; the caller syncs before the list is read
  for (const auto& [lo, hi] : law_range) law_lo = std::min(law_lo, lo), law_hi = std::max(law_hi, hi);
  uniform_law = n > 0 && law_lo == law_hi ? law_lo : kNone;
  i.swap(c.i);
  j.swap(c.j);
  history.swap(new_hist);
  touching.swap(new_touch);
  threads = 0;  // partition() again
}

void PairList::find_uniform_law() {
  uniform_law = law_index.empty() ? kNone : law_index[0];
  for (std::uint32_t e : law_index)
    if (e != uniform_law) uniform_law = kNone;
}

// CSR by first particle (the carry-over at the next rebuild looks up (a, b) among the pairs with i = a):
// count, prefix sums, fill with start as the cursor, shift back by one.
void PairList::index_by_first(std::size_t np) {
  const std::size_t n = i.size();
  start.assign(np + 1, 0);
  for (std::size_t k = 0; k < n; ++k) ++start[i[k] + 1];
  for (std::size_t q = 0; q < np; ++q) start[q + 1] += start[q];
  entry.resize(n);
  for (std::size_t k = 0; k < n; ++k) entry[start[i[k]]++] = static_cast<std::uint32_t>(k);
  for (std::size_t q = np; q >= 1; --q) start[q] = start[q - 1];
  start[0] = 0;
}

void PairList::rename(const std::vector<std::uint32_t>& map, std::size_t np) {
  const std::size_t n = i.size(), ws = static_cast<std::size_t>(width);
  std::size_t out = 0;
  for (std::size_t k = 0; k < n; ++k) {
    std::uint32_t a = map[i[k]], b = map[j[k]];
    if (a == Particles::kGone || b == Particles::kGone) continue;
    // A pair stays (lower index, higher index). A permutation may swap its ends: the springs are then
    // seen from the other particle, so they change sign (the tangential spring follows v_rel = v_j - v_i,
    // the rolling one w_i - w_j: both odd under i <-> j; negation is exact).
    const bool swap = a > b;
    if (swap) std::swap(a, b);
    i[out] = a;
    j[out] = b;
    r_star[out] = r_star[k];
    m_star[out] = m_star[k];
    rsum[out] = rsum[k];
    law_index[out] = law_index[k];
    touching[out] = touching[k];
    double* h = history.data() + out * ws;
    std::copy_n(history.data() + k * ws, ws, h);  // out <= k: a forward copy
    if (swap)
      for (std::size_t e = 0; e < ws; ++e) h[e] = -h[e];
    ++out;
  }
  i.resize(out);
  j.resize(out);
  r_star.resize(out);
  m_star.resize(out);
  rsum.resize(out);
  law_index.resize(out);
  touching.resize(out);
  history.resize(out * ws);
  threads = 0;
  index_by_first(np);
}

void PairList::fill_ghosts(const Particles& p) {
  for (std::size_t g = 0; g < ghosts.size(); ++g) {
    const std::uint32_t q = ghosts[g];
    ghost[parity][g] = {p.x[q], p.v[q], p.has_rotation ? p.omega[q] : Vec3{}};
  }
}

void PairList::sync_cross() {
  const std::size_t ws = static_cast<std::size_t>(width);
  if (threads <= 1 || ws == 0) return;
  for (std::size_t c = 0; c < cross_pairs.size(); ++c)
    std::copy_n(&cross_hist[parity][c * ws], ws, &history[cross_pairs[c] * ws]);
}

void pair_forces(const LawTable& laws, const RollingTable& rolling, const StepContext& ctx, Particles& p,
                 PairList& pairs, int thread, int parity) {
  std::visit(
      [&](const auto& table, const auto& roll) {
        pair_pass<LawOf<decltype(table)>, LawOf<decltype(roll)>>(table, roll, ctx, p, pairs, thread, parity);
      },
      laws, rolling);
}

void WallState::update(const std::vector<Wall>& walls, double t) {
  const std::size_t nw = walls.size();
  shift.resize(nw);
  vel.resize(nw);
  origin.resize(nw);
  active.resize(nw);
  rect.resize(nw);
  for (std::size_t k = 0; k < nw; ++k) {
    shift[k] = walls[k].displacement(t);
    origin[k] = walls[k].origin + shift[k];
    rect[k] = walls[k].kind == WallKind::rectangle;
    vel[k] = walls[k].velocity_at(t);
    active[k] = walls[k].active(t);
  }
}

}  // namespace pastemix::model
