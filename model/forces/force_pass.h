// SPDX-License-Identifier: MIT
// Force passes: every force on a particle besides the pair contacts is a pass with one interface, listed in
// forces/registry.h. The World runs the list in order each step and times each pass on its own profile line;
// it never names a concrete pass in the step (only set_fluid() and fluid() reach the fluid pass by type).
//
// A pass is a struct with
//   static constexpr PassInfo info  what it reads from the particle state, what it adds, whether it needs the
//                                   pair list, and the profile line it is timed on (its name);
//   bool active() const             whether this scene has it (no walls, no [[fluid]]: the pass costs nothing);
// and, by what `info.adds` says:
//   adds::acceleration  Vec3 acceleration() const: a body acceleration (m/s2), constant in a step, a term of
//                       the plain half kick v += (f/m + a) h (gravity);
//   adds::force         add(step, a): adds to particle a's force / torque / rolling capacity after the pair
//                       pass, per particle by its owner thread (walls);
//   adds::kick          claims(a), kick(a, v, F, m, r, h, g), members(t): owns the half kick of the particles it
//                       claims (fluid: the stable implicit drag kick of fluid/drag_kick.h, the one the tests
//                       test); the plain kick skips them, the pass kicks and drifts them after the others
//                       (members(t): thread t's own, ascending);
// optionally
//   prepare(step)       once per step and thread, before the pair pass (the walls' positions at t; the fluid
//                       field's update of the thread's own particles; the flow coupling's cycle, on one
//                       thread, with its barrier);
//   begin_batch(p, pairs, threads), end_batch()  on one thread, before and after the team runs a batch of
//                       steps (the fluid field's lanes, and the rise of its batch's last step);
//   lists_rebuilt(), particles_removed() or particles_removed(map, count)  after a neighbour rebuild / an
//                       outflow removal (the fluid field's candidate list and per-particle arrays; the flow
//                       coupling's, renamed through the map);
//   partition_cost(a)   particle a's own work in the pass, in PairList::partition's units, so that the
//                       threads' slabs balance it too (the fluid: its members' drag kicks);
//   particles_moved(map)  after the World's spatial sort (map: old -> new dense index, a permutation): a pass
//                       with per-particle state moves it with the particles.
// Each particle's operations stay its own and in the same order (pair forces, then the force passes in
// list order, then one kick), so splitting the step into passes changes no bit (scripts/bitwise_check.sh).
#pragma once

#include <concepts>
#include <tuple>
#include <type_traits>
#include <vector>

#include "model/contacts.h"
#include "model/particles.h"
#include "model/profile.h"
#include "model/walls.h"

namespace pastemix::model {

// What a pass reads from the particle state (bit set).
namespace reads {
inline constexpr unsigned position = 1u << 0, velocity = 1u << 1, spin = 1u << 2, mass = 1u << 3,
                          radius = 1u << 4, material = 1u << 5, force = 1u << 6;
}
// What a pass adds (bit set; see above for the member functions each asks for).
namespace adds {
inline constexpr unsigned acceleration = 1u << 0, force = 1u << 1, torque = 1u << 2, rolling_capacity = 1u << 3,
                          kick = 1u << 4;
}

struct PassInfo {
  const char* name;       // the pass's name: its profile line's, where it has a line of its own
  Profile::Stage stage;   // the line it is timed on
  unsigned reads = 0;     // reads:: bits
  unsigned adds = 0;      // adds:: bits
  bool needs_pairs = false;  // reads the pair list (dense indices of the pairs, in prepare())
};

// One thread's view of the step, given to prepare() and add(): the contact and rolling laws (the walls are
// contacts), the time, the state and the lists.
template <class Law, class Roll>
struct PassStep {
  const std::vector<typename Law::Params>& laws;
  const std::vector<typename Roll::Params>& rolling;
  const StepContext& ctx;
  const std::vector<Wall>& walls;
  WallContacts& wall_contacts;
  Particles& p;
  PairList& pairs;  // the flow pass refreshes ghost copies of velocities it changed (forces/flow_forces.h)
  int thread = 0;
  int parity = 0;   // the ghost buffer this step's pair pass reads (PairList::ghost)
};

template <class P>
concept ForcePass =
    requires(const P& cp) {
      { P::info } -> std::convertible_to<PassInfo>;
      { cp.active() } -> std::same_as<bool>;
    } &&
    (!(P::info.adds & adds::acceleration) || requires(const P& cp) {
      { cp.acceleration() } -> std::same_as<Vec3>;
    }) &&
    (!(P::info.adds & adds::kick) || requires(const P& cp, long a, const Vec3& v) {
      { cp.claims(a) } -> std::same_as<bool>;
      { cp.kick(a, v, v, 1.0, 1.0, 1.0, v) } -> std::same_as<Vec3>;
      { cp.members(0) } -> std::convertible_to<const std::vector<long>&>;
    });

// The registered passes, in the order of the step.
template <ForcePass... Passes>
using PassList = std::tuple<Passes...>;

// Calls f(pass) for each pass of the list, in order.
template <class List, class F>
void for_each_pass(List& list, F&& f) {
  std::apply([&](auto&... pass) { (f(pass), ...); }, list);
}

// The sum of the active passes' body accelerations (m/s2): the first one as it is, so that gravity alone
// gives its own bits (0 + g would turn a -0 component into +0).
template <class List>
Vec3 body_acceleration(const List& list) {
  Vec3 sum;
  bool first = true;
  std::apply(
      [&](const auto&... pass) {
        auto one = [&](const auto& q) {
          if constexpr (std::decay_t<decltype(q)>::info.adds & adds::acceleration)
            if (q.active()) sum = first ? q.acceleration() : sum + q.acceleration(), first = false;
        };
        (one(pass), ...);
      },
      list);
  return sum;
}

// The first active kick pass that claims particle a: calls f(pass) and returns true; false if none does.
template <class List, class F>
bool with_kick_pass(const List& list, long a, F&& f) {
  return std::apply(
      [&](const auto&... pass) {
        auto one = [&](const auto& q) {
          if constexpr (std::decay_t<decltype(q)>::info.adds & adds::kick) {
            if (q.active() && q.claims(a)) return f(q), true;
          }
          return false;
        };
        return (one(pass) || ...);
      },
      list);
}

}  // namespace pastemix::model
