// SPDX-License-Identifier: MIT
// Slump test -> paste yield stress (Pashias, Boger et al. 1996, cylindrical mould with H ~ D).
//
// Dimensionless slump S' = S/H and yield stress tau' = tau_y / (rho g H) obey
//   S' = 1 - 2 tau' (1 - ln 2 tau'),            0 < tau' < 1/2.
// With u = 2 tau' and w = ln u - 1 this is w e^w = -(1 - S')/e, and u < 1 picks the lower branch:
//   tau' = -(1 - S') / (2 W_-1(-(1 - S')/e)).
// We compute both this closed form and a bracketed (bisection) root of the forward relation; if they
// disagree by more than 1e-9 relative, that is a RuntimeFailure (a bug in one of them, not bad data).
// tau' >= 1/2 means no slump at all (S = 0): the yield stress is then only bounded below, an InputError.
#pragma once

#include "base/csv.h"
#include "lab/ingest/ingest.h"

namespace pastemix::lab {

// Forward relation: S' for tau' in (0, 1/2].
double pashias_slump(double tau_prime);
// Inverse by Lambert W_-1. Requires 0 < S' < 1.
double pashias_tau_lambert(double slump_prime);
// Inverse by bisection of the forward relation on (0, 1/2), to full double precision.
double pashias_tau_bracketed(double slump_prime);
// Both, checked against each other (throws RuntimeFailure on a disagreement above 1e-9 relative).
double pashias_tau(double slump_prime);

const std::vector<ColumnSpec>& slump_columns();
// Columns: trial, H_mm, D_mm, paste_density_kg_m3, slump_mm, and optionally the printed yield_stress_Pa,
// yield_stress_mean_Pa. Returns paste.yield_stress and paste.density.
IngestResult ingest_slump(const CsvTable& table, const ColumnUnits& units);

}  // namespace pastemix::lab
