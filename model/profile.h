// SPDX-License-Identifier: MIT
// Profile: wall-clock seconds per stage of the step, as seen by thread 0. Its own header because the force
// passes (forces/force_pass.h) name the line they are timed on.
#pragma once

#include <array>

namespace pastemix::model {

// The stages in the order of the step:
//   kick_drift      the first half kick and drift of a batch of steps (World::advance; the later ones are
//                   fused into `kick`)
//   neighbor        list rebuilds (and the threads' partition, and the spatial sort of the particles)
//   contact_forces  the pair pass (contact and rolling laws over the pair list)
//   walls           the wall pass (forces/wall_forces.h): wall forces of the particles near a wall; with
//                   rotation (the block kick, World::close_kicks_blocked) only
//                   its per-step set-up: each particle's wall forces are then computed just before its kick and
//                   timed in `kick`
//   kick            the closing half kick, the next opening half kick and drift of the particles; gravity
//                   (forces/gravity.h) is a term of this kick (a = f/m + g); in the block kick also the kick
//                   passes' particles (the fluid's) and the wall forces
//   fluid           the fluid pass (forces/fluid_forces.h): the field's update, then (outside the block kick)
//                   the fluid kicks and drifts of the particles inside a region
//   wait            thread 0 waiting at the step's barrier for the other threads
//   output          writing snapshots (run.cpp)
struct Profile {
  enum Stage { kick_drift, neighbor, contact_forces, walls, kick, fluid, wait, output, count };
  static constexpr std::array<const char*, count> names{"kick_drift", "neighbor", "contact_forces", "walls",
                                                        "kick",       "fluid",    "wait",           "output"};
  std::array<double, count> seconds{};
  long rebuilds = 0;
  long sorts = 0;  // spatial sorts of the particle store (WorldConfig::sort_every), timed in `neighbor`
};

}  // namespace pastemix::model
