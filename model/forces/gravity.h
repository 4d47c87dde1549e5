// SPDX-License-Identifier: MIT
// Gravity: a body acceleration g (m/s2), the scene's [physics] gravity. It is a term of the plain half kick,
// v += (f/m + g) h, in one expression: split into a pass of its own (f += m g, or v += g h) it would change
// the rounding of every step, so it has no profile line of its own and is timed inside `kick`. The fluid
// kick adds it as the force m g (forces/fluid_forces.h).
#pragma once

#include "model/forces/force_pass.h"

namespace pastemix::model {

struct Gravity {
  static constexpr PassInfo info{"gravity", Profile::kick, 0, adds::acceleration, false};
  Vec3 g{0, 0, -9.81};  // m/s2

  bool active() const { return true; }
  Vec3 acceleration() const { return g; }
};

}  // namespace pastemix::model
