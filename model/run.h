// SPDX-License-Identifier: MIT
// Running a scene to its end time with snapshots, energy samples, a progress line and diagnostics.
//
//   Scene s = load_scene("pour_box.toml");
//   RunSummary r = run_scene(s, "out");   // writes out/pour_box.h5 and out/pour_box.xmf (both or neither)
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "model/scene.h"
#include "model/stop_rule.h"

namespace pastemix::model {

struct RunOptions {
  bool progress = true;        // throttled progress line on stderr
  double progress_every_s = 2.0;  // wall seconds between progress lines
  int check_every = 50;        // steps between full diagnostics (NaN and domain are checked every step)
  std::string stem;            // output file stem; empty: the scene file's stem (realizations: NAME_rK)
  // Checkpoints (model/checkpoint.h), OUT/STEM.checkpoint.h5: every [output] checkpoint_interval of
  // simulated time and/or every checkpoint_wall_s of wall-clock time (0: not by wall time); removed once
  // the result is published. resume: continue from it. resume_with: the command that would, stored in it.
  double checkpoint_wall_s = 0.0;
  bool resume = false;
  std::string resume_with;
  // Called once with the final state, after the loop and before the result is published: a study's
  // quantity of interest of the final state (app/study), taken in the same run that writes the checkpoints.
  std::function<void(const World&)> at_end;
};

struct RunSummary {
  std::filesystem::path h5, xmf;
  long steps = 0;
  double wall_seconds = 0.0;
  double steps_per_second = 0.0;
  int threads = 1;
  Profile profile;
  std::string profile_table;   // the per-stage table printed at the end of `pastemix run`
  // Outflow ([domain] on_exit = "remove"): particles removed at the domain boundary, their mass (kg) and
  // the total particle mass (kg: those left at the end + the escaped).
  bool outflow = false;
  std::size_t escaped_count = 0;
  double escaped_mass = 0.0, total_mass = 0.0;
  std::string escaped_line() const;  // one line for `pastemix run` ("" without outflow)
  // How the run ended: by the [stop] rule at rest, or at end_time (a warning when the rule asked for rest).
  StopOutcome stop;
  bool failed_to_rest() const { return stop.rule_at_rest && !stop.fired; }
  long resumed_at_step = -1;   // --resume: the checkpoint's step (-1: a run from t = 0)
  long checkpoints = 0;        // checkpoints written by this run
};

// Output files are named after options.stem, else the scene file's stem. On a RuntimeFailure nothing is left
// behind but the last checkpoint (if any): the run can be resumed from it with a smaller step, say.
RunSummary run_scene(const Scene& scene, const std::filesystem::path& out_dir, const RunOptions& options = {});

std::string format_profile(const Profile& p, long steps, double wall_seconds, std::size_t particles);

}  // namespace pastemix::model
