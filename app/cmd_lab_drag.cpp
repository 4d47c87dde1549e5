// SPDX-License-Identifier: MIT
// `pastemix lab drag-fit DIR`: the settling-sphere drag-curve pipeline (its own issue fills this in).
#include "app/commands.h"

namespace pastemix::app {

void register_lab_drag_commands(CLI::App& /*lab*/) {}

}  // namespace pastemix::app
