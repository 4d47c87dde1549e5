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

namespace {

// The slump trials as read and reduced: per trial tau_y (Pa), density (kg/m3), tau' and mould height H (m),
// and the printed tau_y (Pa) with its cell text where the table has them.
struct SlumpTrials {
  std::vector<double> tau, rho, tau_prime, heights, printed;
  std::vector<std::string> printed_cells;
};

// tau' of one trial from S/H (Pashias-Boger), with the row's checks: S < H, a slump at all, H ~ D.
double trial_tau_prime(const CsvTable& t, const CsvTable::Row& row, double H, double D, double S, double density) {
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
  try {
    return pashias_tau(S / H);
  } catch (const RuntimeFailure& e) {
    // At S/H -> 0 or 1 the inversion cannot be trusted to 1e-9; the slump test cannot resolve such a
    // value either (a slump of 1e-15 mm, or a hair below the mould height).
    t.fail(row, "slump_mm",
           fmt::format("slump {} m of H = {} m (S/H = {:.3g}) is at the edge of what the Pashias-Boger relation "
                       "resolves: {}",
                       S, H, S / H, e.what()));
  }
}

void read_trial(const CsvTable& t, const CsvTable::Row& row, const ColumnUnits& units, bool has_printed,
                SlumpTrials& s) {
  const double H = t.number(row, "H_mm", Range::positive) * units.factor("H_mm");
  const double D = t.number(row, "D_mm", Range::positive) * units.factor("D_mm");
  const double density = t.number(row, "paste_density_kg_m3", Range::positive) *
                         units.factor("paste_density_kg_m3");
  check_plausible(t, row, "paste_density_kg_m3", density, plausible_density, units);
  const double S = t.number(row, "slump_mm", Range::non_negative) * units.factor("slump_mm");
  const double tp = trial_tau_prime(t, row, H, D, S, density);
  s.tau_prime.push_back(tp);
  s.tau.push_back(tp * density * units::g * H);
  if (units.plausibility_checks() && s.tau.back() > plausible_paste_yield_stress.hi)
    t.fail(row, "slump_mm",
           fmt::format("gives tau_y = {:.0f} Pa, more than {:g} Pa, which is not plausible for a paste; check the "
                       "units of H_mm and paste_density_kg_m3 (or set allow_implausible_values = true in the "
                       "manifest's [slump] table)",
                       s.tau.back(), plausible_paste_yield_stress.hi));
  s.rho.push_back(density);
  s.heights.push_back(H);
  if (has_printed) {
    auto p = t.optional_number(row, "yield_stress_Pa", Range::positive);
    if (p) {
      s.printed.push_back(*p * units.factor("yield_stress_Pa"));
      s.printed_cells.push_back(t.text(row, "yield_stress_Pa"));
    }
  }
}

// Printed values: do they agree with ours within their rounding? If not, say by how much and whether a
// different mould height in tau_y = tau' rho g H explains them (the thesis's case: 0.150 m vs 0.152 m).
void check_printed(const SlumpTrials& s, double mean, const std::string& path, std::vector<Warning>& warnings) {
  if (s.printed.size() != s.tau.size() || s.printed.empty()) return;
  bool disagree = false;
  double rel_min = 1e300, rel_max = -1e300, rel_sum = 0.0, implied_h = 0.0;
  const std::size_t n = s.tau.size();
  for (std::size_t k = 0; k < n; ++k) {
    disagree = disagree || std::abs(s.printed[k] - s.tau[k]) > rounding_tolerance(s.printed_cells[k]);
    const double rel = (s.tau[k] - s.printed[k]) / s.tau[k];
    rel_min = std::min(rel_min, rel);
    rel_max = std::max(rel_max, rel);
    rel_sum += rel;
    implied_h += s.printed[k] / (s.tau_prime[k] * s.rho[k] * units::g) / static_cast<double>(n);
  }
  if (!disagree) return;
  const double h_mm = std::round(implied_h * 1e3);  // the height, to the mm, that the printed values imply
  bool explained = true;
  for (std::size_t k = 0; k < n; ++k)
    explained = explained && std::abs(s.tau_prime[k] * s.rho[k] * units::g * h_mm * 1e-3 - s.printed[k]) <=
                                 rounding_tolerance(s.printed_cells[k]);
  std::vector<std::string> ours;
  for (double x : s.tau) ours.push_back(fmt::format("{:.1f}", x));
  std::string msg = fmt::format(
      "printed yield stresses {} Pa (mean {:.1f}) disagree with the recomputed {} Pa (mean {:.1f}): the "
      "printed values are {:.1f} % lower on average ({:.1f} to {:.1f} %)",
      fmt::join(s.printed_cells, ", "), summarize(s.printed).mean, fmt::format("{}", fmt::join(ours, ", ")), mean,
      100.0 * rel_sum / static_cast<double>(n), 100.0 * rel_min, 100.0 * rel_max);
  if (explained && std::abs(h_mm * 1e-3 - s.heights.front()) > 1e-9)
    msg += fmt::format("; consistent with H = {:.3f} m instead of the mould's {:.3f} m in tau_y = tau' rho g H "
                       "(reproduces every printed value within its rounding); we keep H = {:.3f} m",
                       h_mm * 1e-3, s.heights.front(), s.heights.front());
  warnings.push_back(Warning{path, msg});
}

// The printed mean is a merged cell repeated on every row: every row is checked, the disagreeing ones reported
// in one warning.
void check_printed_mean(const CsvTable& t, const ColumnUnits& units, double mean, std::vector<Warning>& warnings) {
  if (!t.has_column("yield_stress_mean_Pa")) return;
  std::vector<int> lines;
  std::string first_cell;
  for (const auto& row : t.rows()) {
    auto m = t.optional_number(row, "yield_stress_mean_Pa", Range::positive);
    if (!m) continue;
    const double printed_mean = *m * units.factor("yield_stress_mean_Pa");
    if (std::abs(printed_mean - mean) > rounding_tolerance(t.text(row, "yield_stress_mean_Pa"))) {
      if (lines.empty()) first_cell = t.text(row, "yield_stress_mean_Pa");
      lines.push_back(row.line);
    }
  }
  if (!lines.empty())
    warnings.push_back(Warning{fmt::format("{}:{}", t.path(), lines.front()),
                               fmt::format("printed mean yield stress {} Pa, recomputed {:.1f} Pa{}",
                                           shown(first_cell), mean, other_lines(lines))});
}

}  // namespace

IngestResult ingest_slump(const CsvTable& t, const ColumnUnits& units) {
  require_spec_columns(t, slump_columns());
  const bool has_printed = t.has_column("yield_stress_Pa");
  require_unique_ids(t, "trial");
  SlumpTrials s;
  for (const auto& row : t.rows()) read_trial(t, row, units, has_printed, s);
  IngestResult out;
  Parameter p = summary_parameter("paste.yield_stress", s.tau, "Pa",
                                  "slump test, Pashias-Boger cylinder S' = 1 - 2 tau'(1 - ln 2 tau'); closed-form "
                                  "Lambert W_-1 inverse checked against a bracketed root (1e-9 rel); tau_y = tau' "
                                  "rho g H, g = 9.81",
                                  t.path());
  p.trials = s.tau;
  out.parameters.push_back(p);
  out.parameters.push_back(
      summary_parameter("paste.density", s.rho, "kg/m3", "as recorded with the slump tests", t.path()));
  check_printed(s, p.value, t.path(), out.warnings);
  check_printed_mean(t, units, p.value, out.warnings);
  return out;
}

}  // namespace pastemix::lab
