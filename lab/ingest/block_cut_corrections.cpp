// SPDX-License-Identifier: MIT
#include "lab/ingest/block_cut_corrections.h"

#include <cmath>
#include <map>

#include <fmt/format.h>

#include "lab/ingest/block_id.h"

namespace pastemix::lab {

const std::vector<ColumnSpec>& block_cut_correction_columns() {
  static const std::vector<ColumnSpec> specs{
      {"case", ""},
      {"block_id", ""},
      {"i", ""},
      {"j", ""},
      {"layer", ""},
      {"M_prime_paste_kg", "kg"},
      {"M_prime_paste_dried_kg", "kg"},
      {"M_paste_dried_corrected_kg", "kg", false},
      {"C_percent", "%", false},
      {"S_percent", "%", false},
  };
  return specs;
}

void apply_block_cut_corrections(BlockCutResult& result, const CsvTable& t, const ColumnUnits& units) {
  require_spec_columns(t, block_cut_correction_columns());
  result.corrected = result.cases;
  std::map<int, BlockGrid*> by_case;
  for (auto& g : result.corrected) by_case[g.case_id] = &g;
  std::map<std::pair<int, int>, int> seen;  // (case, block) -> line
  auto& cmp = result.printed_corrected;
  for (const auto& row : t.rows()) {
    const long case_id = t.integer(row, "case");
    auto it = by_case.find(static_cast<int>(case_id));
    if (it == by_case.end())
      t.fail(row, "case", fmt::format("case {} has no blocks in the block-cut file", case_id));
    BlockGrid& g = *it->second;
    const BlockIndex ix = parse_block_row(t, row);
    const int b = block_index(ix.i, ix.j, ix.k);
    if (auto [s, fresh] = seen.try_emplace({g.case_id, b}, row.line); !fresh)
      t.fail(row, "block_id", fmt::format("duplicate correction of block {} in case {} (first on line {})",
                                          block_id_of(b), case_id, s->second));
    const double wet = t.number(row, "M_prime_paste_kg", Range::non_negative) * units.factor("M_prime_paste_kg");
    const double dried = t.number(row, "M_prime_paste_dried_kg", Range::non_negative) *
                         units.factor("M_prime_paste_dried_kg");
    if (dried > wet)
      t.fail(row, "M_prime_paste_dried_kg",
             fmt::format("dried mass {} kg exceeds the wet mass {} kg", dried, wet));
    const double corrected = g.M_paste[b] - dried;
    if (corrected < -1e-12)
      t.fail(row, "M_prime_paste_dried_kg",
             fmt::format("exceeds the block's dried paste mass {} kg (line {} of the block-cut file)", g.M_paste[b],
                         g.line[b]));
    g.M_paste[b] = std::max(corrected, 0.0);
    g.corrected[b] = 1;
    compute_block(g, b);

    // The thesis computed its printed values from unrounded masses; ours come from masses printed to 4
    // decimals. Allow what that rounding propagates (the corrected paste mass is a difference of two rounded
    // values, +-1e-4 kg; M_wr +-5e-5 kg), plus the rounding of the printed value itself.
    const double dp = 1e-4 / std::max(g.M_paste[b], 1e-4), dw = 5e-5 / std::max(g.M_wr[b], 5e-5);
    const std::string loc = where(t, row);
    if (t.has_column("M_paste_dried_corrected_kg"))
      if (auto m = t.optional_number(row, "M_paste_dried_corrected_kg", Range::non_negative)) {
        const double p = *m * units.factor("M_paste_dried_corrected_kg");
        if (std::abs(p - g.M_paste[b]) > 1.01e-4)
          result.warnings.push_back({loc, fmt::format("case {} {}: printed corrected paste mass {} kg, "
                                                      "recomputed {:.4f} kg",
                                                      case_id, block_id_of(b), p, g.M_paste[b])});
      }
    if (t.has_column("C_percent"))
      if (auto c = t.optional_number(row, "C_percent", Range::non_negative)) {
        const double p = *c * units.factor("C_percent");
        const double err = std::abs(g.C[b] - p);
        ++cmp.n_C;
        cmp.max_C_error_pp = std::max(cmp.max_C_error_pp, 100.0 * err);
        const double tol = g.C[b] * (1.0 - g.C[b]) * (dp + dw) + 0.01 * rounding_tolerance(t.text(row, "C_percent"));
        if (err > tol)
          result.warnings.push_back({loc, fmt::format("case {} {}: printed corrected C {:.1f} %, recomputed "
                                                      "{:.2f} % (beyond the +-{:.2f} pp that mass rounding explains)",
                                                      case_id, block_id_of(b), 100 * p, 100 * g.C[b], 100 * tol)});
      }
    if (t.has_column("S_percent") && std::isfinite(g.S_raw[b]))
      if (auto s = t.optional_number(row, "S_percent", Range::non_negative)) {
        const double p = *s * units.factor("S_percent");
        const double err = std::abs(g.S_raw[b] - p);
        ++cmp.n_S;
        if (p > 0) cmp.max_S_rel_error = std::max(cmp.max_S_rel_error, err / p);
        const double tol = g.S_raw[b] * (dp + dw) + 0.01 * rounding_tolerance(t.text(row, "S_percent"));
        if (err > tol)
          result.warnings.push_back({loc, fmt::format("case {} {}: printed corrected S {:.0f} %, recomputed "
                                                      "{:.1f} % (beyond the +-{:.1f} pp that mass rounding explains)",
                                                      case_id, block_id_of(b), 100 * p, 100 * g.S_raw[b], 100 * tol)});
      }
  }
  for (const auto& g : result.corrected)
    for (int b = 0; b < kBlocks; ++b)
      if (g.corrected[b] && static_cast<SFlag>(g.flag[b]) == SFlag::capped) ++cmp.n_capped;
}

}  // namespace pastemix::lab
