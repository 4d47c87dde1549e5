// SPDX-License-Identifier: MIT
// The flow solver's yield-stress validations (model/flow/validations_bingham.h), on `validate flow`:
//   pastemix validate flow poiseuille [--cells 32] [--m 1000]   Bingham plane Poiseuille, 1/2, 1, 2 x cells
//   pastemix validate flow incline [--cells 24] [--m 1000]      Bingham film at 0.8 h_c (m, 2 m) and 1.5 h_c
//   pastemix validate flow cliff [--cells 8] [--m 1000]         vertical cuts of 2 and 6 tau_y/(rho g), m and 2 m
//   pastemix validate flow slump [--cells 10 5] [--m 1000 [2000]] [--store out/lab/parameters.toml]
//                                [--lift-speed 60 [43 100 | inf]] [--max-time 4] [--progress 0.05]
//                                the lab's slump test, the mould lifted at mm/s (inf: at once)
// Each prints its error against the analytic answer, its cost and the paste-volume drift.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <omp.h>

#include "app/commands.h"
#include "model/flow/bingham.h"
#include "model/flow/validations_bingham.h"

namespace pastemix::app {

namespace {

using namespace pastemix::flow;

void print_cost(const Cost& c, double drift, double divergence) { print_flow_cost(c, drift, divergence, "    "); }

void run_poiseuille(int cells, double m) {
  fmt::print("poiseuille: Bingham plane Poiseuille, H = 2 cm, tau_y 138 Pa, eta_B 0.7 Pa s, plug half-width H/4, "
             "Papanastasiou m = {:g} s\n",
             m);
  std::vector<PoiseuilleResult> res;
  for (int n : {cells / 2, cells, 2 * cells}) {
    res.push_back(bingham_poiseuille(n, m));
    const PoiseuilleResult& r = res.back();
    fmt::print("  {} cells: L2 error {:.3e} (relative), max {:.3e} of the plug speed; plug width {:.4f} mm (exact "
               "{:.4f}, {:+.2f} % = {:+.2f} cells); plug speed {:.6f} m/s (exact {:.6f}); steady to {:.1e}\n",
               n, r.l2_error, r.max_error, 1e3 * r.plug_width, 1e3 * r.plug_width_exact,
               100 * (r.plug_width / r.plug_width_exact - 1), (r.plug_width - r.plug_width_exact) / (r.H / n),
               r.plug_speed, r.plug_speed_exact, r.last_change);
    print_cost(r.cost, r.volume_drift, r.max_divergence);
  }
  fmt::print("  observed order (L2): {} -> {}: {:.2f}, {} -> {}: {:.2f}; bound at {} cells: L2 <= 1 %\n", cells / 2,
             cells, std::log2(res[0].l2_error / res[1].l2_error), cells, 2 * cells,
             std::log2(res[1].l2_error / res[2].l2_error), cells);
}

void run_incline(int cells, double m) {
  fmt::print("incline: Bingham layer on a 30 degree plane, periodic, no-slip floor, air under a lid; tau_y 138 Pa, "
             "eta_B 0.7 Pa s, rho 1843 kg/m3; {} cells across the layer\n",
             cells);
  double creep[2] = {0, 0};
  int i = 0;
  for (double mm : {m, 2 * m}) {
    const InclineResult r = bingham_incline(0.8, cells, mm);
    creep[i++] = r.surface_speed;
    fmt::print("  h = 0.8 h_c = {:.3f} mm, m = {:g} s: surface speed {:.3e} m/s (bound 1e-5) after {:.2f} s, last "
               "change {:.1e}\n",
               1e3 * r.h, mm, r.surface_speed, r.time, r.last_change);
    print_cost(r.cost, r.volume_drift, r.max_divergence);
  }
  fmt::print("  creep ratio m -> 2 m: {:.4f} (halves or better: >= 2; Papanastasiou's creep rate -ln(1 - tau/tau_y) / m "
             "gives 2 - O(eta_B / (tau_y m)))\n",
             creep[0] / creep[1]);
  for (double mm : {m, 2 * m}) {
    const InclineResult r = bingham_incline(1.5, cells, mm);
    fmt::print("  h = 1.5 h_c = {:.3f} mm, m = {:g} s: surface speed {:.6f} m/s, analytic {:.6f}: {:+.3f} % (bound 2 %) "
               "after {:.2f} s, last change {:.1e}\n",
               1e3 * r.h, mm, r.surface_speed, r.surface_speed_exact,
               100 * (r.surface_speed / r.surface_speed_exact - 1), r.time, r.last_change);
    print_cost(r.cost, r.volume_drift, r.max_divergence);
  }
}

void run_cliff(int cells, double m) {
  fmt::print("cliff: plane-strain vertical cut, tau_y 138 Pa, rho 1843 kg/m3 (tau_y/(rho g) = {:.3f} mm), {} cells "
             "across H, 2 s; critical height ~3.77 tau_y/(rho g)\n",
             1e3 * 138.0 / (1843.0 * 9.81), cells);
  for (double k : {2.0, 6.0})
    for (double mm : {m, 2 * m}) {
      const CliffResult r = bingham_cliff(k, cells, mm);
      fmt::print("  H = {:g} tau_y/(rho g) = {:.2f} mm, m = {:g} s: movement (integral of the max paste speed) {:.3e} "
                 "m = {:.4f} cells; foot moved {:.3f} mm, top fell {:.3f} mm ({:.1f} % of H)\n",
                 k, 1e3 * r.H, mm, r.displacement, r.displacement / r.h, 1e3 * r.front_advance, 1e3 * r.top_drop,
                 100 * r.top_drop / r.H);
      print_cost(r.cost, r.volume_drift, r.max_divergence);
    }
}

// One line per `every` s of flow time: where the step's cost goes (CG iterations per solve, the step), what
// limits dt (the fastest face against the paste's speed), and the CPU time so far.
class SlumpMonitor {
 public:
  SlumpMonitor(double every, const LiftedMould& mould)
      : every_(every), next_(every), cpu0_(std::clock()), mould_(mould) {}
  void operator()(const FlowSolver& s) {
    const StepStats& st = s.last();
    ++steps_;
    pressure_ += st.projection.solve.iterations;
    viscous_ += st.viscous.iterations;
    max_pressure_ = std::max(max_pressure_, st.projection.solve.iterations);
    max_viscous_ = std::max(max_viscous_, st.viscous.iterations);
    if (s.time() < next_) return;
    next_ = s.time() + every_;
    fmt::print("    t {:.3f} s: {} steps (dt {:.2e} s), CG per solve pressure {:.1f} (max {}), viscous {:.1f} (max {}); "
               "max speed {:.3e} m/s, paste: max {:.3e} m/s, RMS {:.3e} m/s; slump {:.1f} mm, spread {:.1f} mm{}; CPU {:.1f} s\n",
               s.time(), steps_, st.dt, static_cast<double>(pressure_) / static_cast<double>(steps_), max_pressure_,
               static_cast<double>(viscous_) / static_cast<double>(steps_), max_viscous_, s.max_speed(), paste_speed(s), paste_rms_speed(s),
               1e3 * slump_shape(s).slump, 1e3 * slump_shape(s).spread,
               mould_.instant() ? std::string() : fmt::format("; mould edge {:.1f} mm", 1e3 * mould_.lower_edge(s.time())),
               static_cast<double>(std::clock() - cpu0_) / CLOCKS_PER_SEC);
    std::fflush(stdout);
    steps_ = 0;
    pressure_ = viscous_ = 0;
    max_pressure_ = max_viscous_ = 0;
  }

 private:
  double every_, next_;
  std::clock_t cpu0_;
  LiftedMould mould_;
  long steps_ = 0, pressure_ = 0, viscous_ = 0;
  int max_pressure_ = 0, max_viscous_ = 0;
};

struct SlumpOptions {
  std::string store = "out/lab/parameters.toml";
  std::vector<double> cells_mm{10.0, 5.0};
  std::vector<double> m{1000.0};
  double max_time = 4.0;  // s
  double progress = 0.0;  // s of flow time between progress lines; 0: none
  double eta_scale = 1.0;  // a sensitivity study only: the store's plastic viscosity times this
  // mm/s; inf: the instantaneous release. 60: ASTM C143's lift, 300 mm in 5 +- 2 s (43-100 mm/s; VALIDATION.md).
  std::vector<double> lift_mm_s{60.0};
  int threads = 1;
};

std::string lift_name(double v_mm_s) {
  return std::isinf(v_mm_s) ? std::string("mould lifted at once") : fmt::format("mould lifted at {:g} mm/s", v_mm_s);
}

void run_slump_at(double cell, double m, double lift_mm_s, const StorePaste& p, const SlumpOptions& o) {
  const double lift = 1e-3 * lift_mm_s;  // m/s (inf stays inf)
  FlowProgress progress;
  if (o.progress > 0) progress = SlumpMonitor(o.progress, slump_mould(lift));
  const SlumpResult r =
      bingham_slump(cell, m, p.yield_stress, p.density, o.eta_scale * p.plastic_viscosity, o.max_time, progress, lift);
  fmt::print("  {:g} mm cells, m = {:g} s, {}{}: {} at t = {:.3f} s (held to {:.3f} s; at the end: paste RMS speed "
             "{:.2e} m/s, rest below {:g}; fastest paste cell {:.2e} m/s, fastest face {:.2e} m/s)\n",
             1e3 * cell, m, lift_name(lift_mm_s),
             std::isinf(lift_mm_s)  ? std::string()
             : r.released > 0.0    ? fmt::format(" (clear of the paste at {:.3f} s)", r.released)
                                   : std::string(" (still on the paste)"),
             r.at_rest ? "at rest" : "NOT at rest", r.time, r.end_time, r.final_speed, kRestSpeed, r.final_max_speed,
             r.final_air_speed);
  fmt::print("    slump {:.1f} mm, Pashias-Boger {:.1f} mm: {:+.1f} % (bound 10 % at 5 mm); spread {:.1f} mm, Roussel & "
             "Coussot {:.1f} mm: {:+.1f} % (bound 10 %)\n",
             1e3 * r.slump, 1e3 * r.slump_pashias, 100 * (r.slump / r.slump_pashias - 1), 1e3 * r.spread,
             1e3 * r.spread_roussel, 100 * (r.spread / r.spread_roussel - 1));
  print_cost(r.cost, r.volume_drift, r.max_divergence);
  std::fflush(stdout);
}

void run_slump(const SlumpOptions& o) {
  const StorePaste p = read_store_paste(o.store, 0.75);
  fmt::print("slump: the 152 mm cylinder (H = D), quarter domain, the 75 % paste from {} ({}: tau_y {:.2f} Pa, eta_B "
             "{:.3g} Pa s, rho {:.1f} kg/m3), Papanastasiou m = {} s\n",
             o.store, p.key, p.yield_stress, p.plastic_viscosity, p.density, fmt::join(o.m, ", "));
  if (o.eta_scale != 1.0)
    fmt::print("  SENSITIVITY RUN: plastic viscosity {:g} x the store's = {:.3g} Pa s (not the acceptance case)\n",
               o.eta_scale, o.eta_scale * p.plastic_viscosity);
  for (double c : o.cells_mm)
    for (double v : o.lift_mm_s)
      for (double m : o.m) run_slump_at(1e-3 * c, m, v, p, o);
}

}  // namespace

void register_flow_bingham_commands(CLI::App& flow) {
  struct Opts {
    int cells = 32, threads = 1;
    double m = 1000.0;
  };
  using Run = void (*)(int, double);
  auto add = [&flow](const char* name, const char* what, int cells, Run run) {
    auto o = std::make_shared<Opts>();
    o->cells = cells;
    CLI::App* a = flow.add_subcommand(name, what);
    a->add_option("--cells", o->cells, fmt::format("cells across (default {})", cells));
    a->add_option("--m", o->m, "Papanastasiou regularisation m, s (default 1000)");
    a->add_option("--threads", o->threads, "OpenMP threads (default 1)");
    a->callback([o, run] {
      omp_set_num_threads(o->threads);
      Eigen::setNbThreads(o->threads);
      run(o->cells, o->m);
    });
  };
  add("poiseuille", "Bingham plane Poiseuille flow vs the analytic plug profile (cells/2, cells, 2 cells)", 32,
      run_poiseuille);
  add("incline", "Bingham layer on an incline: at rest below h_c, the analytic film above", 24, run_incline);
  auto so = std::make_shared<SlumpOptions>();
  CLI::App* sl = flow.add_subcommand("slump", "the lab's slump test vs Pashias-Boger (slump) and Roussel & Coussot (spread)");
  sl->add_option("--store", so->store, "the lab parameter store (default out/lab/parameters.toml)");
  sl->add_option("--cells", so->cells_mm, "cell sizes in mm (default 10 5)");
  sl->add_option("--m", so->m, "Papanastasiou regularisation m, s, one or more (default 1000)")
      ->check(CLI::PositiveNumber);
  sl->add_option("--max-time", so->max_time, "stop if not at rest by then, s (default 4)")->check(CLI::PositiveNumber);
  sl->add_option("--progress", so->progress, "print a progress line every this many s of flow time (default: none)")
      ->check(CLI::NonNegativeNumber);
  sl->add_option("--eta-scale", so->eta_scale,
                 "sensitivity only: the plastic viscosity times this (default 1: the store's value)")
      ->check(CLI::PositiveNumber);
  sl->add_option("--lift-speed", so->lift_mm_s,
                 "the mould's lift speed, mm/s, one or more; inf: lifted at once (default 60: ASTM C143's 300 mm in 5 s)")
      ->check(CLI::Validator(
          [](std::string& text) {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            return (end != text.c_str() && *end == '\0' && v > 0.0) ? std::string()
                                                                      : "a positive speed in mm/s, or inf";
          },
          "POSITIVE|inf"));
  sl->add_option("--threads", so->threads, "OpenMP threads (default 1)");
  sl->callback([so] {
    omp_set_num_threads(so->threads);
    Eigen::setNbThreads(so->threads);
    run_slump(*so);
  });
  add("cliff", "plane-strain vertical cut: 2 tau_y/(rho g) stands, 6 tau_y/(rho g) collapses", 8, run_cliff);
}

}  // namespace pastemix::app
