// SPDX-License-Identifier: MIT
#include "lab/ingest/sieve.h"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "base/error.h"

namespace pastemix::lab {

const std::vector<ColumnSpec>& sieve_columns() {
  static const std::vector<ColumnSpec> specs{{"sieve_mm", "mm"}, {"mass_retained_g", "g"}};
  return specs;
}

SieveResult ingest_sieve(const CsvTable& t, const ColumnUnits& units, double d_cut) {
  require_spec_columns(t, sieve_columns());
  struct Sieve {
    double size, mass;
    int line;
  };
  std::vector<Sieve> stack;
  for (const auto& row : t.rows()) {
    Sieve s{t.number(row, "sieve_mm", Range::non_negative) * units.factor("sieve_mm"),
            t.number(row, "mass_retained_g", Range::non_negative) * units.factor("mass_retained_g"), row.line};
    for (const auto& o : stack)
      if (o.size == s.size)
        t.fail(row, "sieve_mm", fmt::format("sieve {} mm listed twice (first on line {})", s.size * 1e3, o.line));
    stack.push_back(s);
  }
  std::sort(stack.begin(), stack.end(), [](const Sieve& a, const Sieve& b) { return a.size < b.size; });
  const Sieve& top = stack.back();
  if (top.mass > 0.0)
    throw InputError(t.path(), top.line, "column 'mass_retained_g'",
                     fmt::format("{} g retained on the top sieve ({} mm): that mass has no upper size; add the next "
                                 "larger sieve with 0 g",
                                 top.mass * 1e3, top.size * 1e3));
  SieveResult out;
  for (const auto& s : stack) out.total_mass += s.mass;
  if (!(out.total_mass > 0.0)) throw InputError(t.path(), 0, "column 'mass_retained_g'", "the sample has no mass");
  const bool has_pan = stack.front().size == 0.0;
  const std::size_t first = has_pan ? 1 : 0;
  if (stack.size() - first < 2)
    throw InputError(t.path(), 0, "column 'sieve_mm'", "need at least two sieves (one interval) besides the pan");
  out.pan_fraction = has_pan ? stack.front().mass / out.total_mass : 0.0;
  double below = has_pan ? stack.front().mass : 0.0;
  double in_psd = 0.0;
  for (std::size_t k = first; k < stack.size(); ++k) {
    out.sieves.push_back(stack[k].size);
    out.passing.push_back(below / out.total_mass);
    below += stack[k].mass;
    if (k + 1 < stack.size()) {
      out.psd.intervals.push_back(PsdInterval{stack[k].size, stack[k + 1].size, stack[k].mass});
      in_psd += stack[k].mass;
    }
  }
  if (!(in_psd > 0.0)) throw InputError(t.path(), 0, "column 'mass_retained_g'", "no mass on any sieve above the pan");
  for (auto& iv : out.psd.intervals) iv.mass_fraction /= in_psd;
  if (out.pan_fraction > 0.0)
    out.warnings.push_back({t.path(), fmt::format("{:.2f} % of the mass is in the pan (below {} mm) and has no lower "
                                                  "size: excluded from the PSD, which is renormalised",
                                                  100 * out.pan_fraction, out.sieves.front() * 1e3)});
  if (d_cut > 0.0) {
    try {
      out.psd = out.psd.cut_below(d_cut);
    } catch (const std::invalid_argument& e) {
      throw InputError(t.path(), 0, "cut", e.what());
    }
    out.cut = d_cut;
  }
  out.psd.check();
  return out;
}

}  // namespace pastemix::lab
