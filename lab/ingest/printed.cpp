// SPDX-License-Identifier: MIT
#include "lab/ingest/printed.h"

#include <cmath>

#include <fmt/format.h>

#include "lab/ingest/ingest.h"

namespace pastemix::lab {

void compare_printed(const CsvTable& t, const CsvTable::Row& row, std::string_view column, double ours,
                     std::string_view what, std::vector<Warning>& warnings) {
  if (!t.has_column(column)) return;
  auto printed = t.optional_number(row, column);
  if (!printed) return;
  const std::string& cell = t.text(row, column);
  if (std::abs(*printed - ours) > rounding_tolerance(cell))
    warnings.push_back(Warning{where(t, row), fmt::format("printed {} {} disagrees with the recomputed {} "
                                                          "(more than its rounding)",
                                                          what, cell, format_value(ours))});
}

void compare_printed_mean(const CsvTable& t, std::string_view column, double ours, std::string_view what,
                          std::vector<Warning>& warnings) {
  if (!t.has_column(column)) return;
  for (const auto& row : t.rows()) {
    if (!t.optional_number(row, column)) continue;
    compare_printed(t, row, column, ours, fmt::format("mean {}", what), warnings);
    return;
  }
}

}  // namespace pastemix::lab
