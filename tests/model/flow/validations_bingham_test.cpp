// SPDX-License-Identifier: MIT
// The yield-stress validations at cheap resolutions with their stated tolerances (the acceptance resolutions:
// `pastemix validate flow poiseuille | incline | cliff`, model/flow/VALIDATION.md part 2).
#include "model/flow/validations_bingham.h"

#include <doctest/doctest.h>
#include <omp.h>

#include <cmath>

using namespace pastemix::flow;
