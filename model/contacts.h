// SPDX-License-Identifier: MIT
// Contacts: the particle-pair list (SoA), its history, and the two force passes.
//
// Determinism without atomics: the pair pass writes one force (and the two torques) per pair into the
// SoA; the gather pass then sums, per particle, its pairs in ascending pair order through a CSR index.
// Both passes are parallel over independent outputs, so the result is bitwise the same for any number of
// threads. Wall contacts are computed per particle (a particle owns its wall contacts), in wall order.
//
// History (tangential spring, rolling spring) is keyed by the sorted pair of particle ids and carried
// from the old list to the new one at every neighbour rebuild, so a lasting contact keeps its spring.
#pragma once

#include <cstdint>
#include <vector>

#include "model/laws/contact_law.h"
#include "model/neighbor.h"
#include "model/particles.h"
#include "model/walls.h"

namespace pastemix::model {

struct PairList {
  int width = 0;                       // history doubles per contact
  std::vector<std::uint32_t> i, j;     // dense indices
  std::vector<std::uint64_t> key;      // (min id << 32) | max id
  // R* = R_i R_j / (R_i + R_j) (m) and m* = m_i m_j / (m_i + m_j) (kg) per pair, computed once per rebuild
  // with the same expressions the pair pass used (so the same bits): two divisions less per contact.
  std::vector<double> r_star, m_star;
  std::vector<double> history;         // width per pair
  // What a touching pair contributes, packed together so the gather reads one or two cache lines per
  // pair (stale for pairs not touching: the gather skips them).
  struct Out {
    Vec3 force_i;            // N, on i (j gets minus)
    Vec3 torque_i, torque_j; // N.m (rotation only)
    double roll_i, roll_j;   // N.m, constant-torque rolling capacity (rotation only)
  };
  std::vector<Out> out;
  std::vector<std::uint32_t> touching;  // 0/1; not uint8: a char store may alias anything and forces reloads
  // CSR: for particle p, entries [start[p], start[p+1]) of `entry` = pair * 2 + (0 if p is i, 1 if j).
  std::vector<std::uint32_t> start, entry;

  std::size_t size() const { return i.size(); }
  // Replaces the pairs by `c`, carrying over the history of pairs present before.
  void rebuild(const CandidatePairs& c, const Particles& p);
};

// Per particle and wall: history slots and a touching flag, plus a Verlet list of the walls within
// radius + skin of each particle (most particles have none, so the wall pass costs nearly nothing).
struct WallContacts {
  int width = 0;
  int walls = 0;
  std::vector<double> history;           // (particle * walls + wall) * width
  std::vector<std::uint32_t> touching;   // particle * walls + wall (not uint8: char stores alias)
  std::vector<std::uint32_t> start;      // CSR: candidate walls of particle p are near[start[p] .. start[p+1])
  std::vector<std::uint16_t> near;
  void resize(std::size_t particles, int n_walls, int history_width);
  // Rebuilds the candidate lists at time t (walls at their positions then); clears the history of
  // particle-wall slots that are no longer candidates.
  void rebuild(const std::vector<Wall>& walls, const Particles& p, double t, double skin);
};

struct StepContext {
  double t = 0.0;    // s, time at which forces are evaluated
  double dt = 0.0;   // s
  int n_materials = 0;
  RollingLaw rolling = RollingLaw::none;
};

// Pair forces, summed into p.f / p.torque / p.rolling_capacity (overwriting them); the law is chosen once
// here with std::visit. With several threads: one output per pair, then gather_pair_forces; with one
// thread the sums are made directly in the same order (bitwise the same result, no second pass).
void compute_pair_forces(const LawTable& laws, const StepContext& ctx, Particles& p, PairList& pairs);
// Sums pair forces into p.f / p.torque / p.rolling_capacity (overwrites them).
void gather_pair_forces(const PairList& pairs, Particles& p);
// Adds wall forces into p.f / p.torque / p.rolling_capacity.
void add_wall_forces(const LawTable& laws, const StepContext& ctx, const std::vector<Wall>& walls,
                     Particles& p, WallContacts& wc);

}  // namespace pastemix::model
