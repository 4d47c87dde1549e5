// SPDX-License-Identifier: MIT
// Contacts: the particle-pair list (SoA), its history, and the two force passes.
//
// Determinism without atomics (several threads): the particles are split into contiguous blocks, one per
// thread, balanced by their pair counts at each rebuild. A thread computes every pair that has a particle
// in its block, in ascending pair order, and adds the force only to its own particles: each particle's sum
// runs over its pairs in ascending pair order, exactly the one-thread order, so the bits do not depend on
// the thread count. A pair across two blocks is computed by both threads (as LIGGGHTS computes pairs
// across a domain cut on both ranks with `newton off`); no per-pair outputs, no gather pass, and a step
// needs one barrier. Its history is double buffered (read from one buffer, written by the owner of i into
// the other) so that the second thread never reads a spring the first has already advanced. Wall
// contacts are computed per particle by its owner, in wall order.
//
// History (tangential spring, rolling spring) belongs to the pair of particles (dense indices) and is
// carried from the old list to the new one at every neighbour rebuild, so a lasting contact keeps its
// spring. Dense indices change when particles are removed (outflow, World::remove_escaped) and when the
// World sorts the store spatially at a rebuild ([neighbor] sort_every): then rename() renames the old
// list's pairs and wall candidates through the old -> new index map (dropping those of removed particles)
// before the rebuild that follows, so the carry-over still finds every remaining contact.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "model/laws/registry.h"
#include "model/neighbor.h"
#include "model/particles.h"
#include "model/wall_batch.h"
#include "model/walls.h"

namespace pastemix::model {

struct PairList {
  int width = 0;                       // history doubles per contact
  std::vector<std::uint32_t> i, j;     // dense indices
  // R* = R_i R_j / (R_i + R_j) (m) and m* = m_i m_j / (m_i + m_j) (kg) per pair, computed once per rebuild
  // with the same expressions the pair pass used (so the same bits): two divisions less per contact.
  std::vector<double> r_star, m_star;
  // R_i + R_j (m) per pair, at the rebuild (the same sum the filter formed): the touching test reads one
  // sequential double instead of two radii gathered by particle (issue 19: ~18 % of a settled bed's samples
  // were the filter).
  std::vector<double> rsum;
  std::vector<std::uint32_t> law_index;  // material[i] * n_materials + material[j]: the law table entry
  // The law table entry of every pair when they all share one (set by rebuild(); 0xffffffff: unknown or
  // several): the batch kernel's parameters are then loaded once per batch, not per contact.
  std::uint32_t uniform_law = 0xffffffffu;
  void find_uniform_law();  // sets uniform_law from law_index
  std::vector<double> history;         // width per pair
  std::vector<std::uint32_t> touching;  // 0/1; not uint8: a char store may alias anything and forces reloads
  // CSR by first particle: the pairs with i = p are entry[start[p] .. start[p+1]), ascending (the history
  // carry-over at rebuilds).
  std::vector<std::uint32_t> start, entry;
  std::vector<double> spare_hist;          // rebuild() builds the new history here, then swaps
  std::vector<std::uint32_t> spare_touch;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> law_range;  // rebuild(): per thread, its lowest and highest law

  // Partition for `threads` threads (0: none yet; rebuild() resets it): thread t owns the particles
  // own[t] (ascending; owner[a] = t) and computes the pairs mine[t] (ascending; kCrossBit below). cross[k] indexes the pairs
  // across two threads' particles (kNone otherwise); their history lives in cross_hist[parity] while the
  // threads run and is copied back into `history` by sync_cross().
  static constexpr std::uint32_t kNone = 0xffffffffu;
  // An entry of mine[t] is a pair index, with kCrossBit set for a cross pair: the pair pass then tells a
  // cross pair, and needs the owners, only from its own list (issue 19: the loads of cross[k] and of both
  // owners for every pair made a settled bed's pair pass ~35 % dearer at 2 threads than at 1).
  static constexpr std::uint32_t kCrossBit = 0x80000000u;
  int threads = 0;
  long partitions = 0;  // partition() calls so far: a stamp that changes whenever the owners may have
  std::vector<std::uint8_t> owner;
  std::vector<std::vector<std::uint32_t>> own;
  std::vector<std::vector<std::uint32_t>> mine;
  // mine[t] cut into segments, in order: a run is at least kMinRun consecutive pair indices without a cross
  // pair, whose pairs the pair pass computes as one thread computes the whole list (both particles are the
  // thread's own; no entry list, no cross lanes); the rest (cross pairs and short runs between them) goes
  // through the thread-part path. On one thread's list that path cost ~25 % more per candidate in the filter
  // than the plain one (case-3 segment, one thread forced through it: 4.5-4.7 against 3.6-3.7 cycles), and a
  // thread's list is mostly one long run (issue 19).
  struct Segment {
    std::uint32_t q0, q1;  // entries mine[t][q0 .. q1)
    bool run;
  };
  static constexpr std::uint32_t kMinRun = 128;
  std::vector<std::vector<Segment>> segments;
  std::vector<std::uint32_t> cross;
  std::vector<std::uint32_t> cross_pairs;  // pair index of each cross slot
  std::vector<double> cross_hist[2];
  // Ghost copies of the particles of cross pairs (position, velocity, angular velocity), double buffered
  // like their history: a pass reads ghost[parity]; each thread writes its own particles' new state into
  // ghost[1 - parity] after their drift. So a thread never reads what another is writing, and a step
  // needs one barrier (after the drift), as MPI codes exchange ghost atoms once per step.
  struct Ghost {
    Vec3 x, v, w;
  };
  std::vector<std::uint32_t> ghost_of;  // per particle: its ghost slot, or kNone
  std::vector<std::uint32_t> ghosts;    // particle of each ghost slot
  std::vector<Ghost> ghost[2];
  int parity = 0;
  // The state of particle q as the threads see it during a pass reading buffer `cur`.
  const Ghost& state(std::uint32_t q, int cur) const { return ghost[cur][ghost_of[q]]; }

  std::size_t size() const { return i.size(); }
  // Replaces the pairs by `c`, carrying over the history of pairs present before (c gets the old arrays).
  // loop_threads: of its loop (model/parallel.h); the result does not depend on it.
  void rebuild(CandidatePairs& c, const Particles& p, int n_materials, int loop_threads);
  // The same, run by every thread of a team inside its parallel region (model/parallel.h); the list is
  // complete after the team's next sync, but for its CSR by first particle (start, entry): one thread calls
  // index_by_first() after that sync (World::rebuild_lists: the thread that is not partitioning).
  void rebuild(CandidatePairs& c, const Particles& p, int n_materials, const Team& team);
  // Splits the particles (positions x) into `threads` slabs, thread t's slab of about share[t] of the total
  // cost (particles, pairs, touching pairs, and `extra` per particle where given: the force passes' own
  // work, e.g. a fluid kick); equal shares without `share`. The slabs (see `slabs`) are ranges of the dense
  // index, or slices across the longest side of the particles' bounding box.
  // work[t]: the cost of thread t's slab (the units of the load balance, World::partition).
  // box: the positions' bounding box (min xyz, max xyz) where the caller has it (the neighbour search's,
  // of the same positions), else computed here.
  void partition(int threads, const std::vector<Vec3>& x, const std::vector<double>* extra = nullptr,
                 const std::vector<double>* share = nullptr, const std::array<double, 6>* box = nullptr);
  std::vector<double> work;
  std::vector<double> cost_scratch;  // partition()'s cost per particle (kept: no allocation per partition)
  // What partition() cuts: Slabs::index where the store is in a spatial order (World's sort at rebuilds,
  // [neighbor] sort_every > 0): index ranges are then spatial slabs too, and each thread's particles, pairs
  // and their cache lines are its own. Slabs::space cuts across the longest side of the bounding box (a
  // store in input order, whose index ranges would cross many pairs), so near a cut the owners of
  // neighbouring indices alternate: case 3 of the main job (cut across its flat pile, ~900 alternations per
  // partition) spent 2.4x the samples of one thread in the pair filter and 2.5x in the kicks, both threads
  // writing into the same cache lines (issue 19).
  enum class Slabs { space, index };
  Slabs slabs = Slabs::space;
  // Copies the cross pairs' history back into `history` (the threads are done).
  void sync_cross();
  // Sets ghost[parity] from the particles (before the threads start).
  void fill_ghosts(const Particles& p);
  // The particles were renamed (map: old -> new dense index, Particles::kGone if removed; np: the new
  // count; an outflow removal or the spatial sort): drops the pairs of removed particles and renames the
  // others, history and touching flags kept (a pair whose ends swap keeps (lower, higher) with its springs
  // negated). The threads are done, sync_cross() has run. Only rebuild() may follow: the partition is reset.
  void rename(const std::vector<std::uint32_t>& map, std::size_t np);
  // The CSR start / entry by first particle (for np particles), of the pairs as they are now.
  void index_by_first(std::size_t np);
};

// Per particle: a Verlet list of the walls within radius + skin (most particles have none, so the wall
// pass costs nearly nothing), and per listed (particle, wall) candidate its history slots and touching
// flag, stored in list order: the wall pass reads them as one stream, not as scattered slots of an
// all-particles x all-walls table. Carried over at each rebuild, like the pair history.
struct WallContacts {
  int width = 0;
  int walls = 0;
  std::vector<std::uint32_t> start;      // CSR: candidate walls of particle p are near[start[p] .. start[p+1])
  std::vector<std::uint16_t> near;
  std::vector<double> history;           // candidate c: [c * width, (c + 1) * width)
  std::vector<std::uint32_t> touching;   // per candidate (not uint8: char stores alias)
  // The particles that have candidate walls, ascending (derived from start by list_particles()): the wall
  // pass visits only them in a block of consecutive particles. A pour's or a bed's bottom layer is one sphere in
  // ten or twelve, and the test of every particle's empty row was a third of the wall pass's own samples.
  std::vector<std::uint32_t> listed;
  void list_particles();
  void resize(std::size_t particles, int n_walls, int history_width);
  // Rebuilds the candidate lists at time t (walls at their positions then), carrying over the history of
  // candidates that stay; a (particle, wall) that is no longer a candidate is not touching, so it has none.
  void rebuild(const std::vector<Wall>& walls, const Particles& p, double t, double skin, int threads);
  // The same, run by every thread of a team inside its parallel region; complete after the team's next sync.
  void rebuild(const std::vector<Wall>& walls, const Particles& p, double t, double skin, const Team& team);
  // rebuild() in its steps, for a team that overlaps them with other work (World::rebuild_neighbors):
  // prepare (one thread), then the candidate flags of the blocks of kWallBlock particles [b0, b1) (any
  // threads, any split of the blocks), then lay_out (one thread, after every block's flags), the rows of the
  // particles [a0, a1) (after lay_out) and swap_in (one thread, after every row).
  void prepare(std::size_t n_particles, std::size_t n_walls);
  static long blocks(std::size_t n_particles);
  void flag_blocks(const std::vector<Wall>& walls, const Particles& p, double t, double skin, long b0, long b1);
  void lay_out();
  void fill_rows(long a0, long a1);
  void swap_in();
  // The particles were renamed (map and np as PairList::rename): each kept particle's candidates move to
  // its new index with their history and flags; a removed particle's are dropped.
  void rename(const std::vector<std::uint32_t>& map, std::size_t np);

 private:
  std::vector<char> cand_;            // rebuild(): per wall and particle (wall k: [k n, (k + 1) n)), candidate or not
  std::vector<std::uint32_t> count_;  // rebuild(): per particle, its candidate walls
  std::size_t cand_walls_ = 0;        // rebuild(): walls per particle in cand_
  std::vector<std::uint32_t> spare_start_, spare_touch_;
  std::vector<std::uint16_t> spare_near_;
  std::vector<double> spare_hist_;
};

struct StepContext {
  double t = 0.0;    // s, time at which forces are evaluated
  double dt = 0.0;   // s
  int n_materials = 0;
};

// Pair forces of thread `thread`'s particles (pairs.partition() done for pairs.threads threads; all of
// them with one thread): their force, torque and rolling capacity are overwritten with the sums over their
// pairs in ascending pair order. Cross pairs read the history from cross_hist[parity] and write
// cross_hist[1 - parity]. The laws are chosen once here with std::visit.
void pair_forces(const LawTable& laws, const RollingTable& rolling, const StepContext& ctx, Particles& p,
                 PairList& pairs, int thread, int parity);

// The walls at the time the forces are evaluated, computed once per step.
struct WallState {
  std::vector<Vec3> shift, vel, origin;
  std::vector<char> active, rect;
  // wall_forces_block: this thread's place in WallContacts::listed (its blocks come in ascending order, so
  // each block's first listed particle is a few entries on; a search per block cost what it saved).
  std::size_t cursor = 0;
  void update(const std::vector<Wall>& walls, double t);
};

// Candidate c's touching flag from its overlap (m); a candidate that stops touching forgets its spring (a new
// contact starts from zero). NaN counts as touching (the force then shows it). Returns the flag.
inline bool mark_wall_touch(WallContacts& wc, std::uint32_t c, double overlap) {
  const bool touch = !(overlap <= 0.0);
  if (!touch && wc.touching[c]) std::fill_n(wc.history.data() + c * static_cast<std::size_t>(wc.width), wc.width, 0.0);
  wc.touching[c] = touch;
  return touch;
}

// Particle a against its wall candidate c: the distance from its centre to the wall's surface (m), the unit
// vector towards the wall and the overlap (m); sets the candidate's touching flag, and a candidate that does
// not touch forgets its spring (a new contact starts from zero). Both wall passes below.
inline bool touch_wall(const std::vector<Wall>& walls, const WallState& ws, const Particles& p, WallContacts& wc,
                       std::size_t a, std::uint32_t c, Vec3& n_to_wall, double& dist, double& overlap) {
  const int k = wc.near[c];
  dist = !ws.active[k] ? 1e300
         : ws.rect[k]  ? rectangle_distance(walls[k], ws.origin[k], p.x[a], &n_to_wall)
                       : wall_distance(walls[k], ws.shift[k], p.x[a], &n_to_wall);
  overlap = p.radius[a] - dist;
  return mark_wall_touch(wc, c, overlap);
}

// A block's wall candidates (particle a[e], candidate c[e]) and, after measure(), each one's distance (m) and
// unit vector towards its wall, as touch_wall computes them: a surface of revolution's (a funnel's cone and
// tube) eight at a time (model/wall_batch.h: the scalar form's operations in its order, the same bits), the
// others one at a time. The direction of an inactive wall's candidate is left unset (it never touches).
struct WallCandidates {
  static constexpr int kCands = 128;
  std::uint32_t a[kCands], c[kCands];
  // Not Vec3[kCands]: its zero-initialisation was a 3 kB memset per block of the wall pass.
  double dist[kCands], nx[kCands], ny[kCands], nz[kCands];
  int n = 0;

  void set(int e, double d, const Vec3& v) { dist[e] = d, nx[e] = v.x, ny[e] = v.y, nz[e] = v.z; }
  void measure(const std::vector<Wall>& walls, const WallState& ws, const Particles& p, const WallContacts& wc) {
    RevolutionLanes R;
    int lane_of[RevolutionLanes::kLanes];  // the candidates in R's lanes
    int nr = 0;
    const auto revolutions = [&] {
      revolution_distances(R, nr);
      for (int l = 0; l < nr; ++l) set(lane_of[l], R.dist[l], {R.nx[l], R.ny[l], R.nz[l]});
      nr = 0;
    };
    for (int e = 0; e < n; ++e) {
      const std::size_t q = a[e];
      const int k = wc.near[c[e]];
      Vec3 v;
      if (!ws.active[k]) {
        dist[e] = 1e300;
      } else if (ws.rect[k]) {
        set(e, rectangle_distance(walls[k], ws.origin[k], p.x[q], &v), v);
      } else if (walls[k].kind == WallKind::revolution) {
        R.set(nr, walls[k], ws.origin[k], p.x[q]), lane_of[nr] = e;
        if (++nr == RevolutionLanes::kLanes) revolutions();
      } else {
        set(e, wall_distance(walls[k], ws.shift[k], p.x[q], &v), v);
      }
    }
    if (nr > 0) revolutions();
  }
};

// Wall forces of particle a added to f / t / roll, its candidate walls in wall order. Inline: the World
// calls it inside its fused per-particle pass (forces, then the kick), one loop over the particles.
template <class Law, class Roll>
inline void wall_forces_one(const std::vector<typename Law::Params>& table,
                            const std::vector<typename Roll::Params>& rolling, const StepContext& ctx,
                            const std::vector<Wall>& walls, const WallState& ws, const Particles& p,
                            WallContacts& wc, std::size_t a, Vec3& f, Vec3& t, double& roll) {
  const bool rot = p.has_rotation;
  const int w = wc.width;
  for (std::uint32_t c = wc.start[a]; c < wc.start[a + 1]; ++c) {
    const int k = wc.near[c];
    const std::size_t slot = c;
    double* hist = w ? &wc.history[slot * static_cast<std::size_t>(w)] : nullptr;
    Vec3 n_to_wall;
    double dist, overlap;
    if (!touch_wall(walls, ws, p, wc, a, c, n_to_wall, dist, overlap)) continue;
    typename Law::Geometry g;
    g.n = n_to_wall;
    g.overlap = overlap;
    const double arm = std::max(dist, 0.0);
    g.R_star = p.radius[a];
    g.m_star = p.mass[a];
    g.v_rel = ws.vel[k] - p.v[a];
    if (rot) {
      g.v_rel -= cross(p.omega[a], g.n * arm);
      g.w_rel = p.omega[a];
    }
    g.arm_i = arm;
    g.dt = ctx.dt;
    const std::size_t pair = static_cast<std::size_t>(p.material[a] * ctx.n_materials + walls[k].material);
    const auto r = Law::force(table[pair], g, hist, w);
    f += r.force_i;
    if (rot) {
      Vec3 moment;  // N.m; +0 without a moment law (the sum's bits as before the laws were split)
      if constexpr (Roll::history_size > 0)
        moment = Roll::moment(rolling[pair], {g.w_rel, r.normal_stiffness, r.normal_force, g.R_star, g.m_star, g.dt},
                              hist + Law::history_size);
      t += cross(g.n * arm, r.tangential_i) + moment;
      if constexpr (Roll::kick_friction) roll += Roll::capacity(rolling[pair], r.normal_force, arm, g.R_star);
    }
  }
}

// wall_forces_one of particles idx[0 .. m) in turn, for a law with a wall batch kernel (Law::WallBatch,
// width = its history size, rotation on, no rolling spring): each touching (particle, wall) candidate is
// staged, in particle and then wall order, with the geometry wall_forces_one computes; Law::wall_force_batch
// computes kBatch of them at a time (several per instruction); the results are added in the same order,
// with the same expressions: the same bits as wall_forces_one per particle.
template <class Law, class Roll>
inline void wall_forces_block(const std::vector<typename Law::Params>& table,
                              const std::vector<typename Roll::Params>& rolling, const StepContext& ctx,
                              const std::vector<Wall>& walls, WallState& ws, Particles& p, WallContacts& wc,
                              const long* idx, int m) {
  static_assert(Roll::history_size == 0, "a rolling spring needs wall_forces_one");
  typename Law::WallBatch B;
  std::uint32_t slot[Law::kBatch];
  std::uint32_t who[Law::kBatch];
  double arm[Law::kBatch];
  std::size_t pair[Law::kBatch];
  int nb = 0;
  auto flush = [&] {
    Law::wall_force_batch(B, nb, ctx.dt);
    for (int e = 0; e < nb; ++e) {
      const std::size_t a = who[e];
      double* hist = &wc.history[slot[e] * static_cast<std::size_t>(Law::history_size)];
      hist[0] = B.hx[e], hist[1] = B.hy[e], hist[2] = B.hz[e];
      const Vec3 n{B.nx[e], B.ny[e], B.nz[e]}, ft{B.tx[e], B.ty[e], B.tz[e]};
      p.f[a] += Vec3{B.fx[e], B.fy[e], B.fz[e]};
      const Vec3 moment;  // +0: no moment law (the sum's bits as wall_forces_one's)
      p.torque[a] += cross(n * arm[e], ft) + moment;
      if constexpr (Roll::kick_friction)
        p.rolling_capacity[a] += Roll::capacity(rolling[pair[e]], B.fn[e], arm[e], B.r_star[e]);
    }
    nb = 0;
  };
  // The block's candidates, in particle and then wall order, WallCandidates::kCands at a time: first their
  // distances (WallCandidates::measure), then, in the same order, touch_wall's flags and springs and the
  // touching ones staged.
  WallCandidates W;
  int& nc = W.n;
  const auto stage = [&] {
    W.measure(walls, ws, p, wc);
    for (int e = 0; e < nc; ++e) {
      const std::size_t a = W.a[e];
      const std::uint32_t c = W.c[e];
      const int k = wc.near[c];
      const double dist = W.dist[e], overlap = p.radius[a] - dist;
      if (!mark_wall_touch(wc, c, overlap)) continue;
      const Vec3 n_to_wall{W.nx[e], W.ny[e], W.nz[e]};
      const double r_arm = std::max(dist, 0.0);
      Vec3 v_rel = ws.vel[k] - p.v[a];
      v_rel -= cross(p.omega[a], n_to_wall * r_arm);
      const double* h = &wc.history[c * static_cast<std::size_t>(Law::history_size)];
      B.nx[nb] = n_to_wall.x, B.ny[nb] = n_to_wall.y, B.nz[nb] = n_to_wall.z;
      B.overlap[nb] = overlap, B.r_star[nb] = p.radius[a], B.m_star[nb] = p.mass[a];
      B.vx[nb] = v_rel.x, B.vy[nb] = v_rel.y, B.vz[nb] = v_rel.z;
      B.hx[nb] = h[0], B.hy[nb] = h[1], B.hz[nb] = h[2];
      pair[nb] = static_cast<std::size_t>(p.material[a] * ctx.n_materials + walls[k].material);
      Law::load_params(B, nb, table[pair[nb]]);
      slot[nb] = c, who[nb] = static_cast<std::uint32_t>(a), arm[nb] = r_arm;
      if (++nb == Law::kBatch) flush();
    }
    nc = 0;
  };
  const auto visit = [&](std::size_t a) {
    for (std::uint32_t c = wc.start[a]; c < wc.start[a + 1]; ++c) {
      W.a[nc] = static_cast<std::uint32_t>(a), W.c[nc] = c;
      if (++nc == WallCandidates::kCands) stage();
    }
  };
  // A block of consecutive particles (one thread, or a run of a thread's slab): only its listed ones, in the
  // same ascending order.
  if (m > 0 && idx[m - 1] - idx[0] == m - 1) {
    const auto first = static_cast<std::uint32_t>(idx[0]), last = static_cast<std::uint32_t>(idx[m - 1]);
    const std::vector<std::uint32_t>& L = wc.listed;
    std::size_t& h = ws.cursor;
    if (h > L.size() || (h > 0 && L[h - 1] >= first))  // a new step, another run or new lists: search
      h = static_cast<std::size_t>(std::lower_bound(L.begin(), L.end(), first) - L.begin());
    while (h < L.size() && L[h] < first) ++h;
    for (; h < L.size() && L[h] <= last; ++h) visit(L[h]);
  } else {
    for (int q = 0; q < m; ++q) visit(static_cast<std::size_t>(idx[q]));
  }
  if (nc > 0) stage();
  if (nb > 0) flush();
}

}  // namespace pastemix::model
