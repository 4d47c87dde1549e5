// SPDX-License-Identifier: MIT
// What a Range (base/csv.h) asks of a number, shared by the CSV cells (csv.cpp) and the TOML keys (params.cpp)
// so both say it in the same words.
#pragma once

#include "base/csv.h"  // Range

namespace pastemix {

// "a positive number", ...: what a value of that range is, for error messages.
const char* range_words(Range range);
// Whether v satisfies the range (a NaN satisfies only Range::any).
bool in_range(double v, Range range);

}  // namespace pastemix
