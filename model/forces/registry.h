// SPDX-License-Identifier: MIT
// The registered force passes (forces/force_pass.h says what one provides), in the order of the step: a new
// force is one header in forces/ plus one entry below. The World runs the list; the pair contacts are the
// contact laws' pass (laws/registry.h), run before these.
#pragma once

#include "model/forces/flow_forces.h"
#include "model/forces/fluid_forces.h"
#include "model/forces/gravity.h"
#include "model/forces/wall_forces.h"

namespace pastemix::model {

using ForcePasses = PassList<Gravity, WallForces, FluidForces, FlowForces>;

}  // namespace pastemix::model
