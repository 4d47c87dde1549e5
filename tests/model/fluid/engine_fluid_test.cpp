// SPDX-License-Identifier: MIT
// Fluid forces through the engine (model/fluid/field.*, fluid_scene.*, single_sphere.*, validations.*):
// analytic water settling at any time step, stick / restart, suspension threshold, terminal velocities
// against the lab solver (linked in this test binary only), surface rise, scene errors and the output.
#include "model/fluid/field.h"

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <omp.h>

#include "base/error.h"
#include "base/h5.h"
#include "lab/drag/settling.h"
#include "lab/drag/terminal_velocity.h"
#include "model/fluid/fluid_scene.h"
#include "validation/fluid/validations.h"
#include "model/parallel.h"
#include "model/run.h"
#include "model/scene.h"
#include "tests/model/scene_text.h"
#include "tests/run_command.h"

using namespace pastemix;
using namespace pastemix::model;
using namespace pastemix::model::fluid;
using namespace pastemix::validation;

namespace {

std::filesystem::path source_dir() { return PASTEMIX_SOURCE_DIR; }

// A well-posed fitted curve (power_blend at its fit's starting point): any admissible curve will do for an
// engine-vs-solver comparison, and it needs no lab reduce run.
const drag::DragCurve kBlend{drag::CurveId::power_blend, {24.0, 1.0, 0.5, 0.4, 1.5}};

// ~300 rocks fall from above into a paste that fills half of the box (the fluid hook tests).
const std::string kCandidatesScene = R"(
seed = 5
time_step = 2e-5
end_time = 1.0
[domain]
min = [-0.02, -0.02, -0.02]
max = [0.12, 0.12, 0.4]
[neighbor]
skin = 1.25e-3
)" + model::test::kRockRolling + model::test::box_wall("[0.0, 0.0, 0.0]", "[0.1, 0.1, 0.35]") + R"([[fluid]]
x = [0.0, 0.05]
y = [0.0, 0.1]
bottom = 0.0
surface = 0.03
density = 1843
rheology = "bingham"
yield_stress = 10
plastic_viscosity = 0.7
curve = "published_4_19"
)" + model::test::rock_factory("0.02", "[0.005, 0.005, 0.05]", "[0.095, 0.095, 0.12]");

// The scene run on 2 threads (every loop parallel), in batches of 400 steps, for `steps` steps.
World two_threads_in_batches(Scene scene, long steps) {
  scene.config.parallel_min_items = 0;
  omp_set_num_threads(2);
  World two = make_world(scene);
  for (long s = 0; s < steps; s += 400) two.advance(400);
  omp_set_num_threads(omp_get_num_procs());
  return two;
}

// Same positions and vertical velocities, bit for bit.
bool same_state(const World& a, const World& b) {
  const auto& p = a.particles();
  const auto& r = b.particles();
  bool same = p.size() == r.size();
  for (std::size_t k = 0; same && k < p.size(); ++k)
    same = p.x[k].x == r.x[k].x && p.x[k].y == r.x[k].y && p.x[k].z == r.x[k].z && p.v[k].z == r.v[k].z;
  return same;
}

SphereRun paste_sphere() {
  SphereRun r;
  r.d = 0.01, r.rho_p = 2700, r.rho_f = 1500, r.eta = 0.1, r.tau_y = 5.0, r.curve = kBlend, r.dt = 1e-4;
  r.depth = 0.2;
  return r;
}

}  // namespace

TEST_CASE("fluid engine: water settling matches v_t (1 - exp(-t/tau)) within 0.5 % for dt 1e-7 .. 1e-3 s") {
  for (double dt : {1e-7, 1e-6, 1e-5, 1e-4, 1e-3}) {
    const WaterSettling w = water_settling(dt);
    INFO("dt = " << dt << " s, max relative error " << w.max_rel_error);
    CHECK(w.v_terminal == doctest::Approx(9.265e-3).epsilon(1e-3));
    CHECK(w.tau == doctest::Approx(1.5e-3));
    CHECK(w.max_rel_error < 0.005);
  }
}

TEST_CASE("fluid engine: suspension threshold: stays exactly at rest above it, sinks just below") {
  const double thr = suspension_threshold(kBlend);
  // (pi/6) / (pi^2/4 + 24 pi/8) for a curve whose Cd Re' -> 24.
  CHECK(thr == doctest::Approx((M_PI / 6.0) / (M_PI * M_PI / 4.0 + 3.0 * M_PI)).epsilon(1e-9));
  SphereRun r = paste_sphere();
  const double scale = 9.81 * r.d * (r.rho_p - r.rho_f);
  r.tau_y = 1.001 * thr * scale;
  const SuspensionResult above = suspension(r, 0.5);
  CHECK(above.displacement == 0.0);  // exactly: no creep
  CHECK(above.speed_end == 0.0);
  r.tau_y = 0.999 * thr * scale;
  const SuspensionResult below = suspension(r, 0.5);
  CHECK(below.displacement > 1e-5);
  CHECK(below.speed_end > 0.0);
}

TEST_CASE("fluid engine: a stuck sphere restarts when another lands on it") {
  // Sphere A suspended in a Bingham fluid (yield number 2x the threshold); a steel ball B dropped on it.
  SphereRun r = paste_sphere();
  r.tau_y = 2.0 * suspension_threshold(kBlend) * 9.81 * r.d * (r.rho_p - r.rho_f);
  r.youngs_modulus = 1e7, r.dt = 1e-5;  // soft contacts: the contact sets the time step, not the fluid
  std::string text = single_sphere_scene(r, 0.6);
  const double za = r.depth - 0.01 - 0.5 * r.d;
  text += "[[particle]]\nmaterial = \"wall\"\nradius = 0.008\nposition = [0, 0, " + std::to_string(za + 0.1) + "]\n";
  const Scene scene = parse_scene(text, "restart.toml");
  World w = make_world(scene);
  const double z0 = w.particles().x[0].z;
  double moved_before_impact = 0.0;
  bool touched = false;
  for (long s = 0; s < 60000; ++s) {
    w.step();
    const auto& p = w.particles();
    if (!touched && norm(p.x[1] - p.x[0]) < 0.005 + 0.008 + 1e-4) touched = true;
    if (!touched) moved_before_impact = std::max(moved_before_impact, std::abs(p.x[0].z - z0));
  }
  CHECK(touched);
  CHECK(moved_before_impact == 0.0);
  CHECK(z0 - w.particles().x[0].z > 1e-3);  // pushed down
  CHECK(w.particles().v[0].z < 0.0);        // still carried down by the heavier ball (B sinks on its own)
}

TEST_CASE("fluid engine: terminal velocities in a 3 m column agree with the lab solver within 1 %") {
  // A few Valentik & Whitmore-like spheres (d, rho_p, suspension 1 and 6 rheologies).
  struct Case {
    double d, rho_p, rho_f, eta, tau;
  };
  for (const Case& c : {Case{0.0159, 6450, 1280, 0.0131, 30.5}, Case{0.019, 6513, 1280, 0.0131, 30.5},
                        Case{0.0254, 7800, 1207, 0.0067, 13.0}, Case{0.0127, 7800, 1207, 0.0067, 13.0}}) {
    SphereRun r;
    r.d = c.d, r.rho_p = c.rho_p, r.rho_f = c.rho_f, r.eta = c.eta, r.tau_y = c.tau, r.curve = kBlend, r.dt = 1e-3;
    const auto lab = lab::drag::solve_terminal_velocity(kBlend, {c.d, c.rho_p, c.rho_f, c.tau, c.eta}, 9.81);
    REQUIRE(lab.outcome == lab::drag::SettlingOutcome::settling);
    const ColumnSettling dem = column_settling(r, 3.0);
    INFO("d = " << c.d << ": lab " << lab.v << " m/s, DEM " << dem.v_final << " m/s");
    CHECK_FALSE(dem.trapped);
    CHECK(dem.v_final == doctest::Approx(lab.v).epsilon(0.01));
  }
}

TEST_CASE("fluid engine: all 121 Valentik & Whitmore spheres: DEM terminal velocity within 1 % of the lab solver") {
  const auto data = lab::drag::read_settling_dataset(source_dir() / "datasets/thesis");
  REQUIRE(data.spheres.size() == 121);
  double worst = 0.0;
  int settling = 0;
  for (const auto& sp : data.spheres) {
    const auto lab = lab::drag::solve_terminal_velocity(kBlend, sp.sphere, 9.81);
    SphereRun r;
    r.d = sp.sphere.d, r.rho_p = sp.sphere.rho_p, r.rho_f = sp.sphere.rho_f, r.tau_y = sp.sphere.tau_y;
    r.eta = sp.sphere.eta_B, r.curve = kBlend, r.dt = 1e-3;
    const ColumnSettling dem = column_settling(r, 3.0);
    INFO("row " << sp.row_id << ": lab " << lab.v << " m/s, DEM " << dem.v_final << " m/s");
    if (lab.outcome == lab::drag::SettlingOutcome::suspended) {
      CHECK(dem.trapped);  // at rest in both
      continue;
    }
    REQUIRE(lab.outcome == lab::drag::SettlingOutcome::settling);
    ++settling;
    CHECK_FALSE(dem.trapped);
    worst = std::max(worst, std::abs(dem.v_final / lab.v - 1.0));
  }
  MESSAGE("max |DEM/lab - 1| = " << worst << " over " << settling << " settling spheres");
  CHECK(settling > 100);
  CHECK(worst < 0.01);
}

TEST_CASE("fluid engine: the surface rises by the submerged volume over the box area, buoyancy floats a light sphere") {
  SphereRun r;
  r.d = 0.02, r.rho_p = 500, r.rho_f = 1000, r.eta = 0.5, r.curve = {drag::CurveId::stokes, {}}, r.dt = 1e-4;
  r.depth = 0.1, r.box_half = 0.05, r.drop = 0.0;  // released with its bottom on the surface
  const SphereTrace tr = run_single_sphere(r, 2.0);
  // Half-submerged at equilibrium (cap volume = rho_p / rho_f of the sphere): centre at the risen surface.
  const double v_half = 0.5 * 4.0 / 3.0 * M_PI * 1e-6;
  CHECK(tr.surface == doctest::Approx(0.1 + v_half / (0.1 * 0.1)).epsilon(1e-6));
  CHECK(tr.z.back() == doctest::Approx(tr.surface).epsilon(1e-4));
  // Without partial submergence the thesis's rule cannot float it: full buoyancy once the centre is below
  // the surface, none above: it hovers around the surface instead of resting half-submerged at z_s.
}

TEST_CASE("fluid scene: bad [[fluid]] tables are InputErrors naming the line") {
  SphereRun r = paste_sphere();
  const std::string base = single_sphere_scene(r, 0.1);
  auto fails = [&](const std::string& from, const std::string& to, const std::string& what) {
    std::string t = base;
    const auto at = t.find(from);
    REQUIRE(at != std::string::npos);
    t.replace(at, from.size(), to);
    try {
      parse_scene(t, "bad.toml");
      FAIL("no error for " << to);
    } catch (const InputError& e) {
      CHECK(std::string(e.what()).find(what) != std::string::npos);
      CHECK(std::string(e.what()).find("bad.toml:") != std::string::npos);
    }
  };
  fails("curve = \"power_blend\"", "curve = \"nope\"", "unknown drag curve");
  fails("coefficients = [24", "coefficients = [-1", "admissible");
  fails("curve = \"power_blend\"", "curve = \"stokes\"", "takes no coefficients");
  fails("density = 1500", "density = -1", "density");
  fails("buoyancy = true", "buoyancy = true\nviscosity = 1", "unknown key");
  fails("surface = 0.2", "surface = -0.1", "above the bottom");
  fails("curve = \"power_blend\"", "curve_from = \"missing.toml\"", "no such file");
  fails("buoyancy = true", "buoyancy = true\ncollective = \"cluster\"", "collective");
  fails("buoyancy = true", "buoyancy = true\ncollective = \"bearing_capacity\"\ncollective_interval = 0", "collective_interval");
}

TEST_CASE("fluid scene: curve_from loads the chosen curve and its coefficients from a parameters.toml") {
  const std::string dir = "model_fluid_curve_from_out";
  std::filesystem::create_directories(dir);
  {
    std::ofstream f(dir + "/parameters.toml");
    f << "[drag_curve.chosen]\ntext = \"power_blend\"\n";
    const char* names[] = {"k", "a", "b", "c", "n"};
    for (int i = 0; i < 5; ++i)
      f << "[drag_curve.power_blend." << names[i] << "]\nvalue = " << kBlend.coefficients[i] << "\nunit = \"-\"\n";
  }
  const drag::DragCurve c = read_chosen_curve(dir + "/parameters.toml");
  CHECK(c.id == drag::CurveId::power_blend);
  CHECK(c.coefficients == kBlend.coefficients);
}

TEST_CASE("fluid output: surface height series, fluid attributes and material densities") {
  const std::string dir = "model_fluid_output_out";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  SphereRun r = paste_sphere();
  std::string text = single_sphere_scene(r, 0.05);
  text += "[output]\ninterval = 0.01\n";
  text.replace(text.find("density = 1500"), 14, "density = 1500\nsolids_fraction = 0.75");
  {
    std::ofstream f(dir + "/ball.toml");
    f << text;
  }
  const Scene scene = load_scene(dir + "/ball.toml");
  RunOptions ro;
  ro.progress = false;
  run_scene(scene, dir, ro);
  H5Reader h5(dir + "/ball.h5");
  CHECK(h5.attribute_double("/", "fluid_density") == 1500.0);
  CHECK(h5.attribute_double("/", "fluid_solids_fraction") == 0.75);
  const double v = 4.0 / 3.0 * M_PI * std::pow(0.005, 3);
  const double half = 10.0 * 0.2;
  CHECK(h5.attribute_double("/", "fluid_surface_z") == doctest::Approx(0.2 + v / (4 * half * half)).epsilon(1e-12));
  CHECK(h5.read_doubles("/timeseries/fluid_surface_z").size() == h5.read_doubles("/timeseries/time").size());
  CHECK(h5.read_doubles("/material_density") == std::vector<double>{2700.0, 7800.0});
}

TEST_CASE("fluid engine: steel balls in paste: distance grows with height and ball size, falls with viscosity") {
  SteelBallPaste p;
  p.dt = 1e-4;  // distances agree with 2e-5 and 5e-6 s to 0.01 mm (validate steel-balls --dt)
  const double d0 = steel_ball_drop(p, 0.0126, 0.0, 0.7).distance;
  const double d255 = steel_ball_drop(p, 0.0126, 0.255, 0.7).distance;
  const double d255_16 = steel_ball_drop(p, 0.016, 0.255, 0.7).distance;
  const double d255_visc = steel_ball_drop(p, 0.0126, 0.255, 1.4).distance;
  CHECK(d0 > 0.0);
  CHECK(d255 > d0);
  CHECK(d255_16 > d255);
  CHECK(d255_visc < d255);
  // Resting ball: net weight below the rest drag (yield number 0.18 > 0.044), so it is suspended, not on the floor.
  CHECK_FALSE(steel_ball_drop(p, 0.016, 0.255, 0.7).reached_bottom);
}

TEST_CASE("fluid engine: calibrate viscosity recovers a known eta_B from a synthetic settling distance") {
  SteelBallPaste p;
  p.dt = 1e-4;
  for (double eta_true : {0.35, 1.3}) {
    const double target = steel_ball_drop(p, 0.0126, 0.255, eta_true).distance;
    const Calibration c = calibrate_viscosity(p, 0.0126, 0.255, target);
    INFO("eta_true " << eta_true << ", calibrated " << c.eta << " after " << c.runs << " runs");
    CHECK(c.eta == doctest::Approx(eta_true).epsilon(1e-3));
  }
  CHECK_THROWS_AS(calibrate_viscosity(p, 0.0126, 0.255, 1.0), RuntimeFailure);  // 1 m: beyond any viscosity
}

TEST_CASE("fluid CLI: validate water, calibrate viscosity, bad input exits 2, unreachable target exits 3") {
  const std::string fixture = (source_dir() / "tests/model/fluid/data/parameters.toml").string();
  const auto w = pastemix::test::run_pastemix("validate water --dt 1e-3");
  CHECK(w.exit_code == 0);
  CHECK(w.output.find("max rel error") != std::string::npos);
  const auto c = pastemix::test::run_pastemix("calibrate viscosity --ball 12.6 --height 255 --distance 57.16 --dt 1e-4"
                                              " --params " + fixture);
  CHECK(c.exit_code == 0);
  CHECK(c.output.find("tau_y 138 Pa (" + fixture + " paste.yield_stress)") != std::string::npos);
  // 57.16 mm is the distance 0.7 Pa.s gives with the mould wall (validate steel-balls, VALIDATION.md 4).
  CHECK(std::stod(c.output.substr(c.output.find("eta_B = ") + 8)) == doctest::Approx(0.7).epsilon(1e-3));
  CHECK(pastemix::test::run_pastemix("calibrate viscosity --distance -3").exit_code == 2);
  CHECK(pastemix::test::run_pastemix("calibrate viscosity --distance 500 --dt 1e-4 --params " + fixture).exit_code == 3);
  // No parameter store: exit 2, naming the path and what to run.
  const auto m = pastemix::test::run_pastemix("validate steel-balls --params /nonexistent/parameters.toml");
  CHECK(m.exit_code == 2);
  CHECK(m.output.find("/nonexistent/parameters.toml") != std::string::npos);
  CHECK(m.output.find("pastemix lab reduce") != std::string::npos);
  // ... unless every value is given (a fixed curve needs no coefficients).
  const auto e = pastemix::test::run_pastemix("calibrate viscosity --distance 57.16 --dt 1e-4 --params /nonexistent/p.toml"
                                              " --tau-y 138 --rho-paste 1843 --curve published_4_19");
  CHECK(e.exit_code == 0);
  // An explicit value overrides the store.
  const auto o = pastemix::test::run_pastemix("calibrate viscosity --distance 57.16 --dt 1e-4 --tau-y 120 --params " +
                                              fixture);
  CHECK(o.exit_code == 0);
  CHECK(o.output.find("tau_y 120 Pa (command line)") != std::string::npos);
  CHECK(std::stod(o.output.substr(o.output.find("eta_B = ") + 8)) > 0.75);  // less yield drag: more viscous
  const auto s = pastemix::test::run_pastemix("validate settling " + (source_dir() / "datasets/thesis").string() +
                                              " --curve published_4_19 --rows 30");
  CHECK(s.exit_code == 0);
  CHECK(s.output.find("trapped 0") != std::string::npos);
}

TEST_CASE("fluid engine: the mould's side wall leaves a vertical fall unchanged, on the axis and near the wall") {
  // The fluid is a force field (no wall effect on the drag); a ball falling straight down never touches the
  // cylinder, so the distance is the same to the bit, with or without it, on the axis or 20 mm off it.
  SteelBallPaste p;
  p.dt = 1e-4;
  const double with = steel_ball_drop(p, 0.016, 0.255, 0.7).distance;
  p.offset = 0.020;  // the 16 mm ball's surface 9.5 mm from the wall
  CHECK(steel_ball_drop(p, 0.016, 0.255, 0.7).distance == with);
  p.mould_wall = false;
  CHECK(steel_ball_drop(p, 0.016, 0.255, 0.7).distance == with);
}

TEST_CASE("fluid switches: buoyancy, yield_term, partial_submergence and surface_rise each change what they say") {
  // buoyancy = false: water settling goes to rho_p g d^2 / (18 eta) (not (rho_p - rho_f) ...).
  SphereRun w;
  w.d = 1e-4, w.rho_p = 2700, w.rho_f = 1000, w.eta = 1e-3, w.curve = {drag::CurveId::stokes, {}}, w.dt = 1e-3;
  w.depth = 0.05, w.box_half = 0.01, w.floor = false, w.buoyancy = false;
  const SphereTrace tw = run_single_sphere(w, 0.03);
  CHECK(-tw.vz.back() == doctest::Approx(2700 * 9.81 * 1e-8 / 18e-3).epsilon(1e-6));
  // yield_term = false: a sphere held by the yield term sinks without the (pi d/2)^2 tau_y term.
  SphereRun r = paste_sphere();
  // 1.2 x the threshold: above 0.0440 (with the term), below 1/18 = 0.0556 (Cd Re' -> 24 alone).
  r.tau_y = 1.2 * suspension_threshold(kBlend) * 9.81 * r.d * (r.rho_p - r.rho_f);
  CHECK(suspension(r, 0.2).displacement == 0.0);
  r.yield_term = false;
  CHECK(suspension(r, 0.2).displacement > 1e-4);
  // partial_submergence / surface_rise, on the field directly: a sphere whose centre is 2 mm above the surface.
  Particles p;
  p.add(0, 0.005, 2700, {0, 0, 0.102}, {}, {});
  FluidRegion reg;
  reg.x_min = reg.y_min = -0.05, reg.x_max = reg.y_max = 0.05, reg.z_bottom = 0, reg.z_surface0 = 0.1;
  reg.law = NewtonianStokes::Params{1000, 1e-3};
  FluidField partial({reg});
  partial.update(p);
  CHECK(partial.inside(0));
  CHECK(partial.submerged_volume(0) == doctest::Approx(M_PI * 0.003 * 0.003 * (0.015 - 0.003) / 3.0));
  CHECK(partial.surface_z(0) == doctest::Approx(0.1 + partial.submerged_volume(0) / 0.01));
  reg.partial_submergence = false;
  reg.surface_rise = false;
  FluidField whole({reg});
  whole.update(p);
  CHECK_FALSE(whole.inside(0));  // centre above the surface: nothing under the thesis's rule
  CHECK(whole.surface_z(0) == 0.1);
  p.x[0].z = 0.098;
  whole.update(p);
  CHECK(whole.submerged_volume(0) == doctest::Approx(4.0 / 3.0 * M_PI * 1.25e-7));
  CHECK(whole.surface_z(0) == 0.1);  // no rise
}

TEST_CASE("fluid hook: the candidate list (particles near a region) gives the same bits as testing every particle") {
  // Some rocks stay beside the region, the rest cross its surface during the run, and the surface rises
  // (the candidate list must follow it).
  const Scene scene = parse_scene(kCandidatesScene, "candidates.toml");
  World listed = make_world(scene);
  World all = make_world(scene);
  REQUIRE(all.fluid() != nullptr);
  auto every = std::make_shared<FluidField>(all.fluid()->regions());
  all.set_fluid(every);
  every->set_candidate_margin(0.0);  // after set_fluid, which sets the World's skin: every particle, every step
  std::size_t max_inside = 0, min_candidates = listed.particles().size();
  for (int s = 0; s < 12000; ++s) {  // 0.24 s: the rocks land in the paste or beside it
    listed.step();
    all.step();
    std::size_t inside = 0;
    for (std::size_t a = 0; a < listed.particles().size(); ++a) inside += listed.fluid()->inside(static_cast<long>(a));
    max_inside = std::max(max_inside, inside);
    min_candidates = std::min(min_candidates, listed.fluid()->candidate_count());
  }
  const auto& p = listed.particles();
  CHECK(same_state(listed, all));
  CHECK(listed.fluid()->surface_z(0) == all.fluid()->surface_z(0));
  CHECK(listed.fluid()->surface_z(0) > 0.03);  // rock entered and the surface rose
  CHECK(max_inside > 20);
  INFO("particles " << p.size() << ", fewest candidates " << min_candidates);
  CHECK(min_candidates < p.size());  // the list really excluded particles far from the region

  // The same run on 2 threads (slabs, ghosts, the fluid update inside the threads' region), in batches of
  // steps: the same bits.
  const World two = two_threads_in_batches(scene, 12000);
  CHECK(same_state(listed, two));
  CHECK(two.fluid()->surface_z(0) == listed.fluid()->surface_z(0));
}

TEST_CASE("fluid hook: with the collective yield rule, 2 threads in batches give the same bits as 1 thread") {
  // The same rocks in a stiffer paste (30 Pa) with clusters sharing its bearing capacity (collective.h).
  std::string text = kCandidatesScene;
  const auto at = text.find("yield_stress = 10");
  REQUIRE(at != std::string::npos);
  text.replace(at, 17, "yield_stress = 30\ncollective = \"bearing_capacity\"");
  const Scene scene = parse_scene(text, "collective.toml");
  World one = make_world(scene);
  long most_clusters = 0;
  double least_factor = 1.0;
  for (int s = 0; s < 12000; s += 400) {
    one.advance(400);
    most_clusters = std::max(most_clusters, one.fluid()->cluster_stats().clusters);
    least_factor = std::min(least_factor, one.fluid()->cluster_stats().min_factor);
  }
  INFO("most clusters " << most_clusters << ", smallest factor " << least_factor);
  CHECK(most_clusters > 0);  // the rule did act
  CHECK(least_factor < 1.0);
  CHECK(same_state(one, two_threads_in_batches(scene, 12000)));
}
