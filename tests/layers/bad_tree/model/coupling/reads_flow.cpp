// SPDX-License-Identifier: MIT
// A fixture of tests/layers/: the engine may include the flow solver (no error expected for this file).
#include "model/flow/solver.h"
#include "model/world.h"
