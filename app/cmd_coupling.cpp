// SPDX-License-Identifier: MIT
// `pastemix validate coupling sphere | piston | hindered | bed | stream | piston-dem | raft`: the coupling's cases (model/coupling, issue 18) with their
// references; the figures of model/coupling/VALIDATION.md. One thread (the cases are serial).
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <omp.h>

#include "app/commands.h"
#include "base/error.h"
#include "model/coupling/hindered.h"
#include "model/coupling/piston.h"
#include "model/coupling/sphere.h"
#include "model/fluid/flow_piston.h"
#include "model/fluid/flow_raft.h"
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
  const double cells = s.box_over_diameter / s.cell_over_diameter;
  fmt::print("sphere h/d {:g}, L/d {:g}, start x y {:.4g} {:.4g} cells, disturbance correction {}: slip {:.5g} m/s "
             "[{:.5g}, {:.5g}] against Hasimoto {:.5g} (Stokes {:.5g}): error {:+.2f} %, resolved pressure force {:+.2f} % "
             "of the drag, Re {:.3g}, {} cells, {} cycles, {:.2f} s\n",
             s.cell_over_diameter, s.box_over_diameter, s.start[0] * cells, s.start[1] * cells,
             s.disturbance ? "on" : "off", r.velocity, r.slip_min,
             r.slip_max, r.reference, r.stokes, 100.0 * r.error, 100.0 * r.pressure_share, r.reynolds, r.cells,
             r.cycles, r.seconds);
}

void print_hindered(const coupling::HinderedSettings& s, const coupling::HinderedResult& r) {
  fmt::print("hindered phi {:g} ({} spheres of {:g} mm, {}^3 cells of {:g} mm, voidage {}, seed {}): v_s/v_t {:.4f}, "
             "n_eff {:.3f} against Richardson-Zaki eps^4.65 = {:.4f} ({:+.1f} %); local slip x eps {:.4f}, carried "
             "{:+.4f}, beta / closure's {:.4f}, pressure {:+.4f}; {:.2f} s\n",
             s.solid_fraction, r.spheres, 1e3 * s.diameter, s.cells, 1e3 * s.cell, s.voidage ? "on" : "off", s.seed,
             r.ratio, r.exponent, r.reference, 100.0 * (r.ratio / r.reference - 1.0), r.local_slip, r.carried,
             r.beta_ratio, r.pressure_share, r.seconds);
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

void print_raft(const model::fluid::RaftSettings& s, const model::fluid::RaftResult& r) {
  for (const auto& t : r.trace)
    fmt::print("  t {:.3f} s: penetration {:.3f} mm, speed {:.3f} mm/s, paste max {:.3f} mm/s, share {:.3f}, slip "
               "{:.3f} mm/s, swirl {:.3g} mm/s\n",
               t.time, 1e3 * t.penetration, 1e3 * t.speed, 1e3 * t.paste_speed, t.share, 1e3 * t.slip, 1e3 * t.swirl);
  fmt::print("raft q {:6.3f} tau_y: penetration {:7.3f} mm (slid {:6.3f}), net q - gamma D {:6.3f} tau_y, end speed "
             "{:7.4f} mm/s, max {:7.3f} mm/s, {:7}, {} cycles, {} flow steps, {:.1f} s\n",
             s.load, 1e3 * r.penetration, 1e3 * r.slid, r.net_load, 1e3 * r.speed_end, 1e3 * r.max_speed,
             r.punched ? "punched" : "held", r.cycles, r.flow_steps, r.seconds);
}

// 1: punched, 0: held, -1: the run failed (the flow's RuntimeFailure, printed: neither).
int raft_at(model::fluid::RaftSettings s, double q) {
  s.load = q;
  try {
    const model::fluid::RaftResult r = model::fluid::run_raft(s);
    print_raft(s, r);
    return r.punched ? 1 : 0;
  } catch (const RuntimeFailure& e) {
    fmt::print("raft q {:6.3f} tau_y: the run failed: {}\n", q, e.what());
    return -1;
  }
}

// q = 3 .. 12 tau_y, then `bisect` halvings between the highest holding load below the first punching one and
// that one: the load at which the raft goes.
void raft_sweep(const model::fluid::RaftSettings& s, int bisect) {
  double held = 0.0, punched = 0.0;  // a failed run (-1) counts as neither
  for (int q = 3; q <= 12; ++q) {
    const int p = raft_at(s, q);
    if (p == 1 && punched == 0.0) punched = q;
    if (p == 0 && punched == 0.0) held = q;
  }
  if (punched == 0.0) return fmt::print("raft: no run up to 12 tau_y A punched\n");
  if (held == 0.0) return fmt::print("raft: no run below {:g} tau_y A held\n", punched);
  for (int k = 0; k < bisect; ++k) {
    const double q = 0.5 * (held + punched);
    const int p = raft_at(s, q);
    if (p < 0) break;
    (p == 1 ? punched : held) = q;
  }
  fmt::print("raft: goes between {:.3f} (holds) and {:.3f} tau_y A (punched): {:.2f} tau_y A; Skempton 5 .. 9\n",
             held, punched, 0.5 * (held + punched));
}

void register_raft(CLI::App* cpl) {
  CLI::App* raft = cpl->add_subcommand("raft", "a 5 cm raft of touching spheres loaded on the Bingham paste "
                                               "(through the engine): holds, or goes (Skempton's 5-9 tau_y)");
  auto rs = std::make_shared<model::fluid::RaftSettings>();
  auto sweep = std::make_shared<bool>(false);
  auto bisect = std::make_shared<int>(3);
  raft->add_option("--load", rs->load, "q / tau_y, the raft's weight over tau_y A (default 3)")->check(CLI::PositiveNumber);
  raft->add_flag("--sweep", *sweep, "q = 3, 4, .. 12, then bisect where it goes");
  raft->add_option("--bisect", *bisect, "halvings after the sweep (default 3)")->check(CLI::NonNegativeNumber);
  raft->add_option("--cell", rs->cell, "cubic cell, m (default 0.005)")->check(CLI::PositiveNumber);
  raft->add_option("--box", rs->box, "the paste box's side, m (default 0.1)")->check(CLI::PositiveNumber);
  raft->add_option("--m", rs->regularisation, "Papanastasiou's m, s (default 1000)")->check(CLI::PositiveNumber);
  raft->add_option("--tau-y", rs->yield_stress, "the paste's yield stress, Pa (default 46)")->check(CLI::PositiveNumber);
  raft->add_option("--paste-density", rs->paste_density, "kg/m3 (default 1789.4)")->check(CLI::PositiveNumber);
  raft->add_option("--time", rs->time, "simulated time, s (default 1)")->check(CLI::PositiveNumber);
  raft->add_option("--dt", rs->time_step, "DEM step, s (default 1e-4)")->check(CLI::PositiveNumber);
  raft->add_option("--interval", rs->coupling_interval, "DEM steps per flow interval (default 50)")->check(CLI::PositiveNumber);
  raft->add_option("--flow-dt", rs->flow_time_step, "the flow's largest sub-step in a cycle, s (default the solver's 1e-2)")
      ->check(CLI::PositiveNumber);
  raft->add_flag("--implicit-stick", rs->implicit_stick, "a yield-held sphere moves with the paste in the flow step");
  raft->add_option("--trace", rs->trace_every, "s between trace lines (default none)")->check(CLI::PositiveNumber);
  raft->callback([rs, sweep, bisect] {
    try {
      if (*sweep) return raft_sweep(*rs, *bisect);
      print_raft(*rs, model::fluid::run_raft(*rs));  // a RuntimeFailure is the command's failure
    } catch (const std::invalid_argument& e) {
      throw InputError("--load", 0, "", e.what());
    }
  });
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
    bool only_without = false, only_with = false, toy = false;
    std::vector<double> start;  // cells
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
  sph->add_flag("--with-correction-only", o->only_with, "only the run with the disturbance correction");
  sph->add_option("--start", o->start, "the sphere's start x y in cells (default 0.37 and 0.41 of the box)")
      ->expected(2);
  sph->callback([o] {
    SphereSettings s = o->sphere;
    s.disturbance = !o->only_without;
    if (o->start.size() == 2) {
      const double cells = s.box_over_diameter / s.cell_over_diameter;
      s.start[0] = o->start[0] / cells, s.start[1] = o->start[1] / cells;
    }
    print_sphere(s, sphere_or_input_error(s));
    if (s.yield_number == 0.0 && s.disturbance && !o->only_with) {
      s.disturbance = false;
      print_sphere(s, sphere_or_input_error(s));
    }
  });

  auto hs = std::make_shared<coupling::HinderedSettings>();
  auto no_voidage = std::make_shared<bool>(false);
  CLI::App* hin = cpl->add_subcommand("hindered", "a uniform suspension settling vs Richardson-Zaki (reported)");
  hin->add_option("--phi", hs->solid_fraction, "solid fraction (default 0.1)")->check(CLI::Range(0.01, 0.4));
  hin->add_flag("--no-voidage", *no_voidage, "without Di Felice's voidage correction");
  auto no_disturbance = std::make_shared<bool>(false);
  hin->add_flag("--no-disturbance", *no_disturbance, "without the disturbance (self-induced velocity) correction");
  hin->add_option("--cells", hs->cells, "cells per axis (default 8)")->check(CLI::PositiveNumber);
  hin->add_option("--cell", hs->cell, "cubic cell, m (default 0.02)")->check(CLI::PositiveNumber);
  hin->add_option("--diameter", hs->diameter, "sphere diameter, m (default 0.005)")->check(CLI::PositiveNumber);
  hin->add_option("--width", hs->width_factor, "kernel width factor c (default 2)")->check(CLI::PositiveNumber);
  hin->add_option("--seed", hs->seed, "seed of the sphere positions (default 5)");
  auto seeds = std::make_shared<int>(1);
  hin->add_option("--seeds", *seeds, "realizations, seeds seed .. seed + N - 1, and their mean (default 1)")
      ->check(CLI::PositiveNumber);
  hin->callback([hs, no_voidage, no_disturbance, seeds] {
    coupling::HinderedSettings s = *hs;
    s.voidage = !*no_voidage;
    s.disturbance = !*no_disturbance;
    double sum = 0.0;
    for (int k = 0; k < *seeds; ++k, ++s.seed) {
      const coupling::HinderedResult r = coupling::run_hindered(s);
      sum += r.ratio;
      print_hindered(s, r);
    }
    if (*seeds > 1) {
      const double eps = 1.0 - s.solid_fraction, mean = sum / *seeds, rz = std::pow(eps, 4.65);
      fmt::print("hindered phi {:g}, mean of {} seeds: v_s/v_t {:.4f} against {:.4f} ({:+.1f} %), n_eff {:.3f}\n",
                 s.solid_fraction, *seeds, mean, rz, 100.0 * (mean / rz - 1.0), std::log(mean) / std::log(eps));
    }
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

  register_raft(cpl);
}

}  // namespace pastemix::app
