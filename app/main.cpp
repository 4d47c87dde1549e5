// SPDX-License-Identifier: MIT
// The `pastemix` command. Thin: parses the command line and hands off to the layers.
//
// Exit codes: 0 success, 1 internal error, 2 bad input (file:line: field: message), 3 a computation that
// could not go on (blow-up, lost particle, no solution), with a diagnosis on stderr.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <new>

#include <fmt/format.h>

#include "app/commands.h"
#include "base/error.h"

int main(int argc, char** argv) {
  CLI::App app{"pastemix: lab reduction, f-DEM of waste rock dumped into paste backfill, mixing analysis"};
  app.require_subcommand(1);
  pastemix::app::register_lab_commands(app);
  pastemix::app::register_model_commands(app);
  pastemix::app::register_analysis_commands(app);
  pastemix::app::register_fluid_commands(app);
  pastemix::app::register_flow_commands(app);
  pastemix::app::register_coupling_commands(app);
  pastemix::app::register_study_commands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const pastemix::InputError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  } catch (const pastemix::RuntimeFailure& e) {
    fmt::print(stderr, "failure: {}\n", e.what());
    return 3;
  } catch (const std::filesystem::filesystem_error& e) {
    // A file-system call the command did not wrap: still the environment's problem, with the path.
    fmt::print(stderr, "error: {}: {}\n", e.path1().string(), e.code().message());
    return 2;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "failure: out of memory (the inputs ask for more memory than this machine has)\n");
    return 3;
  } catch (const std::exception& e) {
    fmt::print(stderr, "internal error: {}\n", e.what());
    return 1;
  }
  return 0;
}
