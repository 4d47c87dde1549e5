// SPDX-License-Identifier: MIT
#include "lab/ingest/printed.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "base/suggest.h"
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

std::string other_lines(const std::vector<int>& lines) {
  if (lines.size() < 2) return {};
  std::vector<int> shown_lines(lines.begin() + 1, lines.begin() + static_cast<long>(std::min<std::size_t>(lines.size(), 6)));
  return fmt::format(" (also on line{} {}{})", lines.size() > 2 ? "s" : "", fmt::join(shown_lines, ", "),
                     lines.size() > 6 ? fmt::format(" and {} more", lines.size() - 6) : "");
}

void compare_printed_mean(const CsvTable& t, std::string_view column, double ours, std::string_view what,
                          std::vector<Warning>& warnings) {
  if (!t.has_column(column)) return;
  // A merged cell repeated on every row: every row is checked (a transcription slip may sit on any of
  // them), and the disagreeing rows are reported in one warning.
  std::vector<int> lines;
  std::string first_cell;
  for (const auto& row : t.rows()) {
    auto printed = t.optional_number(row, column);
    if (!printed) continue;
    const std::string& cell = t.text(row, column);
    if (std::abs(*printed - ours) <= rounding_tolerance(cell)) continue;
    if (lines.empty()) first_cell = cell;
    lines.push_back(row.line);
  }
  if (lines.empty()) return;
  warnings.push_back(Warning{fmt::format("{}:{}", t.path(), lines.front()),
                             fmt::format("printed mean {} {} disagrees with the recomputed {} (more than its "
                                         "rounding){}",
                                         what, shown(first_cell), format_value(ours), other_lines(lines))});
}

}  // namespace pastemix::lab
