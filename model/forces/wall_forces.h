// SPDX-License-Identifier: MIT
// The wall pass: contact forces of the walls (walls.h) on the particles near them, by the scene's contact
// and rolling laws (a wall is an infinite-radius, infinite-mass sphere of its own material). Per particle,
// its candidate walls (WallContacts, rebuilt with the pair list) in wall order, added to the pair sums of its
// owner thread; most particles have no candidate and are skipped (WallContacts::listed).
#pragma once

#include <vector>

#include "model/forces/force_pass.h"

namespace pastemix::model {

struct WallForces {
  static constexpr PassInfo info{"walls", Profile::walls,
                                 reads::position | reads::velocity | reads::spin | reads::mass | reads::radius |
                                     reads::material,
                                 adds::force | adds::torque | adds::rolling_capacity, false};
  bool any = false;                 // the scene has walls
  std::vector<WallState> state;     // per thread: the walls at the time of the forces

  bool active() const { return any; }
  void resize(int threads) { state.resize(static_cast<std::size_t>(threads)); }

  template <class Law, class Roll>
  void prepare(const PassStep<Law, Roll>& s) {
    state[static_cast<std::size_t>(s.thread)].update(s.walls, s.ctx.t);
  }

  // add(s, a) of particles idx[0 .. m) in turn (the same bits), batched for a law with a wall batch kernel.
  template <class Law, class Roll>
  void add_block(const PassStep<Law, Roll>& s, const long* idx, int m) {
    if constexpr (requires { typename Law::WallBatch; } && Roll::history_size == 0) {
      if (s.wall_contacts.width == Law::history_size && s.p.has_rotation) {
        wall_forces_block<Law, Roll>(s.laws, s.rolling, s.ctx, s.walls, state[static_cast<std::size_t>(s.thread)], s.p,
                                     s.wall_contacts, idx, m);
        return;
      }
    }
    for (int e = 0; e < m; ++e) add(s, idx[e]);
  }

  template <class Law, class Roll>
  void add(const PassStep<Law, Roll>& s, long a) {
    const WallContacts& wc = s.wall_contacts;
    if (wc.start[a] == wc.start[a + 1]) return;
    Particles& p = s.p;
    const bool rot = p.has_rotation;
    Vec3 f = p.f[a], tq;
    double rc = 0.0;
    if (rot) {
      tq = p.torque[a];
      rc = p.rolling_capacity[a];
    }
    wall_forces_one<Law, Roll>(s.laws, s.rolling, s.ctx, s.walls, state[static_cast<std::size_t>(s.thread)], p,
                               s.wall_contacts, static_cast<std::size_t>(a), f, tq, rc);
    p.f[a] = f;
    if (rot) {
      p.torque[a] = tq;
      p.rolling_capacity[a] = rc;
    }
  }
};

}  // namespace pastemix::model
