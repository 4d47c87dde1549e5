// SPDX-License-Identifier: MIT
#include "lab/ingest/slump.h"

#include <cmath>
#include <numeric>

#include <fmt/format.h>

#include "base/error.h"
#include "base/suggest.h"
#include "base/stats.h"
#include "base/units.h"
#include "lab/ingest/printed.h"
#include "lab/lambert_w.h"

namespace pastemix::lab {

double pashias_slump(double tau_prime) {
  const double u = 2.0 * tau_prime;
  return 1.0 - u * (1.0 - std::log(u));
}

double pashias_tau_lambert(double slump_prime) {
  const double a = 1.0 - slump_prime;
  return -a / (2.0 * lambert_w_minus1(-a / 2.718281828459045235));
}

double pashias_tau_bracketed(double slump_prime) {
  // S'(tau') falls monotonically from 1 (tau' -> 0) to 0 (tau' = 1/2): dS'/dtau' = 2 ln(2 tau') < 0.
  double lo = 0.0, hi = 0.5;
  for (int k = 0; k < 200 && hi - lo > 1e-17; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    if (pashias_slump(mid) > slump_prime) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

double pashias_tau(double slump_prime) {
  const double closed = pashias_tau_lambert(slump_prime);
  const double root = pashias_tau_bracketed(slump_prime);
  if (!(std::abs(closed - root) <= 1e-9 * std::abs(root)))
    throw RuntimeFailure(fmt::format("Pashias-Boger inverse: Lambert W gives tau' = {:.17g}, the bracketed root "
                                     "{:.17g} (S' = {:.17g}); relative difference above 1e-9",
                                     closed, root, slump_prime));
  return closed;
}

const std::vector<ColumnSpec>& slump_columns() {
  static const std::vector<ColumnSpec> specs{
      {"trial", ""},
      {"H_mm", "mm"},
      {"D_mm", "mm"},
      {"paste_density_kg_m3", "kg/m3"},
      {"slump_mm", "mm"},
      {"yield_stress_Pa", "Pa", false},
      {"yield_stress_mean_Pa", "Pa", false},
  };
  return specs;
}

IngestResult ingest_slump(const CsvTable& t, const ColumnUnits& units) {
  require_spec_columns(t, slump_columns());
  const bool has_printed = t.has_column("yield_stress_Pa");
  std::vector<double> tau, rho, tau_prime, heights, printed;
  std::vector<std::string> printed_cells;
  require_unique_ids(t, "trial");
  for (const auto& row : t.rows()) {
    const double H = t.number(row, "H_mm", Range::positive) * units.factor("H_mm");
    const double D = t.number(row, "D_mm", Range::positive) * units.factor("D_mm");
    const double density = t.number(row, "paste_density_kg_m3", Range::positive) *
                           units.factor("paste_density_kg_m3");
    check_plausible(t, row, "paste_density_kg_m3", density, plausible_density, units);
    const double S = t.number(row, "slump_mm", Range::non_negative) * units.factor("slump_mm");
    if (S >= H)
      t.fail(row, "slump_mm",
             fmt::format("slump {} m is not smaller than the mould height H = {} m (a slump cannot exceed the "
                         "mould; check the units and the columns)",
                         S, H));
    if (S <= 0.0)
      t.fail(row, "slump_mm",
             fmt::format("no slump: tau' = tau_y/(rho g H) >= 0.5, so the yield stress is only bounded below "
                         "(tau_y >= {:.1f} Pa); the slump test cannot measure it",
                         0.5 * density * units::g * H));
    if (std::abs(H / D - 1.0) > 0.25)
      t.fail(row, "D_mm", fmt::format("the Pashias-Boger cylinder relation needs H ~ D; got H/D = {:.2f}", H / D));
    double tp = 0.0;
    try {
      tp = pashias_tau(S / H);
    } catch (const RuntimeFailure& e) {
      // At S/H -> 0 or 1 the inversion cannot be trusted to 1e-9; the slump test cannot resolve such a
      // value either (a slump of 1e-15 mm, or a hair below the mould height).
      t.fail(row, "slump_mm",
             fmt::format("slump {} m of H = {} m (S/H = {:.3g}) is at the edge of what the Pashias-Boger relation "
                         "resolves: {}",
                         S, H, S / H, e.what()));
    }
    tau_prime.push_back(tp);
    tau.push_back(tp * density * units::g * H);
    if (units.plausibility_checks() && tau.back() > plausible_paste_yield_stress.hi)
      t.fail(row, "slump_mm",
             fmt::format("gives tau_y = {:.0f} Pa, more than {:g} Pa, which is not plausible for a paste; check the "
                         "units of H_mm and paste_density_kg_m3 (or set allow_implausible_values = true in the "
                         "manifest's [slump] table)",
                         tau.back(), plausible_paste_yield_stress.hi));
    rho.push_back(density);
    heights.push_back(H);
    if (has_printed) {
      auto p = t.optional_number(row, "yield_stress_Pa", Range::positive);
      if (p) {
        printed.push_back(*p * units.factor("yield_stress_Pa"));
        printed_cells.push_back(t.text(row, "yield_stress_Pa"));
      }
    }
  }
  IngestResult out;
  Parameter p = summary_parameter("paste.yield_stress", tau, "Pa",
                                  "slump test, Pashias-Boger cylinder S' = 1 - 2 tau'(1 - ln 2 tau'); closed-form "
                                  "Lambert W_-1 inverse checked against a bracketed root (1e-9 rel); tau_y = tau' "
                                  "rho g H, g = 9.81",
                                  t.path());
  p.trials = tau;
  out.parameters.push_back(p);
  out.parameters.push_back(summary_parameter("paste.density", rho, "kg/m3", "as recorded with the slump tests", t.path()));

  // Printed values: do they agree with ours within their rounding? If not, say by how much and whether a
  // different mould height in tau_y = tau' rho g H explains them (the thesis's case: 0.150 m vs 0.152 m).
  if (printed.size() == tau.size() && !printed.empty()) {
    bool disagree = false;
    double rel_min = 1e300, rel_max = -1e300, rel_sum = 0.0, implied_h = 0.0;
    for (std::size_t k = 0; k < tau.size(); ++k) {
      disagree = disagree || std::abs(printed[k] - tau[k]) > rounding_tolerance(printed_cells[k]);
      const double rel = (tau[k] - printed[k]) / tau[k];
      rel_min = std::min(rel_min, rel);
      rel_max = std::max(rel_max, rel);
      rel_sum += rel;
      implied_h += printed[k] / (tau_prime[k] * rho[k] * units::g) / static_cast<double>(tau.size());
    }
    if (disagree) {
      const double h_mm = std::round(implied_h * 1e3);  // the height, to the mm, that the printed values imply
      bool explained = true;
      for (std::size_t k = 0; k < tau.size(); ++k)
        explained = explained &&
                    std::abs(tau_prime[k] * rho[k] * units::g * h_mm * 1e-3 - printed[k]) <=
                        rounding_tolerance(printed_cells[k]);
      std::string msg = fmt::format(
          "printed yield stresses {} Pa (mean {:.1f}) disagree with the recomputed {} Pa (mean {:.1f}): the "
          "printed values are {:.1f} % lower on average ({:.1f} to {:.1f} %)",
          fmt::join(printed_cells, ", "), summarize(printed).mean,
          [&] {
            std::vector<std::string> v;
            for (double x : tau) v.push_back(fmt::format("{:.1f}", x));
            return fmt::format("{}", fmt::join(v, ", "));
          }(),
          p.value, 100.0 * rel_sum / static_cast<double>(tau.size()), 100.0 * rel_min, 100.0 * rel_max);
      if (explained && std::abs(h_mm * 1e-3 - heights.front()) > 1e-9)
        msg += fmt::format("; consistent with H = {:.3f} m instead of the mould's {:.3f} m in tau_y = tau' rho g H "
                           "(reproduces every printed value within its rounding); we keep H = {:.3f} m",
                           h_mm * 1e-3, heights.front(), heights.front());
      out.warnings.push_back(Warning{t.path(), msg});
    }
  }
  if (t.has_column("yield_stress_mean_Pa")) {
    // The mean is a merged cell repeated on every row: every row is checked, the disagreeing ones reported
    // in one warning.
    std::vector<int> lines;
    std::string first_cell;
    for (const auto& row : t.rows()) {
      auto m = t.optional_number(row, "yield_stress_mean_Pa", Range::positive);
      if (!m) continue;
      const double printed_mean = *m * units.factor("yield_stress_mean_Pa");
      if (std::abs(printed_mean - p.value) > rounding_tolerance(t.text(row, "yield_stress_mean_Pa"))) {
        if (lines.empty()) first_cell = t.text(row, "yield_stress_mean_Pa");
        lines.push_back(row.line);
      }
    }
    if (!lines.empty())
      out.warnings.push_back(Warning{fmt::format("{}:{}", t.path(), lines.front()),
                                     fmt::format("printed mean yield stress {} Pa, recomputed {:.1f} Pa{}",
                                                 shown(first_cell), p.value, other_lines(lines))});
  }
  return out;
}

}  // namespace pastemix::lab
