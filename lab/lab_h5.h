// SPDX-License-Identifier: MIT
// lab.h5: the reduced lab data for programs (the analysis layer, the plotting script).
//
// Layout (every grid is float64 [4][3][3] row-major, index [i-1][j-1][k-1]: i = 1..4 along the 20 cm side,
// j = 1..3 along the 16.5 cm side, k = layer 1..3 from the top; C and S are fractions 0..1, NaN = undefined):
//   /                       attrs software, command, created, dataset, manifest, grid_layout
//   /parameters/<key>/      attrs value, sd, n, unit, provenance, method, source (text, note if any); dataset
//                           trials (if any); paste_rheology.* (lab/rheology/paste_rheology.h) among them
//   /block_cut/case_<n>/    C, S, S_raw, flag (int32, 0 value, 1 capped, 2 no rock, 3 no K), M_wr, M_paste_dried,
//                           C_printed, S_printed, line (source line); attrs K (NaN if unknown), K_source
//   /block_cut/case_<n>/corrected/  C, S, S_raw, flag, M_paste_dried, applied (int32, 1 = Table 3.3 row)
//   /block_cut/             attrs comparison figures against the printed C and S
//   /psd/mixing_case_<n>/   d_min, d_max (m), mass_fraction; attrs source
//   /sieve/<name>/          d_min, d_max, mass_fraction, sieves (m), passing; attrs source, provenance, pan_fraction, cut_m
//   /warnings               strings "where: message";  /inputs  strings (relative to the dataset folder)
#pragma once

#include <filesystem>

#include "lab/reduce.h"
#include "lab/run_info.h"

namespace pastemix::lab {

void write_lab_h5(const std::filesystem::path& path, const ReduceResult& result, const RunInfo& info);

}  // namespace pastemix::lab
