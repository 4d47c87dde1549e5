// SPDX-License-Identifier: MIT
// `pastemix run` when the disk refuses a write (issue 20, item 1): exit 2 naming the file, the earlier
// results intact, no partial left. It used to abort (exit 134) with an uncaught H5::Exception.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "tests/run_command.h"

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("run: a write refused by the disk is exit 2 with the path, old results stay, no partial is left") {
  const fs::path dir = fs::absolute(fmt::format("model_full_disk_{}", ::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "hertz_impact_m1.h5") << "old result";
  std::ofstream(dir / "hertz_impact_m1.xmf") << "old xdmf";
  // A file-size limit of 8 blocks (4 or 8 KB; the result is ~40 KB) makes the kernel refuse the writes with
  // EFBIG as a full disk does with ENOSPC; SIGXFSZ ignored so that write() returns the error.
  const auto r = pastemix::test::run_pastemix(
      fmt::format("run '{}' --out '{}' --quiet --threads 1",
                  pastemix::test::source_path("datasets/scenes/hertz_impact_m1.toml"), dir.string()),
      "trap '' XFSZ; ulimit -f 8;");
  INFO(r.output);
  CHECK(r.exit_code == 2);
  CHECK(r.output.find((dir / "hertz_impact_m1.h5").string()) != std::string::npos);
  CHECK(r.output.find("cannot write") != std::string::npos);
  CHECK(slurp(dir / "hertz_impact_m1.h5") == "old result");
  CHECK(slurp(dir / "hertz_impact_m1.xmf") == "old xdmf");
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 2);
  fs::remove_all(dir);
}
