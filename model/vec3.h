// SPDX-License-Identifier: MIT
// The engine's 3-vector is the project's one (base/vec3.h); this header keeps `model::Vec3` and the
// engine's includes working.
#pragma once

#include "base/vec3.h"

namespace pastemix::model {
using pastemix::Vec3;
}  // namespace pastemix::model
