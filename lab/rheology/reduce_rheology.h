// SPDX-License-Identifier: MIT
// The [paste_rheology] step of `lab reduce`: the measured 75 % paste (paste.yield_stress and paste.density of
// the slump step, the steel-ball eta_B named in the manifest) + a one-parameter family -> the rheology at every
// solids content a mixing case uses (lab/rheology/paste_rheology.h), keys paste_rheology.*.
//
//   [paste_rheology]
//   family = "exponential"                 # or "packing"
//   anchor_solids_fraction = 0.75          # the measured paste (C_w, by mass)
//   anchor_plastic_viscosity = 0.7         # Pa.s, steel-ball calibration (thesis Table 4.4)
//   anchor_plastic_viscosity_source = "..."
//   anchor_curve = "published_4_19"        # the drag curve that eta_B belongs to
//   solids_density = 2710                  # kg/m3, tailings
//   water_density = 1000                   # kg/m3
//
// The shape parameter is the family's prior unless `lab reduce --rheology-calibration FILE` gives a record
// of `pastemix calibrate rheology` (then the record's family and value, provenance "calibrated on case N").
// Runs after [slump] and [mixing_program] (the step table's order); it needs both (an error says so).
#pragma once

#include "base/params.h"
#include "lab/manifest.h"
#include "lab/reduce.h"

namespace pastemix::lab::rheology {

void run_paste_rheology(const Params& table, const Manifest& manifest, ReduceResult& result);

}  // namespace pastemix::lab::rheology
