// SPDX-License-Identifier: MIT
// The interface correction of thesis Table 3.3 (block_cut_corrections.csv).
//
// Some top-layer blocks hold a lump of pure paste that never mixed (estimated from photos as a wet mass
// M'_paste and its dried mass M'_paste.dried). Counting it as paste that fills the rock's voids inflates S far
// above 100 %, so it is subtracted before computing C and S: M_p,corrected = M_p - M'_paste.dried. The result
// is reported SEPARATELY (BlockCutResult::corrected), beside the uncorrected grids, never in place of them.
#pragma once

#include "base/csv.h"
#include "lab/ingest/block_cut.h"

namespace pastemix::lab {

const std::vector<ColumnSpec>& block_cut_correction_columns();
// Columns: case, block_id, i, j, layer, M_prime_paste_kg, M_prime_paste_dried_kg, and optionally the printed
// M_paste_dried_corrected_kg, C_percent, S_percent. Every row must name a block of `result.cases`, once.
// Fills result.corrected and result.printed_corrected; warns where printed values disagree beyond what the
// 4-decimal rounding of the masses explains.
void apply_block_cut_corrections(BlockCutResult& result, const CsvTable& table, const ColumnUnits& units);

}  // namespace pastemix::lab
