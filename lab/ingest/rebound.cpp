// SPDX-License-Identifier: MIT
#include "lab/ingest/rebound.h"

#include <cmath>

#include <fmt/format.h>

#include "lab/ingest/printed.h"

namespace pastemix::lab {

const std::vector<ColumnSpec>& rebound_columns() {
  static const std::vector<ColumnSpec> specs{
      {"test", ""},
      {"steel_ball_diameter_mm", "mm"},
      {"steel_ball_density_kg_m3", "kg/m3"},
      {"falling_height_mm", "mm"},
      {"rebound_height_mm", "mm"},
      {"restitution_coefficient", "-", false},
      {"restitution_coefficient_mean", "-", false},
  };
  return specs;
}

IngestResult ingest_rebound(const CsvTable& t, const ColumnUnits& units) {
  require_spec_columns(t, rebound_columns());
  IngestResult out;
  std::vector<double> e, diameter, density;
  require_unique_ids(t, "test");
  for (const auto& row : t.rows()) {
    diameter.push_back(t.number(row, "steel_ball_diameter_mm", Range::positive) *
                       units.factor("steel_ball_diameter_mm"));
    density.push_back(t.number(row, "steel_ball_density_kg_m3", Range::positive) *
                      units.factor("steel_ball_density_kg_m3"));
    check_plausible(t, row, "steel_ball_density_kg_m3", density.back(), plausible_density, units);
    const double hf = t.number(row, "falling_height_mm", Range::positive) * units.factor("falling_height_mm");
    const double hr = t.number(row, "rebound_height_mm", Range::non_negative) * units.factor("rebound_height_mm");
    if (hr >= hf)
      t.fail(row, "rebound_height_mm",
             fmt::format("rebound height {} m is not below the drop height {} m (restitution would be >= 1; "
                         "check for swapped columns or units)",
                         hr, hf));
    e.push_back(std::sqrt(hr / hf));
    compare_printed(t, row, "restitution_coefficient", e.back(), "restitution", out.warnings);
  }
  Parameter p = summary_parameter("steel_ball.restitution", e, "-",
                                  "rebound (drop) test, steel ball on steel plate, e = sqrt(H_r/H_f); mean over "
                                  "drop heights",
                                  t.path());
  compare_printed_mean(t, "restitution_coefficient_mean", p.value, "restitution", out.warnings);
  p.trials = e;
  out.parameters.push_back(p);
  const char* recorded = "as recorded with the rebound tests";
  out.parameters.push_back(summary_parameter("steel_ball.diameter", diameter, "m", recorded, t.path()));
  out.parameters.push_back(summary_parameter("steel_ball.density", density, "kg/m3", recorded, t.path()));
  return out;
}

}  // namespace pastemix::lab
