// SPDX-License-Identifier: MIT
// The memory floor of one step (issue 19's scaling series): how long does it take only to move the state a
// step of the engine touches, with the engine's layout, for a pile that fits the caches and for one that does
// not? It builds the bench pour's lattice (12 layers, 1080 spheres a layer per K^2; the spatial sort's order,
// the layers fastest) with the engine's per-particle arrays (model/particles.h: Vec3 rows of position,
// velocity, spin, force and torque; radius, inverse mass and inertia, rolling capacity; the positions kept
// at the last rebuild, model/motion.h) and per-pair arrays (model/contacts.h: the two indices, R_i + R_j, R*,
// m*, three spring doubles, the touching flag), then times the two sweeps of a step with as little
// arithmetic as keeps every load and store:
//   pairs  each pair's own arrays read and its spring and flag written, in order, the partner's rows read
//          where the pair names it, and each sphere's rows and sums read and written once (the least traffic
//          of the pair pass: its sums held in registers);
//   kick   each sphere in order: force, torque, capacity, velocity, spin, position read, velocity, spin and
//          position written, force, torque and capacity cleared, its move since the rebuild measured (the
//          closing and opening half kicks and the drift).
// No neighbour rebuild, no force law, no fluid: a lower bound on the engine's time per particle-step for
// this layout and these two passes. Prints ns per particle-step at K = 1, 2, 4 (12,960 / 51,840 / 207,360
// spheres) and the bytes each step moves.
//
// Usage: pastemix_state_sweep [--steps N] [--k "1 2 4"]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "model/vec3.h"

namespace {

using pastemix::model::Vec3;
using Clock = std::chrono::steady_clock;

struct State {
  // Per particle (the engine's Particles and Motion::x_at_rebuild).
  std::vector<Vec3> x, v, w, f, t, x0;
  std::vector<double> radius, inv_mass, inv_inertia, cap;
  // Per pair (the engine's PairList).
  std::vector<std::uint32_t> i, j, touching;
  std::vector<double> rsum, r_star, m_star, hist;
  std::size_t bytes_per_step = 0;  // each array once per sweep that reads or writes it (B)
};

// The bench pour's lattice at scale K (bench/tools/make_pour.py: 12 layers of (36 K) x (30 K) spheres of
// 1.25 mm radius, 2.6 mm apart), numbered as the sort leaves it (layers fastest, then y, then x), with the
// half list of its neighbours within r_i + r_j + skin that a settling pile has: the next sphere in z, y, x and
// the y-z diagonal.
State lattice(int k) {
  const long nz = 12, ny = 30L * k, nx = 36L * k, n = nx * ny * nz;
  State s;
  const auto sz = static_cast<std::size_t>(n);
  s.x.resize(sz), s.v.resize(sz), s.w.resize(sz), s.f.resize(sz), s.t.resize(sz), s.x0.resize(sz);
  s.radius.assign(sz, 1.25e-3), s.inv_mass.assign(sz, 1.0 / 2.26e-5), s.inv_inertia.assign(sz, 1.0 / 1.4e-11);
  s.cap.assign(sz, 0.0);
  auto at = [&](long ix, long iy, long iz) { return static_cast<std::uint32_t>((ix * ny + iy) * nz + iz); };
  for (long ix = 0; ix < nx; ++ix)
    for (long iy = 0; iy < ny; ++iy)
      for (long iz = 0; iz < nz; ++iz) {
        const std::uint32_t a = at(ix, iy, iz);
        s.x[a] = {2.6e-3 * double(ix), 2.6e-3 * double(iy), 2.6e-3 * double(iz)};
        s.x0[a] = s.x[a];
        s.v[a] = {0.0, 0.0, -1e-3 * double(a % 7)};
        const long nb[4][3] = {{ix, iy, iz + 1}, {ix, iy + 1, iz}, {ix + 1, iy, iz}, {ix, iy + 1, iz + 1}};
        for (const auto& q : nb)
          if (q[0] < nx && q[1] < ny && q[2] < nz) s.i.push_back(a), s.j.push_back(at(q[0], q[1], q[2]));
      }
  const std::size_t np = s.i.size();
  s.touching.assign(np, 0), s.rsum.assign(np, 2.5e-3), s.r_star.assign(np, 6.25e-4), s.m_star.assign(np, 1.13e-5);
  s.hist.assign(3 * np, 0.0);
  // pairs: i, j, touching, rsum, r_star, m_star, hist read (+ hist, touching written); both spheres' x, v, w
  // read and f, t, cap read and written, counted once per sphere (a sorted list reuses them from cache).
  const std::size_t per_pair = 3 * 4 + 3 * 8 + 3 * 8, written_pair = 4 + 3 * 8;
  const std::size_t sphere_pairs = 3 * 24 + 2 * (2 * 24 + 8);
  // kick: f, t, cap, v, w, x, x0, inv_mass, inv_inertia read; v, w, x written; f, t, cap cleared.
  const std::size_t sphere_kick = 7 * 24 + 3 * 8 + 3 * 24 + 2 * 24 + 8;
  s.bytes_per_step = np * (per_pair + written_pair) + sz * (sphere_pairs + sphere_kick);
  return s;
}

// The pair sweep: every array of the pair pass read once and its written arrays written once, in order (as
// if each sphere's sums were held in registers: the least traffic the pass can have). The partners' rows are
// read where the pair names them (a sorted list finds most of them in cache).
double pair_sweep(State& s) {
  const std::size_t np = s.i.size();
  double acc = 0.0;
  for (std::size_t k = 0; k < np; ++k) {
    const std::uint32_t b = s.j[k];
    const double q = s.rsum[k] + s.r_star[k] + s.m_star[k] + double(s.touching[k]) + s.x[b].z + s.v[b].z + s.w[b].z;
    double* h = &s.hist[3 * k];
    h[0] += 1e-30 * q, h[1] += 1e-30, h[2] += 1e-30;
    s.touching[k] = q < 0.0;
    acc += double(s.i[k]);
  }
  for (std::size_t a = 0; a < s.x.size(); ++a) {
    // Each sphere's own rows and its sums, once: read x, v, w, f, t, cap; write f, t, cap.
    const double q = s.x[a].x + s.v[a].y + s.w[a].z;
    s.f[a] += Vec3{q, q, q} * 1e-30, s.t[a] += Vec3{q, q, q} * 1e-30, s.cap[a] += 1e-30 * q;
  }
  return acc;
}

// The kick sweep: the two half kicks, the rolling friction's clamp, the drift, the move since the rebuild.
double kick_sweep(State& s, double h) {
  double max2 = 0.0;
  for (std::size_t a = 0; a < s.x.size(); ++a) {
    s.v[a] += s.f[a] * (h * s.inv_mass[a]) + Vec3{0.0, 0.0, -9.81 * h};
    const Vec3 wn = s.w[a] + s.t[a] * (h * s.inv_inertia[a]);
    const double stop = h * s.cap[a] * s.inv_inertia[a], len2 = norm2(wn);
    s.w[a] = len2 <= stop * stop ? Vec3{} : wn;
    s.x[a] += s.v[a] * h;
    max2 = std::max(max2, norm2(s.x[a] - s.x0[a]));
    s.f[a] = {}, s.t[a] = {}, s.cap[a] = 0.0;
  }
  return max2;
}

}  // namespace

int main(int argc, char** argv) {
  int steps = 200;
  std::vector<int> ks{1, 2, 4};
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--steps") && a + 1 < argc) {
      steps = std::atoi(argv[++a]);
    } else if (!std::strcmp(argv[a], "--k") && a + 1 < argc) {
      ks.clear();
      std::istringstream in(argv[++a]);
      for (int k; in >> k;) ks.push_back(k);
    } else {
      std::fprintf(stderr, "usage: pastemix_state_sweep [--steps N] [--k \"1 2 4\"]\n");
      return 2;
    }
  }
  if (steps < 1 || ks.empty() || *std::min_element(ks.begin(), ks.end()) < 1) {
    std::fprintf(stderr, "pastemix_state_sweep: --steps and every K must be >= 1\n");
    return 2;
  }
  std::printf("state sweep: the bench pour's lattice, the engine's arrays, one thread, %d steps, best of 3\n", steps);
  std::printf("%3s %9s %12s %10s %10s %10s %8s %9s\n", "K", "N", "pairs/sphere", "pairs ns", "kick ns",
              "total ns", "B/step", "GB/s");
  for (int k : ks) {
    State s = lattice(k);
    const double n = double(s.x.size());
    double best_pairs = 1e30, best_kick = 1e30, sink = 0.0;
    for (int rep = 0; rep < 3; ++rep) {
      double tp = 0.0, tk = 0.0;
      for (int step = 0; step < steps; ++step) {
        const auto t0 = Clock::now();
        sink += pair_sweep(s);
        const auto t1 = Clock::now();
        sink += kick_sweep(s, 1e-5);
        tp += std::chrono::duration<double>(t1 - t0).count();
        tk += std::chrono::duration<double>(Clock::now() - t1).count();
      }
      best_pairs = std::min(best_pairs, tp), best_kick = std::min(best_kick, tk);
    }
    const double ns_p = 1e9 * best_pairs / (steps * n), ns_k = 1e9 * best_kick / (steps * n);
    std::printf("%3d %9.0f %12.2f %10.2f %10.2f %10.2f %8.0f %9.1f\n", k, n, double(s.i.size()) / n, ns_p, ns_k,
                ns_p + ns_k, double(s.bytes_per_step) / n,
                double(s.bytes_per_step) * steps / (best_pairs + best_kick) * 1e-9);
    if (sink < 0.0) std::puts("");
  }
  std::printf("ns per particle-step: the time to move the state of one step and nothing else (no rebuild, no "
              "force law): a floor under the engine's cost at each size; B/step = bytes per sphere each step "
              "touches, counted once per sweep\n");
  return 0;
}
