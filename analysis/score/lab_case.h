// SPDX-License-Identifier: MIT
// One mixing case's measured block grid, read from lab.h5 (written by `pastemix lab reduce`, lab/lab_h5.h).
//
// A case is known when lab.h5 has /parameters/mixing.case_<n>.* (the mixing programme, cases 1-7); it has
// lab data when /block_cut/case_<n> exists (cases 1-5: the thesis's grids of cases 6 and 7 are reserved for
// blind validation and are not in the dataset). Scoring needs the grid; maps only need K.
#pragma once

#include <filesystem>
#include <limits>
#include <string>

#include "lab/ingest/block_cut.h"

namespace pastemix::analysis {

struct LabCase {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  std::string lab_path;
  int case_id = 0;
  bool has_grid = false;
  lab::BlockGrid grid;               // C, S, S_raw, flag, M_wr, M_paste, K (uncorrected Table 3.2 grid)
  double K = nan;                    // kg/m3; NaN if lab.h5 gives none for this case
  std::string K_source;
  double solids_fraction = nan;      // - (mixing programme), NaN if absent
  double falling_height = nan;       // m
  double d_min = nan, d_max = nan;   // m, the rock sizes of the programme (/psd/mixing_case_<n>); NaN if absent
};

// Reads case `case_id`. An unknown case -> InputError naming lab.h5 and the case. When `need_grid` and the
// case has no block grid (cases 6, 7) -> InputError saying so (maps still work).
LabCase read_lab_case(const std::filesystem::path& lab_h5, int case_id, bool need_grid);

}  // namespace pastemix::analysis
