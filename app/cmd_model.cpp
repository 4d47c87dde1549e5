// SPDX-License-Identifier: MIT
// `pastemix run SCENE.toml [--out DIR] [--threads N] [--quiet]`: runs an f-DEM scene, writes HDF5 + XDMF,
// prints the per-stage profile.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "app/commands.h"
#include "model/run.h"
#include "model/scene.h"
#include "model/scene_override.h"

namespace pastemix::app {

void register_model_commands(CLI::App& app) {
  struct Opts {
    std::string scene;
    std::string out = ".";
    int threads = 0;
    bool quiet = false;
    std::vector<std::string> sets;
    std::string overrides;
  };
  auto opts = std::make_shared<Opts>();
  CLI::App* run = app.add_subcommand("run", "run an f-DEM scene (TOML) and write <stem>.h5 + <stem>.xmf");
  run->add_option("scene", opts->scene, "scene file (TOML, format in model/scene.h)")->required();
  run->add_option("--out", opts->out, "output folder (default: current)");
  run->add_option("--threads", opts->threads, "OpenMP threads (default: OMP_NUM_THREADS or all cores)");
  run->add_flag("--quiet", opts->quiet, "no progress line");
  run->add_option("--set", opts->sets, "override a scene value: key.path=value (model/scene_override.h)");
  run->add_option("--overrides", opts->overrides, "file of key.path = value lines (as pastemix sweep writes), applied before --set");
  run->callback([opts] {
    if (opts->threads > 0) omp_set_num_threads(opts->threads);
    std::vector<std::string> sets;
    if (!opts->overrides.empty()) sets = model::read_override_file(opts->overrides);
    sets.insert(sets.end(), opts->sets.begin(), opts->sets.end());
    const model::Scene scene = model::load_scene(opts->scene, sets);
    // The time step against the Rayleigh time of the smallest sphere (DESIGN.md section 3): informative,
    // the right step is found by a convergence study, not by habit.
    {
      double tr = 1e300;
      const auto& p = scene.particles;
      for (std::size_t a = 0; a < p.size(); ++a) {
        const auto& m = scene.materials[static_cast<std::size_t>(p.material[a])];
        tr = std::min(tr, M_PI * p.radius[a] * std::sqrt(m.density / m.shear_modulus()) /
                              (0.8766 + 0.163 * m.poisson_ratio));
      }
      fmt::print(stderr, "time step {:.3g} s = {:.1f} % of the Rayleigh time of the smallest sphere ({:.3g} s)\n",
                 scene.config.dt, 100.0 * scene.config.dt / tr, tr);
    }
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
