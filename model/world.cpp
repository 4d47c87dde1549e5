// SPDX-License-Identifier: MIT
// The step, in order (each stage timed into Profile):
//
//   1. integration:  v += dt/2 a(t);  omega likewise;  x += dt v            (velocity Verlet, first half)
//   2. neighbor:     rebuild the Verlet pair list if some particle moved > skin/2 since the last build
//   3. contacts:     pair forces, summed per particle in ascending pair order
//   4. walls:        per particle, in wall order, at the walls' positions at t + dt
//   5. integration:  v += dt/2 a(t + dt);  omega likewise
//
// advance(n) runs n steps with one parallel region per stretch between rebuilds: each thread owns a slab
// of particles (PairList::partition) and does 3-5 for its own particles, and in the same sweep 1 of the
// next step; then the one barrier of the step (the positions of every particle are needed for the next
// pair forces, and the displacements for the rebuild decision). Pairs across two slabs are computed by
// both threads from ghost copies (contacts.h).
//
// Velocity-dependent forces (dashpots, the tangential spring increment) use the half-step velocities, as
// LIGGGHTS does; the scheme is second order for the conservative part. Rotation is integrated only when
// the Plan allocated it. The constant-directional rolling torque (EDEM "standard") is not added to the
// torque: its magnitude sum M = sum mu_r F_n R_i is applied in each half kick as a friction on omega that
// can stop the spin but never reverse it (omega* = omega + h tau/I; |omega*| <= h M/I -> omega = 0, else
// |omega| shrinks by h M/I). That is the explicit law's own torque whenever the spin survives the step,
// and it removes the chatter at omega -> 0 that makes piles under the raw law never come to rest.
//
// Forces are passes (forces/force_pass.h, listed in forces/registry.h): gravity (a body acceleration, a term
// of the kick), the walls (forces added per particle after the pair sum) and the fluid (forces/fluid_forces.h,
// only with [[fluid]]: before the pair pass the field finds the particles in a region and their submerged
// volumes; the plain kick skips them and the pass kicks and drifts them, in ascending order, from the field's
// member list, with buoyancy + drag integrated stably, never reversing v). Each pass is timed on its own
// profile line. A particle's operations are its own and keep their order (pair sum, wall forces, one kick),
// so running them as separate sweeps over the particles changes no bit.
//
// Outflow (on_exit = "remove"): a drift that takes a particle out of the domain flags it, as it flags a NaN,
// and the batch of passes stops at the step's barrier (advance() then handles it between passes: positions
// at t, forces at t not yet computed). There, one thread: the health checks (NaN, energy: still fatal), the
// escaped-mass limit, the record, then the particles are compacted (Particles::remove_if, order kept), the
// pair list and wall candidates renamed through the old -> new index map (the pairs and candidates of the
// removed particles dropped, every other history kept) and the lists rebuilt at once, carrying the
// histories over as at any rebuild. All of it is serial and in ascending index order, so a removal gives the
// same bits at any thread count; a run without an escape never enters it (the same bits as without outflow).
//
// No atomics and no reductions into shared sums: a particle's force is summed by its owner over its pairs
// in ascending pair order, as with one thread, so the trajectory is bitwise identical for any thread
// count (and for any batching of steps into advance()).
#include "model/world.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "base/error.h"
#include "model/kick_block.h"
#include "model/parallel.h"

#include <omp.h>

namespace pastemix::model {

namespace {

using Clock = std::chrono::steady_clock;

struct StageTimer {
  double& slot;
  Clock::time_point t0 = Clock::now();
  ~StageTimer() { slot += std::chrono::duration<double>(Clock::now() - t0).count(); }
};

}  // namespace

World::World(WorldConfig config, std::vector<Material> materials, LawTable laws, RollingTable rolling,
             Particles particles, std::vector<Wall> walls, int history_width)
    : cfg_(config), materials_(std::move(materials)), laws_(std::move(laws)), rolling_(std::move(rolling)),
      p_(std::move(particles)), walls_(std::move(walls)) {
  kick_friction_ = std::visit([](const auto& r) { return LawOf<decltype(r)>::kick_friction; }, rolling_);
  pairs_.width = history_width;
  wall_contacts_.resize(p_.size(), static_cast<int>(walls_.size()), history_width);
  // The passes' settings from the scene (the fluid pass: set_fluid()).
  std::get<Gravity>(forces_).g = cfg_.gravity;
  std::get<WallForces>(forces_).any = !walls_.empty();
  accel_ = body_acceleration(forces_);
}

// Half kick of one particle: v += h a; omega += h tau / I, then the non-reversing rolling friction.
inline void World::kick_one(long a, double h, bool rot, bool roll) {
  // A kick pass (the fluid) owns the kick of the particles it claims; the force it is given includes m g.
  const bool claimed = with_kick_pass(forces_, a, [&](const auto& pass) {
    p_.v[a] = pass.kick(a, p_.v[a], p_.f[a] + accel_ * p_.mass[a], p_.mass[a], p_.radius[a], h, accel_);
  });
  if (!claimed) p_.v[a] += (p_.f[a] * p_.inv_mass[a] + accel_) * h;
  if (rot) {
    Vec3 w = p_.omega[a] + p_.torque[a] * (h * p_.inv_inertia[a]);
    if (roll && p_.rolling_capacity[a] > 0.0) {
      const double stop = h * p_.rolling_capacity[a] * p_.inv_inertia[a];  // rad/s the friction can remove
      const double len = norm(w);
      w = len <= stop ? Vec3{} : w * (1.0 - stop / len);
    }
    p_.omega[a] = w;
  }
}


// v after the closing half kick of a step and the opening half kick of the next (the same force, unclaimed a).
inline void World::kick_velocity_twice(long a, double h) {
  const Vec3 dv = (p_.f[a] * p_.inv_mass[a] + accel_) * h;
  Vec3 v = p_.v[a];
  v += dv;
  v += dv;
  p_.v[a] = v;
}

// v after the two half kicks, by the kick pass that claims particle a (the fluid's, as kick_one twice gives
// it: its force includes m g) or as kick_velocity_twice.
inline void World::kick_claimed_twice(long a, double h) {
  const bool claimed = with_kick_pass(forces_, a, [&](const auto& pass) {
    const Vec3 F = p_.f[a] + accel_ * p_.mass[a];
    const Vec3 v = pass.kick(a, p_.v[a], F, p_.mass[a], p_.radius[a], h, accel_);
    p_.v[a] = pass.kick(a, v, F, p_.mass[a], p_.radius[a], h, accel_);
  });
  if (!claimed) kick_velocity_twice(a, h);
}

// The two half kicks of particles a0 .. a0 + 7 by the first active kick pass, where it claims all eight and
// can kick them at once (FluidForces::kick8; a0 .. a0 + 3 and kick4 with AVX2 alone): the bits
// kick_claimed_twice gives each. False: nothing done.
bool World::kick8_by_pass(long a0, double h) {
  bool done = false, first = true;
  for_each_pass(forces_, [&](auto& pass) {
    if constexpr ((std::decay_t<decltype(pass)>::info.adds & adds::kick) != 0)
      if (first && pass.active()) {
        first = false;  // only the pass kick_claimed_twice would ask first
#if defined(PASTEMIX_AVX2_LANES)
        if constexpr (requires { pass.kick4(a0, p_, accel_, h); }) done = pass.kick4(a0, p_, accel_, h);
#else
        if constexpr (requires { pass.kick8(a0, p_, accel_, h); }) done = pass.kick8(a0, p_, accel_, h);
#endif
      }
  });
  return done;
}

// The closing half kick of a step and the opening half kick of the next (the same force): kick_one twice,
// with the shared factors computed once and v, omega kept in registers in between (the same bits).
inline void World::kick_twice(long a, double h, bool rot, bool roll) {
  if (with_kick_pass(forces_, a, [](const auto&) {})) {
    kick_one(a, h, rot, roll);
    kick_one(a, h, rot, roll);
    return;
  }
  kick_velocity_twice(a, h);
  if (rot) {
    const Vec3 dw = p_.torque[a] * (h * p_.inv_inertia[a]);
    Vec3 w = p_.omega[a];
    const double cap = p_.rolling_capacity[a];  // N.m
    if (roll)
      kick::spin_twice(w.x, w.y, w.z, dw.x, dw.y, dw.z, h * cap * p_.inv_inertia[a], cap > 0.0);
    else
      w = (w + dw) + dw;
    p_.omega[a] = w;
  }
}

inline Vec3 World::drift_one(long a, long& first_bad) {
  p_.x[a] += p_.v[a] * cfg_.dt;
  const Vec3& x = p_.x[a];
  const Vec3 lo = cfg_.domain_min, hi = cfg_.domain_max;
  // NaN fails every comparison, so "not inside" also catches it.
  if (!(x.x >= lo.x && x.x <= hi.x && x.y >= lo.y && x.y <= hi.y && x.z >= lo.z && x.z <= hi.z))
    first_bad = std::min(first_bad, a);
  return x - x_at_rebuild_[a];
}

int World::threads_for(long n) const { return model::threads_for(n, cfg_.parallel_min_items); }

// What passes() hands its threads and what thread 0 hands back.
struct World::Batch {
  long n = 0;
  double h = 0.0;
  bool initial = false;
  int threads = 1;
  Motion moved;
  long done = 0, drifts = 0;
  double t_end = 0.0;
  Motion moved_end;
  long bad_end = std::numeric_limits<long>::max();
  int parity_end = 0;
  std::array<double, Profile::count> seconds{};  // s, thread 0's stages
};

// One thread's part of a batch: its particles, the ghost buffer it reads, the drift results of this step,
// and (thread 0) the clock of the stage being timed.
struct World::Lane {
  int me = 0, threads = 1, cur = 0;
  bool rot = false, roll = false;
  const std::uint32_t* own = nullptr;  // null with one thread: every particle
  long n_own = 0;
  // This step's displacements (model/motion.h). refine: its drifts are measured against the common
  // displacement u (m, World::common_shift) as well, into `lanes`; otherwise only their largest |dx|^2 is
  // kept (a2max: the usual test, a few operations less per particle while the lists are far from due;
  // World::refine_moves). `moved`: the single particles' (kick passes' members).
  bool refine = false;
  Vec3 u;
  MotionLanes lanes;
  double a2max = 0.0;
  Motion moved;
  // Refining: squared displacements a2[e] = |dx|^2, b2[e] = |dx - u|^2 of m particles (m <= kick::kBlock; a2
  // and b2 padded here with zeros).
  void add_moves(double* a2, double* b2, int m) {
    int padded = m;
    for (; padded % MotionLanes::kLanes != 0; ++padded) a2[padded] = b2[padded] = 0.0;
    lanes.add(a2, b2, padded);
  }
  // Particle displacement dx (m), one at a time (into `moved`).
  void add_move(const Vec3& dx) {
    const double a2 = norm2(dx);
    moved.add(a2, refine ? norm2(dx - u) : a2);
  }
  Motion total() const {
    Motion all = refine ? lanes.total() : Motion::within(a2max);
    all.merge(moved);
    return all;
  }
  long bad = std::numeric_limits<long>::max();
  std::array<double, Profile::count>* seconds = nullptr;  // thread 0 only
  Clock::time_point lap;
  long particle(long q) const { return own ? static_cast<long>(own[q]) : q; }
  // Thread 0: the time since the last lap goes to `stage`.
  void time(Profile::Stage stage) {
    if (!seconds) return;
    const auto now = Clock::now();
    (*seconds)[stage] += std::chrono::duration<double>(now - lap).count();
    lap = now;
  }
};

// The closing half kick of particle a, and with Then::kick_drift the next opening half kick and drift.
inline Vec3 World::close_kick(Lane& lane, long a, Then then, double h) {
  if (then == Then::kick) {
    kick_one(a, h, lane.rot, lane.roll);
    return {};
  }
  kick_twice(a, h, lane.rot, lane.roll);
  const Vec3 dx = drift_one(a, lane.bad);
  publish_ghost(lane, a);
  return dx;
}

// The state the other threads read in the next pass (cross pairs), after particle a's drift.
inline void World::publish_ghost(const Lane& lane, long a) {
  if (lane.threads > 1 && pairs_.ghost_of[a] != PairList::kNone)
    pairs_.ghost[lane.cur ^ 1][pairs_.ghost_of[a]] = {p_.x[a], p_.v[a], lane.rot ? p_.omega[a] : Vec3{}};
}


// The force passes' kinds of addition (those run per particle after its pair sum, before its kick).
constexpr auto kForceAdds = adds::force | adds::torque | adds::rolling_capacity;

namespace {

// One force pass on particles idx[0 .. m): batched where the pass has add_block(), else add() per particle.
template <class Pass, class Step>
void add_block_of(Pass& pass, const Step& s, const long* idx, int m) {
  if constexpr (requires { pass.add_block(s, idx, m); })
    pass.add_block(s, idx, m);
  else
    for (int e = 0; e < m; ++e) pass.add(s, idx[e]);
}

}  // namespace

// The force passes of particles idx[0 .. m), pass by pass in list order. A pass's addition reads and writes
// only its particle.
template <class Law, class Roll>
void World::add_force_passes(const PassStep<Law, Roll>& s, const long* idx, int m) {
  for_each_pass(forces_, [&](auto& pass) {
    if constexpr ((std::decay_t<decltype(pass)>::info.adds & kForceAdds) != 0)
      if (pass.active()) add_block_of(pass, s, idx, m);
  });
}

// The force passes, then close_kick(Then::kick_drift), of every particle of the lane, with rotation on,
// kick::kBlock particles at a time: the velocities kicked as kick_twice does (a kick pass's particle by the
// pass), the block's spins by spin_block (spin_twice; without a rolling friction, w + dw + dw), then the spins
// stored, the drifts and the ghost copies, in the particles' order. Each particle gets the operations the force passes, kick_twice and
// drift_one give it: the same bits. (The force and kick passes' time is then in the profile's kick stage.)
template <class Law, class Roll>
void World::close_kicks_blocked(const PassStep<Law, Roll>& s, Lane& lane, double h) {
  using kick::kBlock;
  kick::SpinBlock b;
  long idx[kBlock];
  // The first stray particle and the largest move in registers: through `lane` (which the stores to the
  // particle arrays may alias) every drift would load and store them. Refining, the block's squared
  // displacements go to the lanes' Motions.
  long bad = lane.bad;
  double a2max = lane.a2max;
  const Vec3 u = lane.u;
  alignas(64) double a2[kBlock], b2[kBlock];
#if defined(__AVX512F__) || defined(PASTEMIX_AVX2_LANES)
  kick::Moves moves{lane.refine, u, a2, b2};
  // Eight particles at a time (four with AVX2 alone; model/kick_block.h) where the block has that many
  // consecutive indices: one thread owns every particle, or a thread's slab after the spatial sort.
  constexpr int W = kick::kLanes;
  const auto full = [&](int e, int m) { return e + W <= m && idx[e + W - 1] == idx[e] + W - 1; };
  const auto claimed_by_pass = [&](long a) { return with_kick_pass(forces_, a, [](const auto&) {}); };
#endif
  for (long q = 0; q < lane.n_own;) {
    int m = 0;
    for (; q < lane.n_own && m < kBlock; ++q) idx[m++] = lane.particle(q);
    // The block's force passes (the walls) first, in list order, while its state is in cache: one pass over
    // the particles instead of two (issue 19: the walls' own pass grew from 6.8 to 11.7 ns per particle-step
    // from the 13k to the 207k pour, memory-bound). A pass's add(a) reads and writes only particle a, so
    // each particle gets its passes' additions in list order, as one particle at a time: the same bits.
    add_force_passes(s, idx, m);
    for (int e = 0; e < m;) {
#if defined(__AVX512F__)
      if (full(e, m)) {
        if (std::none_of(idx + e, idx + e + 8, claimed_by_pass))
          kick::velocity8(p_, accel_, h, idx[e]);
        else if (!kick8_by_pass(idx[e], h))
          for (int l = e; l < e + 8; ++l) kick_claimed_twice(idx[l], h);
        kick::spins8(p_, h, b, e, idx[e]);
        e += 8;
        continue;
      }
#elif defined(PASTEMIX_AVX2_LANES)
      if (full(e, m)) {
        if (std::none_of(idx + e, idx + e + 4, claimed_by_pass))
          kick::velocity4(p_, accel_, h, idx[e]);
        else if (!kick8_by_pass(idx[e], h))
          for (int l = e; l < e + 4; ++l) kick_claimed_twice(idx[l], h);
        kick::spins4(p_, h, b, e, idx[e]);
        e += 4;
        continue;
      }
#endif
      const long a = idx[e];
      // A particle a kick pass claims (the fluid's) gets its velocity from the pass, as kick_one twice gives
      // it, and its spin in the block like any other (before, its two scalar spin kicks, with their sqrt,
      // division and unpredictable branch, were ~40 % of the fluid's kick of a bed in air, issue 19).
      kick_claimed_twice(a, h);
      const Vec3 dw = p_.torque[a] * (h * p_.inv_inertia[a]);
      const Vec3& w = p_.omega[a];
      const double cap = p_.rolling_capacity[a];
      b.wx[e] = w.x, b.wy[e] = w.y, b.wz[e] = w.z, b.dx[e] = dw.x, b.dy[e] = dw.y, b.dz[e] = dw.z;
      b.stop[e] = h * cap * p_.inv_inertia[a];
      b.cap[e] = cap;
      ++e;
    }
    if (lane.roll)
      kick::spin_block(b, m);
    else
      kick::spin_free(b, m);
    for (int e = 0; e < m;) {
#if defined(__AVX512F__) || defined(PASTEMIX_AVX2_LANES)
      if (full(e, m)) {
#if defined(__AVX512F__)
        kick::drift8(p_, x_at_rebuild_.data(), b, e, idx[e], cfg_.dt, cfg_.domain_min, cfg_.domain_max, bad, moves);
#else
        kick::drift4(p_, x_at_rebuild_.data(), b, e, idx[e], cfg_.dt, cfg_.domain_min, cfg_.domain_max, bad, moves);
#endif
        for (int l = e; l < e + W; ++l) publish_ghost(lane, idx[l]);
        e += W;
        continue;
      }
#endif
      const long a = idx[e];
      p_.omega[a] = {b.wx[e], b.wy[e], b.wz[e]};
      const Vec3 dx = drift_one(a, bad);
      if (lane.refine)
        a2[e] = norm2(dx), b2[e] = norm2(dx - u);
      else
        a2max = std::max(a2max, norm2(dx));
      publish_ghost(lane, a);
      ++e;
    }
    if (lane.refine) lane.add_moves(a2, b2, m);
  }
#if defined(__AVX512F__) || defined(PASTEMIX_AVX2_LANES)
  if (!lane.refine) a2max = std::max(a2max, moves.largest());
#endif
  lane.bad = bad, lane.a2max = a2max;
}

template <class Law, class Roll>
void World::step_lane(const PassStep<Law, Roll>& s, Lane& lane, Then then, double h) {
  for_each_pass(forces_, [&](auto& pass) {
    if constexpr (requires { pass.prepare(s); })
      if (pass.active()) pass.prepare(s), lane.time(pass.info.stage);
  });
  pair_forces(laws_, rolling_, s.ctx, p_, pairs_, lane.me, lane.cur);
  lane.time(Profile::contact_forces);
  // Every particle's kick in blocks, each particle's force passes just before its kick (close_kicks_blocked).
  const bool blocked = then == Then::kick_drift && lane.rot;
  // Otherwise, per owned particle, after its pair sum: the force passes in list order (walls: in wall order),
  // kick::kBlock particles at a time.
  if (!blocked)
    for_each_pass(forces_, [&](auto& pass) {
      if constexpr ((std::decay_t<decltype(pass)>::info.adds & kForceAdds) != 0)
        if (pass.active()) {
          long idx[kick::kBlock];
          for (long q = 0; q < lane.n_own;) {
            int m = 0;
            for (; q < lane.n_own && m < kick::kBlock; ++q) idx[m++] = lane.particle(q);
            add_block_of(pass, s, idx, m);
          }
          lane.time(pass.info.stage);
        }
    });
  if (then == Then::nothing) return;
  if (blocked) {
    close_kicks_blocked(s, lane, h);
  } else {
    double a2max = lane.a2max;
    alignas(64) double a2[kick::kBlock], b2[kick::kBlock];
    for (long q = 0; q < lane.n_own;) {
      int m = 0;
      for (; q < lane.n_own && m < kick::kBlock; ++q) {
        const long a = lane.particle(q);
        if (with_kick_pass(forces_, a, [](const auto&) {})) continue;
        const Vec3 dx = close_kick(lane, a, then, h);
        if (!lane.refine) {
          a2max = std::max(a2max, norm2(dx));
          continue;
        }
        a2[m] = norm2(dx), b2[m] = norm2(dx - lane.u), ++m;
      }
      if (lane.refine) lane.add_moves(a2, b2, m);
    }
    lane.a2max = a2max;
  }
  lane.time(Profile::kick);
  // The kick passes' particles, ascending, each by its owner (its operations are its own: any order of the
  // particles gives the same bits).
  for_each_pass(forces_, [&](auto& pass) {
    if constexpr ((std::decay_t<decltype(pass)>::info.adds & adds::kick) != 0)
      if (pass.active() && !blocked) {
        for (long a : pass.members(lane.me)) lane.add_move(close_kick(lane, a, then, h));
        lane.time(pass.info.stage);
      }
  });
}

template <class Law, class Roll>
void World::run_lane(const std::vector<typename Law::Params>& laws,
                     const std::vector<typename Roll::Params>& rolling, Batch& batch) {
  Lane lane;
  lane.me = omp_get_thread_num();
  lane.threads = batch.threads;
  lane.cur = pairs_.parity;
  lane.rot = p_.has_rotation;
  lane.roll = kick_friction_;
  const bool master = lane.me == 0;
  if (batch.threads > 1) {
    const auto& own = pairs_.own[static_cast<std::size_t>(lane.me)];
    lane.own = own.data(), lane.n_own = static_cast<long>(own.size());
  } else {
    lane.n_own = static_cast<long>(p_.size());
  }
  if (master) lane.seconds = &batch.seconds, lane.lap = Clock::now();
  const int n_materials = static_cast<int>(materials_.size());
  double t = t_;  // every thread advances its own copy: the same additions, the same bits
  long done = 0, drifts = 0;
  Motion moved_all = batch.moved;
  long bad_all = std::numeric_limits<long>::max();
  // This thread's busy time: its steps' work, without the waits at the step barriers (the load balance).
  auto since = Clock::now();
  double busy = 0.0;
  for (;;) {
    const StepContext ctx{t, cfg_.dt, n_materials};
    const PassStep<Law, Roll> s{laws, rolling, ctx, walls_, wall_contacts_, p_, pairs_, lane.me, lane.cur};
    const Then then = batch.initial ? Then::nothing : (done + 1 < batch.n ? Then::kick_drift : Then::kick);
    lane.moved = Motion{}, lane.lanes = MotionLanes{}, lane.a2max = 0.0, lane.bad = std::numeric_limits<long>::max();
    lane.refine = refine_moves(moved_all);  // every thread alike: from the merged displacements
    lane.u = common_shift(t + cfg_.dt);     // the drift moves the particles to t + dt
    step_lane(s, lane, then, batch.h);
    ++done;
    lane.cur ^= 1;  // the cross pairs' history just written
    if (then != Then::kick_drift) break;  // the end of the region is the barrier
    // The next step has begun: its positions are needed by every thread, and its displacement and domain
    // results by the rebuild decision, which every thread takes alike.
    ++drifts;
    auto& slot = results_[done & 1];
    slot[static_cast<std::size_t>(lane.me)] = {lane.total(), lane.bad};
    busy += std::chrono::duration<double>(Clock::now() - since).count();
    step_barrier_.wait(omp_get_num_threads());
    since = Clock::now();
    lane.time(Profile::wait);
    moved_all = Motion{};
    for (const auto& r : slot) {
      moved_all.merge(r.moved);
      bad_all = std::min(bad_all, r.bad);
    }
    t += cfg_.dt;
    if (bad_all != std::numeric_limits<long>::max() || rebuild_due(moved_all, t)) break;
  }
  busy += std::chrono::duration<double>(Clock::now() - since).count();
  if (batch.threads > 1) busy_[static_cast<std::size_t>(lane.me)].s += busy;
  if (master) {
    batch.done = done, batch.drifts = drifts, batch.t_end = t;
    batch.moved_end = moved_all, batch.bad_end = bad_all, batch.parity_end = lane.cur;
  }
}

long World::passes(long n, double h, bool initial, Motion& moved) {
  Batch batch;
  batch.n = n, batch.h = h, batch.initial = initial, batch.moved = moved;
  batch.threads = threads_for(static_cast<long>(p_.size()));
  if (pairs_.threads != batch.threads || imbalanced(batch.threads)) partition(batch.threads, p_.x);
  if (batch.threads > 1) pairs_.fill_ghosts(p_);
  std::get<WallForces>(forces_).resize(batch.threads);
  for (auto& r : results_) r.resize(static_cast<std::size_t>(batch.threads));
  if (batch.threads > 1 && busy_.size() != static_cast<std::size_t>(batch.threads))
    busy_.assign(static_cast<std::size_t>(batch.threads), {});
  auto timed_hooks = [&](auto&& hook) {  // the passes' serial work around the team, on the fluid line
    StageTimer timer{profile_.seconds[Profile::fluid]};
    for_each_pass(forces_, hook);
  };
  timed_hooks([&](auto& pass) {
    if constexpr (requires { pass.begin_batch(p_, pairs_, batch.threads); })
      if (pass.active()) pass.begin_batch(p_, pairs_, batch.threads);
  });
  std::visit(
      [&](const auto& table, const auto& rolling) {
        using Law = LawOf<decltype(table)>;
        using Roll = LawOf<decltype(rolling)>;
#pragma omp parallel num_threads(batch.threads)
        run_lane<Law, Roll>(table, rolling, batch);
      },
      laws_, rolling_);
  timed_hooks([](auto& pass) {
    if constexpr (requires { pass.end_batch(); })
      if (pass.active()) pass.end_batch();
  });
  // A pass's failure inside the region (it cannot leave it: forces/flow_forces.h) stops the run here, after
  // the batch's hooks (the fluid field's state is then whole).
  for_each_pass(forces_, [](const auto& pass) {
    if constexpr (requires { pass.rethrow(); })
      if (pass.active()) pass.rethrow();
  });
  pairs_.parity = batch.parity_end;
  pairs_.sync_cross();
  t_ = batch.t_end;
  steps_ += batch.drifts;
  moved = batch.moved_end;
  if (batch.bad_end != std::numeric_limits<long>::max() && bad_index_ < 0) bad_index_ = batch.bad_end;
  for (int k : {Profile::contact_forces, Profile::walls, Profile::kick, Profile::fluid, Profile::wait})
    profile_.seconds[k] += batch.seconds[k];
  return batch.done;
}

// First half kick and drift in one loop, with the domain check and the displacements since the last
// rebuild (max, top-two and min reductions: exact in any order, so any schedule gives the same result).
Motion World::kick_drift(double h) {
  const long n = static_cast<long>(p_.size());
  const bool rot = p_.has_rotation;
  const bool roll = kick_friction_;
  const Vec3 u = common_shift(t_ + cfg_.dt);  // the drift moves the particles to t + dt
  Motion moved;
  long bad = std::numeric_limits<long>::max();
  const bool parallel = threads_for(n) > 1;
#pragma omp parallel if (parallel)
  {
    Motion mine;
    long my_bad = std::numeric_limits<long>::max();
#pragma omp for schedule(static, 256) nowait
    for (long a = 0; a < n; ++a) {
      kick_one(a, h, rot, roll);
      const Vec3 dx = drift_one(a, my_bad);
      mine.add(norm2(dx), norm2(dx - u));
    }
#pragma omp critical(pastemix_kick_drift)
    {
      moved.merge(mine);
      bad = std::min(bad, my_bad);
    }
  }
  if (bad != std::numeric_limits<long>::max() && bad_index_ < 0) bad_index_ = bad;
  return moved;
}

// A step: kick and drift (fused into the previous step's last pass, except at the start of a batch),
// t += dt, the domain check, a rebuild if due, then the forces at t and the closing half kick.
void World::advance(long n) {
  if (n <= 0) return;
  const double h = 0.5 * cfg_.dt;
  Motion moved;
  if (!started_) {
    {
      StageTimer timer{profile_.seconds[Profile::neighbor]};
      rebuild_neighbors();
    }
    passes(1, h, true, moved);
    started_ = true;
  }
  {
    StageTimer timer{profile_.seconds[Profile::kick_drift]};
    moved = kick_drift(h);
  }
  t_ += cfg_.dt;
  ++steps_;
  for (long left = n; left > 0;) {
    if (bad_index_ >= 0) flagged(moved);
    if (rebuild_due(moved, t_)) {
      StageTimer timer{profile_.seconds[Profile::neighbor]};
      rebuild_neighbors();
    }
    left -= passes(left, h, false, moved);
  }
  if (bad_index_ >= 0) flagged(moved);
}

void World::flagged(Motion& moved) {
  if (cfg_.on_exit == ExitRule::stop) {
    check();
    return;
  }
  check_particles(false);  // NaN / inf and energy blow-ups stop the run whatever on_exit says
  StageTimer timer{profile_.seconds[Profile::neighbor]};
  remove_escaped(moved);
}

}  // namespace pastemix::model
