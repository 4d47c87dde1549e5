// SPDX-License-Identifier: MIT
// Each layer registers its subcommands on the `pastemix` CLI11 app through one function here.
#pragma once

#include <CLI/CLI.hpp>

namespace pastemix::flow {
struct Cost;
}

namespace pastemix::app {

// A subcommand that groups others and that several layers add to (`calibrate`): created by the first caller,
// found by the next.
inline CLI::App* group_subcommand(CLI::App& app, const std::string& name, const std::string& description) {
  for (CLI::App* sub : app.get_subcommands({}))
    if (sub->get_name() == name) return sub;
  CLI::App* sub = app.add_subcommand(name, description);
  sub->require_subcommand(1);
  return sub;
}

// `pastemix lab ...` (app/cmd_lab.cpp); it calls the drag registration below for its own subcommand.
void register_lab_commands(CLI::App& app);
// `pastemix lab drag-fit ...` (app/cmd_lab_drag.cpp), registered on the `lab` subcommand.
void register_lab_drag_commands(CLI::App& lab);
// `pastemix run ...` and other engine commands (app/cmd_model.cpp).
void register_model_commands(CLI::App& app);
// `pastemix maps ...` and `pastemix score ...` (app/cmd_analysis.cpp).
void register_analysis_commands(CLI::App& app);
// `pastemix validate ...`, `pastemix calibrate viscosity` (fluid, app/cmd_fluid.cpp).
void register_fluid_commands(CLI::App& app);
// `pastemix validate flow ...`, `pastemix flow run` (the flow solver, app/cmd_flow.cpp).
void register_flow_commands(CLI::App& app);
// `pastemix validate coupling sphere | piston | hindered` (the particles-paste coupling, app/cmd_coupling.cpp).
void register_coupling_commands(CLI::App& app);
// `pastemix validate flow poiseuille | incline | cliff | slump` (yield-stress cases, app/cmd_flow_bingham.cpp),
// registered on the `validate flow` subcommand.
void register_flow_bingham_commands(CLI::App& validate_flow);
// The two lines every flow validation prints: cost (cells, steps, cell-steps/s, CG iterations per solve) and
// conservation (paste volume drift, leftover divergence), each line starting with `indent`.
void print_flow_cost(const flow::Cost& c, double drift, double divergence, const char* indent);
// `pastemix sweep` (app/cmd_study.cpp).
void register_study_commands(CLI::App& app);

}  // namespace pastemix::app
