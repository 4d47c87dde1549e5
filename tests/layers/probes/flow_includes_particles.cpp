// SPDX-License-Identifier: MIT
// Compiled with pastemix::flow's include path only (tests/layers/CMakeLists.txt): the particle engine is not
// on it, so this include must not compile.
#include "model/particles.h"
