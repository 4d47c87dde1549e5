// SPDX-License-Identifier: MIT
// An empty folder for a test's outputs.
#pragma once

#include <filesystem>

namespace pastemix::test {

// An empty folder at `path` (what was there is removed first).
inline std::filesystem::path fresh_dir(const std::filesystem::path& path) {
  std::filesystem::remove_all(path);
  std::filesystem::create_directories(path);
  return path;
}

}  // namespace pastemix::test
