// SPDX-License-Identifier: MIT
// The control of the two probes beside it: with pastemix::analysis's include path, its own headers, the lab's
// and base's compile.
#include "analysis/plot.h"
#include "base/error.h"
#include "lab/lab_h5.h"
