// SPDX-License-Identifier: MIT
// The fluid pass: buoyancy and the drag of the fluid regions ([[fluid]], fluid/field.h). Each step, before
// the pair pass, the field finds the particles inside a region and their submerged volumes (each thread for
// its own particles; the collective rule's cluster updates read every member and the pair list, behind a
// barrier, every collective_interval); the plain kick skips those
// particles and the pass kicks them with FluidField::kick, i.e. the stable implicit drag kick of
// fluid/drag_kick.h (buoyancy + drag integrated exactly for the linear part, never reversing v). Without
// [[fluid]] there is no field and the pass is inactive: one pointer test per kick.
#pragma once

#include <omp.h>

#include <memory>
#include <vector>

#include "model/fluid/field.h"
#include "model/forces/force_pass.h"

namespace pastemix::model {

struct FluidForces {
  static constexpr PassInfo info{"fluid", Profile::fluid,
                                 reads::position | reads::velocity | reads::mass | reads::radius | reads::force,
                                 adds::kick, true};
  std::shared_ptr<fluid::FluidField> field;

  bool active() const { return field != nullptr; }

  // Before the team runs: the field's per-particle arrays and its threads' lanes (made anew whenever the
  // pair list was partitioned again: the owners may have changed).
  void begin_batch(const Particles& p, const PairList& pairs, int threads) {
    field->begin_batch(p, threads, pairs.partitions);
  }
  template <class Law, class Roll>
  void prepare(const PassStep<Law, Roll>& s) {
    // Each thread finds which of its own particles are inside (every position it reads is its own): no
    // barrier, except on the steps of a cluster update, which read every member and the pair list.
    const int threads = omp_get_num_threads();
    field->update_part(s.p, s.thread, threads > 1 ? &s.pairs.own[static_cast<std::size_t>(s.thread)] : nullptr);
    if (!field->cluster_due(s.thread)) return;
#pragma omp barrier
#pragma omp single
    field->step_clusters(s.p, &s.pairs.i, &s.pairs.j, threads);
    // A cluster update's footprints (the costly part of the collective rule) are shared by the team, then
    // one thread applies the factors; the single's barriers keep every kick after it (same bits as 1 thread).
    if (field->clusters_pending()) {
      field->footprints(s.thread);
#pragma omp barrier
#pragma omp single
      field->finish_clusters(s.p);
    }
  }
  // After the team: the last step's surface rise, the merged member list (members(), the checkpoint).
  void end_batch() { field->end_batch(); }

  // The pair list was rebuilt (before any particle had moved the skin, half the field's margin): the
  // candidates are refreshed.
  void lists_rebuilt() { field->mark_stale(); }
  // Particles were removed (outflow): the field's per-particle arrays are anew at the next update.
  void particles_removed() { field->particles_removed(); }
  // The World sorted the particles (map: old -> new dense index): the field's arrays move with them.
  void particles_moved(const std::vector<std::uint32_t>& map) { field->particles_moved(map); }

  bool claims(long a) const { return field->inside(a); }
  // Particle a's share of the threads' partition beyond a dry particle's (PairList::partition's units, one
  // candidate pair test): a member of the last update costs its membership test, constants and drag kick,
  // about 8 units (estimated from the case-3 profile: with none, one thread held all of the paste's rock).
  double partition_cost(long a) const { return field->known_inside(a) ? 8.0 : 0.0; }
  // Thread t's particles that the pass kicks (its own, ascending).
  const std::vector<long>& members(int thread) const { return field->members(thread); }
  // Particles a0 .. a0 + 7's two half kicks at once where the field can (FluidField::kick8_linear): true
  // when done (all eight claimed by this pass), false with nothing changed.
  bool kick8(long a0, Particles& p, const Vec3& g, double h) const {
#if defined(__AVX512F__)
    return field->kick8_linear(a0, p, g, h) || field->kick8_affine(a0, p, g, h);
#else
    (void)a0, (void)p, (void)g, (void)h;
    return false;
#endif
  }
#if defined(PASTEMIX_AVX2_LANES)
  // The same for particles a0 .. a0 + 3 (AVX2 alone: FluidField::kick4_linear, kick4_affine).
  bool kick4(long a0, Particles& p, const Vec3& g, double h) const {
    return field->kick4_linear(a0, p, g, h) || field->kick4_affine(a0, p, g, h);
  }
#endif
  // New velocity after a half kick h (s) under the non-drag force F (N, gravity included).
  Vec3 kick(long a, const Vec3& v, const Vec3& F, double mass, double radius, double h, const Vec3& g) const {
    return field->kick(a, v, F, mass, radius, h, g);
  }
};

}  // namespace pastemix::model
