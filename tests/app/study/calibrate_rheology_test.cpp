// SPDX-License-Identifier: MIT
// `pastemix calibrate rheology` (app/study/calibrate_rheology.h) on the TINY scene of tests/app/study/data:
// a synthetic calibration recovers a known shape parameter, a rerun recomputes nothing, the CLI writes the
// record into the store, and bad inputs are errors naming what is wrong.
#include "app/study/calibrate_rheology.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "base/error.h"
#include "base/params.h"
#include "lab/parameters_toml.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::app::study;
namespace fs = std::filesystem;
namespace rh = pastemix::lab::rheology;

namespace {

const fs::path kDir = fs::temp_directory_path() / fmt::format("pastemix_calrheo_{}", static_cast<long>(::getpid()));

// A parameter store as `lab reduce` writes it (the same writer), with the model at its prior.
std::string write_store() {
  rh::Model m;
  m.anchor.yield_stress = 137.97, m.anchor.yield_stress_sd = 6.03;
  m.anchor.plastic_viscosity = 0.7, m.anchor.curve = "published_4_19", m.anchor.density = 1843.0;
  const rh::Prior p = rh::prior(m.family, m.anchor);
  m.shape = p.mid(), m.shape_sd = p.sd();
  lab::ReduceResult r;
  r.parameters = rh::store_parameters(m, {}, {0.725}, {"2"}, "test anchor");
  fs::create_directories(kDir);
  const std::string path = (kDir / "parameters.toml").string();
  std::ofstream(path) << lab::parameters_toml(r, {"test", "test", "now"});
  return path;
}

model::SceneDoc tiny(const std::string& store) {
  model::SceneDoc d = model::SceneDoc::parse_file(test::source_path("tests/app/study/data/rheology_tiny.toml"));
  d.set("fluid.0.rheology_from", "\"" + store + "\"");
  return d;
}

RheologyCalOptions tiny_options(const std::string& store, const std::string& out) {
  RheologyCalOptions o;
  o.store = store;
  o.out = kDir / out;
  o.seeds = 3;
  o.jobs = 2;
  o.quiet = true;
  o.layout.layer_thickness = 0.005;  // 1 x 1 block of 6 x 6 cm, layers of 5 mm (the tiny box)
  o.layout.count = {1, 1};
  o.layout.size = {0.06, 0.06};
  return o;
}

}  // namespace

TEST_CASE("calibrate rheology: the quadratic surrogate finds an exact parabola's vertex, sd from spread over curvature") {
  const std::vector<double> p{0, 1, 2, 3, 4};
  std::vector<double> J, se(5, 0.1);
  for (double x : p) J.push_back(3.0 + 2.0 * (x - 1.3) * (x - 1.3));
  const QuadFit f = fit_quadratic(p, J, se);
  REQUIRE(f.ok);
  CHECK(f.vertex == doctest::Approx(1.3).epsilon(1e-12));
  CHECK(f.c2 == doctest::Approx(2.0).epsilon(1e-12));
  CHECK(f.sd_curvature == doctest::Approx(std::sqrt(0.1 / 2.0)).epsilon(1e-12));
  CHECK(f.sd >= f.sd_curvature);
  std::vector<double> down;
  for (double x : p) down.push_back(-x * x);
  CHECK_FALSE(fit_quadratic(p, down, se).ok);  // no minimum: no result
  CHECK(layer_objective({1, 2, 3}, {1, 2, 3}) == 0.0);
  CHECK(layer_objective({2, 2, 3}, {1, 2, 3}) == doctest::Approx(1.0 / 3.0));
}

TEST_CASE("calibrate rheology: a synthetic target made at b = 0.40 is recovered within 1 sd and a rerun computes nothing") {
  const std::string store = write_store();
  const model::SceneDoc base = tiny(store);
  // The target: the seed-mean per-layer rock of runs at the known value (the same seeds as the calibration).
  RheologyCalOptions t = tiny_options(store, "target");
  t.values = {0.40, 0.50, 0.60};
  t.refine = 0;
  t.target_layers = std::array<double, 3>{1.0, 1.0, 1.0};
  const RheologyCalResult made = calibrate_rheology(base, t);
  REQUIRE(made.points.front().shape == 0.40);
  REQUIRE(made.points.front().failure.empty());
  const std::array<double, 3> target = made.points.front().layers;
  for (double m : target) CHECK(m > 1e-4);  // rock in every layer: all three numbers constrain b
  // The calibration: the prior grid (0.40 is not on it) and one refinement round.
  RheologyCalOptions o = tiny_options(store, "cal");
  o.target_layers = target;
  const RheologyCalResult r = calibrate_rheology(base, o);
  const double range = r.prior.hi - r.prior.lo;
  REQUIRE_MESSAGE(r.fit.ok, calibration_table(r, o));
  MESSAGE(calibration_table(r, o));
  CHECK(std::abs(r.fit.vertex - 0.40) <= r.fit.sd);
  CHECK(r.fit.sd <= 0.2 * range);
  CHECK(r.runs_executed == r.runs_total);
  CHECK(r.points.size() >= 6);
  for (const auto& p : r.points) CHECK(p.runs.size() == 3);
  // Every run's result file is on disk under its scene hash; the same command again computes nothing.
  int files = 0;
  for (const auto& e : fs::directory_iterator(o.out / "runs")) files += e.path().extension() == ".h5";
  CHECK(files == r.runs_total);
  const RheologyCalResult again = calibrate_rheology(base, o);
  CHECK(again.runs_executed == 0);
  CHECK(again.runs_total == r.runs_total);
  CHECK(again.fit.vertex == r.fit.vertex);
  CHECK(again.fit.sd == r.fit.sd);
  // The record round-trips through the lab reader.
  const std::string record = write_calibration_outputs(r, o, "test");
  const rh::Calibration c = rh::read_calibration(record);
  CHECK(c.shape == r.fit.vertex);
  CHECK(c.case_id == 2);
  CHECK(fs::exists(o.out / "points.csv"));
  CHECK(fs::exists(o.out / "table.txt"));
}

TEST_CASE("calibrate rheology: bad inputs are errors naming what is wrong") {
  const std::string store = write_store();
  RheologyCalOptions o = tiny_options(store, "bad");
  o.target_layers = std::array<double, 3>{1e-3, 1e-3, 1e-3};
  auto error_of = [&](const model::SceneDoc& d, const RheologyCalOptions& opt) {
    try {
      calibrate_rheology(d, opt);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  RheologyCalOptions out_of_prior = o;
  out_of_prior.values = {0.3, 0.4, 0.9};
  CHECK(error_of(tiny(store), out_of_prior).find("exponential.b = 0.9") != std::string::npos);
  model::SceneDoc typed = model::SceneDoc::parse(
      "seed = 1\n[[fluid]]\nrheology = \"bingham\"\nyield_stress = 69.0\nsolids_fraction = 0.725\n", "typed.toml");
  CHECK(error_of(typed, o).find("rheology_from") != std::string::npos);
  RheologyCalOptions no_store = o;
  no_store.store = kDir / "none.toml";
  CHECK(error_of(tiny(store), no_store).find("pastemix lab reduce") != std::string::npos);
  RheologyCalOptions fam = o;
  fam.family = "power";
  CHECK(error_of(tiny(store), fam).find("unknown family") != std::string::npos);
}

TEST_CASE("calibrate rheology CLI: a run killed part-way continues from its checkpoint, with the same result") {
  const std::string store = write_store();
  auto args_for = [&](const std::string& out, const std::string& every) {
    return fmt::format(
        "calibrate rheology --case 2 --scene '{}' --set fluid.0.rheology_from='\"{}\"' --params '{}' --seeds 1 "
        "--jobs 1 --points 3 --refine 0 --values 0.45 --layer-thickness 0.005 --target-layers 0.002,0.004,0.002 "
        "--out '{}' --no-store --checkpoint-every {}",
        test::source_path("tests/app/study/data/rheology_tiny.toml"), store, store, out, every);
  };
  const fs::path out = kDir / "killed";
  fs::create_directories(out / "runs");
  // A checkpoint at every stop of the run loop (1e-9 s of wall clock): the kill finds one to resume.
  const std::string killed = args_for(out.string(), "1e-9");
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", (std::string("exec '") + PASTEMIX_BINARY + "' " + killed + " >/dev/null 2>&1").c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  auto has_checkpoint = [&] {
    for (const auto& e : fs::directory_iterator(out / "runs"))
      if (e.path().string().ends_with(".checkpoint.h5")) return true;
    return false;
  };
  const auto t0 = std::chrono::steady_clock::now();
  while (!has_checkpoint() && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // a few more checkpoints: not always the first
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  REQUIRE_MESSAGE(has_checkpoint(), "no checkpoint was written before the kill");
  const auto resumed = test::run_pastemix(killed);
  INFO(resumed.output);
  REQUIRE((resumed.exit_code == 0 || resumed.exit_code == 3));
  CHECK(resumed.output.find("resumed from its checkpoint") != std::string::npos);
  CHECK_FALSE(has_checkpoint());  // published: the checkpoint is gone
  const auto whole = test::run_pastemix(args_for((kDir / "whole").string(), "0"));
  REQUIRE(whole.exit_code == resumed.exit_code);
  // The per-run line (layer masses to 0.01 g) and the result file: the same as a run never stopped.
  auto layers_line = [](const std::string& o) { return o.substr(o.find("shape 0.45 seed"), o.find(")", o.find("shape 0.45 seed")) - o.find("shape 0.45 seed")); };
  CHECK(layers_line(resumed.output).substr(0, layers_line(resumed.output).find("(")) ==
        layers_line(whole.output).substr(0, layers_line(whole.output).find("(")));
}

TEST_CASE("calibrate rheology CLI: a smoke run on the tiny scene writes table, PNG, record and the store") {
  const std::string store = write_store();
  const std::string out = (kDir / "cli").string();
  const std::string args = fmt::format(
      "calibrate rheology --case 2 --scene '{}' --set fluid.0.rheology_from='\"{}\"' --params '{}' --seeds 1 "
      "--jobs 2 --points 3 --refine 0 --values 0.3 0.45 0.6 --layer-thickness 0.005 --target-layers "
      "0.002,0.004,0.002 --out '{}' --quiet --dataset '{}'",
      test::source_path("tests/app/study/data/rheology_tiny.toml"), store, store, out,
      test::source_path("datasets/thesis"));
  auto r = test::run_pastemix(args + " --no-store");
  // The 1 x 1 grid is not the default 4 x 3 one: every block but (1,1) lies outside the box, so the test
  // scene's per-layer masses come from its centre blocks; the run must still end with a result or exit 3.
  INFO(r.output);
  REQUIRE((r.exit_code == 0 || r.exit_code == 3));
  CHECK(r.output.find("runs: 3 in all, 3 computed now") != std::string::npos);
  auto again = test::run_pastemix(args);
  // The same command again, now writing the store: every run is read back from OUT/runs.
  CHECK(again.output.find("runs: 3 in all, 0 computed now, 3 read back") != std::string::npos);
  CHECK(again.exit_code == r.exit_code);
  if (r.exit_code == 0) {
    CHECK(fs::exists(kDir / "cli" / "rheology_calibration.toml"));
    CHECK(r.output.find("store updated") == std::string::npos);
    CHECK(again.output.find("store updated") != std::string::npos);
    const Params p = Params::parse_file(store);
    CHECK(p.table("paste_rheology").table("model").table("calibration").string("text") == "calibrated on case 2");
  }
  fs::remove_all(kDir);
}
