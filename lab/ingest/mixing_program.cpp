// SPDX-License-Identifier: MIT
#include "lab/ingest/mixing_program.h"

#include <fmt/format.h>

namespace pastemix::lab {

const std::vector<ColumnSpec>& mixing_program_columns() {
  static const std::vector<ColumnSpec> specs{
      {"case", ""},
      {"d_wr_min_mm", "mm"},
      {"d_wr_max_mm", "mm"},
      {"waste_rock_size_class", "", false},
      {"waste_rock_tint", "", false},
      {"falling_height_cm", "cm"},
      {"paste_solids_content_percent", "%"},
  };
  return specs;
}

std::vector<MixingCase> ingest_mixing_program(const CsvTable& t, const ColumnUnits& units) {
  require_spec_columns(t, mixing_program_columns());
  std::vector<MixingCase> out;
  for (const auto& row : t.rows()) {
    MixingCase c;
    c.line = row.line;
    const long id = t.integer(row, "case");
    if (id < 1) t.fail(row, "case", fmt::format("expected a case number >= 1, got {}", id));
    c.case_id = static_cast<int>(id);
    for (const auto& o : out)
      if (o.case_id == c.case_id) t.fail(row, "case", fmt::format("case {} listed twice (first on line {})", id, o.line));
    const double lo = t.number(row, "d_wr_min_mm", Range::positive) * units.factor("d_wr_min_mm");
    const double hi = t.number(row, "d_wr_max_mm", Range::positive) * units.factor("d_wr_max_mm");
    if (!(hi > lo)) t.fail(row, "d_wr_max_mm", fmt::format("upper sieve {} m is not above the lower {} m", hi, lo));
    c.psd.intervals.push_back(PsdInterval{lo, hi, 1.0});
    c.falling_height = t.number(row, "falling_height_cm", Range::positive) * units.factor("falling_height_cm");
    c.solids_fraction = t.number(row, "paste_solids_content_percent", Range::positive) *
                        units.factor("paste_solids_content_percent");
    if (c.solids_fraction > 1.0)
      t.fail(row, "paste_solids_content_percent", "solids content above 100 %");
    if (t.has_column("waste_rock_size_class")) c.size_class = t.text(row, "waste_rock_size_class");
    if (t.has_column("waste_rock_tint")) c.tint = t.text(row, "waste_rock_tint");
    out.push_back(c);
  }
  return out;
}

}  // namespace pastemix::lab
