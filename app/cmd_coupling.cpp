// SPDX-License-Identifier: MIT
// `pastemix validate coupling sphere | piston | hindered`: the coupling's cases (model/coupling, issue 18) with their
// references; the figures of model/coupling/VALIDATION.md. One thread (the cases are serial).
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <omp.h>

#include "app/commands.h"
#include "base/error.h"
#include "model/coupling/hindered.h"
#include "model/coupling/piston.h"
#include "model/coupling/sphere.h"
#include "model/fluid/flow_piston.h"
#include "model/fluid/flow_stability.h"

namespace pastemix::app {

namespace {

using coupling::SphereResult;
using coupling::SphereSettings;

void print_sphere(const SphereSettings& s, const SphereResult& r) {
  if (s.yield_number > 0.0) {
    fmt::print("sphere Bingham Y = {:g} (m = {:g} s), h/d {:g}, L/d {:g}: slip {:.4g} m/s, max |v| {:.3g} m/s and "
               "settled {:.3g} mm over the last {:.3g} s, {} cells, {} cycles, {:.2f} s\n",
               s.yield_number, s.regularisation, s.cell_over_diameter, s.box_over_diameter, r.velocity,
               r.max_speed_late, 1e3 * r.travel, 0.5 * r.cycles * s.coupling_interval, r.cells, r.cycles, r.seconds);
    return;
  }
  fmt::print("sphere h/d {:g}, L/d {:g}, disturbance correction {}: slip {:.5g} m/s [{:.5g}, {:.5g}] against "
             "Hasimoto {:.5g} (Stokes {:.5g}): error {:+.2f} %, Re {:.3g}, {} cells, {} cycles, {:.2f} s\n",
             s.cell_over_diameter, s.box_over_diameter, s.disturbance ? "on" : "off", r.velocity, r.slip_min,
             r.slip_max, r.reference, r.stokes, 100.0 * r.error, r.reynolds, r.cells, r.cycles, r.seconds);
}

SphereResult sphere_or_input_error(const SphereSettings& s) {
  try {
    return coupling::run_sphere(s);
  } catch (const std::invalid_argument& e) {
    throw InputError("--cell-over-d", 0, "",
                     fmt::format("--cell-over-d {:g} / --box-over-d {:g}: {}", s.cell_over_diameter,
                                 s.box_over_diameter, e.what()));
  }
}

}  // namespace

void register_coupling_commands(CLI::App& app) {
  CLI::App* validate = group_subcommand(app, "validate", "validations");
  CLI::App* cpl = validate->add_subcommand("coupling", "the particles-paste coupling (model/coupling) against references");
  cpl->require_subcommand(1);
  // The cases are small and their figures are quoted at one thread (model/coupling/VALIDATION.md): the flow
  // solver's loops would only wait on each other here.
  cpl->parse_complete_callback([] { omp_set_num_threads(1); });

  struct Opts {
    SphereSettings sphere;
    bool only_without = false, toy = false;
    double cell = 0.01;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* sph = cpl->add_subcommand("sphere", "a sphere settling in a periodic box vs Hasimoto; Bingham stick");
  sph->add_option("--cell-over-d", o->sphere.cell_over_diameter, "cell size / sphere diameter (default 1)")
      ->check(CLI::PositiveNumber);
  sph->add_option("--box-over-d", o->sphere.box_over_diameter, "box side / diameter, whole cells (default 8)")
      ->check(CLI::PositiveNumber);
  sph->add_option("--yield-number", o->sphere.yield_number,
                  "Y = tau_y / (g d (rho_p - rho_f)): > 0 runs the Bingham paste (default 0: Newtonian)")
      ->check(CLI::NonNegativeNumber);
  sph->add_option("--interval", o->sphere.coupling_interval, "coupling interval, s (default 0.005)")
      ->check(CLI::PositiveNumber);
  sph->add_flag("--without-correction", o->only_without, "only the run without the disturbance correction");
  sph->callback([o] {
    SphereSettings s = o->sphere;
    s.disturbance = !o->only_without;
    print_sphere(s, sphere_or_input_error(s));
    if (s.yield_number == 0.0 && s.disturbance) {
      s.disturbance = false;
      print_sphere(s, sphere_or_input_error(s));
    }
  });

  auto hs = std::make_shared<coupling::HinderedSettings>();
  auto no_voidage = std::make_shared<bool>(false);
  CLI::App* hin = cpl->add_subcommand("hindered", "a uniform suspension settling vs Richardson-Zaki (reported)");
  hin->add_option("--phi", hs->solid_fraction, "solid fraction (default 0.1)")->check(CLI::Range(0.01, 0.4));
  hin->add_flag("--no-voidage", *no_voidage, "without Di Felice's voidage correction");
  hin->callback([hs, no_voidage] {
    coupling::HinderedSettings s = *hs;
    s.voidage = !*no_voidage;
    const coupling::HinderedResult r = coupling::run_hindered(s);
    fmt::print("hindered phi {:g} ({} spheres of {:g} mm, {}^3 cells of {:g} mm, voidage {}): v_s/v_t {:.4f}, "
               "n_eff {:.3f} against Richardson-Zaki eps^4.65 = {:.4f}, {:.2f} s\n",
               s.solid_fraction, r.spheres, 1e3 * s.diameter, s.cells, 1e3 * s.cell, s.voidage ? "on" : "off", r.ratio,
               r.exponent, r.reference, r.seconds);
  });

  CLI::App* pis = cpl->add_subcommand("piston", "a glued block pushed into the paste: the surface rise (no DEM)");
  pis->add_option("--cell", o->cell, "cubic cell, m (default 0.01)")->check(CLI::PositiveNumber);
  pis->add_flag("--toy", o->toy, "drop d eps_f/dt from the projection (the toy coupling: no rise)");
  pis->callback([o] {
    coupling::PistonSettings s;
    s.cell = o->cell;
    s.with_rate = !o->toy;
    const coupling::PistonResult r = coupling::run_piston(s);
    fmt::print("piston {:g} m cells{}: rise {:.5g} mm (expected {:.5g} mm, error {:.3g}), paste volume error {:.3g}, "
               "alpha in [{:.3g}, {:.6g}], {:.2f} s\n",
               s.cell, o->toy ? " (toy: no d eps_f/dt)" : "", 1e3 * r.rise_measured, 1e3 * r.rise_expected,
               r.relative_error, r.volume_error, r.alpha_min, r.alpha_max, r.seconds);
  });

  for (const char* name : {"bed", "stream"}) {
    CLI::App* st = cpl->add_subcommand(name, std::string(name) == "bed"
                                                 ? "a packed bed at rest in the paste: no energy growth, no NaN"
                                                 : "a dense stream falling through air into the paste: no energy growth, no NaN");
    auto ss = std::make_shared<model::fluid::StabilitySettings>();
    ss->name = name;
    st->add_option("--layers", ss->layers, "bed: spheres per side; stream: spheres / 10 (default 4)")->check(CLI::PositiveNumber);
    st->add_option("--relaxations", ss->relaxations, "DEM step over the drag relaxation time (default 10)")->check(CLI::PositiveNumber);
    st->add_option("--intervals", ss->interval, "DEM steps per flow interval (default 1)")->check(CLI::PositiveNumber);
    st->add_option("--time", ss->time, "simulated time, s (default 0.02)")->check(CLI::PositiveNumber);
    st->add_option("--cell", ss->cell, "cubic cell, m (default 0.01)")->check(CLI::PositiveNumber);
    st->callback([ss] {
      const model::fluid::StabilityResult r = model::fluid::run_stability(*ss);
      fmt::print("{} {} spheres of {:g} mm, DEM step {:.3g} s = {:g} tau (tau {:.3g} s, paste {:.4g} Pa s), interval {}: "
                 "energy growth {:.3g} J = {:.3g} of the budget K(0) + released (<= 0: none; K(end) {:.3g} J, released {:.3g} J), max sphere speed {:.3g} m/s, "
                 "paste volume error {:.3g}, {} steps, {} cycles, {:.2f} s\n",
                 ss->name, r.spheres, 1e3 * ss->diameter, r.dt, ss->relaxations, r.tau, r.viscosity, ss->interval,
                 r.growth, r.growth / r.budget, r.kinetic_end, r.released_end, r.max_speed, r.paste_volume_error, r.steps, r.cycles, r.seconds);
    });
  }

  CLI::App* dem = cpl->add_subcommand("piston-dem", "the piston's 27 spheres as DEM particles through the engine "
                                                    "(a dynamics = \"flow\" scene): the surface rise");
  auto ds = std::make_shared<model::fluid::DemPistonSettings>();
  dem->add_option("--cell", ds->cell, "cubic cell, m (default 0.005)")->check(CLI::PositiveNumber);
  dem->add_option("--dt", ds->time_step, "DEM step, s (default 1e-4)")->check(CLI::PositiveNumber);
  dem->add_option("--eta", ds->eta, "paste viscosity, Pa s (default 5)")->check(CLI::PositiveNumber);
  dem->add_option("--settle", ds->settle_time, "s the block is held after the push (default 1)")->check(CLI::PositiveNumber);
  dem->add_option("--interval", ds->coupling_interval, "DEM steps per flow interval (default 50)")->check(CLI::PositiveNumber);
  dem->callback([ds] {
    const model::fluid::DemPistonResult r = model::fluid::run_dem_piston(*ds);
    fmt::print("piston-dem {:g} m cells, DEM step {:g} s x {}: rise {:.5g} mm (expected {:.5g} mm, error {:.3g}), "
               "paste volume error {:.3g}, free-surface spread {:.3g} mm, flow speed at the end {:.3g} m/s, {} steps, "
               "{} cycles, {} flow steps, {:.2f} s\n",
               ds->cell, ds->time_step, ds->coupling_interval, 1e3 * r.rise_measured, 1e3 * r.rise_expected,
               r.relative_error, r.volume_error, 1e3 * r.surface_spread, r.max_speed_end, r.steps, r.cycles,
               r.flow_steps, r.seconds);
  });
}

}  // namespace pastemix::app
