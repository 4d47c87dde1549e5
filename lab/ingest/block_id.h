// SPDX-License-Identifier: MIT
// Block ids "M_ijk" of the cut-block grid and their consistency with the i, j, layer columns.
#pragma once

#include <string>

#include "base/csv.h"

namespace pastemix::lab {

struct BlockIndex {
  int i = 0, j = 0, k = 0;  // 1-based: i along the 20 cm side, j along the 16.5 cm side, k = layer from the top
};

// Reads block_id, i, j, layer from a row; the id must be "M_ijk" with i in 1..4, j in 1..3, k in 1..3, and the
// three columns must repeat its digits. Throws InputError naming the line and the offending column.
BlockIndex parse_block_row(const CsvTable& table, const CsvTable::Row& row);
// "M_ijk" for grid index b (see block_index in block_cut.h).
std::string block_id_of(int b);

}  // namespace pastemix::lab
