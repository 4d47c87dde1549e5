// SPDX-License-Identifier: MIT
// The neighbour rebuild (World::rebuild_neighbors, World::rebuild_lists), when it is due (World::rebuild_due,
// model/motion.h) and the spatial sort of the particle store ([neighbor] sort_every, issue 19:
// World::cell_order, World::sort_particles), apart from the step (model/world.cpp).
#include "model/world.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>

#include <fmt/format.h>

#include "base/error.h"

namespace pastemix::model {

bool World::rebuild_due(const Motion& moved, double t) const {
  // The pair list stays valid while no pair's gap has closed by the skin (model/motion.h bounds that), the
  // wall candidates (walls within radius + skin) while particle plus wall motion stays below the skin, and
  // the fluid's candidates (margin 2 skin, set_fluid) while no particle has moved the skin. A wall's motion is
  // |v| (t - t_build); a removed wall needs no rebuild (it is skipped when inactive).
  double wall_move = 0.0;
  for (const Wall& wall : walls_)
    wall_move = std::max(wall_move, norm(wall.displacement(t) - wall.displacement(t_at_rebuild_)));
  return moved.pair_bound() > cfg_.skin || std::sqrt(moved.max2()) + wall_move > cfg_.skin;
}

bool World::refine_moves(const Motion& moved) const {
  // The refined test pays off only once the usual one, 2 max|dx| > skin, is near: from 80 % of it on (a
  // list that lives more than five steps reaches it before it would be due).
  return 2.0 * std::sqrt(moved.max2()) > 0.8 * cfg_.skin;
}

void World::set_shift_velocity() {
  // The fast particles' mean velocity: a falling stream's, whose spheres then count as hardly moving
  // (model/motion.h). Serial, in index order: the same for any thread count. Any value is exact; this one
  // cut chapter-7 test 1's rebuilds over its first 0.3 s by 35 % (1,553 -> 1,013) and the bench pour's, whose
  // impacts throw spheres back up, by 14 % (248 -> 214).
  double vmax2 = 0.0;
  for (const Vec3& v : p_.v) vmax2 = std::max(vmax2, norm2(v));
  Vec3 sum;
  long count = 0;
  for (const Vec3& v : p_.v)
    if (norm2(v) >= 0.25 * vmax2) sum += v, ++count;
  shift_velocity_ = count > 0 ? sum * (1.0 / static_cast<double>(count)) : Vec3{};
}

// Pairs and wall candidates are rebuilt together, with the same skin: the wall lists cost one distance per
// particle and candidate wall, far less than the pair search, and a thin skin keeps them short (settled
// bed: 2,837 wall candidates with a 1 mm skin against 6,114 with 5 mm). Which candidates a list holds never
// changes a force: a pair or wall contact is computed whenever it touches, and every touching one is listed.
void World::rebuild_neighbors() {
  if (cfg_.sort_every > 0) {
    if (rebuilds_since_sort_ == 0) sort_particles();
    rebuilds_since_sort_ = (rebuilds_since_sort_ + 1) % cfg_.sort_every;
  }
  for_each_pass(forces_, [](auto& pass) {
    if constexpr (requires { pass.lists_rebuilt(); })
      if (pass.active()) pass.lists_rebuilt();
  });
  rebuild_lists(threads_for(static_cast<long>(p_.size())));  // (sets the shift velocity too)
  t_at_rebuild_ = t_;
  ++profile_.rebuilds;
}

// The candidate pairs, the pair list, the wall lists, the kept positions and the threads' partition, on
// `threads` threads.
void World::rebuild_lists(int threads) {
  const int n_materials = static_cast<int>(materials_.size());
#ifdef PASTEMIX_VALIDATE
  search_.build(p_.x, p_.radius, cfg_.skin, candidates_, threads);
  // Expensive check: the cell list must find exactly the brute-force pairs.
  if (brute_force_pairs(p_.x, p_.radius, cfg_.skin).i.size() != candidates_.i.size())
    throw RuntimeFailure(fmt::format("neighbour list at t = {} s disagrees with brute force", t_));
  pairs_.rebuild(candidates_, p_, n_materials, threads);
  wall_contacts_.rebuild(walls_, p_, t_, cfg_.skin, threads);
  x_at_rebuild_ = p_.x;
  set_shift_velocity();
  partition(threads, p_.x);
#else
  // The search, the pair list, the wall lists and the partition in one team, synced by the yielding
  // barrier: as separate libgomp regions (about ten regions and barriers per rebuild) the second thread
  // slept and woke at each under OMP_WAIT_POLICY=passive, and the 2-thread pour's rebuilds took as long as
  // on one thread (issue 19). The team sorts the particles into the search's grids and flags the wall
  // candidates (model/neighbor.h: side) together; while thread 0 partitions, thread 1 lays out the wall
  // lists, keeps the positions of this build and computes the shift velocity (model/motion.h).
  const std::size_t n = p_.size();
  std::exception_ptr failure;
  run_team(threads, step_barrier_, [&](const Team& team) {
    if (team.me == 0) wall_contacts_.prepare(n, walls_.size());
    team.sync();  // (the search may return before its own first sync: one particle)
    auto flags = [&](const Team& part) {
      long b0 = 0, b1 = 0;
      part.range(WallContacts::blocks(n), b0, b1);
      wall_contacts_.flag_blocks(walls_, p_, t_, cfg_.skin, b0, b1);
    };
    search_.build(p_.x, p_.radius, cfg_.skin, candidates_, team, flags);
    if (team.size == 1) flags(team);
    team.sync();
    pairs_.rebuild(candidates_, p_, n_materials, team);
    // Thread 0 finishes the pair list; the other thread then indexes it by first particle (for the next
    // rebuild's carry-over) beside thread 0's partition, which is the longer (13k pour, 2 threads, session 31's
    // timers: thread 0's pair-list phase, which ended with the index, 0.029 s against thread 1's 0.022 s).
    team.sync();  // (no wait for a team of one)
    if (team.me == (team.size > 1 ? 1 : 0)) {
      pairs_.index_by_first(n);
      wall_contacts_.lay_out();
      wall_contacts_.fill_rows(0, static_cast<long>(n));
      wall_contacts_.swap_in();
      x_at_rebuild_ = p_.x;
      // Reads the velocities only; serial after the team, it was ~4 % of the 2-thread pour's rebuild.
      set_shift_velocity();
    }
    // The threads' particles and pairs (slabs of the new positions), for the thread count of this build.
    // (An error leaves the region first: nobody syncs after this.)
    if (team.me == 0) try {
        partition(threads, p_.x, n >= 2 ? &search_.box() : nullptr);  // the search's box of these positions
      } catch (...) {
        failure = std::current_exception();
      }
  });
  if (failure) std::rethrow_exception(failure);
#endif
}

std::array<int, 3> World::slab_axes(std::array<int, 3> axis) const {
  // The threads' slabs are ranges of the sorted index (PairList::Slabs::index), so they are cut across the
  // slowest axis, and the pairs across a cut are done twice (from ghost copies). The longest side is the
  // usual choice, but not where a funnel or a stream stands above a flat pile: there a cut across the
  // height goes through the whole pile (case 3 of the main job: ~2,000 ghost particles, 5 % of the pairs
  // crossing, against ~1,000 and 2.8 % across its 20 cm side). So the slowest axis is the one whose middle
  // plane (by count) has the fewest particles within one largest diameter of it, the longest side keeping
  // its place unless another has under 3/4 of its count (no flip-flop between sorts). A function of the
  // positions only: the same order for any thread count.
  const std::size_t n = p_.size();
  double rmax = 0.0;
  for (double r : p_.radius) rmax = std::max(rmax, r);
  const double band = 2.0 * rmax + cfg_.skin;  // m
  std::array<long, 3> near{};
  std::vector<double> c(n);
  for (int k = 0; k < 3; ++k) {
    for (std::size_t a = 0; a < n; ++a) c[a] = k == 0 ? p_.x[a].x : k == 1 ? p_.x[a].y : p_.x[a].z;
    // The count needs no order: the median's partial sort in place.
    std::nth_element(c.begin(), c.begin() + static_cast<long>(n / 2), c.end());
    const double mid = c[n / 2];
    for (double q : c) near[k] += std::abs(q - mid) < band;
  }
  int best = axis[2];
  for (int k : {axis[1], axis[0]})
    if (4 * near[k] < 3 * near[axis[2]] && near[k] < near[best]) best = k;
  if (best == axis[2]) return axis;
  std::array<int, 3> order{};
  int f = 0;
  for (int k : axis)
    if (k != best) order[f++] = k;
  order[2] = best;
  return order;
}

// The cell order of the particles: a grid over their bounding box with the cells of the finest neighbour
// level (2 r_max + skin, r_max < 2 r_min: 4 r_min + skin), coarsened while it has more than ~4 cells per
// particle (a sparse cloud), cells numbered with the shortest side of the box fastest and the longest
// slowest (or the side slab_axes picks), particles in a cell by their current index (a counting sort:
// stable, linear). Why this order: the pair pass then sweeps the box along its slowest side, and its
// working set is a few layers of cells across the two other sides (a 207k-sphere pour: ~4,000 spheres,
// ~1 MB, inside the L2 cache), where the insertion order put a sphere's partners of the next lattice layer
// 17,280 entries away; and the threads' slabs (PairList::partition, Slabs::index) are index ranges, cut
// across the slowest axis.
std::vector<std::uint32_t> World::cell_order() const {
  const std::size_t n = p_.size();
  std::vector<std::uint32_t> map(n);
  if (n == 0) return map;
  Vec3 lo = p_.x[0], hi = p_.x[0];
  double rmin = p_.radius[0];
  for (std::size_t a = 0; a < n; ++a) {
    const Vec3& q = p_.x[a];
    lo = {std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z)};
    hi = {std::max(hi.x, q.x), std::max(hi.y, q.y), std::max(hi.z, q.z)};
    rmin = std::min(rmin, p_.radius[a]);
  }
  const std::array<double, 3> ext{hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
  std::array<int, 3> axis{0, 1, 2};  // fastest .. slowest
  std::stable_sort(axis.begin(), axis.end(), [&](int u, int w) { return ext[u] < ext[w]; });
  axis = slab_axes(axis);
  double cell = 4.0 * rmin + cfg_.skin;
  std::array<long, 3> dim{};
  auto cells = [&] {
    for (int k = 0; k < 3; ++k) dim[k] = static_cast<long>(ext[axis[k]] / cell) + 1;
    return static_cast<double>(dim[0]) * static_cast<double>(dim[1]) * static_cast<double>(dim[2]);
  };
  while (cells() > 4.0 * static_cast<double>(n) + 64.0) cell *= 1.5;
  const double inv = 1.0 / cell;
  auto coord = [](const Vec3& q, int k) { return k == 0 ? q.x : k == 1 ? q.y : q.z; };
  std::vector<std::uint32_t> key(n), start(static_cast<std::size_t>(dim[0] * dim[1] * dim[2]) + 1, 0);
  for (std::size_t a = 0; a < n; ++a) {
    long c[3];
    for (int k = 0; k < 3; ++k)
      c[k] = std::clamp(static_cast<long>((coord(p_.x[a], axis[k]) - coord(lo, axis[k])) * inv), 0L, dim[k] - 1);
    key[a] = static_cast<std::uint32_t>((c[2] * dim[1] + c[1]) * dim[0] + c[0]);
    ++start[key[a] + 1];
  }
  for (std::size_t c = 0; c + 1 < start.size(); ++c) start[c + 1] += start[c];
  for (std::size_t a = 0; a < n; ++a) map[a] = start[key[a]]++;
  return map;
}

void World::sort_particles() {
  const std::vector<std::uint32_t> map = cell_order();
  bool same = true;
  for (std::size_t a = 0; a < map.size() && same; ++a) same = map[a] == a;
  if (same) return;
  const std::size_t n = p_.size();
  // Four moves of disjoint data: the pair list's (~4 pairs per sphere, 64 B each) on one thread, the
  // particles', wall lists' and passes' (~300 B per sphere) on the other. Serial, the sort left the second
  // thread idle: chapter-7 test 1 on 2 threads (perf, session 41), 1.3 % of thread 0's samples fell in
  // the sort while thread 1 did nothing. Each move reads only `map` and writes only its own arrays: the
  // same bits on any thread count.
  std::exception_ptr failure;
  run_team(threads_for(static_cast<long>(n)), step_barrier_, [&](const Team& team) {
    try {
      if (team.me == (team.size > 1 ? 1 : 0)) pairs_.rename(map, n);
      if (team.me != 0) return;
      p_.apply_map(map, n);
      wall_contacts_.rename(map, n);
      for_each_pass(forces_, [&](auto& pass) {
        if constexpr (requires { pass.particles_moved(map); })
          if (pass.active()) pass.particles_moved(map);
      });
    } catch (...) {
#pragma omp critical(pastemix_sort_failure)
      failure = std::current_exception();
    }
  });
  if (failure) std::rethrow_exception(failure);
  ++profile_.sorts;
}

}  // namespace pastemix::model
