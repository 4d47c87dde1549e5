// SPDX-License-Identifier: MIT
// libFuzzer target: a dataset manifest (lab/manifest.h) over the thesis's CSV files, through every reduce
// step except the drag-curve fit (seconds of Ceres per input; its manifest table is still read).
//
// The input is written as manifest.toml into a scratch folder that holds links to datasets/thesis/*.csv.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "fuzz/fuzz_common.h"
#include "lab/manifest.h"
#include "lab/reduce.h"

namespace {

std::filesystem::path scratch() {
  namespace fs = std::filesystem;
  static const fs::path dir = [] {
    const fs::path d = fs::temp_directory_path() / ("pastemix_fuzz_manifest_" + std::to_string(::getpid()));
    fs::create_directories(d);
    for (const auto& e : fs::directory_iterator(PASTEMIX_SOURCE_DIR "/datasets/thesis"))
      if (e.path().extension() == ".csv" && !fs::exists(d / e.path().filename()))
        fs::create_symlink(e.path(), d / e.path().filename());
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pastemix;
  const auto dir = scratch();
  {
    std::FILE* f = std::fopen((dir / "manifest.toml").c_str(), "wb");
    if (!f) return 0;
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  }
  fuzz::guarded([&] {
    const lab::Manifest m = lab::Manifest::load(dir);
    const Params& root = m.root();
    lab::ReduceResult r;
    if (auto ds = root.optional_table("dataset")) {
      (void)ds->string_or("name", "");
      ds->ignore("description");
    }
    for (const auto& step : lab::reduce_steps()) {
      if (std::string(step.key) == "drag_curve") {
        root.ignore("drag_curve");
        continue;
      }
      if (auto table = root.optional_table(step.key)) step.run(*table, m, r);
    }
    root.finish();
  });
  return 0;
}
