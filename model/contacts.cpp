// SPDX-License-Identifier: MIT
#include "model/contacts.h"

#include "model/parallel.h"

#include <algorithm>
#include <variant>

#include <omp.h>

namespace pastemix::model {

namespace {

std::uint64_t pair_key(std::int64_t a, std::int64_t b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b)), hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

// Direct = false: one output per pair, gathered afterwards (parallel). Direct = true (one thread): the
// forces are added to the particles in ascending pair order right away, which is exactly the order the
// gather uses (its CSR lists each particle's pairs in ascending order), so both give the same bits.
template <class Law, bool Direct>
void pair_pass(const std::vector<typename Law::Params>& table, const StepContext& ctx, Particles& p,
               PairList& L) {
  const bool rot = p.has_rotation;
  const bool constant_roll = ctx.rolling == RollingLaw::constant_torque;
  const long n = static_cast<long>(L.size());
  const int w = L.width;
  if constexpr (Direct) {
    std::fill(p.f.begin(), p.f.end(), Vec3{});
    if (rot) {
      std::fill(p.torque.begin(), p.torque.end(), Vec3{});
      std::fill(p.rolling_capacity.begin(), p.rolling_capacity.end(), 0.0);
    }
  }
  // The body is a lambda so that the one-thread path is a plain loop (no outlined OpenMP function).
  auto body = [&](long k) {
      const std::uint32_t a = L.i[k], b = L.j[k];
      const Vec3 d = p.x[b] - p.x[a];
      const double rsum = p.radius[a] + p.radius[b];
      const double dist2 = norm2(d);
      double* hist = w ? &L.history[static_cast<std::size_t>(k) * w] : nullptr;
      if (dist2 >= rsum * rsum) {
        // Not touching: forget the springs (a new contact starts from zero displacement). The force slots
        // are left stale: the gather skips pairs that are not touching.
        if (L.touching[k]) {
          std::fill(hist, hist + w, 0.0);
          L.touching[k] = 0;
        }
        return;
      }
      L.touching[k] = 1;
      const double dist = std::sqrt(dist2);
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
        g.w_rel = p.omega[a] - p.omega[b];
      }
      g.arm_i = arm_a;
      g.dt = ctx.dt;
      const auto& prm = table[static_cast<std::size_t>(p.material[a] * ctx.n_materials + p.material[b])];
      const auto r = Law::force(prm, g, hist, w);
      if constexpr (Direct) {
        p.f[a] += r.force_i;
        p.f[b] -= r.force_i;
        if (rot) {
          const Vec3 nxt = cross(g.n, r.tangential_i);  // (arm n) x F_t = arm (n x F_t): one cross per pair
          p.torque[a] += nxt * arm_a + r.rolling_torque_i;
          p.torque[b] += nxt * arm_b - r.rolling_torque_i;
          if (constant_roll) {
            p.rolling_capacity[a] += prm.rolling_friction * r.normal_force * arm_a;
            p.rolling_capacity[b] += prm.rolling_friction * r.normal_force * arm_b;
          }
        }
      } else {
        PairList::Out& o = L.out[k];
        o.force_i = r.force_i;
        if (rot) {
          const Vec3 nxt = cross(g.n, r.tangential_i);
          o.torque_i = nxt * arm_a + r.rolling_torque_i;
          o.torque_j = nxt * arm_b - r.rolling_torque_i;
          if (constant_roll) {
            o.roll_i = prm.rolling_friction * r.normal_force * arm_a;
            o.roll_j = prm.rolling_friction * r.normal_force * arm_b;
          }
        }
      }
  };
  if constexpr (Direct) {
    for (long k = 0; k < n; ++k) body(k);
  } else {
#pragma omp parallel for schedule(static) if (n >= parallel_min_items)
    for (long k = 0; k < n; ++k) body(k);
  }
}

template <class Law>
void wall_pass(const std::vector<typename Law::Params>& table, const StepContext& ctx,
               const std::vector<Wall>& walls, Particles& p, WallContacts& wc) {
  const bool rot = p.has_rotation;
  const bool constant_roll = ctx.rolling == RollingLaw::constant_torque;
  const int nw = static_cast<int>(walls.size());
  const int w = wc.width;
  std::vector<Vec3> shift(walls.size()), vel(walls.size()), origin(walls.size());
  std::vector<char> active(walls.size()), rect(walls.size());
  for (int k = 0; k < nw; ++k) {
    shift[k] = walls[k].displacement(ctx.t);
    origin[k] = walls[k].origin + shift[k];
    rect[k] = walls[k].kind == WallKind::rectangle;
    vel[k] = walls[k].velocity_at(ctx.t);
    active[k] = walls[k].active(ctx.t);
  }
  const long n = static_cast<long>(p.size());
#pragma omp parallel for schedule(static) if (n >= parallel_min_items)
  for (long a = 0; a < n; ++a) {
    for (std::uint32_t c = wc.start[a]; c < wc.start[a + 1]; ++c) {
      const int k = wc.near[c];
      const std::size_t slot = static_cast<std::size_t>(a) * nw + k;
      double* hist = w ? &wc.history[slot * w] : nullptr;
      Vec3 n_to_wall;
      const double dist = !active[k] ? 1e300
                          : rect[k]  ? rectangle_distance(walls[k], origin[k], p.x[a], &n_to_wall)
                                     : wall_distance(walls[k], shift[k], p.x[a], &n_to_wall);
      const double overlap = p.radius[a] - dist;
      if (overlap <= 0.0) {
        if (wc.touching[slot]) std::fill(hist, hist + w, 0.0);
        wc.touching[slot] = 0;
        continue;
      }
      wc.touching[slot] = 1;
      typename Law::Geometry g;
      g.n = n_to_wall;
      g.overlap = overlap;
      const double arm = std::max(dist, 0.0);
      g.R_star = p.radius[a];
      g.m_star = p.mass[a];
      g.v_rel = vel[k] - p.v[a];
      if (rot) {
        g.v_rel -= cross(p.omega[a], g.n * arm);
        g.w_rel = p.omega[a];
      }
      g.arm_i = arm;
      g.dt = ctx.dt;
      const auto& prm = table[static_cast<std::size_t>(p.material[a] * ctx.n_materials + walls[k].material)];
      const auto r = Law::force(prm, g, hist, w);
      p.f[a] += r.force_i;
      if (rot) {
        p.torque[a] += cross(g.n * arm, r.tangential_i) + r.rolling_torque_i;
        if (constant_roll) p.rolling_capacity[a] += prm.rolling_friction * r.normal_force * arm;
      }
    }
  }
}

}  // namespace

void WallContacts::resize(std::size_t particles, int n_walls, int history_width) {
  walls = n_walls;
  width = history_width;
  history.assign(particles * static_cast<std::size_t>(n_walls) * static_cast<std::size_t>(width), 0.0);
  touching.assign(particles * static_cast<std::size_t>(n_walls), 0);
}

void WallContacts::rebuild(const std::vector<Wall>& w, const Particles& p, double t, double skin) {
  const std::size_t n = p.size();
  start.assign(n + 1, 0);
  near.clear();
  std::vector<Vec3> shift(w.size());
  for (std::size_t k = 0; k < w.size(); ++k) shift[k] = w[k].displacement(t);
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t k = 0; k < w.size(); ++k) {
      Vec3 nn;
      const bool candidate = w[k].active(t) && wall_distance(w[k], shift[k], p.x[a], &nn) < p.radius[a] + skin;
      const std::size_t slot = a * static_cast<std::size_t>(walls) + k;
      if (candidate) {
        near.push_back(static_cast<std::uint16_t>(k));
      } else if (touching[slot]) {
        touching[slot] = 0;
        std::fill_n(&history[slot * static_cast<std::size_t>(width)], width, 0.0);
      }
    }
    start[a + 1] = static_cast<std::uint32_t>(near.size());
  }
}

void PairList::rebuild(const CandidatePairs& c, const Particles& p) {
  // Old keys sorted, for the history carry-over by binary search.
  std::vector<std::uint32_t> order(key.size());
  for (std::uint32_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
  std::vector<std::uint64_t> old_sorted(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) old_sorted[k] = key[order[k]];

  const std::size_t n = c.i.size();
  std::vector<std::uint64_t> new_key(n);
  std::vector<double> new_hist(n * static_cast<std::size_t>(width), 0.0);
  std::vector<std::uint32_t> new_touch(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    new_key[k] = pair_key(p.id[c.i[k]], p.id[c.j[k]]);
    if (old_sorted.empty()) continue;
    auto it = std::lower_bound(old_sorted.begin(), old_sorted.end(), new_key[k]);
    if (it == old_sorted.end() || *it != new_key[k]) continue;
    const std::size_t old = order[static_cast<std::size_t>(it - old_sorted.begin())];
    new_touch[k] = touching[old];
    // The key is symmetric but (i, j) may have swapped: history is stored as seen from the smaller id,
    // so no sign flip is needed as long as i holds the smaller id, which build_pairs guarantees (i < j by
    // dense index and ids are assigned in index order). A swap would need the history negated.
    std::copy_n(&history[old * width], width, &new_hist[k * width]);
  }
  i = c.i;
  j = c.j;
  key = std::move(new_key);
  history = std::move(new_hist);
  touching = std::move(new_touch);
  out.assign(n, Out{});
  r_star.resize(n);
  m_star.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t a = i[k], b = j[k];
    r_star[k] = p.radius[a] * p.radius[b] / (p.radius[a] + p.radius[b]);
    m_star[k] = p.mass[a] * p.mass[b] / (p.mass[a] + p.mass[b]);
  }
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
    entry[fill[i[k]]++] = static_cast<std::uint32_t>(2 * k);
    entry[fill[j[k]]++] = static_cast<std::uint32_t>(2 * k + 1);
  }
}

void compute_pair_forces(const LawTable& laws, const StepContext& ctx, Particles& p, PairList& pairs) {
  const bool direct = omp_get_max_threads() == 1 || static_cast<long>(pairs.size()) < parallel_min_items;
  std::visit(
      [&](const auto& table) {
        using Params = typename std::decay_t<decltype(table)>::value_type;
        if constexpr (std::is_same_v<Params, HertzMindlin::Params>) {
          if (direct) {
            pair_pass<HertzMindlin, true>(table, ctx, p, pairs);
          } else {
            pair_pass<HertzMindlin, false>(table, ctx, p, pairs);
            gather_pair_forces(pairs, p);
          }
        }
      },
      laws);
}

void add_wall_forces(const LawTable& laws, const StepContext& ctx, const std::vector<Wall>& walls, Particles& p,
                     WallContacts& wc) {
  if (walls.empty()) return;
  std::visit(
      [&](const auto& table) {
        using Params = typename std::decay_t<decltype(table)>::value_type;
        if constexpr (std::is_same_v<Params, HertzMindlin::Params>) wall_pass<HertzMindlin>(table, ctx, walls, p, wc);
      },
      laws);
}

void gather_pair_forces(const PairList& L, Particles& p) {
  const long n = static_cast<long>(p.size());
  const bool rot = p.has_rotation;
#pragma omp parallel for schedule(static) if (n >= parallel_min_items)
  for (long a = 0; a < n; ++a) {
    Vec3 f, t;
    double roll = 0.0;
    for (std::uint32_t e = L.start[a]; e < L.start[a + 1]; ++e) {
      const std::uint32_t k = L.entry[e] >> 1;
      if (!L.touching[k]) continue;
      if ((L.entry[e] & 1u) == 0) {
        const PairList::Out& o = L.out[k];
        f += o.force_i;
        if (rot) {
          t += o.torque_i;
          roll += o.roll_i;
        }
      } else {
        const PairList::Out& o = L.out[k];
        f -= o.force_i;
        if (rot) {
          t += o.torque_j;
          roll += o.roll_j;
        }
      }
    }
    p.f[a] = f;
    if (rot) {
      p.torque[a] = t;
      p.rolling_capacity[a] = roll;
    }
  }
}

}  // namespace pastemix::model
