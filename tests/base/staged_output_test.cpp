// SPDX-License-Identifier: MIT
#include "base/staged_output.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "base/error.h"

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

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

fs::path fresh_dir(const std::string& name) {
  auto dir = fs::temp_directory_path() / fmt::format("pastemix_staged_{}_{}", name, static_cast<long>(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

}  // namespace

TEST_CASE("staged output: a rename that fails half-way through commit leaves the whole old set") {
  const auto dir = fresh_dir("half");
  for (const char* n : {"a.txt", "b.txt", "c.txt"}) std::ofstream(dir / n) << "old " << n;
  {
    pastemix::StagedOutput out;
    out.write_text(dir / "a.txt", "new a");
    out.write_text(dir / "b.txt", "new b");
    out.write_text(dir / "c.txt", "new c");
    out.write_text(dir / "d.txt", "new d");  // a file the old set did not have
    ::setenv("PASTEMIX_FAULT_RENAME", "c.txt", 1);  // a and b are moved in before c fails
    CHECK_THROWS_WITH_AS(out.commit(), doctest::Contains("c.txt"), pastemix::InputError);
    ::unsetenv("PASTEMIX_FAULT_RENAME");
  }
  CHECK(slurp(dir / "a.txt") == "old a.txt");
  CHECK(slurp(dir / "b.txt") == "old b.txt");
  CHECK(slurp(dir / "c.txt") == "old c.txt");
  CHECK(names_in(dir) == std::vector<std::string>{"a.txt", "b.txt", "c.txt"});  // no partial, old or d.txt
  {
    pastemix::StagedOutput out;
    out.write_text(dir / "a.txt", "new a");
    out.write_text(dir / "d.txt", "new d");
    out.commit();
  }
  CHECK(slurp(dir / "a.txt") == "new a");
  CHECK(names_in(dir) == std::vector<std::string>{"a.txt", "b.txt", "c.txt", "d.txt"});
  fs::remove_all(dir);
}

TEST_CASE("staged output: partials and old copies of a dead process are removed, a live one's are kept") {
  const auto dir = fresh_dir("stale");
  // PIDs above the kernel's pid_max (4194304 at most) are never alive.
  std::ofstream(dir / "r.h5.partial-999999999") << "killed run";
  std::ofstream(dir / "r.h5.old-999999998") << "killed commit";
  const auto live = fmt::format("r.h5.partial-{}", static_cast<long>(::getppid()));
  std::ofstream(dir / live) << "a parallel run";
  {
    pastemix::StagedOutput out;
    out.write_text(dir / "r.h5", "new");
    out.commit();
  }
  CHECK(names_in(dir) == std::vector<std::string>{"r.h5", live});
  fs::remove_all(dir);
}

TEST_CASE("staged output: a TOML file that would not parse is refused before anything is written") {
  const auto dir = fresh_dir("toml");
  std::ofstream(dir / "p.toml") << "a = 1\n";
  {
    pastemix::StagedOutput out;
    CHECK_THROWS_WITH_AS(out.write_text(dir / "p.toml", "# ok\nTraceback (most recent call last):\n"),
                         doctest::Contains("would not be valid TOML (line 2"), std::logic_error);
  }
  CHECK(slurp(dir / "p.toml") == "a = 1\n");
  CHECK(names_in(dir) == std::vector<std::string>{"p.toml"});
  fs::remove_all(dir);
}

TEST_CASE("staged output: an output folder that is a file is an input error naming it") {
  const auto dir = fresh_dir("notdir");
  std::ofstream(dir / "file") << "x";
  pastemix::StagedOutput out;
  CHECK_THROWS_WITH_AS(out.path(dir / "file" / "a.txt"), doctest::Contains("the output folder is a file"),
                       pastemix::InputError);
  fs::remove_all(dir);
}
