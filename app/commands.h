// SPDX-License-Identifier: MIT
// Each layer registers its subcommands on the `pastemix` CLI11 app through one function here.
#pragma once

#include <CLI/CLI.hpp>

namespace pastemix::app {

// `pastemix lab ...` (app/cmd_lab.cpp); it calls the drag registration below for its own subcommand.
void register_lab_commands(CLI::App& app);
// `pastemix lab drag-fit ...` (app/cmd_lab_drag.cpp), registered on the `lab` subcommand.
void register_lab_drag_commands(CLI::App& lab);
// `pastemix run ...` and other engine commands (app/cmd_model.cpp).
void register_model_commands(CLI::App& app);
// `pastemix maps ...` and `pastemix score ...` (app/cmd_analysis.cpp).
void register_analysis_commands(CLI::App& app);
// `pastemix sweep` (app/cmd_study.cpp).
void register_study_commands(CLI::App& app);

}  // namespace pastemix::app
