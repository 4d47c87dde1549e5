// SPDX-License-Identifier: MIT
// Sieve analysis -> particle-size distribution (base/psd.h).
//
// File format (one row per sieve of the stack, any order):
//   sieve_mm,mass_retained_g
//   8.0,0        <- the top sieve: nothing may be retained on it (it is d_max; mass above it has no size)
//   5.0,75.1     <- retained on 5.0 mm = particles in [5.0, 8.0) mm
//   ...
//   0,3.2        <- optional pan (sieve 0): passed the finest sieve; it has no lower size, so it is excluded
//                   from the PSD (reported as the pan fraction), exactly as a PSD cut at the finest sieve would
// Interval k is [sieve_k, next larger sieve) with the mass retained on sieve_k. Cumulative passing at each
// sieve is the mass on all finer sieves and the pan over the total. A cut (d_cut) drops the intervals whose
// upper sieve is <= d_cut and renormalises the rest (Psd::cut_below).
#pragma once

#include <vector>

#include "base/csv.h"
#include "base/psd.h"
#include "lab/ingest/ingest.h"

namespace pastemix::lab {

struct SieveResult {
  Psd psd;                      // after the pan is excluded and the cut applied
  std::vector<double> sieves;   // m, ascending (the pan excluded)
  std::vector<double> passing;  // cumulative mass fraction passing each sieve (pan included in the total)
  double total_mass = 0.0;      // kg, all the sample
  double pan_fraction = 0.0;    // mass fraction in the pan
  double cut = 0.0;             // m, 0 if none
  std::vector<Warning> warnings;
};

const std::vector<ColumnSpec>& sieve_columns();
// d_cut: 0 for none (m).
SieveResult ingest_sieve(const CsvTable& table, const ColumnUnits& units, double d_cut = 0.0);

}  // namespace pastemix::lab
