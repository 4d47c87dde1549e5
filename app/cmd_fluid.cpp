// SPDX-License-Identifier: MIT
// Fluid validations and calibration through the engine (validation/fluid/validations.h):
//   pastemix validate water [--dt 1e-7,1e-6,...]                 settling in water: error vs time step
//   pastemix validate settling DATASET --curve NAME [--params parameters.toml] [--rows N] [--dt S]
//                                                                 121 Valentik & Whitmore spheres, DEM vs lab
//   pastemix validate suspension                                 rest above / sinking below the yield number
//   pastemix validate steel-balls [PASTE] [--no-wall] [--offset MM]   settling distance vs falling height
//   pastemix validate ball-pour [PASTE] [--seeds 15] [--out DIR]  68 balls from the funnel (app/cmd_fluid_pour.cpp)
//   pastemix calibrate viscosity --ball 12.6 --height 255 --distance D [PASTE]   eta_B from one ball
// PASTE = [--params out/lab/parameters.toml] [--tau-y PA] [--rho-paste KG_M3] [--eta PA_S] [--curve NAME]
// (app/fluid_paste.h: values from the lab parameter store, overridable).
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app/commands.h"
#include "app/fluid_paste.h"
#include "base/error.h"
#include "base/staged_output.h"
#include "lab/drag/settling.h"
#include "lab/drag/terminal_velocity.h"
#include "model/fluid/fluid_scene.h"
#include "validation/fluid/steel_ball_flow.h"
#include "validation/fluid/validations.h"
#include "base/units.h"

namespace pastemix::app {

namespace {

using namespace pastemix::model::fluid;
using namespace pastemix::validation;

drag::DragCurve curve_option(const std::string& name, const std::string& params) {
  auto id = drag::find_curve(name);
  if (!id) throw InputError("--curve", 0, "curve", fmt::format("unknown drag curve '{}'", name));
  if (drag::curve_info(*id).n_coefficients == 0) return {*id, {}};
  if (params.empty())
    throw InputError("--curve", 0, "curve", fmt::format("curve {} needs --params parameters.toml (lab reduce)", name));
  return read_chosen_curve(params, name);
}


void register_water(CLI::App* val) {
  auto dts = std::make_shared<std::vector<double>>(std::vector<double>{1e-7, 1e-6, 1e-5, 2.5e-5, 1e-4, 1e-3});
  CLI::App* water = val->add_subcommand("water", "0.1 mm, 2700 kg/m3 settling in water vs v_t (1 - exp(-t/tau))");
  water->add_option("--dt", *dts, "time steps (s)")->delimiter(',');
  water->callback([dts] {
    fmt::print("settling of a 0.1 mm, 2700 kg/m3 sphere in water (Stokes), engine vs analytic, t in (0, 10 tau]\n");
    fmt::print("{:>10} {:>8} {:>14} {:>10}\n", "dt (s)", "steps", "max rel error", "dt/tau");
    for (double dt : *dts) {
      const WaterSettling w = water_settling(dt);
      fmt::print("{:>10.3g} {:>8} {:>14.3e} {:>10.3g}\n", dt, w.steps, w.max_rel_error, dt / w.tau);
    }
  });
}

struct SettleOpts {
  std::string dataset, curve = "power_blend", params;
  int rows = 0;
  double dt = 1e-3, column = 3.0;
};

// The worst |DEM/lab - 1| over the spheres compared, and the counts of the summary line.
struct SettleTally {
  double worst = 0.0;
  int worst_row = 0, trapped = 0, compared = 0, inconsistent = 0;
};

// One Valentik & Whitmore sphere: the DEM column against the lab force balance, one table row.
void settle_row(const lab::drag::SettlingSphere& sp, const drag::DragCurve& curve, const SettleOpts& so,
                SettleTally& tally) {
  const auto lab = lab::drag::solve_terminal_velocity(curve, sp.sphere, 9.81);
  SphereRun r;
  r.d = sp.sphere.d, r.rho_p = sp.sphere.rho_p, r.rho_f = sp.sphere.rho_f, r.tau_y = sp.sphere.tau_y;
  r.eta = sp.sphere.eta_B, r.curve = curve, r.dt = so.dt;
  const ColumnSettling c = column_settling(r, so.column);
  // Trapped: at rest in the DEM although the force balance has no rest state (the lab says it moves).
  const bool held = lab.outcome == lab::drag::SettlingOutcome::suspended;
  tally.trapped += c.trapped && !held;
  std::string outcome = lab::drag::to_string(lab.outcome);
  double diff = NAN;
  if (lab.outcome == lab::drag::SettlingOutcome::settling) {
    diff = 100.0 * (c.v_final / lab.v - 1.0);
    ++tally.compared;
    if (std::abs(diff) > tally.worst) tally.worst = std::abs(diff), tally.worst_row = sp.row_id;
  } else {
    ++tally.inconsistent;
  }
  if (c.trapped) outcome += held ? " (DEM at rest too)" : " TRAPPED";
  if (!c.trapped && held) outcome += " (DEM MOVES)";
  fmt::print("{:>4} {:>3} {:>8.2f} {:>10.5f} {:>10.5f} {:>9.4f} {:>8.4f} {}\n", sp.row_id, sp.suspension,
             1e3 * sp.sphere.d, lab.v, c.v_final, diff, 100.0 * c.v_change, outcome);
}

void register_settling(CLI::App* val) {
  auto so = std::make_shared<SettleOpts>();
  CLI::App* settle = val->add_subcommand("settling", "DEM terminal velocities of the Valentik & Whitmore spheres");
  settle->add_option("dataset", so->dataset, "dataset folder (valentik_whitmore_1965_*.csv)")->required();
  settle->add_option("--curve", so->curve, "drag curve name (default power_blend)");
  settle->add_option("--params", so->params, "parameters.toml with the curve's coefficients (lab reduce)");
  settle->add_option("--rows", so->rows, "only the first N spheres (0 = all)");
  settle->add_option("--dt", so->dt, "time step (s), default 1e-3");
  settle->add_option("--column", so->column, "column height (m), default 3");
  settle->callback([so] {
    const drag::DragCurve curve = curve_option(so->curve, so->params);
    const auto data = lab::drag::read_settling_dataset(so->dataset);
    fmt::print("{:>4} {:>3} {:>8} {:>10} {:>10} {:>9} {:>8} {}\n", "row", "sus", "d (mm)", "v_lab", "v_dem",
               "diff %", "steady%", "outcome");
    SettleTally tally;
    const std::size_t n = so->rows > 0 ? std::min<std::size_t>(so->rows, data.spheres.size()) : data.spheres.size();
    for (std::size_t k = 0; k < n; ++k) settle_row(data.spheres[k], curve, *so, tally);
    fmt::print("curve {}: {} spheres, {} compared, max |DEM/lab - 1| = {:.4f} % (row {}), trapped {}, "
               "no consistent lab solution {}\n",
               so->curve, n, tally.compared, tally.worst, tally.worst_row, tally.trapped, tally.inconsistent);
  });
}

void register_suspension(CLI::App* val) {
  CLI::App* susp = val->add_subcommand("suspension", "rest above the yield-number threshold, sinking below it");
  susp->callback([] {
    // A 10 mm, 2700 kg/m3 sphere in a 1500 kg/m3 Bingham fluid (eta 0.1 Pa.s), the 4.19 curve.
    const drag::DragCurve curve{drag::CurveId::published_4_19, {}};
    const double thr = suspension_threshold(curve);
    fmt::print("threshold tau_y / (g d (rho_p - rho_f)) = {:.6f} (engine rest drag, curve 4.19)\n", thr);
    fmt::print("{:>10} {:>10} {:>14} {:>12}\n", "Y/Y_c", "tau_y", "displacement", "speed");
    for (double f : {2.0, 1.01, 1.001, 0.999, 0.99, 0.5}) {
      SphereRun r;
      r.d = 0.01, r.rho_p = 2700, r.rho_f = 1500, r.eta = 0.1, r.curve = curve, r.dt = 1e-4, r.depth = 0.2;
      r.tau_y = f * thr * 9.81 * r.d * (r.rho_p - r.rho_f);
      const SuspensionResult s = suspension(r, 1.0);  // 1 s at rest
      fmt::print("{:>10.4g} {:>10.4g} {:>14.6e} {:>12.6e}\n", f, r.tau_y, s.displacement, s.speed_end);
    }
  });
}

struct BallOpts {
  double dt = 2e-5, offset = 0.0;
  bool no_wall = false;
  PasteOpts paste;
  std::vector<double> flow_cells;  // m; empty: the at-rest table only
  validation::FlowBallSettings flow;
};

// The Table 4.4 grid (m): ball diameters and falling heights, and its header row.
const std::vector<double> kBallDiameters{0.008, 0.0126, 0.016}, kBallHeights{0.0, 0.105, 0.150, 0.255};

void print_ball_header() {
  fmt::print("{:>10}", "ball (mm)");
  for (double h : kBallHeights) fmt::print(" {:>9}", fmt::format("H={:.0f}", 1e3 * h));
}

// The same grid with dynamics = "flow" (validation/fluid/steel_ball_flow.h) at one cell size: distance (mm),
// * = reached the floor, ~ = still moving at the end (its speed follows); then each run's cost.
void print_flow_ball_table(const SteelBallPaste& p, double eta, double cell, const validation::FlowBallSettings& base) {
  validation::FlowBallSettings f = base;
  f.cell = cell;
  std::string cost;
  double used = 0.0;
  print_ball_header();
  fmt::print("   cell / d\n");
  for (double d : kBallDiameters) {
    fmt::print("{:>10.1f}", 1e3 * d);
    for (double h : kBallHeights) {
      const validation::FlowBallDrop b = validation::steel_ball_drop_flow(p, d, h, eta, f);
      used = b.cell;
      fmt::print(" {:>9}", fmt::format("{:.2f}{}", 1e3 * b.drop.distance,
                                       b.drop.reached_bottom ? "*" : (b.at_rest ? "" : "~")));
      const auto& J = b.split;
      cost += fmt::format("  {:.1f} mm from {:.0f} mm: {:.2f} s to rest, end speed {:.3g} mm/s, {} flow intervals, "
                          "{:.1f} s wall{}; impulses from the entry (mN s, up +): m dv {:.3f} = gravity {:.3f} + "
                          "pressure {:.3f} (hydrostatic {:.3f}, the rest {:.3f}) + drag {:.3f}\n",
                          1e3 * d, 1e3 * h, b.drop.time_to_rest, 1e3 * b.speed_end, b.cycles, b.seconds,
                          b.at_rest || b.drop.reached_bottom ? "" : " (NOT at rest)", 1e3 * J.momentum,
                          1e3 * J.gravity, 1e3 * J.pressure, 1e3 * J.hydrostatic, 1e3 * (J.pressure - J.hydrostatic),
                          1e3 * J.drag);
    }
    fmt::print("   {:.3g}\n", used / d);
  }
  fmt::print("(cell {:.4g} mm; * = reached the floor, ~ = still moving at the end)\n{}", 1e3 * used, cost);
}

// The Table 4.4 grid: settling distance (mm) per ball diameter and falling height; * = reached the bottom.
void print_ball_table(const SteelBallPaste& p, double eta) {
  print_ball_header();
  fmt::print("\n");
  for (double d : kBallDiameters) {
    fmt::print("{:>10.1f}", 1e3 * d);
    for (double h : kBallHeights) {
      const BallDrop b = steel_ball_drop(p, d, h, eta);
      fmt::print(" {:>9}", fmt::format("{:.2f}{}", 1e3 * b.distance, b.reached_bottom ? "*" : ""));
    }
    fmt::print("\n");
  }
}

void register_steel_balls(CLI::App* val) {
  auto bo = std::make_shared<BallOpts>();
  CLI::App* balls = val->add_subcommand("steel-balls", "Table 4.4: settling distance vs falling height");
  add_paste_options(balls, bo->paste);
  balls->add_option("--dt", bo->dt, "time step (s), default 2e-5");
  balls->add_flag("--no-wall", bo->no_wall, "leave out the mould's side wall (cylinder 75 mm)");
  balls->add_option("--offset", bo->offset, "release point's distance from the mould axis (mm), default 0");
  balls->add_option("--flow", bo->flow_cells, "also with dynamics = \"flow\" at these cell sizes (m; repeat)")
      ->check(CLI::PositiveNumber);
  add_flow_options(balls, bo->flow.coupling_interval, bo->flow.regularisation);
  balls->callback([bo] {
    const Paste paste = resolve_paste(bo->paste);
    SteelBallPaste p = steel_ball_paste(paste);
    p.dt = bo->dt, p.mould_wall = !bo->no_wall, p.offset = 1e-3 * bo->offset;
    if (!(p.offset >= 0.0 && p.offset + 0.008 < 0.5 * std::sqrt(pastemix::units::pi / 4.0) * p.mould_diameter))
      throw InputError("--offset", 0, "offset", "must leave the 16 mm ball inside the mould's fluid box (mm)");
    print_paste(paste);
    fmt::print("steel balls ({} kg/m3), mould {} x {} mm{}, release {} mm off the axis, dt {} s\nsettling distance = "
               "initial paste surface to the ball's bottom at rest (mm)\n",
               p.rho_ball, 1e3 * p.mould_diameter, 1e3 * p.mould_height,
               p.mould_wall ? " with its side wall" : " WITHOUT side wall", bo->offset, p.dt);
    print_ball_table(p, paste.eta);
    for (double cell : bo->flow_cells) {
      fmt::print("\nwith dynamics = \"flow\" (coupling interval {}, regularisation m = {:g} s, rest: |v| < {:g} mm/s for "
                 "{:g} s):\n",
                 bo->flow.coupling_interval, bo->flow.regularisation, 1e3 * bo->flow.rest_speed, bo->flow.rest_time);
      print_flow_ball_table(p, paste.eta, cell, bo->flow);
    }
  });
}

void register_validate(CLI::App& app) {
  CLI::App* val = app.add_subcommand("validate", "fluid validations through the engine");
  val->require_subcommand(1);
  register_water(val);
  register_settling(val);
  register_pour(val);
  register_suspension(val);
  register_steel_balls(val);
}

void register_calibrate(CLI::App& app) {
  CLI::App* cal = group_subcommand(app, "calibrate", "calibrate an unmeasurable parameter against lab tests");
  struct Opts {
    double ball = 12.6, height = 255.0, distance = 0.0, dt = 2e-5;
    PasteOpts paste;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* visc = cal->add_subcommand("viscosity", "paste plastic viscosity from a steel ball's settling distance");
  visc->add_option("--ball", o->ball, "ball diameter (mm), default 12.6");
  visc->add_option("--height", o->height, "falling height of the ball's bottom above the paste (mm), default 255");
  visc->add_option("--distance", o->distance, "measured settling distance: paste surface to ball bottom (mm)")
      ->required();
  add_paste_options(visc, o->paste, /*with_eta=*/false);
  visc->add_option("--dt", o->dt, "time step (s)");
  visc->callback([o] {
    if (!(o->ball > 0.0)) throw InputError("--ball", 0, "ball", "must be positive (mm)");
    if (!(o->height >= 0.0)) throw InputError("--height", 0, "height", "must be non-negative (mm)");
    if (!(o->distance > 0.0)) throw InputError("--distance", 0, "distance", "must be positive (mm)");
    const Paste paste = resolve_paste(o->paste, /*need_eta=*/false);
    SteelBallPaste p = steel_ball_paste(paste);
    p.dt = o->dt;
    print_paste(paste);
    const Calibration c = calibrate_viscosity(p, 1e-3 * o->ball, 1e-3 * o->height, 1e-3 * o->distance);
    fmt::print("eta_B = {:.6g} Pa.s (distance {:.4f} mm at that viscosity; {} engine runs; ball {} mm, height {} mm, "
               "mould wall on)\n",
               c.eta, 1e3 * c.distance, c.runs, o->ball, o->height);
  });
}

}  // namespace

void register_fluid_commands(CLI::App& app) {
  register_validate(app);
  register_calibrate(app);
}

}  // namespace pastemix::app
