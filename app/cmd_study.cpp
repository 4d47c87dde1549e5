// SPDX-License-Identifier: MIT
// `pastemix sweep SCENE.toml --vary dt|psd_cut|youngs_modulus --qoi NAME [--values ...] [--levels N]
//  [--tol REL] [--seeds N] [--material NAME] [--set key=value ...] [--out DIR]`: speed against error
// (app/study/sweep.h).
#include <memory>

#include <fmt/format.h>

#include "app/commands.h"
#include "app/study/qoi.h"
#include "app/study/sweep.h"

namespace pastemix::app {

void register_study_commands(CLI::App& app) {
  struct Opts {
    std::string scene;
    study::SweepOptions o;
    std::vector<std::string> sets;
  };
  auto opts = std::make_shared<Opts>();
  std::string qoi_help = "quantity of interest:";
  for (const auto& q : study::qoi_registry()) qoi_help += " " + q.name + " (" + q.unit + ")";
  CLI::App* s = app.add_subcommand("sweep", "speed against error: run a scene over a ladder of one setting");
  s->add_option("scene", opts->scene, "scene file (TOML)")->required();
  s->add_option("--vary", opts->o.vary, "dt | youngs_modulus | psd_cut")->required()->check(
      CLI::IsMember({"dt", "youngs_modulus", "psd_cut"}));
  s->add_option("--qoi", opts->o.qoi, qoi_help)->required();
  s->add_option("--values", opts->o.values, "ladder values, coarse -> fine (default: see app/study/sweep.h)");
  s->add_option("--levels", opts->o.levels, "default-ladder length (default 4)");
  s->add_option("--tol", opts->o.tol, "relative tolerance on the QoI (default 0.01)");
  s->add_option("--seeds", opts->o.seeds, "runs per point with seeds seed, seed+1, ... (default 1)");
  s->add_option("--material", opts->o.material, "youngs_modulus: the material varied (default: the first)");
  s->add_option("--set", opts->sets, "scene override key.path=value applied before the ladder");
  s->add_option("--out", opts->o.out, "output folder (default sweep_out)");
  s->add_flag("--quiet", opts->o.quiet, "no per-run lines");
  s->callback([opts] {
    model::SceneDoc base = model::SceneDoc::parse_file(opts->scene);
    for (const auto& a : opts->sets) base.apply(a);
    const study::SweepResult r = study::sweep(base, opts->o);
    fmt::print("{}", r.table);
    study::write_outputs(r, opts->o);
    fmt::print("wrote {0}/sweep.csv, {0}/sweep.png{1}\n", opts->o.out.string(),
               r.override_text.empty() ? "" : fmt::format(", {}/chosen_overrides.toml", opts->o.out.string()));
  });
}

}  // namespace pastemix::app
