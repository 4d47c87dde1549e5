// SPDX-License-Identifier: MIT
// Each layer registers its subcommands on the `pastemix` CLI11 app through one function here.
#pragma once

#include <CLI/CLI.hpp>

namespace pastemix::app {

// `pastemix lab ...` (app/cmd_lab.cpp)
void register_lab_commands(CLI::App& app);

}  // namespace pastemix::app
