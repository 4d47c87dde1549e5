// SPDX-License-Identifier: MIT
// libFuzzer target: the strict CSV reader (base/csv.h) and every cell accessor on what it parsed.
#include "base/csv.h"
#include "fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pastemix;
  fuzz::guarded([&] {
    const CsvTable t = CsvTable::parse(fuzz::as_text(data, size), "fuzz.csv");
    for (const auto& row : t.rows())
      for (const auto& column : t.header()) {
        fuzz::guarded([&] { (void)t.number(row, column, Range::positive); });
        fuzz::guarded([&] { (void)t.optional_number(row, column, Range::fraction); });
        fuzz::guarded([&] { (void)t.integer(row, column); });
      }
    // The hints of a missing column (separator, nearest name) and of an unknown one.
    fuzz::guarded([&] { t.require_columns({"trial", "slump_mm"}); });
    fuzz::guarded([&] { t.require_only_columns({"trial", "slump_mm"}); });
  });
  return 0;
}
