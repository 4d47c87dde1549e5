// SPDX-License-Identifier: MIT
// Tilt test -> static friction coefficient mu_s = H_l / L (thesis Table 4.7, steel ball on a steel plate),
// with H_l the lift height at which sliding starts and L the plate length. Only the ratio matters, so the
// two columns must share a dimension (the thesis printed "cm" for what are more likely mm).
#pragma once

#include "base/csv.h"
#include "lab/ingest/ingest.h"

namespace pastemix::lab {

const std::vector<ColumnSpec>& tilt_columns();
// Columns: trial, L_cm_as_printed, H_l_cm_as_printed, and optionally the printed static_friction_coefficient
// and static_friction_coefficient_mean. Returns steel_ball.static_friction.
IngestResult ingest_tilt(const CsvTable& table, const ColumnUnits& units);

}  // namespace pastemix::lab
