// SPDX-License-Identifier: MIT
// The fluid pass: buoyancy and the drag of the fluid regions ([[fluid]], fluid/field.h). Each step, before
// the pair pass, the field finds the particles inside a region and their submerged volumes (one thread: it
// reads every particle's position and, for the collective rule, the pair list); the plain kick skips those
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

  template <class Law, class Roll>
  void prepare(const PassStep<Law, Roll>& s) {
    // The update reads the positions of every particle (all drifted: the step's barrier) and must precede
    // every kick: one thread, then the barrier of `single`.
#pragma omp single
    field->update(s.p, &s.pairs.i, &s.pairs.j, omp_get_num_threads());
    // A cluster update's footprints (the costly part of the collective rule) are shared by the team, then
    // one thread applies the factors; the single's barriers keep every kick after it (same bits as 1 thread).
    if (field->clusters_pending()) {
      field->footprints(omp_get_thread_num());
#pragma omp barrier
#pragma omp single
      field->finish_clusters(s.p);
    }
  }

  // The pair list was rebuilt: no particle has moved skin/2 since, the candidates are refreshed.
  void lists_rebuilt() { field->mark_stale(); }
  // Particles were removed (outflow): the field's per-particle arrays are anew at the next update.
  void particles_removed() { field->particles_removed(); }
  // The World sorted the particles (map: old -> new dense index): the field's arrays move with them.
  void particles_moved(const std::vector<std::uint32_t>& map) { field->particles_moved(map); }

  bool claims(long a) const { return field->inside(a); }
  const std::vector<long>& members() const { return field->members(); }
  // New velocity after a half kick h (s) under the non-drag force F (N, gravity included).
  Vec3 kick(long a, const Vec3& v, const Vec3& F, double mass, double radius, double h, const Vec3& g) const {
    return field->kick(a, v, F, mass, radius, h, g);
  }
};

}  // namespace pastemix::model
