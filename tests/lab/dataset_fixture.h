// SPDX-License-Identifier: MIT
// A scratch copy of datasets/thesis for tests that feed `pastemix lab reduce` one defect at a time.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "tests/run_command.h"

namespace pastemix::test {

namespace fs = std::filesystem;


inline std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
inline void write_text(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// 1-based line of the first occurrence of `needle` in a file.
inline int line_of(const fs::path& p, const std::string& needle) {
  std::stringstream in(read_text(p));
  std::string l;
  for (int n = 1; std::getline(in, l); ++n)
    if (l.find(needle) != std::string::npos) return n;
  FAIL("'" << needle << "' not in " << p);
  return 0;
}

// A scratch copy of the thesis dataset; removed when the test ends.
struct Dataset {
  fs::path dir;
  explicit Dataset(const std::string& name) {
    dir = fs::temp_directory_path() / fmt::format("pastemix_bad_{}_{}", name, static_cast<long>(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const auto& e : fs::directory_iterator(source_path("datasets/thesis")))
      if (e.path().extension() == ".csv" || e.path().extension() == ".toml")
        fs::copy_file(e.path(), dir / e.path().filename());
  }
  ~Dataset() { fs::remove_all(dir); }
  fs::path file(const std::string& name) const { return dir / name; }
  // Replaces line `line` (1-based) of `name` with `text`.
  void set_line(const std::string& name, int line, const std::string& text) const {
    std::stringstream in(read_text(file(name)));
    std::string out, l;
    for (int n = 1; std::getline(in, l); ++n) out += (n == line ? text : l) + "\n";
    write_text(file(name), out);
  }
  // Replaces the first occurrence of `from` in `name`.
  void replace(const std::string& name, const std::string& from, const std::string& to) const {
    std::string t = read_text(file(name));
    const auto at = t.find(from);
    REQUIRE_MESSAGE(at != std::string::npos, from);
    t.replace(at, from.size(), to);
    write_text(file(name), t);
  }
  // Runs `lab reduce` and checks: exit 2, the message contains `expected`, and nothing was written.
  void expect_reduce_error(const std::string& expected) const {
    const fs::path out = dir / "out";
    const auto r = run_pastemix(fmt::format("lab reduce '{}' --out '{}'", dir.string(), out.string()));
    INFO(r.output);
    CHECK(r.exit_code == 2);
    CHECK(r.output.find(expected) != std::string::npos);
    CHECK(!fs::exists(out));
  }
};


}  // namespace pastemix::test
