// SPDX-License-Identifier: MIT
// Compiled with pastemix::analysis's include path only (tests/layers/CMakeLists.txt): the engine's headers are
// not on it, so this include must not compile.
#include "model/world.h"
