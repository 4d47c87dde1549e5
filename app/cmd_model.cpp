// SPDX-License-Identifier: MIT
// `pastemix run SCENE.toml [--out DIR] [--threads N] [--quiet]`: runs an f-DEM scene, writes HDF5 + XDMF,
// prints the per-stage profile.
#include <omp.h>

#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "app/commands.h"
#include "model/run.h"
#include "model/scene.h"

namespace pastemix::app {

void register_model_commands(CLI::App& app) {
  struct Opts {
    std::string scene;
    std::string out = ".";
    int threads = 0;
    bool quiet = false;
  };
  auto opts = std::make_shared<Opts>();
  CLI::App* run = app.add_subcommand("run", "run an f-DEM scene (TOML) and write <stem>.h5 + <stem>.xmf");
  run->add_option("scene", opts->scene, "scene file (TOML, format in model/scene.h)")->required();
  run->add_option("--out", opts->out, "output folder (default: current)");
  run->add_option("--threads", opts->threads, "OpenMP threads (default: OMP_NUM_THREADS or all cores)");
  run->add_flag("--quiet", opts->quiet, "no progress line");
  run->callback([opts] {
    if (opts->threads > 0) omp_set_num_threads(opts->threads);
    const model::Scene scene = model::load_scene(opts->scene);
    model::RunOptions ro;
    ro.progress = !opts->quiet;
    const model::RunSummary r = model::run_scene(scene, opts->out, ro);
    fmt::print("{} particles, {} steps of {:.3g} s, {} thread(s)\n", scene.particles.size(), r.steps, scene.config.dt,
               r.threads);
    fmt::print("{}", r.profile_table);
    fmt::print("wrote {} and {}\n", r.h5.string(), r.xmf.string());
  });
}

}  // namespace pastemix::app
