// SPDX-License-Identifier: MIT
// The scene hashes the studies store are those of the code before the one-document change (model/scene_doc.h):
// `calibrate rheology` keeps every run as runs/<scene hash>.h5 and finds it again by that hash, and a result's
// scene_hash names its scene in `score`. The expected values were printed by the previous SceneDoc (main at
// ad5b09a, raw toml++ edits) for the same edits of the shipped scenes; a change here recomputes every cached
// calibration run.
#include <doctest/doctest.h>

#include <fstream>
#include <string>

#include "app/study/calibrate.h"
#include "app/study/calibrate_rheology.h"
#include "app/study/sweep.h"
#include "model/output.h"
#include "model/scene_doc.h"
#include "tests/run_command.h"

using namespace pastemix;

namespace {

model::SceneDoc scene(const std::string& name) {
  return model::SceneDoc::parse_file(test::source_path("datasets/scenes/" + name + ".toml"));
}

std::string hash(const model::SceneDoc& d) { return model::scene_hash(d.text()); }

}  // namespace

TEST_CASE("scene hashes under overrides are those of the previous document code") {
  model::SceneDoc c3 = scene("mixing_case3");
  c3.apply_file(test::source_path("datasets/scenes/mixing_fast.overrides.toml"));
  c3.set("seed", "2");
  CHECK(hash(c3) == "eab17804df35abf1");
  model::SceneDoc c7 = scene("pour_ch7_test3");
  c7.apply_file(test::source_path("datasets/scenes/pour_ch7_fast.overrides.toml"));
  c7.apply("end_time=0.05");
  CHECK(hash(c7) == "bca7f9caae5cf52e");
}

TEST_CASE("scene hashes of the calibration and sweep edits are those of the previous document code") {
  // calibrate rheology: the store's rheology written into the [[fluid]], then the seed.
  for (const auto& [seed, want] : {std::pair{"1", "e81eab339d743722"}, std::pair{"3", "07762685223dd6a4"}}) {
    model::SceneDoc d = app::study::with_rheology(scene("mixing_case2"), 136.123456789, 0.7123, 1843.5);
    d.set("seed", seed);
    CHECK(hash(d) == want);
  }
  model::SceneDoc fast = scene("mixing_case5");
  fast.apply_file(test::source_path("datasets/scenes/mixing_fast.overrides.toml"));
  model::SceneDoc d5 = app::study::with_rheology(fast, 12.5, 0.3, 1800);
  d5.set("seed", "2");
  CHECK(hash(d5) == "4f61be224c38ce73");
  // sweep: each ladder kind; calibrate rolling-resistance.
  app::study::SweepOptions o;
  o.vary = "psd_cut";
  CHECK(hash(app::study::at_value(scene("funnel_lift"), o, 2e-3)) == "8b3ac1768f4d7325");
  o.vary = "dt";
  CHECK(hash(app::study::at_value(scene("mixing_case3"), o, 1e-5)) == "0e9e1d364d0ba52e");
  o.vary = "youngs_modulus";
  CHECK(hash(app::study::at_value(scene("mixing_case3"), o, 1e8)) == "8db31b5ba4d21597");
  CHECK(hash(app::study::with_rolling_resistance(scene("repose_ch5"), 0.15)) == "60664fbe9f737127");
}
