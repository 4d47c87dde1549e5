// SPDX-License-Identifier: MIT
// The moving paste's pass ([[fluid]] dynamics = "flow", fluid/flow_coupling.h): before the pair pass, on one
// thread, the coupling closes a cycle every coupling_interval steps (the flow interval, the exchange's change
// of the particles' velocities, whose ghost copies it refreshes for the other threads) and opens the next; the
// plain kick skips the particles in the flow box and the pass kicks them with the paste's drag against the
// frozen fluid and the pending pressure force. Without a flow region there is no coupling and the pass is
// inactive: one pointer test per kick (the at-rest scenes pay nothing else, bit for bit).
#pragma once

#include <omp.h>

#include <memory>
#include <vector>

#include "model/fluid/flow_coupling.h"
#include "model/forces/force_pass.h"

namespace pastemix::model {

struct FlowForces {
  static constexpr PassInfo info{"flow", Profile::fluid,
                                 reads::position | reads::velocity | reads::mass | reads::radius | reads::force,
                                 adds::kick, false};
  std::shared_ptr<fluid::FlowCoupling> coupling;

  bool active() const { return coupling != nullptr; }

  template <class Law, class Roll>
  void prepare(const PassStep<Law, Roll>& s) {
    // Every kick of the step needs the cycle's drag, and the flow interval reads every particle's position:
    // one thread, then the barrier of `single`. A velocity the exchange changed is copied into the ghost
    // buffer the other threads read in this step's pair pass (cross pairs).
#pragma omp single
    {
      const std::vector<long>& changed = coupling->prepare(s.p);
      if (omp_get_num_threads() > 1)
        for (long a : changed) {
          const std::uint32_t slot = s.pairs.ghost_of[static_cast<std::size_t>(a)];
          if (slot != PairList::kNone) s.pairs.ghost[s.parity][slot].v = s.p.v[static_cast<std::size_t>(a)];
        }
    }
  }

  // After the World's parallel region: the coupling's failure, if any (fluid/flow_coupling.h).
  void rethrow() const { coupling->rethrow(); }
  // The World sorted or removed particles (map: old -> new dense index, Particles::kGone if removed).
  void particles_moved(const std::vector<std::uint32_t>& map) { coupling->renumber(map, map.size()); }
  void particles_removed(const std::vector<std::uint32_t>& map, std::size_t count) { coupling->renumber(map, count); }

  bool claims(long a) const { return coupling->claims(a); }
  const std::vector<long>& members() const { return coupling->members(); }
  Vec3 kick(long a, const Vec3& v, const Vec3& F, double mass, double, double h, const Vec3&) const {
    return coupling->kick(a, v, F, mass, h);
  }
};

}  // namespace pastemix::model
