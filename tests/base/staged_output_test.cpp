// SPDX-License-Identifier: MIT
#include "base/staged_output.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <doctest/doctest.h>

namespace fs = std::filesystem;

TEST_CASE("staged output: nothing appears until commit, and an abort leaves the old file") {
  auto dir = fs::temp_directory_path() / "pastemix_staged_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  { std::ofstream(dir / "a.txt") << "old"; }
  try {
    pastemix::StagedOutput out;
    out.write_text(dir / "a.txt", "new");
    out.write_text(dir / "b.txt", "b");
    CHECK_FALSE(fs::exists(dir / "b.txt"));
    throw std::runtime_error("input failed half-way");
  } catch (const std::runtime_error&) {
  }
  CHECK_FALSE(fs::exists(dir / "b.txt"));
  std::ifstream in(dir / "a.txt");
  std::string s;
  in >> s;
  CHECK(s == "old");
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);  // no partial files left
  {
    pastemix::StagedOutput out;
    out.write_text(dir / "b.txt", "b");
    out.commit();
  }
  CHECK(fs::exists(dir / "b.txt"));
  fs::remove_all(dir);
}
