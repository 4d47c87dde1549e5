// SPDX-License-Identifier: MIT
// The sweep on real runs: the two-sphere Hertz impact (Table 5.1 material 1) on a coarse dt ladder, the
// PSD-cut edit, and the command's outputs.
#include "app/study/sweep.h"

#include <sstream>
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "base/error.h"
#include "tests/run_command.h"
#include "base/units.h"

using namespace pastemix;
using namespace pastemix::app::study;

namespace {

// Hertz (1882) peak force of two equal elastic spheres closing at v: delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5),
// F_max = 4/3 E* sqrt(R*) delta_max^1.5.
double hertz_peak_force(double E, double rho, double nu, double R, double v) {
  const double m = rho * 4.0 / 3.0 * pastemix::units::pi * R * R * R, ms = m / 2, Rs = R / 2, Es = E / (2 * (1 - nu * nu));
  const double d = std::pow(15 * ms * v * v / (16 * Es * std::sqrt(Rs)), 0.4);
  return 4.0 / 3.0 * Es * std::sqrt(Rs) * std::pow(d, 1.5);
}

}  // namespace

TEST_CASE("Hertz impact, material 1: the chosen dt's peak force is within 1 % of the Hertz solution") {
  const auto base = model::SceneDoc::parse_file(test::source_path("datasets/scenes/hertz_impact_m1.toml"));
  SweepOptions o;
  o.vary = "dt";
  o.qoi = "peak_force";
  o.values = {1.28e-5, 6.4e-6, 3.2e-6, 1.6e-6, 8e-7};  // 1.2 down to 0.07 Rayleigh times
  o.tol = 0.01;
  o.quiet = true;
  const SweepResult r = sweep(base, o);
  MESSAGE(r.table);
  const double exact = hertz_peak_force(200e9, 7750, 0.3, 0.01, 20.0);  // 35.62 kN
  // The reference (Richardson or finest) agrees with Hertz far inside the tolerance ...
  CHECK(std::abs(r.ref.qoi / exact - 1) < 2e-3);
  // ... and the chosen step, chosen against that reference, is within the tolerance of the exact value too
  // (tol plus the reference's own error).
  REQUIRE(r.choice.index >= 0);
  const auto& c = r.points[static_cast<std::size_t>(r.choice.index)];
  CHECK(std::abs(c.qoi / exact - 1) <= o.tol + 2e-3);
  // The coarsest step (1.2 Rayleigh times) is not good enough: the choice is not trivial.
  CHECK(r.choice.rel_error[0] > o.tol);
}

TEST_CASE("psd_cut drops the intervals below the cut and renormalises - a cut above all is an error") {
  const auto base = model::SceneDoc::parse_file(test::source_path("datasets/scenes/funnel_lift.toml"));
  SweepOptions o;
  o.vary = "psd_cut";
  model::SceneDoc d = base;
  d.set("factory.0.psd", "[{d_min = 1e-3, d_max = 2e-3, fraction = 0.2}, {d_min = 2e-3, d_max = 4e-3, fraction = 0.8}]");
  const model::SceneDoc cut = at_value(d, o, 2e-3);
  CHECK(cut.get("factory.0.psd.0.d_min") == "0.002");
  CHECK(std::stod(cut.get("factory.0.psd.0.fraction")) == doctest::Approx(1.0));
  CHECK_FALSE(cut.has("factory.0.psd.1"));
  // The step follows the smallest sphere kept (d_min 1 mm -> 2 mm doubles it); --fixed-dt keeps it.
  CHECK(std::stod(cut.get("time_step")) == doctest::Approx(2 * std::stod(d.get("time_step"))).epsilon(1e-12));
  SweepOptions fixed = o;
  fixed.fixed_dt = true;
  CHECK(at_value(d, fixed, 2e-3).get("time_step") == d.get("time_step"));
  CHECK(default_ladder(d, o) == std::vector<double>{1e-3, 0.0});
  CHECK_THROWS_AS(at_value(d, o, 4e-3), InputError);
}

TEST_CASE("a run that blows up is a failed point, not the end of the sweep, --jobs 2 gives the same numbers") {
  const auto base = model::SceneDoc::parse_file(test::source_path("datasets/scenes/hertz_impact_m3.toml"));
  SweepOptions o;
  o.vary = "dt";
  o.qoi = "max_overlap";
  o.values = {4e-5, 8e-7, 4e-7};  // 4e-5 s is ~3 Rayleigh times: kinetic-energy blow-up at step 1
  o.quiet = true;
  const SweepResult one = sweep(base, o);
  REQUIRE(one.failed.size() == 1);
  CHECK(one.failed[0].value == 4e-5);
  CHECK(one.failed[0].reason.find("kinetic-energy blow-up") != std::string::npos);
  REQUIRE(one.points.size() == 2);
  CHECK(one.table.find("FAILED") != std::string::npos);
  CHECK(one.choice.index >= 0);
  o.jobs = 2;
  const SweepResult two = sweep(base, o);
  REQUIRE(two.points.size() == 2);
  for (std::size_t k = 0; k < 2; ++k) CHECK(two.points[k].qoi == one.points[k].qoi);
  // A step longer than the run is a bad setting (exit 2 from the command), not a point with no steps.
  o.values = {2e-4};
  CHECK_THROWS_AS(sweep(base, o), InputError);
}

TEST_CASE("a run with the at-rest [stop] rule that reaches end_time before rest is a failed point") {
  // The two spheres fly apart at 10 m/s after the impact: never at rest within end_time.
  std::ifstream in(test::source_path("datasets/scenes/hertz_impact_m3.toml"));
  std::stringstream text;
  text << in.rdbuf() << "\n[stop]\nrule = \"at_rest\"\ncheck_interval = 1e-5\n";
  const auto base = model::SceneDoc::parse(text.str(), "impact_at_rest.toml");
  SweepOptions o;
  o.vary = "dt";
  o.qoi = "max_overlap";
  o.values = {8e-7, 4e-7};
  o.quiet = true;
  try {
    sweep(base, o);
    FAIL("the sweep should have failed");
  } catch (const RuntimeFailure& e) {
    // Every point failed: the sweep reports the first failure, with the moving mass.
    CHECK(std::string(e.what()).find("end_time 8e-05 s reached before the rock came to rest") != std::string::npos);
    CHECK(std::string(e.what()).find("g moving faster than 0.01 m/s") != std::string::npos);
  }
}

TEST_CASE("pastemix sweep writes the table, CSV, override file - a bad --qoi is exit 2") {
  const auto dir = std::filesystem::temp_directory_path() / "pastemix_sweep_test";
  std::filesystem::remove_all(dir);
  const std::string scene = test::source_path("datasets/scenes/hertz_impact_m3.toml");
  const auto r = test::run_pastemix("sweep '" + scene + "' --vary dt --qoi max_overlap --values 8e-7 4e-7 2e-7 --tol 0.02 --quiet --out '" +
                                    dir.string() + "'");
  CHECK(r.exit_code == 0);
  CHECK(r.output.find("<- chosen") != std::string::npos);
  CHECK(std::filesystem::exists(dir / "sweep.csv"));
  REQUIRE(std::filesystem::exists(dir / "chosen_overrides.toml"));
  // The override file runs.
  const auto run = test::run_pastemix("run '" + scene + "' --quiet --out '" + dir.string() + "' --overrides '" +
                                      (dir / "chosen_overrides.toml").string() + "'");
  CHECK(run.exit_code == 0);
  const auto bad = test::run_pastemix("sweep '" + scene + "' --vary dt --qoi nothing --out '" + dir.string() + "'");
  CHECK(bad.exit_code == 2);
  CHECK(bad.output.find("--qoi") != std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("lift_speed lifts every lifted wall at the value and stretches end_time to the same lift height") {
  const auto base = model::SceneDoc::parse_file(test::source_path("datasets/scenes/repose_ch5.toml"));
  SweepOptions o;
  o.vary = "lift_speed";
  o.levels = 3;
  const auto ladder = default_ladder(base, o);
  REQUIRE(ladder.size() == 3);
  CHECK(ladder[0] == doctest::Approx(0.04));
  CHECK(ladder[2] == doctest::Approx(0.01));
  const auto d = at_value(base, o, 0.04);
  CHECK(d.number("wall.1.velocity.2") == 0.04);
  CHECK(d.number("wall.1.velocity.0") == 0.0);
  // 10 s: the lift from 0.02 s, then 1 s of settling (settle_s): 8.98 s of lift at 0.01 m/s; at 0.04 m/s the
  // same height takes 8.98 / 4 s, and the settling keeps its second.
  CHECK(std::stod(d.get("end_time")) == doctest::Approx(0.02 + 8.98 / 4 + 1.0).epsilon(1e-12));
  CHECK(d.load().walls[1].velocity.z == 0.04);
  const auto flat = model::SceneDoc::parse_file(test::source_path("datasets/scenes/hertz_impact_m1.toml"));
  CHECK_THROWS_AS(at_value(flat, o, 0.02), InputError);
}
