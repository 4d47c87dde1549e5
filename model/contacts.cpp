// SPDX-License-Identifier: MIT
#include "model/contacts.h"

#include "model/parallel.h"

#include <algorithm>
#include <variant>

#include <omp.h>

namespace pastemix::model {

namespace {

// Candidates are taken in chunks small enough for L1: a branch-free filter pass finds the touching pairs
// of the chunk (keeping their separation vectors), then a dense pass computes their forces. About 40 % of
// the candidates of a settled bed are not touching; a mixed loop mispredicted the "touching?" branch.
constexpr long kChunk = 256;

// Direct = false: each touching pair writes its two gather slots (summed afterwards, in parallel). Direct = true (one
// thread): the forces are added to the particles in ascending pair order right away, which is exactly the
// order the gather uses (its CSR lists each particle's pairs in ascending order), so both give the same bits.
template <class Law, bool Direct>
void pair_chunk(const std::vector<typename Law::Params>& table, const StepContext& ctx, Particles& p, PairList& L,
                long k0, long k1) {
  const bool rot = p.has_rotation;
  const bool constant_roll = ctx.rolling == RollingLaw::constant_torque;
  // Only the elastic-plastic law reads the relative rotation and returns a rolling torque. Without it the
  // torque terms skip "+ 0": x + (+0) differs from x only for x = -0, and a torque sum that starts at +0
  // never becomes -0 (round to nearest), so adding -0 or +0 to it gives the same bits.
  const bool spring_roll = ctx.rolling == RollingLaw::elastic_plastic;
  const int w = L.width;
  std::uint32_t idx[kChunk];
  Vec3 sep[kChunk];
  double sep2[kChunk], rsums[kChunk];
  long m = 0;
  for (long k = k0; k < k1; ++k) {
    const std::uint32_t a = L.i[k], b = L.j[k];
    const Vec3 d = p.x[b] - p.x[a];
    const double rsum = p.radius[a] + p.radius[b];
    const double dist2 = norm2(d);
    const bool touch = !(dist2 >= rsum * rsum);
    idx[m] = static_cast<std::uint32_t>(k);
    sep[m] = d;
    sep2[m] = dist2;
    rsums[m] = rsum;
    m += touch;
    // Not touching: forget the springs (a new contact starts from zero displacement) and clear the pair's
    // gather slots (the gather adds every slot of a particle).
    if (!touch && L.touching[k]) {
      std::fill_n(&L.history[static_cast<std::size_t>(k) * w], w, 0.0);
      L.slots[L.slot_i[k]] = PairList::Slot{};
      L.slots[L.slot_j[k]] = PairList::Slot{};
    }
    L.touching[k] = touch;
  }
  for (long q = 0; q < m; ++q) {
    const std::uint32_t k = idx[q];
    const std::uint32_t a = L.i[k], b = L.j[k];
    const Vec3 d = sep[q];
    const double rsum = rsums[q];
    double* hist = w ? &L.history[static_cast<std::size_t>(k) * w] : nullptr;
    const double dist = std::sqrt(sep2[q]);
    typename Law::Geometry g;
    g.n = d * (1.0 / dist);
    g.overlap = rsum - dist;
    const double arm_a = p.radius[a] - 0.5 * g.overlap, arm_b = p.radius[b] - 0.5 * g.overlap;
    g.R_star = L.r_star[k];
    g.m_star = L.m_star[k];
    g.v_rel = p.v[b] - p.v[a];
    if (rot) {
      // omega_b x (-arm_b n) - omega_a x (arm_a n) = -(arm_a omega_a + arm_b omega_b) x n: one cross.
      g.v_rel -= cross(p.omega[a] * arm_a + p.omega[b] * arm_b, g.n);
      if (spring_roll) g.w_rel = p.omega[a] - p.omega[b];
    }
    g.arm_i = arm_a;
    g.dt = ctx.dt;
    const auto& prm = table[L.law_index[k]];
    const auto r = Law::force(prm, g, hist, w);
    if constexpr (Direct) {
      p.f[a] += r.force_i;
      p.f[b] -= r.force_i;
      if (rot) {
        const Vec3 nxt = cross(g.n, r.tangential_i);  // (arm n) x F_t = arm (n x F_t): one cross per pair
        p.torque[a] += spring_roll ? nxt * arm_a + r.rolling_torque_i : nxt * arm_a;
        p.torque[b] += spring_roll ? nxt * arm_b - r.rolling_torque_i : nxt * arm_b;
        if (constant_roll) {
          p.rolling_capacity[a] += prm.rolling_friction * r.normal_force * arm_a;
          p.rolling_capacity[b] += prm.rolling_friction * r.normal_force * arm_b;
        }
      }
    } else {
      PairList::Slot& oi = L.slots[L.slot_i[k]];
      PairList::Slot& oj = L.slots[L.slot_j[k]];
      oi.f = r.force_i;
      oj.f = -r.force_i;
      if (rot) {
        const Vec3 nxt = cross(g.n, r.tangential_i);
        oi.t = spring_roll ? nxt * arm_a + r.rolling_torque_i : nxt * arm_a;
        oj.t = spring_roll ? nxt * arm_b - r.rolling_torque_i : nxt * arm_b;
        if (constant_roll) {
          oi.roll = prm.rolling_friction * r.normal_force * arm_a;
          oj.roll = prm.rolling_friction * r.normal_force * arm_b;
        }
      }
    }
  }
}

// Orphaned worksharing: called inside the World's parallel region the chunks are shared by its threads
// (and the implicit barrier at the end of `omp for` / `omp single` is the one the gather needs); called
// outside any region it runs on the calling thread alone.
template <class Law, bool Direct>
void pair_pass(const std::vector<typename Law::Params>& table, const StepContext& ctx, Particles& p,
               PairList& L) {
  const long n = static_cast<long>(L.size());
  const long chunks = (n + kChunk - 1) / kChunk;
  if constexpr (Direct) {
#pragma omp single
    {
      std::fill(p.f.begin(), p.f.end(), Vec3{});
      if (p.has_rotation) {
        std::fill(p.torque.begin(), p.torque.end(), Vec3{});
        std::fill(p.rolling_capacity.begin(), p.rolling_capacity.end(), 0.0);
      }
      for (long c = 0; c < chunks; ++c) pair_chunk<Law, true>(table, ctx, p, L, c * kChunk, std::min(n, (c + 1) * kChunk));
    }
  } else {
    // Dynamic: on a shared machine a thread that lost its core does not hold up the others.
#pragma omp for schedule(dynamic, 4)
    for (long c = 0; c < chunks; ++c) pair_chunk<Law, false>(table, ctx, p, L, c * kChunk, std::min(n, (c + 1) * kChunk));
  }
}

}  // namespace

void WallContacts::resize(std::size_t particles, int n_walls, int history_width) {
  walls = n_walls;
  width = history_width;
  start.assign(particles + 1, 0);
  near.clear();
  history.clear();
  touching.clear();
}

void WallContacts::rebuild(const std::vector<Wall>& w, const Particles& p, double t, double skin) {
  const std::size_t n = p.size();
  const std::size_t nw = w.size();
  std::vector<Vec3> shift(nw);
  std::vector<char> active(nw);
  for (std::size_t k = 0; k < nw; ++k) {
    shift[k] = w[k].displacement(t);
    active[k] = w[k].active(t);
  }
  // Candidate flags in parallel (one distance per particle and wall), then the CSR in order.
  std::vector<char> cand(n * nw, 0);
  const long nn = static_cast<long>(n);
#pragma omp parallel for schedule(static) if (nn >= parallel_min_items)
  for (long a = 0; a < nn; ++a) {
    const double reach = p.radius[a] + skin;
    for (std::size_t k = 0; k < nw; ++k) {
      bool candidate = false;
      // The bound only skips walls that are clearly out of reach (the margin absorbs its round-off).
      if (active[k] && wall_distance_bound(w[k], shift[k], p.x[a]) < reach * (1.0 + 1e-9)) {
        Vec3 unused;
        candidate = wall_distance(w[k], shift[k], p.x[a], &unused) < reach;
      }
      cand[static_cast<std::size_t>(a) * nw + k] = candidate;
    }
  }
  std::vector<std::uint32_t> new_start(n + 1, 0);
  std::vector<std::uint16_t> new_near;
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t k = 0; k < nw; ++k)
      if (cand[a * nw + k]) new_near.push_back(static_cast<std::uint16_t>(k));
    new_start[a + 1] = static_cast<std::uint32_t>(new_near.size());
  }
  // History carry-over, per particle from its old candidates (a few entries).
  const std::size_t wd = static_cast<std::size_t>(width);
  std::vector<double> new_hist(new_near.size() * wd, 0.0);
  std::vector<std::uint32_t> new_touch(new_near.size(), 0);
#pragma omp parallel for schedule(static) if (nn >= parallel_min_items)
  for (long a = 0; a < nn; ++a) {
    for (std::uint32_t c = new_start[a]; c < new_start[a + 1]; ++c)
      for (std::uint32_t o = start[a]; o < start[a + 1]; ++o) {
        if (near[o] != new_near[c]) continue;
        if (touching[o]) {
          new_touch[c] = 1;
          std::copy_n(&history[o * wd], wd, &new_hist[c * wd]);
        }
        break;
      }
  }
  start = std::move(new_start);
  near = std::move(new_near);
  history = std::move(new_hist);
  touching = std::move(new_touch);
}

void PairList::rebuild(const CandidatePairs& c, const Particles& p, int n_materials) {
  const std::size_t n = c.i.size();
  std::vector<double> new_hist(n * static_cast<std::size_t>(width), 0.0);
  std::vector<std::uint32_t> new_touch(n, 0);
  r_star.resize(n);
  m_star.resize(n);
  law_index.resize(n);
  // History carry-over: a new pair (a, b) looks for (a, b) among the old pairs of a (its old CSR row, a
  // few entries). Only touching pairs carry a spring (a pair stops touching -> its history is zeroed).
  // Dense indices are stable (particles are never reordered or removed), so (a, b) names the same two
  // particles in both lists, and a < b in both (build_pairs), so the stored spring needs no sign flip.
  const bool carry = !start.empty() && width > 0;
  const long nn = static_cast<long>(n);
#pragma omp parallel for schedule(static) if (nn >= parallel_min_items)
  for (long k = 0; k < nn; ++k) {
    const std::uint32_t a = c.i[k], b = c.j[k];
    r_star[k] = p.radius[a] * p.radius[b] / (p.radius[a] + p.radius[b]);
    m_star[k] = p.mass[a] * p.mass[b] / (p.mass[a] + p.mass[b]);
    law_index[k] = static_cast<std::uint32_t>(p.material[a] * n_materials + p.material[b]);
    if (!carry) continue;
    for (std::uint32_t e = start[a]; e < start[a + 1]; ++e) {
      if (entry[e] & 1u) continue;  // a is j of that old pair: not (a, b) with a < b
      const std::uint32_t old = entry[e] >> 1;
      if (j[old] != b) continue;
      if (touching[old]) {
        new_touch[k] = 1;
        std::copy_n(&history[static_cast<std::size_t>(old) * width], width,
                    &new_hist[static_cast<std::size_t>(k) * width]);
      }
      break;
    }
  }
  i = c.i;
  j = c.j;
  history = std::move(new_hist);
  touching = std::move(new_touch);
  slots.assign(2 * n, Slot{});
  slot_i.resize(n);
  slot_j.resize(n);
  // CSR per particle, entries in ascending pair order.
  const std::size_t np = p.size();
  start.assign(np + 1, 0);
  for (std::size_t k = 0; k < n; ++k) {
    ++start[i[k] + 1];
    ++start[j[k] + 1];
  }
  for (std::size_t q = 0; q < np; ++q) start[q + 1] += start[q];
  entry.resize(2 * n);
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::size_t k = 0; k < n; ++k) {
    slot_i[k] = fill[i[k]]++;
    slot_j[k] = fill[j[k]]++;
    entry[slot_i[k]] = static_cast<std::uint32_t>(2 * k);
    entry[slot_j[k]] = static_cast<std::uint32_t>(2 * k + 1);
  }
}

void compute_pair_forces(const LawTable& laws, const StepContext& ctx, Particles& p, PairList& pairs, bool direct) {
  std::visit(
      [&](const auto& table) {
        using Params = typename std::decay_t<decltype(table)>::value_type;
        if constexpr (std::is_same_v<Params, HertzMindlin::Params>) {
          if (direct)
            pair_pass<HertzMindlin, true>(table, ctx, p, pairs);
          else
            pair_pass<HertzMindlin, false>(table, ctx, p, pairs);
        }
      },
      laws);
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
