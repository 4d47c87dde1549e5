// SPDX-License-Identifier: MIT
// libFuzzer target: TOML params with unknown-key detection (base/params.h): typed reads of the keys a
// scene reads, sub-tables, arrays of tables, and finish() with its "did you mean".
#include "base/params.h"
#include "fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pastemix;
  fuzz::guarded([&] {
    const Params p = Params::parse(fuzz::as_text(data, size), "fuzz.toml");
    fuzz::guarded([&] { (void)p.number("time_step", Range::positive); });
    fuzz::guarded([&] { (void)p.number_or("end_time", 1.0, Range::non_negative); });
    fuzz::guarded([&] { (void)p.integer_or("seed", 1); });
    fuzz::guarded([&] { (void)p.string_or("name", ""); });
    fuzz::guarded([&] { (void)p.choice_or("law", {"hertz_mindlin", "linear"}, "hertz_mindlin"); });
    fuzz::guarded([&] { (void)p.boolean_or("rotation", true); });
    fuzz::guarded([&] { (void)p.optional_numbers("gravity", 3); });
    fuzz::guarded([&] {
      if (auto d = p.optional_table("domain")) {
        (void)d->numbers("min", 3);
        (void)d->numbers("max", 3);
      }
    });
    fuzz::guarded([&] {
      for (const Params& m : p.tables("material")) {
        (void)m.string("name");
        (void)m.number("density", Range::positive);
        (void)m.number_or("poisson_ratio", 0.3, Range::fraction);
      }
    });
    for (const auto& k : p.keys()) (void)p.line_of(k);
    p.finish();
  });
  return 0;
}
