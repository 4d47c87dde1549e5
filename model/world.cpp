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
// Fluid hook (model/fluid/field.h, only with [[fluid]]): after the forces at t + dt, fluid->update() finds
// the particles in a region and their submerged volumes (and raises the surface); the half kicks of those
// particles are replaced by the fluid kick (buoyancy + drag integrated stably, never reversing v). The
// update and these particles' kicks and drifts are the fluid pass, timed on its own profile line: each
// thread skips its particles inside a region in the per-particle sweep and then kicks and drifts them, in
// ascending order, from the field's member list (each particle's operations are its own, so the order of
// the particles does not change a bit).
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

#include <chrono>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "base/error.h"
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
}

// Pairs and wall candidates are rebuilt together, with the same skin: the wall lists cost one distance per
// particle and candidate wall, far less than the pair search, and a thin skin keeps them short (settled
// bed: 2,837 wall candidates with a 1 mm skin against 6,114 with 5 mm). Which candidates a list holds never
// changes a force: a pair or wall contact is computed whenever it touches, and every touching one is listed.
void World::rebuild_neighbors() {
  if (fluid_) fluid_->mark_stale();  // fluid candidates: no particle has moved skin/2 since this rebuild
  search_.build(p_.x, p_.radius, cfg_.skin, candidates_);
#ifdef PASTEMIX_VALIDATE
  // Expensive check: the cell list must find exactly the brute-force pairs.
  if (brute_force_pairs(p_.x, p_.radius, cfg_.skin).i.size() != candidates_.i.size())
    throw RuntimeFailure(fmt::format("neighbour list at t = {} s disagrees with brute force", t_));
#endif
  pairs_.rebuild(candidates_, p_, static_cast<int>(materials_.size()));
  wall_contacts_.rebuild(walls_, p_, t_, cfg_.skin);
  x_at_rebuild_ = p_.x;
  // The threads' particles and pairs (slabs of the new positions), for the thread count of this build.
  pairs_.partition(static_cast<long>(p_.size()) >= parallel_min_items ? omp_get_max_threads() : 1, p_.x);
  t_at_rebuild_ = t_;
  ++profile_.rebuilds;
}

// Half kick of one particle: v += h a; omega += h tau / I, then the non-reversing rolling friction.
inline void World::kick_one(long a, double h, bool rot, bool roll) {
  if (fluid_ && fluid_->inside(a))  // fluid hook
    p_.v[a] = fluid_->kick(a, p_.v[a], p_.f[a] + cfg_.gravity * p_.mass[a], p_.mass[a], p_.radius[a], h, cfg_.gravity);
  else
    p_.v[a] += (p_.f[a] * p_.inv_mass[a] + cfg_.gravity) * h;
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

// The closing half kick of a step and the opening half kick of the next (the same force): kick_one twice,
// with the shared factors computed once and v, omega kept in registers in between (the same bits).
inline void World::kick_twice(long a, double h, bool rot, bool roll) {
  if (fluid_ && fluid_->inside(a)) {
    kick_one(a, h, rot, roll);
    kick_one(a, h, rot, roll);
    return;
  }
  const Vec3 dv = (p_.f[a] * p_.inv_mass[a] + cfg_.gravity) * h;
  Vec3 v = p_.v[a];
  v += dv;
  v += dv;
  p_.v[a] = v;
  if (rot) {
    const Vec3 dw = p_.torque[a] * (h * p_.inv_inertia[a]);
    Vec3 w = p_.omega[a];
    if (roll && p_.rolling_capacity[a] > 0.0) {
      const double stop = h * p_.rolling_capacity[a] * p_.inv_inertia[a];  // rad/s the friction can remove
      for (int k = 0; k < 2; ++k) {
        w = w + dw;
        const double len = norm(w);
        w = len <= stop ? Vec3{} : w * (1.0 - stop / len);
      }
    } else {
      w = w + dw;
      w = w + dw;
    }
    p_.omega[a] = w;
  }
}

inline void World::drift_one(long a, double& d2, long& first_bad) {
  p_.x[a] += p_.v[a] * cfg_.dt;
  const Vec3& x = p_.x[a];
  const Vec3 lo = cfg_.domain_min, hi = cfg_.domain_max;
  // NaN fails every comparison, so "not inside" also catches it.
  if (!(x.x >= lo.x && x.x <= hi.x && x.y >= lo.y && x.y <= hi.y && x.z >= lo.z && x.z <= hi.z))
    first_bad = std::min(first_bad, a);
  d2 = std::max(d2, norm2(x - x_at_rebuild_[a]));
}

bool World::rebuild_due(double moved2, double t) const {
  // The lists stay valid while no particle has moved more than skin/2 since their build, and, for the wall
  // candidates, particle plus wall motion stays below skin/2; a wall's motion is |v| (t - t_build); a
  // removed wall needs no rebuild (it is skipped when inactive).
  double wall_move = 0.0;
  for (const Wall& wall : walls_)
    wall_move = std::max(wall_move, norm(wall.displacement(t) - wall.displacement(t_at_rebuild_)));
  const double half = 0.5 * cfg_.skin;
  return moved2 > half * half || (wall_move > 0.0 && std::sqrt(moved2) + wall_move > half);
}

long World::passes(long n, double h, bool initial, double& moved2) {
  const long np = static_cast<long>(p_.size());
  const int threads = np >= parallel_min_items ? omp_get_max_threads() : 1;
  if (pairs_.threads != threads) pairs_.partition(threads, p_.x);
  if (threads > 1) pairs_.fill_ghosts(p_);
  wall_state_.resize(static_cast<std::size_t>(threads));
  for (auto& r : results_) r.resize(static_cast<std::size_t>(threads));
  const bool rot = p_.has_rotation;
  const bool roll = kick_friction_;
  const bool has_walls = !walls_.empty();
  const int n_materials = static_cast<int>(materials_.size());
  long done = 0, drifts = 0;
  double t_end = t_, d2_end = moved2;
  long bad_end = std::numeric_limits<long>::max();
  int parity_end = pairs_.parity;
  double pair_s = 0.0, particle_s = 0.0, fluid_s = 0.0, wait_s = 0.0;
  const bool wet = fluid_ != nullptr;
  std::visit(
      [&](const auto& table, const auto& rolling) {
        using Law = LawOf<decltype(table)>;
        using Roll = LawOf<decltype(rolling)>;
#pragma omp parallel num_threads(threads)
        {
          const int me = omp_get_thread_num();
          const bool master = me == 0;
          // Thread 0 alone: every particle; several: the thread's own, ascending.
          const std::uint32_t* own = threads > 1 ? pairs_.own[static_cast<std::size_t>(me)].data() : nullptr;
          const long n_own = threads > 1 ? static_cast<long>(pairs_.own[static_cast<std::size_t>(me)].size()) : np;
          WallState& ws = wall_state_[static_cast<std::size_t>(me)];
          double t = t_;  // every thread advances its own copy: the same additions, the same bits
          int cur = pairs_.parity;
          long my_done = 0, my_drifts = 0;
          double d2_all = moved2;
          long bad_all = std::numeric_limits<long>::max();
          for (;;) {
            const auto c0 = Clock::now();
            // The fluid update reads the positions of every particle (all drifted: the barrier) and must
            // precede every kick; one thread, then the barrier of `single`.
            if (fluid_) {
#pragma omp single
              fluid_->update(p_, &pairs_.i, &pairs_.j);
            }
            const auto cf = Clock::now();
            ws.update(walls_, t);
            const StepContext ctx{t, cfg_.dt, n_materials};
            const Then then = initial ? Then::nothing : (my_done + 1 < n ? Then::kick_drift : Then::kick);
            pair_forces(laws_, rolling_, ctx, p_, pairs_, me, cur);
            const auto c1 = Clock::now();
            double d2 = 0.0;
            long bad = std::numeric_limits<long>::max();
            // The closing half kick (and the next opening half kick and drift) of particle a. h and roll by
            // value: clang (the fuzz build) rejects their implicit capture inside std::visit's lambda and the
            // OpenMP region ("reference to local variable declared in enclosing function").
            auto close_kick = [&, h, roll](long a) {
              if (then == Then::kick) {
                kick_one(a, h, rot, roll);
                return;
              }
              kick_twice(a, h, rot, roll);
              drift_one(a, d2, bad);
              // The state the other threads read in the next pass (cross pairs).
              if (threads > 1 && pairs_.ghost_of[a] != PairList::kNone)
                pairs_.ghost[cur ^ 1][pairs_.ghost_of[a]] = {p_.x[a], p_.v[a], rot ? p_.omega[a] : Vec3{}};
            };
            // Per owned particle, in this order: pair forces (summed above), wall forces in wall order,
            // then the half kick (and the next opening half kick and drift): the same operations in the
            // same order as separate passes, one sweep of memory.
            for (long q = 0; q < n_own; ++q) {
              const long a = own ? own[q] : q;
              if (has_walls && wall_contacts_.start[a] != wall_contacts_.start[a + 1]) {
                Vec3 f = p_.f[a], tq;
                double rc = 0.0;
                if (rot) {
                  tq = p_.torque[a];
                  rc = p_.rolling_capacity[a];
                }
                wall_forces_one<Law, Roll>(table, rolling, ctx, walls_, ws, p_, wall_contacts_,
                                           static_cast<std::size_t>(a), f, tq, rc);
                p_.f[a] = f;
                if (rot) {
                  p_.torque[a] = tq;
                  p_.rolling_capacity[a] = rc;
                }
              }
              if (then == Then::nothing || (wet && fluid_->inside(a))) continue;  // fluid: below
              close_kick(a);
            }
            const auto c2 = Clock::now();
            if (wet && then != Then::nothing)
              for (long a : fluid_->members())
                if (threads == 1 || pairs_.owner[static_cast<std::size_t>(a)] == me) close_kick(a);
            const auto c3 = Clock::now();
            ++my_done;
            cur ^= 1;  // the cross pairs' history just written
            if (master) {
              pair_s += std::chrono::duration<double>(c1 - cf).count();
              particle_s += std::chrono::duration<double>(c2 - c1).count();
              fluid_s += std::chrono::duration<double>(cf - c0).count() + std::chrono::duration<double>(c3 - c2).count();
            }
            if (then != Then::kick_drift) break;  // the end of the region is the barrier
            // The next step has begun: its positions are needed by every thread, and its displacement and
            // domain results by the rebuild decision, which every thread takes alike.
            ++my_drifts;
            auto& slot = results_[my_done & 1];
            slot[static_cast<std::size_t>(me)] = {d2, bad};
#pragma omp barrier
            if (master) wait_s += std::chrono::duration<double>(Clock::now() - c2).count();
            d2_all = 0.0;
            for (const auto& r : slot) {
              d2_all = std::max(d2_all, r.d2);
              bad_all = std::min(bad_all, r.bad);
            }
            t += cfg_.dt;
            if (bad_all != std::numeric_limits<long>::max() || rebuild_due(d2_all, t)) break;
          }
          if (master) {
            done = my_done;
            drifts = my_drifts;
            t_end = t;
            d2_end = d2_all;
            bad_end = bad_all;
            parity_end = cur;
          }
        }
      },
      laws_, rolling_);
  pairs_.parity = parity_end;
  pairs_.sync_cross();
  t_ = t_end;
  steps_ += drifts;
  moved2 = d2_end;
  if (bad_end != std::numeric_limits<long>::max() && bad_index_ < 0) bad_index_ = bad_end;
  profile_.seconds[Profile::contact_forces] += pair_s;
  profile_.seconds[Profile::walls_kick] += particle_s;
  profile_.seconds[Profile::fluid] += fluid_s;
  profile_.seconds[Profile::wait] += wait_s;
  return done;
}

// First half kick and drift in one loop, with the domain check and the displacement since the last
// rebuild (max and min reductions: exact in any order, so any schedule gives the same result).
double World::kick_drift(double h) {
  const long n = static_cast<long>(p_.size());
  const bool rot = p_.has_rotation;
  const bool roll = kick_friction_;
  double max_d2 = 0.0;
  long bad = std::numeric_limits<long>::max();
  const bool parallel = n >= parallel_min_items && omp_get_max_threads() > 1;
#pragma omp parallel for schedule(static, 256) reduction(max : max_d2) reduction(min : bad) if (parallel)
  for (long a = 0; a < n; ++a) {
    kick_one(a, h, rot, roll);
    drift_one(a, max_d2, bad);
  }
  if (bad != std::numeric_limits<long>::max() && bad_index_ < 0) bad_index_ = bad;
  return max_d2;
}

// A step: kick and drift (fused into the previous step's last pass, except at the start of a batch),
// t += dt, the domain check, a rebuild if due, then the forces at t and the closing half kick.
void World::advance(long n) {
  if (n <= 0) return;
  const double h = 0.5 * cfg_.dt;
  double moved2 = 0.0;
  if (!started_) {
    {
      StageTimer timer{profile_.seconds[Profile::neighbor]};
      rebuild_neighbors();
    }
    passes(1, h, true, moved2);
    started_ = true;
  }
  {
    StageTimer timer{profile_.seconds[Profile::kick_drift]};
    moved2 = kick_drift(h);
  }
  t_ += cfg_.dt;
  ++steps_;
  for (long left = n; left > 0;) {
    if (bad_index_ >= 0) flagged(moved2);
    if (rebuild_due(moved2, t_)) {
      StageTimer timer{profile_.seconds[Profile::neighbor]};
      rebuild_neighbors();
    }
    left -= passes(left, h, false, moved2);
  }
  if (bad_index_ >= 0) flagged(moved2);
}

void World::flagged(double& moved2) {
  if (cfg_.on_exit == ExitRule::stop) {
    check();
    return;
  }
  check_particles(false);  // NaN / inf and energy blow-ups stop the run whatever on_exit says
  StageTimer timer{profile_.seconds[Profile::neighbor]};
  remove_escaped(moved2);
}

namespace {

bool outside(const Vec3& x, const Vec3& lo, const Vec3& hi) {
  return !(x.x >= lo.x && x.x <= hi.x && x.y >= lo.y && x.y <= hi.y && x.z >= lo.z && x.z <= hi.z);
}

std::string left_domain(const Vec3& lo, const Vec3& hi) {
  return fmt::format("left the domain [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] m", lo.x, hi.x, lo.y,
                     hi.y, lo.z, hi.z);
}

}  // namespace

void World::remove_escaped(double& moved2) {
  const std::size_t n = p_.size();
  const Vec3 lo = cfg_.domain_min, hi = cfg_.domain_max;
  std::vector<char> gone(n, 0);
  double total = escaped_mass_, leaving = 0.0;  // kg: every particle ever in the world; those leaving now
  std::size_t last = n;
  for (std::size_t a = 0; a < n; ++a) {
    total += p_.mass[a];
    if (!outside(p_.x[a], lo, hi)) continue;
    gone[a] = 1;
    leaving += p_.mass[a];
    last = a;
  }
  bad_index_ = -1;
  if (last == n) return;  // nothing outside (a flag without a cause cannot happen: NaN was checked)
  const double lost = escaped_mass_ + leaving;
  if (lost > cfg_.max_escaped_fraction * total)
    fail(last, fmt::format("{}; {:.6g} kg of particles have now left ({:.3g} % of {:.6g} kg), more than "
                           "[domain] max_escaped_fraction = {:g}: many escapes are a blow-up, not a splash "
                           "(time step too large for the stiffness?)",
                           left_domain(lo, hi), lost, 100.0 * lost / total, total, cfg_.max_escaped_fraction));
  for (std::size_t a = 0; a < n; ++a)
    if (gone[a])
      escaped_.push_back({p_.id[a], t_, p_.mass[a], p_.radius[a], p_.material[a], p_.x[a], p_.v[a]});
  escaped_mass_ = lost;
  const std::vector<std::uint32_t> map = p_.remove_if(gone);
  pairs_.remove_particles(map, p_.size());
  wall_contacts_.remove_particles(map);
  if (fluid_) fluid_->particles_removed();
  rebuild_neighbors();
  moved2 = 0.0;
}

void World::fail(std::size_t a, const std::string& cause) const {
  const Vec3& x = p_.x[a];
  const Vec3& v = p_.v[a];
  throw RuntimeFailure(fmt::format(
      "particle id {} at t = {:.6g} s (step {}): {}; position ({:.6g}, {:.6g}, {:.6g}) m, velocity "
      "({:.6g}, {:.6g}, {:.6g}) m/s",
      p_.id[a], t_, steps_, cause, x.x, x.y, x.z, v.x, v.y, v.z));
}

void World::check_particles(bool domain) const {
  const std::size_t n = p_.size();
  const Vec3 lo = cfg_.domain_min, hi = cfg_.domain_max;
  for (std::size_t a = 0; a < n; ++a) {
    const Vec3& x = p_.x[a];
    const Vec3& v = p_.v[a];
    if (!std::isfinite(x.x + x.y + x.z + v.x + v.y + v.z)) fail(a, "non-finite position or velocity (NaN/inf)");
    if (p_.has_rotation && !std::isfinite(p_.omega[a].x + p_.omega[a].y + p_.omega[a].z))
      fail(a, "non-finite angular velocity");
    if (domain && outside(x, lo, hi)) fail(a, left_domain(lo, hi));
  }
  if (cfg_.kinetic_limit > 0.0) {
    double ke = 0.0, ke_max = -1.0;
    std::size_t worst = 0;
    for (std::size_t a = 0; a < n; ++a) {
      const double e = 0.5 * p_.mass[a] * norm2(p_.v[a]);
      ke += e;
      if (e > ke_max) {
        ke_max = e;
        worst = a;
      }
    }
    if (ke > cfg_.kinetic_limit)
      fail(worst, fmt::format("kinetic-energy blow-up: total {:.6g} J exceeds the limit {:.6g} J (the "
                              "initial energy plus the largest fall in the domain); time step too large for "
                              "the stiffness?",
                              ke, cfg_.kinetic_limit));
  }
}

Energies World::energies() const {
  Energies e;
  const std::size_t n = p_.size();
  for (std::size_t a = 0; a < n; ++a) {
    e.kinetic += 0.5 * p_.mass[a] * norm2(p_.v[a]);
    if (p_.has_rotation) e.rotational += 0.5 * norm2(p_.omega[a]) / p_.inv_inertia[a];
    e.potential -= p_.mass[a] * dot(cfg_.gravity, p_.x[a]);
  }
  const std::size_t nm = materials_.size();
  // The contact law's normal-spring energy (its tangential spring excluded).
  std::visit(
      [&](const auto& table) {
        using Law = LawOf<decltype(table)>;
        auto pair_of = [&](int ma, int mb) -> const auto& { return table[static_cast<std::size_t>(ma) * nm + mb]; };
        for (std::size_t k = 0; k < pairs_.size(); ++k) {
          const auto a = pairs_.i[k], b = pairs_.j[k];
          const double rsum = p_.radius[a] + p_.radius[b];
          const double d = rsum - norm(p_.x[b] - p_.x[a]);
          if (d <= 0.0) continue;
          ++e.pair_contacts;
          const double rs = p_.radius[a] * p_.radius[b] / rsum;
          e.elastic += Law::elastic_energy(pair_of(p_.material[a], p_.material[b]), rs, d);
        }
        for (std::size_t a = 0; a < n; ++a)
          for (const Wall& w : walls_) {
            if (!w.active(t_)) continue;
            Vec3 nn;
            const double d = p_.radius[a] - wall_distance(w, w.displacement(t_), p_.x[a], &nn);
            if (d <= 0.0) continue;
            ++e.wall_contacts;
            e.elastic += Law::elastic_energy(pair_of(p_.material[a], w.material), p_.radius[a], d);
          }
      },
      laws_);
  return e;
}

}  // namespace pastemix::model
