// SPDX-License-Identifier: MIT
// The flow solver's commands (model/flow/):
//   pastemix validate flow cavity [--n 64] [--re 100] [--max-time S]  lid-driven cavity vs Ghia, Ghia & Shin (1982)
//   pastemix validate flow still [--time 1]                           flat paste/air interface at rest
//   pastemix validate flow dam-break [--cells 20] [--T-max 5.5]       water column vs Martin & Moyce (1952)
//   pastemix flow run CASE.toml [--out DIR] [--threads N]             a [flow] case -> NAME.h5 + NAME.xmf
// Each validation prints its error against the reference, its cost (cells x steps / s, CG iterations per
// solve), the paste-volume drift and, where the reference allows, the observed order of convergence.
#include <algorithm>
#include <cmath>
#include <memory>

#include <Eigen/Core>
#include <fmt/format.h>
#include <omp.h>

#include "app/commands.h"
#include "base/error.h"
#include "base/staged_output.h"
#include "model/flow/flow_config.h"
#include "model/flow/flow_output.h"
#include "model/flow/validations.h"

namespace pastemix::app {

namespace {

using namespace pastemix::flow;

std::string reference(const std::string& name) {
  return std::string(PASTEMIX_SOURCE_DIR) + "/datasets/reference/" + name;
}

void set_threads(int threads) {
  if (threads <= 0) return;
  omp_set_num_threads(threads);
  Eigen::setNbThreads(threads);
}

void print_cost(const Cost& c, double drift, double divergence) { print_flow_cost(c, drift, divergence, "  "); }

void run_cavity(int n, int re, double max_time, bool order) {
  const GhiaReference ref = read_ghia(reference("ghia_ghia_shin_1982_cavity.csv"), re);
  std::vector<int> sizes{n};
  if (order) sizes.insert(sizes.begin(), n / 2);
  std::vector<double> errs;
  for (int m : sizes) {
    const CavityResult r = cavity(m, re, ref, max_time);
    fmt::print("cavity Re {} on {} x {} (2 cells deep, periodic): t = {:.0f} s (lid times), last change per lid time "
               "{:.2e}\n",
               re, m, m, r.time, r.steady_change);
    fmt::print("  {:>8} {:>10} {:>10} | {:>8} {:>10} {:>10}\n", "y", "u Ghia", "u model", "x", "v Ghia", "v model");
    for (std::size_t i = 0; i < ref.u_vertical.position.size(); ++i)
      fmt::print("  {:>8.4f} {:>10.5f} {:>10.5f} | {:>8.4f} {:>10.5f} {:>10.5f}\n", ref.u_vertical.position[i],
                 ref.u_vertical.velocity[i], r.model_u[i], ref.v_horizontal.position[i], ref.v_horizontal.velocity[i],
                 r.model_v[i]);
    fmt::print("  max |error| / U_lid: u {:.4f}, v {:.4f}; rms: u {:.4f}, v {:.4f}\n", r.max_error_u, r.max_error_v,
               r.rms_error_u, r.rms_error_v);
    print_cost(r.cost, r.volume_drift, r.max_divergence);
    errs.push_back(std::max(r.rms_error_u, r.rms_error_v));
  }
  if (errs.size() == 2 && errs[1] > 0)
    fmt::print("observed order (rms error vs Ghia, {} -> {} cells): {:.2f} (Ghia's own 129 x 129 solution is the "
               "reference, so this flattens as the error nears its accuracy)\n",
               sizes[0], sizes[1], std::log2(errs[0] / errs[1]));
}

void run_still(double time) {
  const StillResult r = still(time);
  fmt::print("still: paste/air interface at z = {:.2f} cells, density ratio 1800, 6 x 6 x 16 cells of 1 cm, open top, "
             "{:.2f} s\n",
             r.interface_cells, r.time);
  fmt::print("  max |u| over all steps: {:.3e} m/s (bound 1e-6)\n", r.max_speed);
  print_cost(r.cost, r.volume_drift, r.max_divergence);
}

void run_dam_break(int cells, double T_max) {
  const Series mm = read_martin_moyce(reference("martin_moyce_1952_n2_2.csv"));
  std::vector<double> T, Z;
  for (std::size_t i = 0; i < mm.T.size(); ++i)
    if (mm.T[i] <= T_max) T.push_back(mm.T[i]), Z.push_back(mm.Z[i]);
  const std::vector<int> grids{cells / 2, cells, 2 * cells};
  std::vector<DamBreakResult> res;
  for (int c : grids) res.push_back(dam_break(c, T));
  fmt::print("dam-break: Martin & Moyce (1952) n^2 = 2, a = 2.25 in, 2-D, free-slip walls; front Z = x/a at the bottom "
             "(alpha = 1/2)\n");
  fmt::print("  {:>6} {:>8}", "T", "Z data");
  for (int c : grids) fmt::print(" {:>9}", fmt::format("Z {}/a", c));
  fmt::print(" {:>10} {:>12} {:>8} {:>10} {:>9}\n", "err " + std::to_string(cells), "fine vs mid", "Z K&O", "K&O vs MM",
             "lead dT");
  // A second experiment on a 1:2 column (Koshizuka & Oka 1996), interpolated to Martin & Moyce's T where it
  // has points: how far two experiments differ, next to how far the model is from either.
  const Series ko = read_martin_moyce(reference("koshizuka_oka_1996_front.csv"));
  auto ko_at = [&ko](double t) {
    for (std::size_t j = 1; j < ko.T.size(); ++j)
      if (t >= ko.T[j - 1] && t <= ko.T[j])
        return ko.Z[j - 1] + (t - ko.T[j - 1]) / (ko.T[j] - ko.T[j - 1]) * (ko.Z[j] - ko.Z[j - 1]);
    return std::nan("");
  };
  double worst = 0.0, worst_grid = 0.0, d01 = 0.0, d12 = 0.0, worst_ko = 0.0, worst_model_ko = 0.0;
  double lead_lo = INFINITY, lead_hi = -INFINITY;
  for (std::size_t i = 0; i < T.size(); ++i) {
    fmt::print("  {:>6.3f} {:>8.3f}", T[i], Z[i]);
    for (const auto& r : res) fmt::print(" {:>9.3f}", r.front[i]);
    const double err = (res[1].front[i] - Z[i]) / Z[i], grid = (res[2].front[i] - res[1].front[i]) / res[1].front[i];
    const double zko = ko_at(T[i]);
    fmt::print(" {:>+9.1f}% {:>+11.1f}%", 100 * err, 100 * grid);
    if (std::isfinite(zko)) fmt::print(" {:>8.3f} {:>+9.1f}%", zko, 100 * (zko - Z[i]) / Z[i]);
    else fmt::print(" {:>8} {:>10}", "-", "-");
    // How much earlier (in T) the model at `cells` reaches the data's Z.
    const double lead = T[i] - time_to_reach(res[1].track, Z[i]);
    fmt::print(" {:>9.3f}\n", lead);
    if (T[i] >= 1.0 && std::isfinite(lead)) lead_lo = std::min(lead_lo, lead), lead_hi = std::max(lead_hi, lead);
    if (T[i] >= 1.0) {
      worst = std::max(worst, std::abs(err));
      worst_grid = std::max(worst_grid, std::abs(grid));
      d01 += std::abs(res[1].front[i] - res[0].front[i]);
      d12 += std::abs(res[2].front[i] - res[1].front[i]);
      if (std::isfinite(zko)) {
        worst_ko = std::max(worst_ko, std::abs(zko - Z[i]) / Z[i]);
        worst_model_ko = std::max(worst_model_ko, std::abs(res[1].front[i] - zko) / zko);
      }
    }
  }
  fmt::print("  T >= 1: max |error| vs data at {} cells across: {:.1f} % (bound 10 %); {} vs {} cells: {:.1f} % (bound 5 %)\n",
             cells, 100 * worst, 2 * cells, cells, 100 * worst_grid);
  fmt::print("  T >= 1 where both experiments have points: Koshizuka & Oka vs Martin & Moyce {:.1f} %; the model at {} "
             "cells vs Koshizuka & Oka {:.1f} %\n",
             100 * worst_ko, cells, 100 * worst_model_ko);
  fmt::print("  T >= 1: the model at {} cells reaches the data's Z earlier by dT = {:.3f} to {:.3f} (a delay at the "
             "experiment's release gives a constant dT)\n",
             cells, lead_lo, lead_hi);
  if (d12 > 0) fmt::print("  observed order of the front (sum over T >= 1 of |Z_2h - Z_h| / |Z_h - Z_h/2|): {:.2f}\n",
                          std::log2(d01 / d12));
  for (std::size_t k = 0; k < res.size(); ++k) {
    fmt::print("  {} cells across:\n", grids[k]);
    print_cost(res[k].cost, res[k].volume_drift, res[k].max_divergence);
  }
}

void run_case(const std::string& path, const std::string& out_dir) {
  const FlowCase c = load_flow_case(path);
  FlowSolver s = make_solver(c);
  StagedOutput out;
  const std::filesystem::path h5 = std::filesystem::path(out_dir) / (c.name + ".h5");
  FlowWriter w(out.path(h5), h5.filename().string(), s, c.source);
  const double v0 = s.paste_volume();
  w.snapshot(s);
  double next = c.output_interval > 0 ? c.output_interval : c.end_time;
  double max_div = 0.0;
  while (s.time() < c.end_time * (1 - 1e-14)) {
    const double target = std::min(next, c.end_time);
    while (s.time() < target * (1 - 1e-14)) {
      double dt = s.next_time_step();
      if (s.time() + dt >= target) dt = target - s.time();
      s.step(dt);
      w.record_step(s);
      const auto& p = s.last().projection;
      if (p.divergence_before > 0) max_div = std::max(max_div, p.divergence_after / p.divergence_before);
    }
    w.snapshot(s);
    next += c.output_interval > 0 ? c.output_interval : c.end_time;
  }
  const int nthreads = omp_get_max_threads();
  out.write_text(std::filesystem::path(out_dir) / (c.name + ".xmf"), w.finish(s, nthreads));
  out.commit();
  const Cost cost = cost_of(s);
  fmt::print("flow {}: {}, {:.3g} s, {} threads\n", c.name, s.grid().describe(), s.time(), nthreads);
  fmt::print("  max |u| at the end {:.3e} m/s\n", s.max_speed());
  print_cost(cost, std::abs(s.paste_volume() - v0) / v0, max_div);
  fmt::print("  wrote {} and {}.xmf\n", h5.string(), c.name);
}

}  // namespace

void register_flow_commands(CLI::App& app) {
  CLI::App* validate = group_subcommand(app, "validate", "validations");
  CLI::App* flow = validate->add_subcommand("flow", "the flow solver (model/flow) against published references");
  flow->require_subcommand(1);
  register_flow_bingham_commands(*flow);

  struct Opts {
    int n = 64, re = 100, cells = 20, threads = 1;
    double max_time = 60.0, time = 1.0, T_max = 5.5;
    bool no_order = false;
    std::string file, out = "out/flow";
  };
  auto o = std::make_shared<Opts>();
  auto threads = [o](CLI::App* a) { a->add_option("--threads", o->threads, "OpenMP threads (default 1)"); };

  CLI::App* cav = flow->add_subcommand("cavity", "lid-driven cavity vs Ghia, Ghia & Shin (1982)");
  cav->add_option("--n", o->n, "cells per side (default 64)");
  cav->add_option("--re", o->re, "Reynolds number: 100 or 1000 (the tabulated ones; default 100)");
  cav->add_option("--max-time", o->max_time, "stop at this time (lid times) if not steady before (default 60)");
  cav->add_flag("--no-order", o->no_order, "skip the half-resolution run (no order of convergence)");
  threads(cav);
  cav->callback([o] {
    set_threads(o->threads);
    run_cavity(o->n, o->re, o->max_time, !o->no_order);
  });

  CLI::App* st = flow->add_subcommand("still", "flat paste/air interface at rest (no spurious currents)");
  st->add_option("--time", o->time, "simulated time (s, default 1)");
  threads(st);
  st->callback([o] {
    set_threads(o->threads);
    run_still(o->time);
  });

  CLI::App* dam = flow->add_subcommand("dam-break", "collapse of a water column vs Martin & Moyce (1952)");
  dam->add_option("--cells", o->cells, "cells across the column (default 20; also runs half and twice)");
  dam->add_option("--T-max", o->T_max, "last reference time T = t sqrt(2g/a) to compare (default 5.5)");
  threads(dam);
  dam->callback([o] {
    set_threads(o->threads);
    run_dam_break(o->cells, o->T_max);
  });

  CLI::App* fl = group_subcommand(app, "flow", "the two-phase flow solver (model/flow)");
  CLI::App* run = fl->add_subcommand("run", "run a [flow] case file -> NAME.h5 + NAME.xmf");
  run->add_option("case", o->file, "TOML file with a [flow] table (keys: model/flow/flow_config.h)")->required();
  run->add_option("--out", o->out, "output folder (default out/flow)");
  threads(run);
  run->callback([o] {
    set_threads(o->threads);
    run_case(o->file, o->out);
  });
}

void print_flow_cost(const flow::Cost& c, double drift, double divergence, const char* indent) {
  fmt::print("{}cost: {} cells x {} steps in {:.2f} s = {:.3g} cell-steps/s; CG iterations per solve: pressure {:.1f}, "
             "viscous {:.1f}\n",
             indent, c.cells, c.steps, c.seconds, c.cell_steps_per_second, c.pressure_iterations, c.viscous_iterations);
  fmt::print("{}paste volume drift {:.3e} (relative); max relative divergence after projection {:.3e}\n", indent,
             drift, divergence);
}

}  // namespace pastemix::app
