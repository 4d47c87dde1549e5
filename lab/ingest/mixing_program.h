// SPDX-License-Identifier: MIT
// The mixing-test programme (thesis Table 3.1): per case, the rock's sieve range, fall height and paste.
//
// The thesis gives no sieve masses for the mixing tests, only the sieve range of each case (2.5-5.0 mm etc.),
// so each case's PSD is a single interval holding all the mass. That is the data, not an assumption; what
// the generator does inside the interval (Gaussian, sigma/mu = 0.25) is the model's assumption.
#pragma once

#include <string>
#include <vector>

#include "base/csv.h"
#include "base/psd.h"
#include "lab/ingest/ingest.h"

namespace pastemix::lab {

struct MixingCase {
  int case_id = 0;
  Psd psd;                     // one interval [d_wr_min, d_wr_max], fraction 1
  double falling_height = 0;   // m
  double solids_fraction = 0;  // paste solids content by mass, 0..1
  std::string size_class, tint;
  int line = 0;
};

const std::vector<ColumnSpec>& mixing_program_columns();
std::vector<MixingCase> ingest_mixing_program(const CsvTable& table, const ColumnUnits& units);

}  // namespace pastemix::lab
