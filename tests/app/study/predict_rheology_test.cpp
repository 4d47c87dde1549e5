// SPDX-License-Identifier: MIT
// `pastemix predict rheology` (app/study/predict_rheology.h) on the TINY scene of tests/app/study/data, put in
// a scene folder as "case 6" (no lab grid: mapped, not scored): the band's rows, a rerun that reads every run
// back, and bad inputs that are errors naming what is wrong.
#include "app/study/predict_rheology.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "base/error.h"
#include "lab/parameters_toml.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::app::study;
namespace fs = std::filesystem;
namespace rh = pastemix::lab::rheology;

namespace {

const fs::path kDir = fs::temp_directory_path() / fmt::format("pastemix_predict_{}", static_cast<long>(::getpid()));

rh::Model prior_model() {
  rh::Model m;
  m.anchor.yield_stress = 137.97, m.anchor.yield_stress_sd = 6.03;
  m.anchor.plastic_viscosity = 0.7, m.anchor.curve = "published_4_19", m.anchor.density = 1843.0;
  const rh::Prior p = rh::prior(m.family, m.anchor);
  m.shape = p.mid(), m.shape_sd = p.sd();
  return m;
}

// A parameter store as `lab reduce` writes it (the same writer), and the tiny scene as case 6 reading it.
PredictOptions tiny_setup(const std::string& out) {
  fs::create_directories(kDir / "scenes");
  lab::ReduceResult r;
  r.parameters = rh::store_parameters(prior_model(), {}, {0.725}, {"6"}, "test anchor");
  const std::string store = (kDir / "parameters.toml").string();
  std::ofstream(store) << lab::parameters_toml(r, {"test", "test", "now"});
  model::SceneDoc d = model::SceneDoc::parse_file(test::source_path("tests/app/study/data/rheology_tiny.toml"));
  d.set("fluid.0.rheology_from", "\"" + store + "\"");
  std::ofstream(kDir / "scenes" / "mixing_case6.toml") << d.text();
  PredictOptions o;
  o.cases = {6};
  o.shape = 0.44, o.shape_sd = 0.05;
  o.seeds = 2;
  o.jobs = 2;
  o.scenes = kDir / "scenes";
  o.store = store;
  o.lab_h5.clear();  // no lab.h5: nothing is scored
  o.out = kDir / out;
  o.quiet = true;
  o.engine = "test";
  o.layout.layer_thickness = 0.005;  // 1 x 1 block of 6 x 6 cm, layers of 5 mm (the tiny box)
  o.layout.count = {1, 1};
  o.layout.size = {0.06, 0.06};
  return o;
}

std::string error_of(const PredictOptions& o) {
  try {
    predict_rheology(o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("predict rheology: a band of 3 values x 2 seeds on the tiny scene, and a rerun that reads everything back") {
  const PredictOptions o = tiny_setup("band");
  const PredictResult r = predict_rheology(o);
  REQUIRE(r.groups.size() == 3);
  CHECK(r.runs_total == 6);
  CHECK(r.computed == 6);
  const rh::Model m = prior_model();
  for (int k = 0; k < 3; ++k) {
    const PredictGroup& g = r.groups[static_cast<std::size_t>(k)];
    CHECK(g.case_id == 6);
    CHECK(g.label == k - 1);
    CHECK(g.shape == doctest::Approx(0.44 + (k - 1) * 0.05).epsilon(1e-14));
    rh::Model at = m;
    at.shape = g.shape;
    CHECK(g.tau_y == rh::yield_stress(at, 0.725));  // the store's model at the scene's solids content
    CHECK_FALSE(g.scored);
    REQUIRE(g.runs.size() == 2);
    CHECK(g.runs[0].seed == 11);  // the scene's seed, then +1: the same at every value
    CHECK(g.runs[1].seed == 12);
    for (const auto& run : g.runs) {
      REQUIRE_MESSAGE(run.failure.empty(), run.failure);
      REQUIRE(run.q.size() == static_cast<std::size_t>(kPredictMaps));
      const double layers = run.q[0] + run.q[1] + run.q[2];
      CHECK(layers > 1e-3);  // the ~8 g of rock is mostly in the grid
      CHECK(run.q[3] == doctest::Approx((run.q[1] + run.q[2]) / layers).epsilon(1e-12));
      CHECK(run.q[4] + run.q[5] == doctest::Approx(0.008).epsilon(0.2));  // mixed + unmixed = the pour
      CHECK(fs::exists(o.out / "runs" / (run.key + ".h5")));
    }
  }
  // Exponential family: tau_y(72.5 %) = tau_75 exp(-2.5 b) falls as b rises across the band.
  CHECK(r.groups[0].tau_y > r.groups[2].tau_y);
  write_band_outputs(r, o);
  std::ifstream csv(o.out / "band.csv");
  int lines = 0;
  for (std::string l; std::getline(csv, l);) ++lines;
  CHECK(lines == 4);  // header + 3 values
  const std::string table = band_table(r, o);
  MESSAGE(table);
  CHECK(table.find("b - sd") != std::string::npos);
  CHECK(table.find("b + sd") != std::string::npos);
  CHECK(table.find("engine test") != std::string::npos);
  CHECK(table.find("overrides: none") != std::string::npos);
  CHECK(table.find("runs: 6 in all, 6 computed now, 0 read back") != std::string::npos);

  const PredictResult again = predict_rheology(o);
  CHECK(again.computed == 0);
  CHECK(again.read_back == 6);
  for (std::size_t g = 0; g < 3; ++g)
    for (std::size_t s = 0; s < 2; ++s) CHECK(again.groups[g].runs[s].q == r.groups[g].runs[s].q);
}

TEST_CASE("predict rheology: bad inputs are errors naming the file or field") {
  PredictOptions o = tiny_setup("bad");
  PredictOptions no_scene = o;
  no_scene.cases = {6, 9};
  CHECK(error_of(no_scene).find("mixing_case9.toml") != std::string::npos);
  PredictOptions outside = o;
  outside.shape = 0.58;  // + 1 sd = 0.63 is above the prior's 0.602
  CHECK(error_of(outside).find("exponential.b = 0.63") != std::string::npos);
  PredictOptions no_record = o;
  no_record.shape.reset(), no_record.shape_sd.reset();
  no_record.calibration = kDir / "missing_calibration.toml";
  CHECK(error_of(no_record).find("missing_calibration.toml") != std::string::npos);
  PredictOptions zero_sd = o;
  zero_sd.shape_sd = 0.0;
  CHECK(error_of(zero_sd).find("positive") != std::string::npos);
  CHECK_FALSE(fs::exists(o.out / "band.txt"));  // nothing written
  // The command: exit 2 with the file named.
  const auto cli = test::run_pastemix(fmt::format("predict rheology --calibration '{}' --cases 6 --scenes '{}' "
                                                  "--params '{}' --lab-h5 '' --out '{}'",
                                                  (kDir / "missing_calibration.toml").string(), o.scenes.string(),
                                                  o.store.string(), (kDir / "cli").string()));
  INFO(cli.output);
  CHECK(cli.exit_code == 2);
  CHECK(cli.output.find("missing_calibration.toml") != std::string::npos);
}

TEST_CASE("predict rheology: a case with a lab grid is scored as `pastemix score` scores the same files") {
  // The lab store of the thesis dataset (cases 1-5 have grids), and the tiny scene as case 4 (72.5 %, its
  // 5-6 mm rock inside case 4's 5-8 mm sieve range), mapped on a 4 x 3 grid of 1.5 x 2 cm blocks covering the
  // tiny box, 5 mm layers: not a meaningful comparison with the lab, but the same numbers as the score command.
  PredictOptions o = tiny_setup("scored");
  const fs::path lab = kDir / "lab";
  const auto reduce = test::run_pastemix(
      fmt::format("lab reduce '{}' --out '{}'", test::source_path("datasets/thesis"), lab.string()));
  REQUIRE_MESSAGE(reduce.exit_code == 0, reduce.output);
  fs::copy_file(o.scenes / "mixing_case6.toml", o.scenes / "mixing_case4.toml", fs::copy_options::overwrite_existing);
  o.cases = {4};
  o.lab_h5 = lab / "lab.h5";
  o.layout.count = {4, 3};
  o.layout.size = {0.015, 0.02};
  const PredictResult r = predict_rheology(o);
  REQUIRE(r.groups.size() == 3);
  const PredictGroup& g = r.groups[1];
  REQUIRE(g.scored);
  REQUIRE(g.ensemble_layers_matched.has_value());
  for (const auto& run : g.runs) REQUIRE(run.q.size() == static_cast<std::size_t>(kPredictScored));
  const std::string grid = "--lab 4 --blocks 4,3 --block-size 0.015,0.02 --layer-thickness 0.005";
  auto score_of = [&](const std::string& files, const std::string& out) {
    const auto s = test::run_pastemix(fmt::format("score {} {} --lab-h5 '{}' --out '{}'", files, grid,
                                                  o.lab_h5.string(), (kDir / out).string()));
    REQUIRE_MESSAGE(s.exit_code == 0, s.output);
    return s.output;
  };
  const fs::path runs = o.out / "runs";
  const std::string both = score_of(fmt::format("'{}' '{}'", (runs / (g.runs[0].key + ".h5")).string(),
                                                (runs / (g.runs[1].key + ".h5")).string()), "score_both");
  CHECK(both.find(fmt::format("mean absolute C error: {:.2f} pp", g.ensemble_mae_pp)) != std::string::npos);
  CHECK(both.find(fmt::format("{} of 3 layers matched", *g.ensemble_layers_matched)) != std::string::npos);
  const std::string one = score_of("'" + (runs / (g.runs[0].key + ".h5")).string() + "'", "score_one");
  CHECK(one.find(fmt::format("mean absolute C error: {:.2f} pp", g.runs[0].q[7])) != std::string::npos);
  CHECK(one.find(fmt::format("{:.0f} of 3 layers matched", g.runs[0].q[6])) != std::string::npos);
  const std::string table = band_table(r, o);
  CHECK(table.find("layers, MAE") != std::string::npos);
}
