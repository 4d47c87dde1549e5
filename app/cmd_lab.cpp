// SPDX-License-Identifier: MIT
// `pastemix lab <kind> FILE` and `pastemix lab reduce DIR`.
#include "app/commands.h"

namespace pastemix::app {

void register_lab_commands(CLI::App& app) {
  auto* lab = app.add_subcommand("lab", "Reduce laboratory measurements to model parameters");
  lab->require_subcommand(1);
  register_lab_drag_commands(*lab);
}

}  // namespace pastemix::app
