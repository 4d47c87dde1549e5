// SPDX-License-Identifier: MIT
// The moving paste's pass ([[fluid]] dynamics = "flow", fluid/flow_coupling.h): before the pair pass, on one
// thread, the coupling closes a cycle every coupling_interval steps (the flow interval, the exchange's change
// of the particles' velocities, whose ghost copies it refreshes for the other threads) and opens the next; the
// plain kick skips the particles in the flow box and the pass kicks them with the paste's drag against the
// frozen fluid and the pending pressure force. Without a flow region there is no coupling and the pass is
// inactive: one pointer test per kick (the at-rest scenes pay nothing else, bit for bit).
//
// The kick passes' interface (forces/force_pass.h) hands each thread its own members, members(t). The
// coupling keeps one ascending list; the pass splits it by the pair list's owners into one list per thread,
// in the same single as the cycle, whenever either may have changed (the coupling's membership stamp, the
// pair list's partition stamp, the team's size, the coupling itself), so each thread kicks exactly the
// members it owns, ascending: the same kicks in the same order as filtering the whole list by owner (the
// bits of any thread count). With one thread the coupling's list is used as it is.
// The pass opts out of the fluid pass's per-thread batching (begin_batch / end_batch, lanes): its per-step
// work is already one thread's (the cycle reads every particle and runs the flow solver, flow_coupling.h),
// so there is no per-thread share of the membership to keep, and the members change only at a cycle's start.
// Nor does it weigh its members in the threads' partition (no partition_cost): the cost of a member's drag
// step against a contact is not measured, and the partition changes no bit, only the balance.
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
      threads_ = omp_get_num_threads();
      if (threads_ > 1) {
        for (long a : changed) {
          const std::uint32_t slot = s.pairs.ghost_of[static_cast<std::size_t>(a)];
          if (slot != PairList::kNone) s.pairs.ghost[s.parity][slot].v = s.p.v[static_cast<std::size_t>(a)];
        }
        split(s.pairs);
      }
    }
  }

  // After the World's parallel region: the coupling's failure, if any (fluid/flow_coupling.h).
  void rethrow() const { coupling->rethrow(); }
  // The World sorted or removed particles (map: old -> new dense index, Particles::kGone if removed).
  void particles_moved(const std::vector<std::uint32_t>& map) { coupling->renumber(map, map.size()); }
  void particles_removed(const std::vector<std::uint32_t>& map, std::size_t count) { coupling->renumber(map, count); }

  bool claims(long a) const { return coupling->claims(a); }
  // Thread t's members, ascending (valid after this step's prepare(): every kick comes after it).
  const std::vector<long>& members(int thread) const {
    return threads_ > 1 ? own_[static_cast<std::size_t>(thread)] : coupling->members();
  }
  Vec3 kick(long a, const Vec3& v, const Vec3& F, double mass, double, double h, const Vec3&) const {
    return coupling->kick(a, v, F, mass, h);
  }

 private:
  // What the split was made from: a list per thread is stale when any of these differs.
  struct SplitKey {
    const fluid::FlowCoupling* coupling = nullptr;
    long membership = -1, partitions = -1;
    int threads = 0;
    bool operator==(const SplitKey&) const = default;
  };
  int threads_ = 1;  // the team's size at the last prepare()
  SplitKey split_;
  std::vector<std::vector<long>> own_;  // per thread: the coupling's members it owns, ascending

  // own_ from the coupling's members and the pair list's owners (one thread, inside the single).
  void split(const PairList& pairs) {
    const SplitKey key{coupling.get(), coupling->membership(), pairs.partitions, threads_};
    if (key == split_) return;
    own_.assign(static_cast<std::size_t>(threads_), {});
    for (long a : coupling->members()) own_[pairs.owner[static_cast<std::size_t>(a)]].push_back(a);
    split_ = key;
  }
};

}  // namespace pastemix::model
