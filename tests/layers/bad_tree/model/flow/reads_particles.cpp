// SPDX-License-Identifier: MIT
// A fixture of tests/layers/: the flow solver including the particle engine.
#include "model/flow/grid.h"
#include "model/particles.h"
