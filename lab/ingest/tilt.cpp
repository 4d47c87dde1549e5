// SPDX-License-Identifier: MIT
#include "lab/ingest/tilt.h"

#include <fmt/format.h>

#include "lab/ingest/printed.h"

namespace pastemix::lab {

const std::vector<ColumnSpec>& tilt_columns() {
  static const std::vector<ColumnSpec> specs{
      {"trial", ""},
      {"L_cm_as_printed", "cm"},
      {"H_l_cm_as_printed", "cm"},
      {"static_friction_coefficient", "-", false},
      {"static_friction_coefficient_mean", "-", false},
  };
  return specs;
}

IngestResult ingest_tilt(const CsvTable& t, const ColumnUnits& units) {
  require_spec_columns(t, tilt_columns());
  IngestResult out;
  std::vector<double> mu;
  require_unique_ids(t, "trial");
  for (const auto& row : t.rows()) {
    const double L = t.number(row, "L_cm_as_printed", Range::positive) * units.factor("L_cm_as_printed");
    const double h = t.number(row, "H_l_cm_as_printed", Range::non_negative) * units.factor("H_l_cm_as_printed");
    if (h >= L)
      t.fail(row, "H_l_cm_as_printed",
             fmt::format("lift height {} m is not below the plate length {} m (the plate cannot be lifted "
                         "higher than it is long)",
                         h, L));
    mu.push_back(h / L);
    compare_printed(t, row, "static_friction_coefficient", mu.back(), "static friction", out.warnings);
  }
  Parameter p = summary_parameter("steel_ball.static_friction", mu, "-",
                                  "tilt test, steel ball on steel plate, mu_s = H_l/L", t.path());
  compare_printed_mean(t, "static_friction_coefficient_mean", p.value, "static friction", out.warnings);
  p.trials = mu;
  out.parameters.push_back(p);
  return out;
}

}  // namespace pastemix::lab
