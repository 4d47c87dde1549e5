// SPDX-License-Identifier: MIT
// A fixture of tests/layers/: an analysis file that includes the engine (cmake/check_layers.cmake must refuse it).

#include "model/world.h"
#include "lab/reduce.h"
