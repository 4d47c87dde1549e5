// SPDX-License-Identifier: MIT
// A test's files: an empty folder for its outputs, and a file's whole text.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace pastemix::test {

// An empty folder at `path` (what was there is removed first).
inline std::filesystem::path fresh_dir(const std::filesystem::path& path) {
  std::filesystem::remove_all(path);
  std::filesystem::create_directories(path);
  return path;
}

// The whole text of a file ("" when it cannot be read).
inline std::string file_text(const std::filesystem::path& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace pastemix::test
