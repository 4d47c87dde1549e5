// SPDX-License-Identifier: MIT
// Rebound (drop) test -> coefficient of restitution e = sqrt(H_r / H_f) (thesis Table 4.6: steel ball on a
// steel plate). Energy ratio of one bounce: the ball cannot rebound higher than it fell, so H_r >= H_f is an
// InputError (swapped columns or units), not a restitution above 1.
#pragma once

#include "base/csv.h"
#include "lab/ingest/ingest.h"

namespace pastemix::lab {

const std::vector<ColumnSpec>& rebound_columns();
// Columns: test, steel_ball_diameter_mm, steel_ball_density_kg_m3, falling_height_mm, rebound_height_mm, and
// optionally the printed restitution_coefficient and restitution_coefficient_mean.
// Returns steel_ball.restitution, steel_ball.diameter and steel_ball.density.
IngestResult ingest_rebound(const CsvTable& table, const ColumnUnits& units);

}  // namespace pastemix::lab
