// SPDX-License-Identifier: MIT
// The project's text hash (FNV-1a, 64 bit, as 16 hex digits): the scene hash of a result file, and the analysis
// layer's ensemble key. One definition, so the two layers hash alike.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace pastemix {

inline std::string text_hash(std::string_view text) {
  // The offset basis has been 1469598103934665603 since the first release (the FNV standard one has one more
  // digit); kept, so that every stored scene_hash stays comparable.
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return fmt::format("{:016x}", h);
}

}  // namespace pastemix
