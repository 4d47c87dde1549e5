// SPDX-License-Identifier: MIT
// libFuzzer target: the block-id parser (lab/ingest/block_id.h) on rows "block_id,i,j,layer".
#include <string>

#include "base/csv.h"
#include "fuzz/fuzz_common.h"
#include "lab/ingest/block_id.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pastemix;
  fuzz::guarded([&] {
    const CsvTable t = CsvTable::parse("block_id,i,j,layer\n" + std::string(fuzz::as_text(data, size)), "fuzz.csv");
    for (const auto& row : t.rows()) fuzz::guarded([&] { (void)lab::parse_block_row(t, row); });
  });
  return 0;
}
