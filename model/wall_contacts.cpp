// SPDX-License-Identifier: MIT
// The wall candidate lists (WallContacts, model/contacts.h): their rebuild in steps a thread team can overlap
// with the neighbour search (World::rebuild_neighbors), and their renaming at a spatial sort or a removal.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "model/contacts.h"

namespace pastemix::model {

namespace {

constexpr long kWallBlock = 256;  // particles per block of the wall-list rebuild (their flags stay in L1)

}  // namespace

void WallContacts::resize(std::size_t particles, int n_walls, int history_width) {
  walls = n_walls;
  width = history_width;
  start.assign(particles + 1, 0);
  listed.clear();
  near.clear();
  history.clear();
  touching.clear();
}

void WallContacts::rebuild(const std::vector<Wall>& w, const Particles& p, double t, double skin, int threads) {
  YieldBarrier barrier;
  run_team(threads, barrier, [&](const Team& team) { rebuild(w, p, t, skin, team); });
}

void WallContacts::rebuild(const std::vector<Wall>& w, const Particles& p, double t, double skin, const Team& team) {
  // One team, three syncs: candidate flags (per wall, one loop over a block of particles for the plane bound,
  // then the exact distance where the bound does not rule the wall out), each particle's count, the CSR
  // offsets (one thread: a prefix sum), then per particle its row and the history carry-over from its old
  // candidates (a few entries). The new lists go into the spare buffers (capacity kept between rebuilds)
  // and are swapped in. (Issue 19: with the flags one particle and wall at a time and the rows by push_back
  // in one thread, this rebuild took 0.38 ms of a 13k pour's ~1.7 ms, at any thread count.)
  if (team.me == 0) prepare(p.size(), w.size());
  team.sync();
  long b0 = 0, b1 = 0;
  team.range(blocks(p.size()), b0, b1);
  flag_blocks(w, p, t, skin, b0, b1);
  team.sync();
  if (team.me == 0) lay_out();
  team.sync();
  long a0 = 0, a1 = 0;
  team.range(static_cast<long>(p.size()), a0, a1);
  fill_rows(a0, a1);
  team.sync();
  if (team.me == 0) swap_in();  // the caller syncs before the lists are read
}

void WallContacts::prepare(std::size_t n_particles, std::size_t n_walls) {
  cand_.resize(n_particles * n_walls);
  count_.resize(n_particles);
  spare_start_.resize(n_particles + 1);
  cand_walls_ = n_walls;
}

long WallContacts::blocks(std::size_t n_particles) {
  return (static_cast<long>(n_particles) + kWallBlock - 1) / kWallBlock;
}

void WallContacts::flag_blocks(const std::vector<Wall>& w, const Particles& p, double t, double skin, long b0,
                               long b1) {
  const std::size_t nw = w.size();
  std::vector<Vec3> shift(nw);
  std::vector<char> active(nw);
  for (std::size_t k = 0; k < nw; ++k) {
    shift[k] = w[k].displacement(t);
    active[k] = w[k].active(t);
  }
  const long nn = static_cast<long>(p.size());
  const Vec3* x = p.x.data();
  const double* radius = p.radius.data();
  std::uint32_t* count = count_.data();
  for (long a0 = b0 * kWallBlock; a0 < std::min(nn, b1 * kWallBlock); a0 += kWallBlock) {
    const long a1 = std::min(nn, a0 + kWallBlock);
    for (long a = a0; a < a1; ++a) count[a] = 0;
    for (std::size_t k = 0; k < nw; ++k) {
      // Wall k's flags of all particles are contiguous (column k): each loop below is one stride-1 pass that
      // the compiler vectorises (with a particle's flags side by side, the stores went one byte at a time and
      // the count per particle was a five-iteration loop: together ~35 % of this function's samples).
      char* ck = cand_.data() + k * static_cast<std::size_t>(nn);
      const Wall& wk = w[k];
      // The bound only skips walls that are clearly out of reach (the margin absorbs its round-off). Its
      // kind is picked here, once per wall, and its parameters copied (the char stores may alias the wall):
      // through wall_distance_bound's dispatch per particle the compiler did not vectorise the loop, and
      // the flags of a 13k pour's box took 0.35 ms per rebuild, longer than the search's serial set-up
      // they run beside.
      const auto flag = [&](auto bound) {
        for (long a = a0; a < a1; ++a) ck[a] = bound(x[a]) < (radius[a] + skin) * (1.0 + 1e-9);
      };
      const Vec3 o = wk.origin + shift[k];
      if (!active[k])
        flag([](const Vec3&) { return std::numeric_limits<double>::infinity(); });
      else if (wk.kind == WallKind::rectangle)
        flag([o, n = wk.unit_normal](const Vec3& q) { return rectangle_distance_bound(o, n, q); });
      else if (wk.kind == WallKind::revolution)
        flag([o, lo = std::min(wk.z0, wk.z1), hi = std::max(wk.z0, wk.z1)](const Vec3& q) {
          return revolution_distance_bound(lo, hi, o, q);
        });
      else
        flag([](const Vec3&) { return 0.0; });
      for (long a = a0; a < a1; ++a) {
        if (!ck[a]) continue;
        Vec3 unused;
        ck[a] = wall_distance(wk, shift[k], x[a], &unused) < radius[a] + skin;
      }
      for (long a = a0; a < a1; ++a) count[a] += static_cast<unsigned char>(ck[a]);
    }
  }
}

void WallContacts::lay_out() {
  const std::size_t n = count_.size();
  std::vector<std::uint32_t>& new_start = spare_start_;
  new_start[0] = 0;
  for (std::size_t a = 0; a < n; ++a) new_start[a + 1] = new_start[a] + count_[a];
  spare_near_.resize(new_start[n]);
  spare_hist_.assign(new_start[n] * static_cast<std::size_t>(width), 0.0);
  spare_touch_.assign(new_start[n], 0);
}

void WallContacts::fill_rows(long a0, long a1) {
  const std::size_t nw = cand_walls_;
  const std::size_t wd = static_cast<std::size_t>(width);
  const std::vector<std::uint32_t>& new_start = spare_start_;
  const char* cand = cand_.data();
  const std::size_t np = count_.size();
  for (long a = a0; a < a1; ++a) {
    std::uint32_t e = new_start[a];
    if (e == new_start[a + 1]) continue;  // no candidate (most particles): nothing to list or carry
    for (std::size_t k = 0; k < nw; ++k)
      if (cand[k * np + static_cast<std::size_t>(a)]) spare_near_[e++] = static_cast<std::uint16_t>(k);
    for (std::uint32_t c = new_start[a]; c < new_start[a + 1]; ++c)
      for (std::uint32_t o = start[a]; o < start[a + 1]; ++o) {
        if (near[o] != spare_near_[c]) continue;
        if (touching[o]) {
          spare_touch_[c] = 1;
          std::copy_n(&history[o * wd], wd, &spare_hist_[c * wd]);
        }
        break;
      }
  }
}

void WallContacts::swap_in() {
  start.swap(spare_start_);
  near.swap(spare_near_);
  history.swap(spare_hist_);
  touching.swap(spare_touch_);
  list_particles();
}

void WallContacts::list_particles() {
  listed.clear();
  for (std::size_t a = 0; a + 1 < start.size(); ++a)
    if (start[a + 1] > start[a]) listed.push_back(static_cast<std::uint32_t>(a));
}

void WallContacts::rename(const std::vector<std::uint32_t>& map, std::size_t np) {
  const std::size_t wd = static_cast<std::size_t>(width);
  // The new rows: their lengths by new index, prefix sums, then each kept row copied to its new place.
  std::vector<std::uint32_t>& new_start = spare_start_;
  new_start.assign(np + 1, 0);
  for (std::size_t a = 0; a + 1 < start.size(); ++a)
    if (map[a] != Particles::kGone) new_start[map[a] + 1] = start[a + 1] - start[a];
  for (std::size_t q = 0; q < np; ++q) new_start[q + 1] += new_start[q];
  const std::size_t total = new_start[np];
  spare_near_.resize(total);
  spare_touch_.resize(total);
  spare_hist_.resize(total * wd);
  for (std::size_t a = 0; a + 1 < start.size(); ++a) {
    if (map[a] == Particles::kGone) continue;
    const std::uint32_t c0 = start[a], c1 = start[a + 1], to = new_start[map[a]];
    std::copy(near.begin() + c0, near.begin() + c1, spare_near_.begin() + to);
    std::copy(touching.begin() + c0, touching.begin() + c1, spare_touch_.begin() + to);
    std::copy_n(history.data() + c0 * wd, (c1 - c0) * wd, spare_hist_.data() + to * wd);
  }
  start.swap(new_start);
  near.swap(spare_near_);
  touching.swap(spare_touch_);
  history.swap(spare_hist_);
  list_particles();
}

}  // namespace pastemix::model
