// SPDX-License-Identifier: MIT
// What the libFuzzer targets share: the contract they check.
//
// Every parser of user input must either succeed or throw InputError (exit 2: file, line, field). Any other
// exception, a crash, a sanitizer report (ASan, UBSan), a hang past -timeout or memory past -rss_limit_mb is
// a finding. `guarded` lets InputError through and nothing else: anything else escapes, std::terminate
// aborts, and libFuzzer records the input.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "base/error.h"

namespace pastemix::fuzz {

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

template <class Fn>
void guarded(Fn&& fn) {
  try {
    fn();
  } catch (const InputError&) {
    // the expected outcome of a bad input
  }
}

}  // namespace pastemix::fuzz
