// SPDX-License-Identifier: MIT
// Comparing a value printed in a source table with our recomputation of it.
//
// A printed value is trusted only to its last printed digit; anything further away is a Warning that names
// the file and line, so transcription slips and inconsistencies in the source are reported, not copied.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/csv.h"
#include "lab/parameter.h"

namespace pastemix::lab {

// If `column` exists and the row's cell is not empty, warns when |printed - ours| exceeds its rounding.
void compare_printed(const CsvTable& t, const CsvTable::Row& row, std::string_view column, double ours,
                     std::string_view what, std::vector<Warning>& warnings);
// Same for a merged "mean" cell repeated on every row: every non-empty row is checked; one warning names
// the first disagreeing row and lists the others.
void compare_printed_mean(const CsvTable& t, std::string_view column, double ours, std::string_view what,
                          std::vector<Warning>& warnings);
// " (also on lines 5, 7 and 3 more)" for the lines after the first; "" for fewer than two.
std::string other_lines(const std::vector<int>& lines);

}  // namespace pastemix::lab
