// SPDX-License-Identifier: MIT
#include "lab/ingest/block_id.h"

#include <fmt/format.h>

#include "lab/ingest/block_cut.h"

namespace pastemix::lab {

BlockIndex parse_block_row(const CsvTable& t, const CsvTable::Row& row) {
  const std::string& id = t.text(row, "block_id");
  auto digit = [&](std::size_t pos, int max) {
    const char c = id[pos];
    return (c >= '1' && c <= '0' + max) ? c - '0' : 0;
  };
  BlockIndex ix;
  if (id.size() == 5 && id.rfind("M_", 0) == 0) ix = BlockIndex{digit(2, kBlocksI), digit(3, kBlocksJ), digit(4, kLayers)};
  if (ix.i == 0 || ix.j == 0 || ix.k == 0)
    t.fail(row, "block_id",
           fmt::format("expected an id 'M_ijk' with i in 1..{}, j in 1..{}, layer k in 1..{}; got '{}'", kBlocksI,
                       kBlocksJ, kLayers, id));
  const std::pair<const char*, int> cols[] = {{"i", ix.i}, {"j", ix.j}, {"layer", ix.k}};
  for (const auto& [col, expected] : cols) {
    const long v = t.integer(row, col);
    if (v != expected)
      t.fail(row, col, fmt::format("block {} has {} = {} by its id, but this column says {}", id, col, expected, v));
  }
  return ix;
}

std::string block_id_of(int b) {
  const int k = b % kLayers + 1;
  const int j = (b / kLayers) % kBlocksJ + 1;
  const int i = b / (kLayers * kBlocksJ) + 1;
  return fmt::format("M_{}{}{}", i, j, k);
}

}  // namespace pastemix::lab
