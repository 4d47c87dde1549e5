// SPDX-License-Identifier: MIT
// `pastemix lab drag-fit DIR [--out OUTDIR] [--no-plots]`: the settling-sphere drag-curve pipeline.
#include <memory>
#include <string>

#include <fmt/format.h>

#include "app/commands.h"
#include "base/units.h"
#include "lab/drag/drag_report.h"

namespace pastemix::app {

namespace {

struct DragFitArgs {
  std::string dir;
  std::string out = "out/drag";
  bool no_plots = false;
  bool robust = false;
};

void run_drag_fit(const DragFitArgs& a) {
  // All inputs are read and every fit done before anything is written (StagedOutput inside).
  const auto r = lab::drag::run_drag_fit(a.dir, units::g, a.robust);
  fmt::print("{}", lab::drag::score_table(r));
  const auto w = lab::drag::write_drag_fit_outputs(r, a.out, !a.no_plots);
  if (!w.plot_message.empty()) fmt::print(stderr, "warning: {}\n", w.plot_message);
  fmt::print("\nwrote:\n");
  for (const auto& p : w.written) fmt::print("  {}\n", p.string());
}

}  // namespace

void register_lab_drag_commands(CLI::App& lab) {
  auto args = std::make_shared<DragFitArgs>();
  auto* cmd = lab.add_subcommand(
      "drag-fit", "Fit Cd(Re') curves to the Valentik & Whitmore spheres; score terminal velocities held out");
  cmd->add_option("DIR", args->dir, "dataset folder (valentik_whitmore_1965_*.csv)")->required();
  cmd->add_option("--out", args->out, "output folder")->capture_default_str();
  cmd->add_flag("--no-plots", args->no_plots, "skip the matplotlib figures");
  cmd->add_flag("--robust", args->robust, "also fit every candidate with a Cauchy loss (scale 0.1, ln units)");
  cmd->callback([args] { run_drag_fit(*args); });
}

}  // namespace pastemix::app
