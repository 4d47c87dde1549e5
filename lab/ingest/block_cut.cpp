// SPDX-License-Identifier: MIT
#include "lab/ingest/block_cut.h"

#include <cmath>

#include <fmt/format.h>

#include "base/error.h"
#include "lab/ingest/block_id.h"

namespace pastemix::lab {

const char* to_string(SFlag f) {
  switch (f) {
    case SFlag::value: return "value";
    case SFlag::capped: return "capped";
    case SFlag::no_rock: return "no_rock";
    case SFlag::no_K: return "no_K";
  }
  return "unknown";
}

void compute_block(BlockGrid& g, int b) {
  const double mw = g.M_wr[b], mp = g.M_paste[b];
  g.C[b] = mw / (mw + mp);
  g.S[b] = g.S_raw[b] = BlockGrid::nan;
  if (!(mw > 0.0)) {
    g.flag[b] = static_cast<std::int32_t>(SFlag::no_rock);
  } else if (!std::isfinite(g.K)) {
    g.flag[b] = static_cast<std::int32_t>(SFlag::no_K);
  } else {
    // Dried-paste density rho_s (1 - e_f/(1 + e_f)): 1693.75 kg/m3 for the thesis's 2710 and 0.6.
    const double rho_dried = g.rho_s[b] * (1.0 - g.e_f[b] / (1.0 + g.e_f[b]));
    g.S_raw[b] = mp * g.K / (rho_dried * mw);
    g.S[b] = std::min(g.S_raw[b], 1.0);
    g.flag[b] = static_cast<std::int32_t>(g.S_raw[b] > 1.0 ? SFlag::capped : SFlag::value);
  }
}

const std::vector<ColumnSpec>& block_cut_columns() {
  static const std::vector<ColumnSpec> specs{
      {"case", ""},          {"block_id", ""},     {"i", ""},
      {"j", ""},             {"layer", ""},        {"M_wr_kg", "kg"},
      {"M_paste_dried_kg", "kg"}, {"rho_s_kg_m3", "kg/m3"}, {"e_f", "-"},
      {"C_percent", "%", false},  {"S_percent", "%", false}, {"S_flag", "", false},
  };
  return specs;
}

namespace {

struct PendingCase {
  BlockGrid grid;
  std::array<bool, kBlocks> seen{};
  int first_line = 0;
  std::vector<std::string> printed_uncapped_over_1;  // "M_111 5202.7 %"
};

void compare_case(const CsvTable& t, const PendingCase& pc, const std::vector<std::string>& printed_flags,
                  BlockCutComparison& cmp, std::vector<Warning>& warnings) {
  const BlockGrid& g = pc.grid;
  std::vector<std::string> over;
  for (int b = 0; b < kBlocks; ++b) {
    const std::string loc = fmt::format("{}:{}", t.path(), g.line[b]);
    const std::string id = block_id_of(b);
    if (std::isfinite(g.C_printed[b])) {
      // The thesis truncates C to one decimal (every difference is positive), so 0.1 pp is its resolution.
      const double err = 100.0 * std::abs(g.C[b] - g.C_printed[b]);
      ++cmp.n_C;
      cmp.max_C_error_pp = std::max(cmp.max_C_error_pp, err);
      if (err > 0.1 + 1e-9)
        warnings.push_back({loc, fmt::format("case {} {}: printed C {:.2f} %, recomputed {:.2f} % (> 0.1 pp)",
                                             g.case_id, id, 100 * g.C_printed[b], 100 * g.C[b])});
    }
    const auto flag = static_cast<SFlag>(g.flag[b]);
    if (flag == SFlag::capped) ++cmp.n_capped;
    const std::string& pflag = printed_flags[b];
    if (pflag == "capped_at_100" && (flag == SFlag::value)) {
      ++cmp.n_flag_disagreements;
      warnings.push_back({loc, fmt::format("case {} {}: printed as capped at 100 %, but eq. 3.8 gives {:.1f} %",
                                           g.case_id, id, 100 * g.S_raw[b])});
    }
    if (pflag.empty() && std::isfinite(g.S_printed[b]) && std::isfinite(g.S_raw[b])) {
      const double p = g.S_printed[b];
      const double rel = p > 0.0 ? std::abs(g.S_raw[b] - p) / p : std::abs(g.S_raw[b]);
      ++cmp.n_S;
      cmp.max_S_rel_error = std::max(cmp.max_S_rel_error, rel);
      if (rel > 0.005)
        warnings.push_back({loc, fmt::format("case {} {}: printed S {:.1f} %, recomputed {:.1f} % with K = {} "
                                             "kg/m3 ({:.2f} % relative)",
                                             g.case_id, id, 100 * p, 100 * g.S_raw[b], g.K, 100 * rel)});
      if (p > 1.0) over.push_back(fmt::format("{} {:.1f} %", id, 100 * p));
      // Printed without a cap flag: a disagreement whenever eq. 3.8 exceeds 1 (printed above 100 %, we cap).
      if ((p > 1.0) || (flag == SFlag::capped)) ++cmp.n_flag_disagreements;
    }
  }
  if (!over.empty())
    warnings.push_back({t.path(), fmt::format("case {}: {} blocks printed with S above 100 % and not capped ({}); "
                                              "S is a fraction of the voids, so we cap them at 100 % and flag "
                                              "them (raw value kept as S_raw)",
                                              g.case_id, over.size(), fmt::join(over, ", "))});
}

}  // namespace

BlockCutResult ingest_block_cut(const CsvTable& t, const ColumnUnits& units, const std::map<int, KInput>& K) {
  require_spec_columns(t, block_cut_columns());
  std::map<int, PendingCase> cases;
  std::map<int, std::vector<std::string>> flags;
  const bool has_flag = t.has_column("S_flag");
  for (const auto& row : t.rows()) {
    const long case_id = t.integer(row, "case");
    if (case_id < 1) t.fail(row, "case", fmt::format("expected a case number >= 1, got {}", case_id));
    const BlockIndex ix = parse_block_row(t, row);
    const int b = block_index(ix.i, ix.j, ix.k);
    auto [it, inserted] = cases.try_emplace(static_cast<int>(case_id));
    PendingCase& pc = it->second;
    if (inserted) {
      pc.grid.case_id = static_cast<int>(case_id);
      pc.first_line = row.line;
      pc.grid.C_printed.fill(BlockGrid::nan);
      pc.grid.S_printed.fill(BlockGrid::nan);
      flags[pc.grid.case_id].assign(kBlocks, "");
      if (auto k = K.find(pc.grid.case_id); k != K.end()) {
        pc.grid.K = k->second.value;
        pc.grid.K_source = k->second.source;
      }
    }
    if (pc.seen[b])
      t.fail(row, "block_id", fmt::format("duplicate block {} in case {} (first on line {})", t.text(row, "block_id"),
                                          case_id, pc.grid.line[b]));
    pc.seen[b] = true;
    BlockGrid& g = pc.grid;
    g.line[b] = row.line;
    g.M_wr[b] = t.number(row, "M_wr_kg", Range::non_negative) * units.factor("M_wr_kg");
    g.M_paste[b] = t.number(row, "M_paste_dried_kg", Range::non_negative) * units.factor("M_paste_dried_kg");
    if (!(g.M_wr[b] + g.M_paste[b] > 0.0))
      t.fail(row, "M_wr_kg", "block holds neither rock nor paste (both masses 0): C is undefined");
    g.rho_s[b] = t.number(row, "rho_s_kg_m3", Range::positive) * units.factor("rho_s_kg_m3");
    g.e_f[b] = t.number(row, "e_f", Range::positive) * units.factor("e_f");
    if (t.has_column("C_percent"))
      if (auto c = t.optional_number(row, "C_percent", Range::non_negative)) g.C_printed[b] = *c * units.factor("C_percent");
    if (t.has_column("S_percent"))
      if (auto s = t.optional_number(row, "S_percent", Range::non_negative)) g.S_printed[b] = *s * units.factor("S_percent");
    if (has_flag) {
      const std::string& f = t.text(row, "S_flag");
      if (!(f.empty() || f == "n/a" || f == "capped_at_100"))
        t.fail(row, "S_flag", fmt::format("expected '', 'n/a' or 'capped_at_100', got '{}'", f));
      flags[g.case_id][b] = f;
    }
    compute_block(g, b);
  }
  BlockCutResult out;
  for (auto& [id, pc] : cases) {
    std::vector<std::string> missing;
    for (int b = 0; b < kBlocks; ++b)
      if (!pc.seen[b]) missing.push_back(block_id_of(b));
    if (!missing.empty())
      throw InputError(t.path(), pc.first_line, "column 'block_id'",
                       fmt::format("case {} (starting here) has {} of {} blocks; missing {}", id,
                                   kBlocks - static_cast<int>(missing.size()), kBlocks, fmt::join(missing, ", ")));
    compare_case(t, pc, flags[id], out.printed, out.warnings);
    if (!std::isfinite(pc.grid.K)) {
      out.warnings.push_back({t.path(), fmt::format("case {}: K = rho_wr/n_wr not given, so S is not computed for "
                                                    "this case (the thesis states no K, and for case 1 prints no "
                                                    "finite S to back-calculate one); give it with --K {}=VALUE or "
                                                    "[[block_cut.K]] in the manifest",
                                                    id, id)});
    } else {
      Parameter p;
      p.key = fmt::format("block_cut.case_{}.K", id);
      p.value = pc.grid.K;
      p.sd = BlockGrid::nan;
      p.unit = "kg/m3";
      p.method = "input: rho_wr/n_wr in eq. 3.8";
      p.provenance = Provenance::assumed;
      p.source = pc.grid.K_source;
      out.parameters.push_back(p);
    }
    out.cases.push_back(pc.grid);
  }
  for (const auto& [id, k] : K)
    if (!cases.count(id))
      throw InputError(t.path(), 0, "", fmt::format("K given for case {}, which has no blocks in this file", id));
  return out;
}

}  // namespace pastemix::lab
