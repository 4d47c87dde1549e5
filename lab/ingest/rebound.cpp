// SPDX-License-Identifier: MIT
#include "lab/ingest/rebound.h"

#include <cmath>

#include <fmt/format.h>

#include "base/stats.h"
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
  const Summary s = summarize(e);
  compare_printed_mean(t, "restitution_coefficient_mean", s.mean, "restitution", out.warnings);
  Parameter p;
  p.key = "steel_ball.restitution";
  p.value = s.mean;
  p.sd = s.sd;
  p.n = s.n;
  p.unit = std::string("-");  // (a temporary: GCC 12 warns falsely, -Wrestrict, on a 1-char literal)
  p.method = "rebound (drop) test, steel ball on steel plate, e = sqrt(H_r/H_f); mean over drop heights";
  p.source = t.path();
  p.trials = e;
  out.parameters.push_back(p);
  auto constant = [&](const char* key, const std::vector<double>& v, const char* unit) {
    const Summary c = summarize(v);
    Parameter q;
    q.key = key;
    q.value = c.mean;
    q.sd = c.sd;
    q.n = c.n;
    q.unit = unit;
    q.method = "as recorded with the rebound tests";
    q.source = t.path();
    out.parameters.push_back(q);
  };
  constant("steel_ball.diameter", diameter, "m");
  constant("steel_ball.density", density, "kg/m3");
  return out;
}

}  // namespace pastemix::lab
