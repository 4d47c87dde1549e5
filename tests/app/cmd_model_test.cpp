// SPDX-License-Identifier: MIT
// `pastemix run --realizations N --seed S` (app/cmd_model.cpp): N files NAME_rK, seeds S + K recorded, and the
// rock differs between realizations (sizes and positions come from the scene seed).
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "base/h5.h"
#include "tests/model/scene_text.h"
#include "tests/fresh_dir.h"
#include "tests/run_command.h"

namespace pastemix {
namespace {

// Tiny scene: 3 g of 2.5-5 mm rock filled into a small box, 20 steps.
const std::string kScene = "seed = 1\ntime_step = 5e-6\nend_time = 1e-4\n[domain]\nmin = [-0.01, -0.01, -0.01]\n"
                           "max = [0.06, 0.06, 0.1]\n" + model::test::kRockRolling +
                           model::test::box_wall("[0, 0, 0]", "[0.05, 0.05, 0.09]") +
                           model::test::rock_factory("0.003", "[0.002, 0.002, 0.002]", "[0.048, 0.048, 0.05]");

std::filesystem::path fresh_dir(const std::string& name) {
  return test::fresh_dir(std::filesystem::temp_directory_path() / name);
}

}  // namespace

TEST_CASE("pastemix run --realizations 2 --seed 11: two files, seeds 11 and 12, different rock") {
  const auto dir = fresh_dir("pastemix_realizations_test");
  const auto scene = dir / "tiny.toml";
  std::ofstream(scene) << kScene;
  const auto r = test::run_pastemix("run '" + scene.string() + "' --quiet --threads 1 --realizations 2 --seed 11 --out '" +
                                    dir.string() + "'");
  REQUIRE_MESSAGE(r.exit_code == 0, r.output);
  for (const char* f : {"tiny_r0.h5", "tiny_r0.xmf", "tiny_r1.h5", "tiny_r1.xmf"})
    CHECK_MESSAGE(std::filesystem::exists(dir / f), f);
  CHECK_FALSE(std::filesystem::exists(dir / "tiny_r2.h5"));
  CHECK_FALSE(std::filesystem::exists(dir / "tiny.h5"));

  const H5Reader a((dir / "tiny_r0.h5").string());
  const H5Reader b((dir / "tiny_r1.h5").string());
  CHECK(a.attribute_int("/", "seed") == 11);
  CHECK(b.attribute_int("/", "seed") == 12);
  const auto ra = a.read_doubles("/snapshots/000000/radius");
  const auto rb = b.read_doubles("/snapshots/000000/radius");
  const auto xa = a.read_doubles("/snapshots/000000/position");
  const auto xb = b.read_doubles("/snapshots/000000/position");
  REQUIRE(!ra.empty());
  REQUIRE(!rb.empty());
  // Different seeds -> different sizes and positions (the first sphere of each is drawn independently).
  CHECK(ra.front() != rb.front());
  CHECK(xa[0] != xb[0]);
}

TEST_CASE("pastemix run --realizations: a factory with its own seed is rejected (exit 2), nothing written") {
  const auto dir = fresh_dir("pastemix_realizations_seed_test");
  const auto scene = dir / "fixed.toml";
  std::string text = kScene;
  text.replace(text.find("shape = \"box\"\nmin = [0.002"), 0, "seed = 5\n");
  std::ofstream(scene) << text;
  const auto r = test::run_pastemix("run '" + scene.string() + "' --quiet --realizations 2 --out '" + dir.string() + "'");
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("factory.seed") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir / "fixed_r0.h5"));
}

}  // namespace pastemix
