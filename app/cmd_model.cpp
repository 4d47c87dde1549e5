// SPDX-License-Identifier: MIT
// `pastemix run SCENE.toml` and other engine commands (the engine-core issue fills this in).
#include "app/commands.h"

namespace pastemix::app {

void register_model_commands(CLI::App& /*app*/) {}

}  // namespace pastemix::app
